"""Snakemake adapter: one scene's initial data, lattice (nc) and DpS (dfnls) runs and their
comparison -> results/initial/<scene>.nc, results/sim/<scene>/{exact,dps}.nc, results/metrics/<scene>.nc."""
from cradle.pipeline import budget, stages
from cradle.pipeline.io import open_dataset
from cradle.pipeline.params import expand_scene
from cradle.pipeline.runner import Progress, run_chain

sm = snakemake  # noqa: F821 (injected by Snakemake)
scene, spec = sm.wildcards.scene, expand_scene(dict(sm.params.spec))
run_chain([
    ("initial", lambda done: stages.initial_data(
        spec, scene, open_dataset(sm.input.homoclinic[0]) if sm.input.homoclinic else None)),
    ("exact", lambda done: stages.exact_run(spec, done["initial"], scene,
                                            progress=Progress(f"exact {scene}", estimate=budget.long_run(spec)))),
    ("dps", lambda done: stages.dps_run(spec, done["initial"], scene, progress=Progress(f"dps {scene}"))),
    ("metrics", lambda done: stages.metrics(spec, done["exact"], done["dps"], scene)),
], {key: sm.output[key] for key in ("initial", "exact", "dps", "metrics")}, sm.log[0], label=scene)
