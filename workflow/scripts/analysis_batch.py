"""Snakemake adapter: one batch of an analysis (cradle.analyses.protocol.Batches) -> its netCDF file
(rules <target>_batch_<form>); the analysis's compute job gathers the batches."""
import logging

from cradle.analyses.registry import ANALYSES, FULL, form_spec
from cradle.data.io import open_dataset
from cradle.pipeline.runner import run
from cradle.specs.declare import from_plain

sm = snakemake  # injected by Snakemake
log = logging.getLogger("cradle")
analysis = ANALYSES[sm.params.analysis]
# the form's spec as the rule resolved it (form_spec: no `reduced` overrides left to apply)
spec = form_spec(from_plain(analysis.spec, dict(sm.params.spec), where=f"beyond.{analysis.name}"), FULL)
key = sm.wildcards.key
run(lambda: analysis.batches.run(spec, key, {name: open_dataset(path) for name, path in sm.input.items()
                                             if name != "code"}, log=log.info),
    sm.output[0], sm.log[0], label=f"{analysis.name} batch {key}")
