"""Snakemake adapter: the movie of one desk toy of the desk-toy analysis's full form, its own run dense around the
impacts (cradle.analyses.desk_toy_movie.movie_run) drawn by cradle.figures.desk_toy_movie ->
results/movies/desk-toy-<toy>.{mp4,gif} and three frames of its first impact (results/movies/stills/)."""
from cradle.pipeline.warm import forward

forward(globals())  # in a local build: run in a child of the warm process, imports paid once

import logging

from cradle.analyses.desk_toy import DeskToyRuns, parse_label
from cradle.analyses.desk_toy_movie import SlowMotion, movie_run
from cradle.analyses.registry import FULL, form_spec
from cradle.figures.desk_toy_movie import STILL_LEAD, animate, impact_frames, write_stills
from cradle.pipeline.runner import setup_logging
from cradle.specs.declare import from_plain

sm = snakemake  # injected by Snakemake
setup_logging(sm.log[0])
m = sm.params.movies
spec = form_spec(from_plain(DeskToyRuns, dict(sm.params.spec), where="beyond.desk-toy"), FULL)
motion = from_plain(SlowMotion, dict(m["desk_toy"]), where="movies.desk_toy")
n_beads, lifted = parse_label(sm.wildcards.toy)
ds = movie_run(spec, n_beads, lifted, motion, m["fps"])
info = animate(ds, sm.output.mp4, m["width"], m["height"], gif=sm.output.gif, gif_fps=m["gif_fps"],
               gif_duration=m["gif_duration"], gif_width=m["gif_width"])
frames = impact_frames(ds, lead=STILL_LEAD)
write_stills(ds, {frames[name]: path for name, path in zip(("before", "during", "after"), sm.output.stills,
                                                           strict=True)}, m["width"], m["height"])
logging.getLogger("cradle").info("%s: %d frames at %d/s (%.3g s), %d impact windows, contact time %.3g s, largest "
                                 "force %.4g N; %s: %d frames", sm.output.mp4, len(info["times"]), m["fps"],
                                 len(info["times"]) / m["fps"], ds.sizes["impact"], ds.attrs["contact_time_s"],
                                 info["force_max"], sm.output.gif, info["gif"]["frames"])
