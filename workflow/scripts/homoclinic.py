"""Snakemake adapter: solve (dpsstn) for one homoclinic entry -> results/homoclinic/<name>.nc."""
from cradle.pipeline.warm import forward

forward(globals())  # in a local build: run in a child of the warm process, imports paid once

from cradle.pipeline.runner import run
from cradle.scenes import stages
from cradle.scenes.spec import HomoclinicEntry
from cradle.specs.declare import from_plain

sm = snakemake  # injected by Snakemake
spec, name = from_plain(HomoclinicEntry, sm.params.spec), sm.wildcards.name
run(lambda: stages.homoclinic_solution(spec, name), sm.output[0], sm.log[0], label=f"homoclinic {name}")
