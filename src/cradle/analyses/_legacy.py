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

from cradle.pipeline import config as cc, layout

#: the form ``all`` builds, and the complete one (its own target)
REDUCED, FULL = "reduced", "full"


@dataclass(frozen=True)
class Analysis:
    name: str              # target stem, figure label and file stem ("mi-statistics")
    module: str            # cradle.analyses.<module>
    run: str               # "function" of that module: run(spec, files, scenes, log) -> DataTree or Dataset
    folder: str            # under the results folder
    forms: tuple = (FULL,)  # (REDUCED, FULL) when `all` builds a cheaper form than the full target
    title: str = ""
    reads_scenes: str = ""  # key under `beyond:` whose `scenes` list names the scenes whose runs it reads
    reads_batches: bool = False  # its input is the mi-statistics batches of its form
    batches: str = ""       # cradle.analyses.<batches>.batch_files(spec, form): its batch files (its own rules)

    @property
    def target(self) -> str:
        """Snakemake target name (``mi_statistics``)."""
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
        files = [p for name in self.scenes(config)
                 for p in layout.scene_paths(name, parts=("initial", "exact", "dps")).values()]
        if self.reads_batches:
            from cradle.analyses import mi_statistics as mistatistics

            spec = self.spec(config, form)
            files += [layout.path("mi-batch", variant=form, N=N, model=m, chunk=c) for N in spec["N"]
                      for m in mistatistics.MODELS for c in range(int(spec["chunks"]))]
        if self.batches:
            files += import_module(f"cradle.analyses.{self.batches}").batch_files(self.spec(config, form), form)
        return files

    def compute(self, spec: dict, files=(), scenes=None, log=None):
        """The output of this analysis, a DataTree (or Dataset) (imports its module only now)."""
        return getattr(import_module(f"cradle.analyses.{self.module}"), self.run)(spec, list(files), scenes or {},
                                                                                   log)


LEGACY: dict[str, Analysis] = {a.name: a for a in (
    Analysis("mi-statistics", "mi_statistics", "run", "mi", forms=(REDUCED, FULL), reads_batches=True,
             title="mi-statistics: thresholds from every batch"),
    Analysis("breather-interactions", "breather_interactions", "run", "interactions", forms=(REDUCED, FULL),
             batches="breather_interactions",
             title="Collisions of two breathers, exact (nc) against DpS (dfnls): outcome statistics (loc1)"),
)}
