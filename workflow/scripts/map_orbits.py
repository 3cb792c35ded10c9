"""Snakemake adapter: orbits of the map G (comp1)-(comp2) -> results/map/<name>.nc."""
from cradle.pipeline.warm import forward

forward(globals())  # in a local build: run in a child of the warm process, imports paid once

from cradle.pipeline.runner import run
from cradle.scenes import stages
from cradle.scenes.spec import MapEntry
from cradle.specs.declare import from_plain

sm = snakemake  # injected by Snakemake
spec, name = from_plain(MapEntry, sm.params.spec), sm.wildcards.name
run(lambda: stages.map_orbits(spec, name), sm.output[0], sm.log[0], label=f"map {name}")
