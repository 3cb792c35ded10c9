"""``cradle animate SCENE``: a movie of a scene's stored exact and DpS runs (:mod:`cradle.figures.movie`).

Reads ``RESULTS/sim/SCENE/{exact,dps}.nc`` only (:func:`cradle.open_scene`), writes
``RESULTS/movies/SCENE.mp4`` (and ``.gif`` with ``--gif``). Frame rate, duration and size default to the
``movies:`` section of the config when the config file exists, else to their declared defaults; a flag
overrides either.
"""
from __future__ import annotations

from pathlib import Path

from cradle.pipeline.cli.common import CliError


def settings(config_path) -> dict:
    """The ``movies:`` settings of the config at ``config_path`` (validated), or the declared defaults."""
    from dataclasses import asdict

    from cradle.pipeline.config.movies import Movies

    path = Path(config_path)
    if path.exists():
        from cradle.pipeline.cli.common import load_config

        return dict(load_config(path)["movies"])
    return asdict(Movies())


#: the flags of `cradle animate` that override a key of ``movies:``
FLAGS = {"fps": "--fps", "duration": "--duration", "width": "--width", "height": "--height", "gif_fps": "--gif-fps"}


def checked_flags(args) -> dict:
    """The keys of ``movies:`` the flags give, each within the bounds its declaration states
    (:class:`cradle.pipeline.config.movies.Movies`): a bad one is refused in one line naming the flag, before
    any frame is drawn."""
    import math

    from cradle.pipeline.config.movies import Movies
    from cradle.specs.declare import from_plain
    from cradle.specs.values import ConfigError

    given = {key: getattr(args, key) for key in FLAGS if getattr(args, key) is not None}
    for key, value in given.items():
        try:
            from_plain(Movies, {key: value})
        except ConfigError as err:
            reason = str(err).split(": ")[-1]   # the schema's words: "0 is less than the minimum of 1"
            raise CliError(f"{FLAGS[key]} {value}: {reason} (the bounds of movies.{key}, "
                           f"docs/config-reference.md)") from None
    for key in ("t_start", "t_end"):
        value = getattr(args, key)
        if value is not None and not math.isfinite(value):
            raise CliError(f"--{key.replace('_', '-')} {value!r}: must be a finite time")
    return given


def cmd_animate(args) -> int:
    from cradle.figures.movie import MovieSpec, animate
    from cradle.pipeline import layout
    from cradle.pipeline.outputs import open_scene

    flags = checked_flags(args)
    given = {**settings(args.config), **flags}
    pick = {k: given[k] for k in ("fps", "duration", "width", "height")}
    try:
        spec = MovieSpec(**pick, t_start=args.t_start, t_end=args.t_end)
        gspec = MovieSpec(fps=given["gif_fps"], duration=given["gif_duration"],
                          width=spec.width, height=spec.height, t_start=args.t_start, t_end=args.t_end)
    except ValueError as err:
        raise CliError(str(err)) from None
    out = Path(args.out or layout.path("movie", args.results, scene=args.scene, ext="mp4"))
    gif = out.with_suffix(".gif") if args.gif else None
    try:
        ds = open_scene(args.scene, root=args.results, metrics=False)
    except FileNotFoundError as err:
        raise CliError(str(err)) from None
    info = animate(ds, out, spec, gif=gif, gif_spec=gspec, gif_width=given["gif_width"])
    times = info["times"]
    print(f"{out}: {len(times)} frames at {spec.fps}/s, {spec.width}x{spec.height}, t = {times[0]:g} .. "
          f"{times[-1]:g} (a frame every {info['dt_frame']:.4g}), displacements x {info['magnification']:.3g}")
    if gif is not None:
        print(f"{gif}: {info['gif']['frames']} frames at {gspec.fps}/s, {given['gif_width']} px wide")
    return 0
