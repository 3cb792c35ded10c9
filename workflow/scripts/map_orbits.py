"""Snakemake adapter: orbits of the map G (comp1)-(comp2) -> results/map/<name>.nc."""
from cradle.scenes import stages
from cradle.pipeline.runner import run

name = snakemake.wildcards.name  # noqa: F821 (injected by Snakemake)
run(lambda: stages.map_orbits(snakemake.params.spec, name),  # noqa: F821
    snakemake.output[0], snakemake.log[0], label=f"map {name}")  # noqa: F821
