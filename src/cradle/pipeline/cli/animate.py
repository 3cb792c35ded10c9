"""``cradle animate SCENE``: a movie of a scene's stored exact and DpS runs (:mod:`cradle.figures.movie`).

Reads ``RESULTS/sim/SCENE/{exact,dps}.nc`` only (:func:`cradle.open_scene`), writes
``RESULTS/movies/SCENE.mp4`` (and ``.gif`` with ``--gif``). Frame rate, duration and size default to the
``movies:`` section of the config when the config file exists, else to their declared defaults; a flag
overrides either.

``cradle animate NAME --desk-toy FILE.nc`` draws instead the desk toy NAME (``n5-lifted1``) of a `desk-toy`
analysis file (results/desk-toy/[full/]desk-toy.nc), to scale and each impact in slow motion: a run of its own
from the file's spec, dense around the impacts (:func:`cradle.analyses.desk_toy_movie.movie_run`, settings
``movies.desk_toy``), (nc) beside the hard-sphere cradle (e of ``--hard``, the file's model index, default 1:
the first restitution), to ``RESULTS/movies/desk-toy-NAME.mp4`` (:func:`cradle.figures.desk_toy_movie.animate`;
``--duration``, ``--t-start`` and ``--t-end`` are refused with it: the movie's frames are its run's).
"""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from cradle.pipeline.cli.common import CliError

if TYPE_CHECKING:
    import argparse



def settings(config_path: str | Path) -> dict:
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


def checked_flags(args: argparse.Namespace) -> dict:
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
    if args.t_start is not None and args.t_end is not None and not args.t_start < args.t_end:
        raise CliError(f"--t-start {args.t_start:g}, --t-end {args.t_end:g}: need t_start < t_end")
    return given


def _may_write(paths: list[Path], stem: str, owner: str, overwrite: bool) -> None:
    """Refuse, before any frame is drawn, a movie path that is another workflow output or an existing file this
    command did not make (:func:`cradle.pipeline.destinations.check`); the movie of this scene is its own."""
    from cradle.pipeline.destinations import Refused, check

    for path in paths:
        makes = ("movie", {"scene": stem, "ext": path.suffix[1:]})
        try:
            check(path, command="cradle animate", makes=makes, owner=owner, overwrite=overwrite)
        except Refused as err:
            raise CliError(str(err)) from None


def _recorded(paths: list[Path | None], owner: str) -> None:
    """Record what wrote each movie (:func:`cradle.data.digests.record_owner`): a later `cradle animate` of the
    same scene may replace it."""
    from cradle.data.digests import record_owner

    for path in paths:
        if path is not None:
            record_owner(path, owner)


def cmd_animate(args: argparse.Namespace) -> int:
    from cradle.figures.movie import EmptyWindow, MovieSpec, animate
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
    desk = getattr(args, "desk_toy", None)
    if desk:
        given_flags = [flag for flag, on in (("--duration", "duration" in flags),
                                             ("--t-start", args.t_start is not None),
                                             ("--t-end", args.t_end is not None)) if on]
        if given_flags:
            raise CliError(f"{', '.join(given_flags)}: not with --desk-toy (its frames are those of its own run, "
                           "dense at each impact: the settings movies.desk_toy, docs/config-reference.md)")
    stem = f"desk-toy-{args.scene}" if desk else args.scene
    out = Path(args.out or layout.path("movie", args.results, scene=stem, ext="mp4"))
    gif = out.with_suffix(".gif") if args.gif else None
    owner = f"cradle animate {stem}"
    _may_write([out] + ([gif] if gif else []), stem, owner, getattr(args, "overwrite", False))
    if desk:
        info = _desk_toy(args, desk, out, given, gif)
        _recorded([out, gif], owner)
        print(f"{out}: {len(info['times'])} frames at {spec.fps}/s, {spec.width}x{spec.height}, t = "
              f"{info['times'][0]:g} .. {info['times'][-1]:g} s, drawn to scale, impacts in slow motion "
              f"(largest contact force {info['force_max']:.3g} N)")
        return 0
    try:
        ds = open_scene(args.scene, root=args.results, metrics=False)
    except FileNotFoundError as err:
        raise CliError(str(err)) from None
    try:
        info = animate(ds, out, spec, gif=gif, gif_spec=gspec, gif_width=given["gif_width"])
    except EmptyWindow as err:   # said before any frame is drawn
        raise CliError(f"--t-start/--t-end: {err}") from None
    _recorded([out, gif], owner)
    times = info["times"]
    print(f"{out}: {len(times)} frames at {spec.fps}/s, {spec.width}x{spec.height}, t = {times[0]:g} .. "
          f"{times[-1]:g} (a frame every {info['dt_frame']:.4g}), displacements x {info['magnification']:.3g}")
    if gif is not None:
        print(f"{gif}: {info['gif']['frames']} frames at {gspec.fps}/s, {given['gif_width']} px wide")
    return 0


def _desk_toy(args: argparse.Namespace, path: Path, out: Path, given: dict, gif: Path | None) -> dict:
    """The movie of desk toy ``args.scene`` of the `desk-toy` file ``path`` (its spec, a run of the movie's own);
    a missing file, group or model is one line."""
    import json

    from cradle.analyses.desk_toy import DeskToyRuns, parse_label
    from cradle.analyses.desk_toy_movie import SlowMotion, movie_run
    from cradle.data.io import open_tree
    from cradle.figures.desk_toy_movie import animate
    from cradle.specs.declare import from_plain

    try:
        tree = open_tree(path)
    except (FileNotFoundError, OSError) as err:
        raise CliError(f"--desk-toy {path}: {err}") from None
    names = [s.strip() for s in str(tree.attrs.get("desk_toys", "")).split(",") if s.strip()]
    if args.scene not in names:
        raise CliError(f"{args.scene}: not a desk toy of {path} (it holds: {', '.join(names) or 'none'})")
    n_models = tree[args.scene].sizes["model"]
    if not 1 <= args.hard < n_models:
        raise CliError(f"--hard {args.hard}: must be a hard-sphere model index of {path}, in [1, {n_models - 1}]")
    spec = from_plain(DeskToyRuns, json.loads(str(tree.attrs["parameters"])), where=f"{path}: parameters")
    n_beads, lifted = parse_label(args.scene)
    motion = from_plain(SlowMotion, dict(given["desk_toy"]), where="movies.desk_toy")
    ds = movie_run(spec, n_beads, lifted, motion, int(given["fps"]), hard=args.hard - 1)
    return animate(ds, out, int(given["width"]), int(given["height"]), gif=gif, gif_fps=int(given["gif_fps"]),
                   gif_duration=float(given["gif_duration"]), gif_width=int(given["gif_width"]))
