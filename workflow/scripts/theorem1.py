"""Snakemake adapter: Theorem 1 measured -> results/theorem1/theorem1.nc (rule theorem1_compute)."""
import logging

from cradle.analyses import theorem1
from cradle.pipeline.runner import run

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = logging.getLogger("cradle")
run(lambda: theorem1.compute(dict(sm.params.spec), log=log.info), sm.output[0], sm.log[0], label="theorem1")
