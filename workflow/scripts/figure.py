"""Snakemake adapter: draw one paper figure from its netCDF inputs -> results/figures/<label>.{pdf,png}; each
input must be the file the workflow's config expects (cradle.pipeline.identity)."""
from cradle.pipeline.warm import forward

forward(globals())  # in a local build: run in a child of the warm process, imports paid once

from pathlib import Path

from cradle.figures import draw
from cradle.pipeline.config import assume_validated
from cradle.pipeline.identity import CONFIG
from cradle.pipeline.outputs import load_inputs
from cradle.pipeline.runner import setup_logging

sm = snakemake  # injected by Snakemake
setup_logging(sm.log[0])
data = load_inputs(sm.params.scenes, Path(sm.output.pdf).parent.parent, config=assume_validated(sm.config),
                   source=CONFIG)
draw(sm.params.label, data, dict(sm.params.options), Path(sm.output.pdf).with_suffix(""))
