"""Snakemake adapter: integrate the DpS equation (dfnls) -> results/sim/<scene>/dps.nc."""
from cradle import stages
from cradle.io import open_dataset
from cradle.runner import Progress, run

sm = snakemake  # noqa: F821 (injected by Snakemake)
scene = sm.wildcards.scene
run(lambda: stages.dps_run(sm.params.spec, open_dataset(sm.input.initial), scene,
                           progress=Progress(f"dps {scene}")),
    sm.output[0], sm.log[0], label=f"dps {scene}")
