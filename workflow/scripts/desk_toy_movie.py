"""Snakemake adapter: the movie of one desk toy of the desk-toy analysis's full form ->
results/movies/desk-toy-<toy>.{mp4,gif} (cradle.analyses.desk_toy.movie_dataset, cradle.figures.movie.animate)."""
from cradle.pipeline.warm import forward

forward(globals())  # in a local build: run in a child of the warm process, imports paid once

import logging

from cradle.analyses.desk_toy import movie_dataset
from cradle.data.io import open_tree
from cradle.figures.movie import MovieSpec, animate
from cradle.pipeline.runner import setup_logging

sm = snakemake  # injected by Snakemake
setup_logging(sm.log[0])
m = sm.params.movies
spec = MovieSpec(fps=m["fps"], duration=m["duration"], width=m["width"], height=m["height"])
gif = MovieSpec(fps=m["gif_fps"], duration=m["gif_duration"], width=m["width"], height=m["height"])
tree = open_tree(sm.input.data)
ds, panels = movie_dataset(tree[sm.wildcards.toy])
info = animate(ds, sm.output.mp4, spec, gif=sm.output.gif, gif_spec=gif, gif_width=m["gif_width"], panels=panels)
logging.getLogger("cradle").info("%s: %d frames, a frame every %.4g s, displacements x %.3g; %s: %d frames",
                                 sm.output.mp4, len(info["indices"]), info["dt_frame"], info["magnification"],
                                 sm.output.gif, info["gif"]["frames"])
