"""Snakemake adapter: exact vs DpS comparison -> results/metrics/<scene>.nc."""
from cradle import stages
from cradle.io import open_dataset
from cradle.runner import run

sm = snakemake  # noqa: F821 (injected by Snakemake)
run(lambda: stages.metrics(sm.params.spec, open_dataset(sm.input.exact), open_dataset(sm.input.dps),
                           sm.wildcards.scene),
    sm.output[0], sm.log[0], label=f"metrics {sm.wildcards.scene}")
