"""Snakemake adapter: solve (dpsstn) for one homoclinic entry -> results/homoclinic/<name>.nc."""
from cradle.scenes import stages
from cradle.pipeline.runner import run

name = snakemake.wildcards.name  # noqa: F821 (injected by Snakemake)
run(lambda: stages.homoclinic_solution(snakemake.params.spec, name),  # noqa: F821
    snakemake.output[0], snakemake.log[0], label=f"homoclinic {name}")  # noqa: F821
