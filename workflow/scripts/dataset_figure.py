"""Snakemake adapter: draw a beyond-the-paper figure from the netCDF of its analysis
-> results/figures/<label>.{pdf,png} (or the variant's folder)."""
from pathlib import Path

from cradle.data.io import open_tree
from cradle.figures import draw_dataset
from cradle.pipeline.runner import setup_logging

sm = snakemake  # injected by Snakemake
setup_logging(sm.log[0])
draw_dataset(sm.params.label, open_tree(sm.input.data), Path(sm.output.pdf).with_suffix(""),
             note=sm.params.get("note", ""))
