"""One drawing function per paper figure, reading netCDF outputs only.

Each module registers its figures in a ``FIGURES = {label: function}`` dict;
a function takes opened :class:`xarray.Dataset` objects (and the figure's
options from config.yaml) and returns a matplotlib Figure; :func:`save_figure`
writes it as ``<stem>.pdf`` and ``<stem>.png``. Modules: :mod:`.maps`
(traj3, traj2), :mod:`.homoclinic` (bcsc), :mod:`.travelling` (plot4-5,
plotcomplin), :mod:`.spacetime` (space-time diagrams and profiles),
:mod:`.spectra` (fft106, fftseuil, fft344), :mod:`.localised` (breathers,
loc1, fini), :mod:`.beyond` and :mod:`.workprecision` (beyond the paper).

Importing this package is cheap (no matplotlib, no figure module): the
Snakefile asks it which module draws a label (:func:`module_of`), and a
figure job imports only that module.
"""
from __future__ import annotations

import re
from pathlib import Path

PNG_DPI = 150
_HERE = Path(__file__).parent


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(fig, stem) -> list[Path]:
    """Save ``fig`` as ``stem.png`` and ``stem.pdf`` with fixed metadata.

    The layout (constrained_layout: the costly part, every tick label is
    measured on each pass) is solved once, for the PNG, then frozen for the
    PDF. No creation date is written, so rebuilding a figure from the same
    data gives the same files.
    """
    stem = Path(stem)
    stem.parent.mkdir(parents=True, exist_ok=True)
    out = []
    for ext, meta in (("png", {"Software": None}), ("pdf", {"CreationDate": None, "ModDate": None})):
        path = stem.with_suffix(f".{ext}")
        fig.savefig(path, dpi=PNG_DPI, metadata=meta)
        fig.set_layout_engine("none")  # keeps the positions found for the PNG
        out.append(path)
    _pyplot().close(fig)
    return out[::-1]


def figure(nrows=1, ncols=1, width=6.4, height=3.6, **kw):
    """A new figure with the project's layout defaults."""
    return _pyplot().subplots(nrows, ncols, figsize=(width, height), constrained_layout=True, **kw)


#: the two registries a module here may define: ``FIGURES`` (paper figures, drawn from the
#: scenes' files by :func:`draw`) and ``DATASET_FIGURES`` (beyond the paper, each drawn from the
#: one netCDF file of its analysis by :func:`draw_dataset`)
REGISTRIES = ("FIGURES", "DATASET_FIGURES")


def _declared(path: Path, registry: str) -> list[str]:
    """The labels of ``registry`` in the module at ``path``, read from its source."""
    m = re.search(rf"^{registry}\s*=\s*\{{(.*?)\}}", path.read_text(), re.M | re.S)
    return re.findall(r"[\"']([\w.-]+)[\"']\s*:", m.group(1)) if m else []


def module_of(label: str, registry: str = "FIGURES") -> str:
    """Name of the module here whose ``registry`` dict draws ``label``, found by reading the
    sources (nothing is imported; the Snakefile uses it to make that module a rule input)."""
    found = [path.stem for path in sorted(_HERE.glob("[!_]*.py")) if label in _declared(path, registry)]
    if len(found) != 1:
        raise KeyError(f"figure {label!r} is drawn by {len(found)} modules of {_HERE} ({found}); "
                       f"known: {sorted(labels(registry))}")
    return found[0]


def labels(registry: str = "FIGURES") -> list[str]:
    """Every label some module here draws in ``registry`` (read from the sources)."""
    return [label for path in sorted(_HERE.glob("[!_]*.py")) for label in _declared(path, registry)]


def drawer(label: str, registry: str = "FIGURES"):
    """The drawing function of ``label``, importing only its module."""
    import importlib

    module = importlib.import_module(f"{__name__}.{module_of(label, registry)}")
    return getattr(module, registry)[label]


def registry() -> dict:
    """label -> drawing function, for every module here (imports them all).

    Each function takes (data, options) and returns a Figure; ``data`` maps
    every name of the figure's `scenes:` list to its Dataset(s) (see
    :func:`load_inputs`), ``options`` is the figure's entry in config.yaml.
    """
    import importlib

    found = {}
    for path in sorted(_HERE.glob("[!_]*.py")):
        module = importlib.import_module(f"{__name__}.{path.stem}")
        for label, func in getattr(module, "FIGURES", {}).items():
            if label in found:
                raise RuntimeError(f"figure {label!r} is drawn by two modules")
            found[label] = func
    return found


def load_inputs(scenes: dict, root) -> dict:
    """Open the netCDF files of a figure's scenes.

    ``scenes`` maps each name to its config section (map, homoclinic,
    scenes). Map and homoclinic names give one Dataset; a scene gives
    ``{"exact": ..., "dps": ..., "metrics": ...}``.
    """
    from ..io import open_dataset

    root = Path(root)
    data = {}
    for name, kind in scenes.items():
        if kind == "map":
            data[name] = open_dataset(root / "map" / f"{name}.nc")
        elif kind == "homoclinic":
            data[name] = open_dataset(root / "homoclinic" / f"{name}.nc")
        else:
            data[name] = {part: open_dataset(path) for part, path in (
                ("exact", root / "sim" / name / "exact.nc"), ("dps", root / "sim" / name / "dps.nc"),
                ("metrics", root / "metrics" / f"{name}.nc"))}
    return data


def draw_dataset(label: str, ds, stem) -> list[Path]:
    """Draw the beyond-the-paper figure ``label`` (a ``DATASET_FIGURES`` entry) from the Dataset
    of its analysis and save it as ``stem``.pdf/.png."""
    return save_figure(drawer(label, "DATASET_FIGURES")(ds), stem)


def draw(label: str, data: dict, options: dict, stem) -> list[Path]:
    """Draw figure ``label`` and save it as ``stem``.pdf/.png (times go to the log)."""
    import logging
    import time

    log = logging.getLogger("cradle")
    t0 = time.perf_counter()
    fig = drawer(label)(data, options)
    t1 = time.perf_counter()
    out = save_figure(fig, stem)
    log.info("figure %s: drawn in %.2f s, saved in %.2f s -> %s", label, t1 - t0, time.perf_counter() - t1,
             ", ".join(map(str, out)))
    return out
