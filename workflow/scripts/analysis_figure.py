"""Snakemake adapter: draw an analysis's figure (``draw`` of cradle/figures/<module>.py) from its netCDF file
-> results/figures/<name>.{pdf,png} (or beside the form's file); or write the tables that module makes instead
(``tables``: the claims table, results/<name>/<name>.{csv,md}). The netCDF file must be the one the workflow's
config expects (cradle.pipeline.identity)."""
from cradle.pipeline.warm import forward

forward(globals())  # in a local build: run in a child of the warm process, imports paid once

from pathlib import Path

from cradle.figures import draw_analysis, write_tables
from cradle.pipeline.identity import job_expectations, open_checked
from cradle.pipeline.runner import setup_logging

sm = snakemake  # injected by Snakemake
setup_logging(sm.log[0])
tree = open_checked(sm.input.data, job_expectations(sm.config), tree=True)
if sm.params.tables:
    write_tables(sm.params.module, tree, {ext: sm.output[ext] for ext in sm.params.tables})
else:
    draw_analysis(sm.params.module, tree, Path(sm.output.pdf).with_suffix(""), note=sm.params.note)
