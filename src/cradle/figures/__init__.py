"""One drawing function per paper figure, reading netCDF outputs only.

:data:`FIGURES` maps each label to its drawing function; a function takes
opened :class:`xarray.Dataset` objects (and the figure's options from
config.yaml) and returns a matplotlib Figure; :func:`save_figure`
writes it as ``<stem>.pdf`` and ``<stem>.png``. Modules: :mod:`.maps`
(traj3, traj2), :mod:`.homoclinic` (bcsc), :mod:`.travelling` (plot4-5,
plotcomplin), :mod:`.spacetime` (space-time diagrams and profiles),
:mod:`.spectra` (fft106, fftseuil, fft344), :mod:`.localised` (breathers,
loc1, fini); beyond the paper, ``draw(tree)`` of the module named as each analysis
(:mod:`.theorem1`, :mod:`.mi_diagram`, :mod:`.mi_growth`, ...; :func:`draw_analysis`).

Importing this package is cheap (no matplotlib, no figure module): the
Snakefile asks it which module draws a label (:func:`module_of`) and
derives the job's code inputs from that module's imports; a figure job
imports only that module.

The figures are :class:`matplotlib.figure.Figure` objects made outside pyplot (:func:`figure`): drawing
one neither changes the session's backend nor adds to pyplot's open figures, so a notebook's
``plt.show()`` keeps drawing; they are rendered to files by matplotlib's own canvases (Agg, PDF).
"""
from __future__ import annotations

import os
from collections.abc import Callable, Hashable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.axes import Axes
    from matplotlib.axis import Axis
    from matplotlib.figure import Figure
    from matplotlib.legend import Legend

#: a paper figure's drawing function: (data, options) -> Figure (:func:`registry`)
Drawer = Callable[[dict, dict], "Figure"]

class AnalysisTree(Protocol):
    """An analysis output tree (an :class:`xarray.DataTree`) as the ``draw(tree)`` bodies read it: its
    attributes, children and root Dataset, and lookups chained through groups to variables
    (``tree["g"]["v"].values``), each Any: xarray types ``DataTree[key]`` as ``DataTree | DataArray``, so
    typing them would need a check or a cast at every link of the chains."""

    @property
    def attrs(self) -> dict[Hashable, Any]: ...

    @property
    def children(self) -> Mapping[str, Any]: ...

    def __getitem__(self, key: str) -> Any: ...

    def to_dataset(self) -> xr.Dataset: ...

PNG_DPI = 150


def save_figure(fig: Figure, stem: str | os.PathLike) -> list[Path]:
    """Save ``fig`` as ``stem.png`` and ``stem.pdf`` with fixed metadata, atomically.

    The layout (constrained_layout: the costly part, every tick label is
    measured on each pass) is solved once, for the PNG, then frozen for the
    PDF. No creation date is written, so rebuilding a figure from the same
    data gives the same files. Both files are written under temporary names
    beside their targets and renamed only once both are complete: a drawing
    that fails part way leaves the previous figure (both files) in place.
    """
    from cradle.data.temporaries import temporary_beside

    stem = Path(stem)
    stem.parent.mkdir(parents=True, exist_ok=True)
    done: list[tuple[str, Path]] = []
    try:
        for ext, meta in (("png", {"Software": None}), ("pdf", {"CreationDate": None, "ModDate": None})):
            path = stem.with_suffix(f".{ext}")
            tmp = temporary_beside(path, suffix=f".tmp.{ext}")  # named after this process: stale if it dies
            done.append((tmp, path))
            fig.savefig(tmp, dpi=PNG_DPI, metadata=meta, format=ext)
            fig.set_layout_engine("none")  # keeps the positions found for the PNG
        mask = os.umask(0)
        os.umask(mask)
        for tmp, path in done:
            os.chmod(tmp, 0o666 & ~mask)
            os.replace(tmp, path)
    finally:
        for tmp, _ in done:
            if os.path.exists(tmp):
                os.remove(tmp)
    return [path for _, path in done][::-1]


#: how each model (the names of an analysis file's `model` coordinate) is marked wherever both are plotted
MODEL_STYLE = {"exact": dict(color="C0", marker="o", label="exact (nc)"),
               "dps": dict(color="C3", marker="x", label="DpS (dfnls)")}


def legend_outside(ax: Axes, fontsize: float = 7, **kw: Any) -> Legend:
    """The legend of ``ax`` beside its right edge, off the data (the layout keeps room for it)."""
    return ax.legend(fontsize=fontsize, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, **kw)


def plain_log_ticks(ax: Axes) -> None:
    """Log axes of ``ax`` spanning less than two decades labelled as plain numbers at 1, 2 and 5 times a
    power of ten (matplotlib labels every minor tick there, in scientific notation, on top of each other)."""
    import math

    from matplotlib.ticker import FuncFormatter

    def label(value: float, _pos: int | None, axis: Axis) -> str:
        lo, hi = sorted(abs(v) for v in axis.get_view_interval())
        if value <= 0 or lo <= 0 or hi / lo >= 100:
            return ""
        mantissa = round(value / 10 ** math.floor(math.log10(value) + 1e-9), 6)
        return f"{value:.3g}" if mantissa in (1.0, 2.0, 5.0) else ""

    for axis in (ax.xaxis, ax.yaxis):
        if axis.get_scale() == "log":
            lo, hi = sorted(abs(v) for v in axis.get_view_interval())
            if lo > 0 and hi / lo < 100:
                axis.set_major_formatter(FuncFormatter(lambda v, p, a=axis: label(v, p, a)))
                axis.set_minor_formatter(FuncFormatter(lambda v, p, a=axis: label(v, p, a)))


def dps_range_top() -> float:
    """The largest amplitude at which DpS was measured to approximate the lattice: 2 eps_max of dps-validity
    (:data:`cradle.specs.values.DPS_EPS_MEASURED`; :func:`cradle.measurements.dps_range.measured_amplitude`)."""
    from cradle.specs.values import DPS_EPS_MEASURED

    return 2.0 * DPS_EPS_MEASURED


def outside_dps_range(a: float) -> str:
    """``"outside DpS's measured range: amplitude ..."`` when the amplitude ``a`` is above :func:`dps_range_top`,
    else ``""``."""
    top = dps_range_top()
    if not a > top:
        return ""
    return (f"outside DpS's measured range: amplitude {a:.3g} > {top:g} = 2 $\\varepsilon_{{max}}$ of dps-validity "
            f"({top / 2.0:g})")


def dps_range_note(name: str, ds: xr.Dataset) -> str:
    """The line a figure comparing DpS with the lattice carries when scene ``name`` is outside DpS's measured range
    (:func:`outside_dps_range`), else ``""``: the amplitude of its run ``ds`` (exact or DpS) at t = 0 as
    :func:`cradle.measurements.dps_range.amplitude_of` counts it, max_n sqrt(x_n^2 + v_n^2) (``x`` alone when
    ``v`` is not stored); ``""`` too when the run's first stored time is not 0."""
    import numpy as np

    if "x" not in ds or float(ds["t"].values[0]) != 0.0:
        return ""
    x0 = np.asarray(ds["x"].values[0], dtype=float)
    v0 = np.asarray(ds["v"].values[0], dtype=float) if "v" in ds else np.zeros_like(x0)
    note = outside_dps_range(float(np.max(np.hypot(x0, v0))))
    return f"{name} is {note}" if note else ""


def scene_caption(name: str, ds: xr.Dataset) -> str:
    """One line of the parameters a scene's file stores (``attrs`` of its exact or DpS run): N, q,
    omega_tw, a, noise, so a changed run is told from the paper's at a glance; a second line when the scene's
    amplitude is outside DpS's measured range (:func:`dps_range_note`)."""
    a = ds.attrs
    parts = [f"{name}:", f"$N = {int(a.get('N', ds.sizes.get('n', 0)))}$"]
    if "q_expr" in a:
        parts.append(f"$q = {str(a['q_expr']).replace('pi', chr(92) + 'pi ').strip()}$")
    for key, tex in (("omega_tw", "\\omega_{tw}"), ("omega_sw", "\\omega_{sw}")):
        if key in a:  # a file written before these attributes, or a test's Dataset, shows what it has
            parts.append(f"${tex} = {float(a[key]):.5g}$")
    if "a" in a:
        parts.append(f"$a = {float(a['a']):.4g}$")
    if str(a.get("noise", "none")) != "none":
        parts.append(f"{a['noise']} noise {float(a.get('noise_amplitude', float('nan'))):g}")
    caption = ", ".join(parts[:1]) + " " + ", ".join(parts[1:])
    note = dps_range_note(name, ds)
    return f"{caption}\n{note}" if note else caption


# -> (Figure, Any): the axes are one Axes or an array of them, as nrows, ncols and squeeze say (matplotlib
# types Figure.subplots' result as Any for that reason)
def figure(nrows: int = 1, ncols: int = 1, width: float = 6.4, height: float = 3.6,
           **kw: Any) -> tuple[Figure, Any]:
    """A new figure and its axes (``kw``: those of :meth:`~matplotlib.figure.Figure.subplots`) with the project's
    layout defaults, outside pyplot: the session's backend and pyplot's figures are left alone."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(width, height), layout="constrained")
    return fig, fig.subplots(nrows, ncols, **kw)


#: Paper figures: label -> "module.function" of this package, drawn from the scenes' files by
#: :func:`draw`. The one table of labels: config validation, the Snakefile and the tests read it.
FIGURES = {
    "traj3": "maps.draw_traj3",
    "traj2": "maps.draw_traj2",
    "bcsc": "homoclinic.draw_bcsc",
    "plot4-5": "travelling.draw_plot4_5",
    "plotcomplin": "travelling.draw_plotcomplin",
    "plot6-7": "spacetime.draw_plot6_7",
    "plot2-3": "spacetime.draw_plot2_3",
    "plot1v5st": "spacetime.draw_plot1v5st",
    "plot1v5": "spacetime.draw_plot1v5",
    "plot8-11": "spacetime.draw_plot8_11",
    "plot9-10": "spacetime.draw_plot9_10",
    "plot29-30": "spacetime.draw_plot29_30",
    "plot26-27": "spacetime.draw_plot26_27",
    "plot28": "spacetime.draw_plot28",
    "fft106": "spectra.draw_fft106",
    "fftseuil": "spectra.draw_fftseuil",
    "fft344": "spectra.draw_fft344",
    "plot18": "localised.draw_plot18",
    "loc1": "localised.draw_loc1",
    "fini": "localised.draw_fini",
}

def module_of(label: str) -> str:
    """Name of the module here that draws the paper figure ``label`` (nothing is imported)."""
    if label not in FIGURES:
        raise KeyError(f"no figure {label!r} (known: {sorted(FIGURES)})")
    return FIGURES[label].split(".")[0]


def labels() -> list[str]:
    """Every paper figure label."""
    return list(FIGURES)


def drawer(label: str) -> Drawer:
    """The drawing function of paper figure ``label``, importing only its module."""
    import importlib

    module_of(label)  # the clear KeyError for an unknown label
    module, func = FIGURES[label].split(".")
    return getattr(importlib.import_module(f"{__name__}.{module}"), func)


def registry() -> dict[str, Drawer]:
    """label -> drawing function for every paper figure (imports every figure module).

    Each function takes (data, options) and returns a Figure; ``data`` maps
    every name of the figure's `scenes:` list to its Dataset(s) (see
    :func:`load_inputs`), ``options`` is the figure's entry in config.yaml.
    """
    return {label: drawer(label) for label in FIGURES}


def draw_analysis(module: str, tree: xr.DataTree, stem: str | os.PathLike, note: str = "") -> list[Path]:
    """Draw the figure of an analysis (``draw`` of ``cradle.figures.<module>``) from its output ``tree`` and
    save it as ``stem``.pdf/.png; ``note`` (e.g. which form of the analysis it shows) goes small in the
    bottom right corner."""
    import importlib

    fig = importlib.import_module(f"{__name__}.{module}").draw(tree)
    if note:  # a figure-level x label: the layout keeps room for it below the panels
        fig.supxlabel(note, x=0.998, ha="right", fontsize=6, color="0.4")
    return save_figure(fig, stem)


def write_tables(module: str, tree: xr.DataTree, paths: dict[str, str | os.PathLike]) -> list[Path]:
    """Write the tables of an analysis (``tables`` of ``cradle.figures.<module>``: format -> text) from its
    output ``tree`` to ``paths`` (format -> file), each atomically."""
    import importlib

    from cradle.data.io import write_text

    tables = importlib.import_module(f"{__name__}.{module}").tables(tree)
    return [write_text(tables[ext], path) for ext, path in paths.items()]


def draw(label: str, data: dict, options: dict, stem: str | os.PathLike) -> list[Path]:
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
