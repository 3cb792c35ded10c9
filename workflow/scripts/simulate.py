"""Snakemake adapter: one scene's initial data, lattice (nc) and DpS (dfnls) runs and their
comparison -> results/initial/<scene>.nc, results/sim/<scene>/{exact,dps}.nc, results/metrics/<scene>.nc
(cradle.pipeline.scene_job: in memory, or block by block for a large store)."""
from cradle.data.io import open_dataset
from cradle.pipeline.scene_job import run_scene
from cradle.scenes.spec import Scene
from cradle.specs.declare import from_plain

sm = snakemake  # injected by Snakemake
run_scene(from_plain(Scene, sm.params.spec), sm.wildcards.scene,
          {key: sm.output[key] for key in ("initial", "exact", "dps", "metrics")}, sm.log[0],
          homoclinic=open_dataset(sm.input.homoclinic[0]) if sm.input.homoclinic else None)
