"""Snakemake adapter: the movie of one scene from its stored runs -> results/movies/<scene>.{mp4,gif}; the runs
must be the files the workflow's config expects (cradle.pipeline.identity)."""
from cradle.pipeline.warm import forward

forward(globals())  # in a local build: run in a child of the warm process, imports paid once

import logging
from pathlib import Path

from cradle.figures.movie import MovieSpec, animate
from cradle.pipeline.config import assume_validated
from cradle.pipeline.outputs import open_scene
from cradle.pipeline.runner import setup_logging

sm = snakemake  # injected by Snakemake
setup_logging(sm.log[0])
m = sm.params.movies
spec = MovieSpec(fps=m["fps"], duration=m["duration"], width=m["width"], height=m["height"])
gif = MovieSpec(fps=m["gif_fps"], duration=m["gif_duration"], width=m["width"], height=m["height"])
root = Path(sm.input.data[0]).parent.parent.parent          # results/sim/<scene>/exact.nc -> results
runs = open_scene(sm.wildcards.scene, root=root, metrics=False, config=assume_validated(sm.config))
info = animate(runs, sm.output.mp4, spec, gif=sm.output.gif, gif_spec=gif, gif_width=m["gif_width"])
logging.getLogger("cradle").info("%s: %d frames, a frame every %.4g time units, displacements x %.3g; %s: %d frames",
             sm.output.mp4, len(info["indices"]), info["dt_frame"], info["magnification"], sm.output.gif,
             info["gif"]["frames"])
