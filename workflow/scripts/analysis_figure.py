"""Snakemake adapter: draw an analysis's figure (``draw`` of cradle/figures/<module>.py) from its netCDF file
-> results/figures/<name>.{pdf,png} (or beside the form's file)."""
from pathlib import Path

from cradle.data.io import open_tree
from cradle.figures import draw_analysis
from cradle.pipeline.runner import setup_logging

sm = snakemake  # noqa: F821 (injected by Snakemake)
setup_logging(sm.log[0])
draw_analysis(sm.params.module, open_tree(sm.input.data), Path(sm.output.pdf).with_suffix(""), note=sm.params.note)
