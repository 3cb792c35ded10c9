"""Snakemake adapter: one analysis (cradle.analyses.registry) -> its netCDF file (rules <target>_compute_<form>).
Its inputs are named as the analysis reads them (another analysis's output as the tree of its groups), each checked
to be the file the workflow's config expects (cradle.pipeline.identity); its spec is rebuilt, and checked, from the
rule's params; the file names itself."""
from cradle.pipeline.warm import forward

forward(globals())  # in a local build: run in a child of the warm process, imports paid once

import logging

from cradle.analyses.registry import ANALYSES, FULL, form_spec
from cradle.data.provenance import identify
from cradle.pipeline.identity import job_expectations, locate, open_checked
from cradle.pipeline.runner import run
from cradle.specs.declare import from_plain

sm = snakemake  # injected by Snakemake
expect = job_expectations(sm.config)  # what each input must be: its entry, today's parameters
log = logging.getLogger("cradle")
analysis = ANALYSES[sm.params.analysis]
# the form's spec as the rule resolved it (form_spec: no `reduced` overrides left to apply)
spec = form_spec(from_plain(analysis.spec, dict(sm.params.spec), where=f"beyond.{analysis.name}"), FULL)


def opened(path):
    """An input, verified: another analysis's output as the tree of its groups, any other file as a Dataset."""
    where = locate(path)
    return open_checked(path, expect, tree=where is not None and where[0] == "analysis")


run(lambda: identify(analysis.compute(spec, {name: opened(path) for name, path in sm.input.items()
                                             if name != "code"}, log=log.info), "analysis", analysis.name),
    sm.output[0], sm.log[0], label=analysis.name)
