"""Snakemake adapter: Theorem 1 measured -> results/theorem1/theorem1.nc (rule theorem1_compute),
or its figure -> results/figures/theorem1.{pdf,png} (rule theorem1_figure)."""
import os

# one BLAS thread: the Newton systems are small, and threads only contend with the other job (-j2)
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

from pathlib import Path  # noqa: E402

sm = snakemake  # noqa: F821 (injected by Snakemake)
if sm.rule == "theorem1_figure":
    from cradle.figures import save_figure
    from cradle.figures.beyond import BEYOND
    from cradle.io import open_dataset
    from cradle.runner import setup_logging

    setup_logging(sm.log[0])
    save_figure(BEYOND["theorem1"](open_dataset(sm.input.data)), Path(sm.output.pdf).with_suffix(""))
else:
    import logging

    from cradle import theorem1
    from cradle.runner import run

    log = logging.getLogger("cradle")
    run(lambda: theorem1.compute(dict(sm.params.spec), log=log.info), sm.output[0], sm.log[0], label="theorem1")
