"""Where every output lives: the one declaration of the results layout.

Paths are relative to a results folder (``results`` for the workflow, a
folder of its own for ``cradle run``). Rules, scripts, the CLI,
:func:`cradle.open_scene` and the figure loader all ask
here; nothing else spells a path. Templates keep Snakemake wildcards
(``{scene}``, ``{name}``, ``{label}``) when those are passed through::

    path("exact", scene="tw-weak")            # results/sim/tw-weak/exact.nc
    path("exact", scene="{scene}")            # results/sim/{scene}/exact.nc (a rule's output)
    path("exact", root="out", scene="tw")     # out/sim/tw/exact.nc
"""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Iterable

    from cradle.analyses.protocol import Analysis, Read

ROOT = "results"

#: kind -> path template under the results folder
TEMPLATES = {
    # stage 1: stationary DpS (dpsstn)
    "homoclinic": "homoclinic/{name}.nc",
    "map": "map/{name}.nc",
    # stages 2-3: one scene
    "initial": "initial/{scene}.nc",
    "exact": "sim/{scene}/exact.nc",
    "dps": "sim/{scene}/dps.nc",
    "metrics": "metrics/{scene}.nc",
    # stage 4
    "figure": "figures/{label}.{ext}",
    "movie": "movies/{scene}.{ext}",       # cradle.figures.movie: a scene's runs in motion (mp4, gif)
    "movie-still": "movies/stills/{scene}-{frame}.png",   # cradle.figures.desk_toy_movie: frames at an impact
    # an analysis of cradle.analyses.registry: its batches (its output and figure follow analysis_output)
    "analysis-batch": "{analysis}/batch/{form}/{key}.nc",
    # bookkeeping
    "log": "logs/{job}.log",
    "kernels": "kernels.txt",  # the compiled kernels' cache key, written once they are compiled
    "benchmark": "benchmarks/{job}.tsv",
}

#: the four files of one scene, written together by the ``simulate`` job
SCENE_PARTS = ("initial", "exact", "dps", "metrics")
#: the files of a scene a figure reads (its runs and their comparison)
RUN_PARTS = ("exact", "dps", "metrics")
#: formats of every figure
FIGURE_FORMATS = ("pdf", "png")


def path(kind: str, root: str | Path = ROOT, **names: str) -> str:
    """The path of one output of ``kind`` (a key of :data:`TEMPLATES`) under ``root``."""
    return str(Path(root) / TEMPLATES[kind].format(**names))


def scene_paths(scene: str, root: str | Path = ROOT, parts: Iterable[str] = SCENE_PARTS) -> dict[str, str]:
    """part -> path for the files of one scene (initial, exact, dps, metrics)."""
    return {part: path(part, root, scene=scene) for part in parts}


def figure_paths(label: str, root: str | Path = ROOT) -> dict[str, str]:
    """ext -> path of the files of one figure."""
    return {ext: path("figure", root, label=label, ext=ext) for ext in FIGURE_FORMATS}


def form_folder(folder: str, form: str, main_form: str, root: str | Path = ROOT) -> str:
    """The folder of one form of an analysis: ``root/folder`` for the form ``all`` builds
    (``main_form``), ``root/folder/<form>`` for another (the full form of floquet, ...)."""
    return str(Path(root) / folder) if form == main_form else str(Path(root) / folder / form)


def form_figure_paths(label: str, folder: str, form: str, main_form: str, root: str | Path = ROOT) -> dict[str, str]:
    """ext -> figure files of one form of an analysis: ``root/figures/<label>.<ext>`` for the form
    ``all`` builds, beside the form's files for another."""
    if form == main_form:
        return figure_paths(label, root)
    return {ext: f"{form_folder(folder, form, main_form, root)}/{label}.{ext}" for ext in FIGURE_FORMATS}


def analysis_output(name: str, form: str, main_form: str, root: str | Path = ROOT) -> str:
    """The netCDF file of one form of analysis ``name``: ``root/<name>/<name>.nc`` for the form ``all``
    builds, ``root/<name>/<form>/<name>.nc`` for another."""
    return f"{form_folder(name, form, main_form, root)}/{name}.nc"


def analysis_figures(name: str, form: str, main_form: str, root: str | Path = ROOT) -> dict[str, str]:
    """ext -> the figure files of one form of analysis ``name`` (``root/figures/<name>.<ext>`` for the form
    ``all`` builds, beside the form's netCDF file for another)."""
    return form_figure_paths(name, name, form, main_form, root)


def analysis_tables(name: str, form: str, main_form: str, formats: Iterable[str],
                    root: str | Path = ROOT) -> dict[str, str]:
    """ext -> the tables an analysis's drawing step writes in place of a figure (the claims table):
    beside its netCDF file, ``root/<name>/[<form>/]<name>.<ext>``."""
    return {ext: f"{form_folder(name, form, main_form, root)}/{name}.{ext}" for ext in formats}


def analysis_drawn(analysis: Analysis, form: str, main_form: str, root: str | Path = ROOT) -> dict[str, str]:
    """ext -> what the drawing step of one form of ``analysis`` (:class:`cradle.analyses.protocol.Analysis`)
    writes: its tables when it declares some, else its figure."""
    if analysis.tables:
        return analysis_tables(analysis.name, form, main_form, analysis.tables, root)
    return analysis_figures(analysis.name, form, main_form, root)


def read_path(read: Read, form: str, root: str | Path = ROOT) -> str:
    """The file of one :class:`cradle.analyses.protocol.Read` of an analysis built in ``form`` (another analysis's
    output: the one of the form ``all`` builds)."""
    names = dict(read.names)
    if read.kind == "analysis":
        from cradle.analyses.registry import ANALYSES

        main = ANALYSES[names["analysis"]].forms[0]
        return analysis_output(names["analysis"], main, main, root)
    if read.kind == "analysis-batch":
        names["form"] = form
    return path(read.kind, root, **names)
