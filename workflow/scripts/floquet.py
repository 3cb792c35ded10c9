"""Snakemake adapter: Bloch-Floquet stability of the exact travelling waves -> results/floquet/floquet.nc
(rule floquet_compute), or its figure -> results/figures/floquet.{pdf,png} (rule floquet_figure)."""
import os

# one BLAS thread: the Hill matrices are small, and threads only contend with the other job (-j2)
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

from pathlib import Path  # noqa: E402

sm = snakemake  # noqa: F821 (injected by Snakemake)
if sm.rule == "floquet_figure":
    from cradle.figures import save_figure
    from cradle.figures.floquet import BEYOND
    from cradle.io import open_dataset
    from cradle.runner import setup_logging

    setup_logging(sm.log[0])
    save_figure(BEYOND["floquet"](open_dataset(sm.input.data)), Path(sm.output.pdf).with_suffix(""))
else:
    import logging

    from cradle import floquet
    from cradle.runner import run

    log = logging.getLogger("cradle")
    run(lambda: floquet.compute(dict(sm.params.spec), log=log.info), sm.output[0], sm.log[0], label="floquet")
