"""Snakemake adapter: one batch of an analysis (cradle.analyses.protocol.Batches) -> its netCDF file
(rules <target>_batch_<form>); the analysis's compute job gathers the batches. Its inputs are checked to be
the files the workflow's config expects (cradle.pipeline.identity); the batch names itself."""
from cradle.pipeline.warm import forward

forward(globals())  # in a local build: run in a child of the warm process, imports paid once

import logging

from cradle.analyses.registry import ANALYSES, FULL, form_spec
from cradle.data.provenance import identify
from cradle.pipeline.identity import job_expectations, open_checked
from cradle.pipeline.runner import run
from cradle.specs.declare import from_plain

sm = snakemake  # injected by Snakemake
expect = job_expectations(sm.config)  # what each input must be: its entry, today's parameters
log = logging.getLogger("cradle")
analysis = ANALYSES[sm.params.analysis]
# the form's spec as the rule resolved it (form_spec: no `reduced` overrides left to apply)
spec = form_spec(from_plain(analysis.spec, dict(sm.params.spec), where=f"beyond.{analysis.name}"), FULL)
key = sm.wildcards.key
run(lambda: identify(analysis.batches.run(spec, key, {name: open_checked(path, expect) for name, path
                                                      in sm.input.items() if name != "code"}, log=log.info),
                     "analysis-batch", f"{analysis.name}/{key}", params=sm.params.spec),
    sm.output[0], sm.log[0], label=f"{analysis.name} batch {key}")
