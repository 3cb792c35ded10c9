"""Snakemake adapter: MI growth rates measured in the scenes' runs -> results/mi/mi-growth.nc (rule
mi_growth_compute), or its figure -> results/figures/mi-growth.{pdf,png} (rule mi_growth_figure)."""
import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

from pathlib import Path  # noqa: E402

sm = snakemake  # noqa: F821 (injected by Snakemake)
if sm.rule == "mi_growth_figure":
    from cradle.figures import save_figure
    from cradle.figures.mi import MI_FIGURES
    from cradle.io import open_dataset
    from cradle.runner import setup_logging

    setup_logging(sm.log[0])
    save_figure(MI_FIGURES["mi-growth"](open_dataset(sm.input.data)), Path(sm.output.pdf).with_suffix(""))
else:
    import logging

    from cradle import migrowth
    from cradle.io import open_dataset
    from cradle.runner import run

    log = logging.getLogger("cradle")

    def compute():
        scenes = {}
        for name, spec in sm.params.scenes.items():
            sims = {m: open_dataset(f"results/sim/{name}/{m}.nc") for m in migrowth.MODELS}
            scenes[name] = (dict(spec), open_dataset(f"results/initial/{name}.nc"), sims)
        return migrowth.compute(dict(sm.params.spec), scenes, log=log.info)

    run(compute, sm.output[0], sm.log[0], label="mi-growth")
