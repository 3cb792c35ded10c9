"""Snakemake adapter for mi-statistics: one batch of runs -> results/mi/batch/<variant>/N<N>-<model>-<chunk>.nc
(rule mi_statistics_batch); the batches are aggregated by the analysis rules (workflow/scripts/analysis.py)."""
import logging

from cradle.analyses import mi_statistics as mistatistics
from cradle.pipeline.runner import run

sm = snakemake  # injected by Snakemake
log = logging.getLogger("cradle")
spec, w = dict(sm.params.spec), sm.wildcards
run(lambda: mistatistics.batch(spec, int(w.N), w.model, int(w.chunk), log=log.info), sm.output[0],
    sm.log[0], label=f"mi-statistics {w.variant} N{w.N} {w.model} chunk {w.chunk}")
