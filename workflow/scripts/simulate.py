"""Snakemake adapter: one scene's initial data, lattice (nc) and DpS (dfnls) runs and their
comparison -> results/initial/<scene>.nc, results/sim/<scene>/{exact,dps}.nc, results/metrics/<scene>.nc
(cradle.pipeline.scene_job: in memory, or block by block for a large store). A breather's homoclinic
solution must be the file the workflow's config expects (cradle.pipeline.identity)."""
from cradle.pipeline.warm import forward

forward(globals())  # in a local build: run in a child of the warm process, imports paid once

from cradle.pipeline.identity import job_expectations, open_checked
from cradle.pipeline.runner import one_line_errors
from cradle.pipeline.scene_job import run_scene
from cradle.scenes.spec import Scene
from cradle.specs.declare import from_plain

sm = snakemake  # injected by Snakemake
one_line_errors()  # the homoclinic input is read before the job's log is set up
homoclinic = sm.input.homoclinic
run_scene(from_plain(Scene, sm.params.spec), sm.wildcards.scene,
          {key: sm.output[key] for key in ("initial", "exact", "dps", "metrics")}, sm.log[0],
          homoclinic=open_checked(homoclinic[0], job_expectations(sm.config)) if homoclinic else None)
