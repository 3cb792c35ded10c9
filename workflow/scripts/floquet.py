"""Snakemake adapter: Bloch-Floquet stability of the exact travelling waves -> results/floquet/floquet.nc
(rule floquet_compute)."""
import logging

from cradle.analyses import floquet
from cradle.pipeline.runner import run

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = logging.getLogger("cradle")
run(lambda: floquet.compute(dict(sm.params.spec), log=log.info), sm.output[0], sm.log[0], label="floquet")
