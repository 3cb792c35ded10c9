"""Snakemake adapter: initial data of one scene -> results/initial/<scene>.nc."""
from cradle import stages
from cradle.io import open_dataset
from cradle.runner import run

sm = snakemake  # noqa: F821 (injected by Snakemake)
hom = open_dataset(sm.input.homoclinic[0]) if sm.input.homoclinic else None
run(lambda: stages.initial_data(sm.params.spec, sm.wildcards.scene, hom),
    sm.output[0], sm.log[0], label=f"initial {sm.wildcards.scene}")
