"""Snakemake adapter: one batch of an analysis (cradle.analyses.protocol.Batches) -> its netCDF file
(rules <target>_batch_<form>); the analysis's compute job gathers the batches."""
import logging

from cradle.analyses.registry import ANALYSES
from cradle.data.io import open_dataset
from cradle.pipeline.runner import run
from cradle.specs.declare import from_plain

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = logging.getLogger("cradle")
analysis = ANALYSES[sm.params.analysis]
spec = from_plain(analysis.spec, dict(sm.params.spec), where=f"beyond.{analysis.name}")
key = sm.wildcards.key
run(lambda: analysis.batches.run(spec, key, {name: open_dataset(path) for name, path in sm.input.items()
                                             if name != "code"}, log=log.info),
    sm.output[0], sm.log[0], label=f"{analysis.name} batch {key}")
