"""TRANSITION ONLY: the analyses not yet moved onto :mod:`cradle.analyses.protocol` (each port removes its
entry here; the module goes when the table is empty). Each declared the old way: its spec, its compute, its figure.

An :class:`Analysis` names the config resolver of its spec, the function that
computes its output from that spec (and, for some, from files of earlier stages) -- a tree of
netCDF groups (:func:`cradle.data.io.make_tree`) named as in the paper from the
``VARIABLES`` its module declares -- the figure label that draws it, and its forms: the reduced form
``all`` builds (``results/<folder>/<name>.nc``, figure
``results/figures/<name>.{pdf,png}``) and, where that is cheaper than the
full one, the full form as its own target (``results/<folder>/full/...``).
One pair of generic rules (``workflow/rules/analyses.smk``) serves every
entry; the Snakefile reads this table and nothing else about them.

Importing this module is cheap (no numpy): the Snakefile plans with it.
"""
from __future__ import annotations

from dataclasses import dataclass
from importlib import import_module

from cradle.pipeline import config as cc
from cradle.pipeline import layout

#: the form ``all`` builds, and the complete one (its own target)
REDUCED, FULL = "reduced", "full"


@dataclass(frozen=True)
class Analysis:
    name: str              # target stem, figure label and file stem ("mi-diagram")
    module: str            # cradle.analyses.<module>
    run: str               # "function" of that module: run(spec, files, scenes, log) -> DataTree or Dataset
    folder: str            # under the results folder
    forms: tuple = (FULL,)  # (REDUCED, FULL) when `all` builds a cheaper form than the full target
    title: str = ""
    reads_scenes: str = ""  # key under `beyond:` whose `scenes` list names the scenes whose runs it reads

    @property
    def target(self) -> str:
        """Snakemake target name (``mi_diagram``)."""
        return self.name.replace("-", "_")

    def output(self, form: str = REDUCED, root=layout.ROOT) -> str:
        """The netCDF file of a form (:func:`cradle.pipeline.layout.form_folder`)."""
        return f"{layout.form_folder(self.folder, form, self.forms[0], root)}/{self.name}.nc"

    def figure(self, form: str = REDUCED, root=layout.ROOT) -> dict[str, str]:
        """ext -> figure file of a form (:func:`cradle.pipeline.layout.form_figure_paths`)."""
        return layout.form_figure_paths(self.name, self.folder, form, self.forms[0], root)

    def spec(self, config: dict, form: str) -> dict:
        """The resolved parameters of one form (cradle.pipeline.config)."""
        resolve = getattr(cc, f"resolved_{self.target}")
        return resolve(config, form) if len(self.forms) > 1 else resolve(config)

    def scenes(self, config: dict) -> list[str]:
        """The scenes whose initial data and runs this analysis reads (mi-growth)."""
        return list(config["beyond"][self.reads_scenes]["scenes"]) if self.reads_scenes else []

    def inputs(self, config: dict, form: str) -> list[str]:
        """The files this analysis reads, in the order its run function takes them."""
        return [p for name in self.scenes(config)
                for p in layout.scene_paths(name, parts=("initial", "exact", "dps")).values()]

    def compute(self, spec: dict, files=(), scenes=None, log=None):
        """The output of this analysis, a DataTree (or Dataset) (imports its module only now)."""
        return getattr(import_module(f"cradle.analyses.{self.module}"), self.run)(spec, list(files), scenes or {},
                                                                                   log)


LEGACY: dict[str, Analysis] = {a.name: a for a in (
    Analysis("theorem1", "theorem1", "run", "theorem1",
             title="Theorem 1 measured: exact travelling waves of (ad) against (wleadingorder)"),
    Analysis("mi-diagram", "mi_diagram", "run", "mi",
             title="Modulational instability of the DpS plane waves: growth-rate map and direct checks"),
    Analysis("floquet", "floquet", "run", "floquet", forms=(REDUCED, FULL),
             title="Bloch-Floquet stability of the exact travelling waves against the DpS threshold"),
    Analysis("breathers", "breathers", "run", "breathers", forms=(REDUCED, FULL),
             title="Exact breathers of (nc): families, Floquet stability, Peierls-Nabarro barrier, distance to DpS"),
    Analysis("dps-validity", "dps_validity", "run", "validity", forms=(REDUCED, FULL),
             title="DpS approximation error: sup over t <= T eps^(1-alpha) of |x - x_app| against eps, T, family, alpha"),
)}
