"""Snakemake adapter: DpS modulational-instability map -> results/mi/mi-diagram.nc (rule mi_diagram_compute)."""
import logging

from cradle.analyses import modulational
from cradle.pipeline.runner import run

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = logging.getLogger("cradle")
run(lambda: modulational.compute(dict(sm.params.spec), log=log.info), sm.output[0], sm.log[0], label="mi-diagram")
