"""Snakemake adapter: draw an analysis's figure (``draw`` of cradle/figures/<module>.py) from its netCDF file
-> results/figures/<name>.{pdf,png} (or beside the form's file); or write the tables that module makes instead
(``tables``: the claims table, results/<name>/<name>.{csv,md})."""
from pathlib import Path

from cradle.data.io import open_tree
from cradle.figures import draw_analysis, write_tables
from cradle.pipeline.runner import setup_logging

sm = snakemake  # injected by Snakemake
setup_logging(sm.log[0])
if sm.params.tables:
    write_tables(sm.params.module, open_tree(sm.input.data), {ext: sm.output[ext] for ext in sm.params.tables})
else:
    draw_analysis(sm.params.module, open_tree(sm.input.data), Path(sm.output.pdf).with_suffix(""),
                  note=sm.params.note)
