"""Snakemake adapter: MI growth rates measured in the scenes' runs -> results/mi/mi-growth.nc
(rule mi_growth_compute)."""
import logging

from cradle.analyses import migrowth
from cradle.pipeline.io import open_dataset
from cradle.pipeline.params import expand_scene
from cradle.pipeline.runner import run

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = logging.getLogger("cradle")


def compute():
    scenes = {}
    for name, spec in sm.params.scenes.items():
        sims = {m: open_dataset(f"results/sim/{name}/{m}.nc") for m in migrowth.MODELS}
        scenes[name] = (expand_scene(dict(spec)), open_dataset(f"results/initial/{name}.nc"), sims)
    return migrowth.compute(dict(sm.params.spec), scenes, log=log.info)


run(compute, sm.output[0], sm.log[0], label="mi-growth")
