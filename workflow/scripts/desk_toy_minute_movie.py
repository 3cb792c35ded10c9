"""Snakemake adapter: the minute movie of one desk toy of the desk-toy-minute analysis's full form, its own run in
real time with chosen impacts in slow motion (cradle.analyses.desk_toy_minute_movie.movie_run) drawn by
cradle.figures.desk_toy_minute_movie -> results/movies/desk-toy-minute-<toy>.{mp4,gif} and three frames
(results/movies/stills/desk-toy-minute-<toy>-{impact,breakup,late}.png)."""
from cradle.pipeline.warm import forward

forward(globals())  # in a local build: run in a child of the warm process, imports paid once

import logging

from cradle.analyses.desk_toy import parse_label
from cradle.analyses.desk_toy_minute import DeskToyMinute
from cradle.analyses.desk_toy_minute_movie import MinuteMovie, movie_run
from cradle.analyses.registry import FULL, form_spec
from cradle.figures.desk_toy_minute_movie import STILLS, animate, still_frames, write_stills
from cradle.pipeline.runner import setup_logging
from cradle.specs.declare import from_plain

sm = snakemake  # injected by Snakemake
setup_logging(sm.log[0])
m = sm.params.movies
spec = form_spec(from_plain(DeskToyMinute, dict(sm.params.spec), where="beyond.desk-toy-minute"), FULL)
motion = from_plain(MinuteMovie, dict(m["desk_toy_minute"]), where="movies.desk_toy_minute")
n_beads, lifted = parse_label(sm.wildcards.toy)
ds = movie_run(spec, n_beads, lifted, motion, m["fps"])
info = animate(ds, sm.output.mp4, m["width"], m["height"], gif=sm.output.gif, gif_fps=m["gif_fps"],
               gif_duration=m["gif_duration"], gif_width=m["gif_width"])
frames = still_frames(ds)
write_stills(ds, {frames[name]: path for name, path in zip(STILLS, sm.output.stills, strict=True)}, m["width"],
             m["height"])
logging.getLogger("cradle").info("%s: %d frames at %d/s (%.3g s of movie for %.3g s of the cradle), %d slow-motion "
                                 "impacts; %s: %d frames", sm.output.mp4, len(info["times"]), m["fps"],
                                 len(info["times"]) / m["fps"], float(ds["t"].values[-1]), ds.sizes["impact"],
                                 sm.output.gif, info["gif"]["frames"])
