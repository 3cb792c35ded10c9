"""Snakemake adapter: compile every kernel a scene's job uses, once, before the scene jobs start
(cradle.integrators.warmup) -> results/kernels.txt, the cache key of the kernels' sources."""
from cradle.pipeline.warm import forward

forward(globals())  # in a local build: run in a child of the warm process, imports paid once

from cradle.data.io import write_text
from cradle.integrators.warmup import compile_kernels
from cradle.pipeline.runner import log, setup_logging

sm = snakemake  # injected by Snakemake
setup_logging(sm.log[0])
key = compile_kernels(progress=log.info)
log.info("kernels compiled or loaded: cache key %s", key)
write_text(key + "\n", sm.output[0])
