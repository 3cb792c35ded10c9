"""One drawing function per paper figure, reading netCDF outputs only.

Each module registers its figures in a ``FIGURES = {label: function}`` dict;
a function takes opened :class:`xarray.Dataset` objects (and the figure's
options from config.yaml) and returns a matplotlib Figure; :func:`save_figure`
writes it as ``<stem>.pdf`` and ``<stem>.png``. Modules: :mod:`.maps`
(traj3, traj2), :mod:`.homoclinic` (bcsc), :mod:`.travelling` (plot4-5,
plotcomplin).
"""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PNG_DPI = 150


def save_figure(fig, stem) -> list[Path]:
    """Save ``fig`` as ``stem.pdf`` and ``stem.png`` with fixed metadata.

    No creation date is written, so rebuilding a figure from the same data
    gives the same files.
    """
    stem = Path(stem)
    stem.parent.mkdir(parents=True, exist_ok=True)
    out = []
    for ext, meta in (("pdf", {"CreationDate": None, "ModDate": None}), ("png", {"Software": None})):
        path = stem.with_suffix(f".{ext}")
        fig.savefig(path, dpi=PNG_DPI, metadata=meta)
        out.append(path)
    plt.close(fig)
    return out


def figure(nrows=1, ncols=1, width=6.4, height=3.6, **kw):
    """A new figure with the project's layout defaults."""
    return plt.subplots(nrows, ncols, figsize=(width, height), constrained_layout=True, **kw)


def registry() -> dict:
    """label -> drawing function, collected from the ``FIGURES`` dict of every module here.

    Each function takes (data, options) and returns a Figure; ``data`` maps
    every name of the figure's `scenes:` list to its Dataset(s) (see
    :func:`load_inputs`), ``options`` is the figure's entry in config.yaml.
    """
    import importlib
    import pkgutil

    found = {}
    for info in pkgutil.iter_modules(__path__):
        module = importlib.import_module(f"{__name__}.{info.name}")
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


def draw(label: str, data: dict, options: dict, stem) -> list[Path]:
    """Draw figure ``label`` and save it as ``stem``.pdf/.png."""
    funcs = registry()
    if label not in funcs:
        raise KeyError(f"no drawing function for figure {label!r}; known: {sorted(funcs)}")
    return save_figure(funcs[label](data, options), stem)
