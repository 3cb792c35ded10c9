"""Snakemake adapter for mi-statistics: one batch of runs -> results/mi/batch/<variant>/N<N>-<model>-<chunk>.nc
(rule mi_statistics_batch), or the batches of a variant -> its mi-statistics.nc (mi_statistics_aggregate_*)."""
import logging

from cradle.analyses import mistatistics
from cradle.pipeline.io import open_dataset
from cradle.pipeline.runner import run

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = logging.getLogger("cradle")
spec = dict(sm.params.spec)
if sm.rule == "mi_statistics_batch":
    w = sm.wildcards
    run(lambda: mistatistics.batch(spec, int(w.N), w.model, int(w.chunk), log=log.info), sm.output[0],
        sm.log[0], label=f"mi-statistics {w.variant} N{w.N} {w.model} chunk {w.chunk}")
else:
    run(lambda: mistatistics.aggregate([open_dataset(p) for p in sm.input.batches], spec), sm.output[0],
        sm.log[0], label=f"mi-statistics {spec['variant']}")
