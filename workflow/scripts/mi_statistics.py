"""Snakemake adapter for mi-statistics: one batch of runs -> results/mi/batch/<variant>/N<N>-<model>-<chunk>.nc
(rule mi_statistics_batch), the batches of a variant -> its mi-statistics.nc (mi_statistics_aggregate_*),
or the figure (mi_statistics_figure_*)."""
import os

# one BLAS thread: the runs are small, and threads only contend with the other job (-j2)
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

from pathlib import Path  # noqa: E402

sm = snakemake  # noqa: F821 (injected by Snakemake)
if sm.rule.startswith("mi_statistics_figure"):
    from cradle.figures import save_figure
    from cradle.figures.mi import MI_FIGURES
    from cradle.io import open_dataset
    from cradle.runner import setup_logging

    setup_logging(sm.log[0])
    save_figure(MI_FIGURES["mi-statistics"](open_dataset(sm.input.data)), Path(sm.output.pdf).with_suffix(""))
else:
    import logging

    from cradle import mistatistics
    from cradle.io import open_dataset
    from cradle.runner import run

    log = logging.getLogger("cradle")
    spec = dict(sm.params.spec)
    if sm.rule == "mi_statistics_batch":
        w = sm.wildcards
        run(lambda: mistatistics.batch(spec, int(w.N), w.model, int(w.chunk), log=log.info), sm.output[0],
            sm.log[0], label=f"mi-statistics {w.variant} N{w.N} {w.model} chunk {w.chunk}")
    else:
        run(lambda: mistatistics.aggregate([open_dataset(p) for p in sm.input.batches], spec), sm.output[0],
            sm.log[0], label=f"mi-statistics {spec['variant']}")
