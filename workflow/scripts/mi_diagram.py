"""Snakemake adapter: DpS modulational-instability map -> results/mi/mi-diagram.nc (rule
mi_diagram_compute), or its figure -> results/figures/mi-diagram.{pdf,png} (rule mi_diagram_figure)."""
import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

from pathlib import Path  # noqa: E402

sm = snakemake  # noqa: F821 (injected by Snakemake)
if sm.rule == "mi_diagram_figure":
    from cradle.figures import save_figure
    from cradle.figures.beyond import BEYOND
    from cradle.io import open_dataset
    from cradle.runner import setup_logging

    setup_logging(sm.log[0])
    save_figure(BEYOND["mi-diagram"](open_dataset(sm.input.data)), Path(sm.output.pdf).with_suffix(""))
else:
    import logging

    from cradle import modulational
    from cradle.runner import run

    log = logging.getLogger("cradle")
    run(lambda: modulational.compute(dict(sm.params.spec), log=log.info), sm.output[0], sm.log[0],
        label="mi-diagram")
