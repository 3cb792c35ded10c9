"""Snakemake adapter: one analysis beyond the paper (cradle.analyses.registry) -> its netCDF file
(rules <name>_compute_<form>)."""
import logging

from cradle.analyses._legacy import LEGACY as ANALYSES
from cradle.data.io import open_dataset
from cradle.pipeline.params import expand_scene
from cradle.pipeline.runner import run

sm = snakemake  # injected by Snakemake
log = logging.getLogger("cradle")
analysis = ANALYSES[sm.params.analysis]
run(lambda: analysis.compute(dict(sm.params.spec), [open_dataset(p) for p in sm.input.data],
                             {name: expand_scene(dict(spec)) for name, spec in sm.params.scenes.items()}, log=log.info),
    sm.output[0], sm.log[0], label=analysis.name)
