"""Snakemake adapter: one analysis (cradle.analyses.registry) -> its netCDF file (rules <target>_compute_<form>).
Its inputs are named as the analysis reads them; its spec is rebuilt, and checked, from the rule's params."""
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
run(lambda: analysis.compute(spec, {name: open_dataset(path) for name, path in sm.input.items() if name != "code"},
                             log=log.info),
    sm.output[0], sm.log[0], label=analysis.name)
