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


def cmd_animate(args) -> int:
    from cradle.figures.movie import MovieSpec, animate
    from cradle.pipeline import layout
    from cradle.pipeline.outputs import open_scene

    given = settings(args.config)
    pick = {k: (getattr(args, k) if getattr(args, k) is not None else given[k])
            for k in ("fps", "duration", "width", "height")}
    try:
        spec = MovieSpec(**pick, t_start=args.t_start, t_end=args.t_end)
        gspec = MovieSpec(fps=args.gif_fps or given["gif_fps"], duration=given["gif_duration"],
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
