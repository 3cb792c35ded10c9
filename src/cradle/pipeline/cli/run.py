"""``cradle run``: one scene (or homoclinic or map entry) computed without Snakemake.

As the workflow's ``simulate`` job does (:func:`cradle.pipeline.scene_job.run_scene`, in memory
or block by block for a large store): a scene's files are written
only after every step succeeded, into the workflow's layout under its own
folder (:data:`RUN_OUT` unless asked otherwise).
"""
from __future__ import annotations

import sys
from pathlib import Path
from typing import TYPE_CHECKING

from cradle.pipeline import layout
from cradle.pipeline.cli.common import PROG, CliError, known_names, load_config, section_of

if TYPE_CHECKING:
    import argparse
    from collections.abc import Callable

    from cradle.pipeline.runner import Output

#: where ``cradle run`` writes by default: its own folder, not the workflow's results/
RUN_OUT = "cradle-runs"


def _may_write(outs: dict, names: dict, overwrite: bool) -> None:
    """Refuse, before any work, a destination of ``outs`` (kind -> path) that is another job's or holds another
    entry (:func:`cradle.pipeline.destinations.check`); ``names`` maps each kind to the name it is written for."""
    from cradle.pipeline.destinations import Refused, check

    for kind, path in outs.items():
        key = "scene" if kind in layout.SCENE_PARTS else "name"
        try:
            check(path, command="cradle run", makes=(kind, {key: names[kind]}), identity=(kind, names[kind]),
                  overwrite=overwrite)
        except Refused as err:
            raise CliError(str(err)) from None


def _stage(compute: Callable[[], Output], out: str | Path, log: str | None, label: str) -> Output:
    """runner.run (atomic write, log, failed/ on StageFailure) of ``compute``; the stage functions
    record the hash of their parameters themselves (``params_sha256``)."""
    from cradle.pipeline.runner import run
    from cradle.scenes.failure import StageFailure

    try:
        return run(compute, out, str(log), label=label)
    except StageFailure as err:
        raise CliError(f"{label}: {err}") from None


def _note_workflow_results(out: Path, config: Path) -> None:
    """``cradle run`` writes into the workflow's own ``results/`` only when asked by name; there, a
    file written outside Snakemake would be taken as up to date with whatever config made it."""
    if out.resolve() == (Path(config).resolve().parent / "results").resolve():
        print(f"{PROG}: note: writing into the workflow's folder {out}; Snakemake will take these files as "
              "built from the current config", file=sys.stderr)


def cmd_run(args: argparse.Namespace) -> int:
    from cradle.pipeline import budget, config as cc
    from cradle.pipeline.scene_job import run_scene
    from cradle.scenes import stages
    from cradle.scenes.failure import StageFailure
    from cradle.scenes.spec import Breather

    cfg = load_config(args.config)  # validate: an over-budget job is refused here, before any work
    name, out = args.scene, Path(args.out)
    section = section_of(cfg, name)
    if section is None:
        raise CliError(f"unknown scene {name!r} (known: {known_names(cfg)})")
    _note_workflow_results(out, args.config)
    overwrite = getattr(args, "overwrite", False)
    if section in ("map", "homoclinic"):
        _may_write({section: Path(layout.path(section, out, name=name))}, {section: name}, overwrite)
    if section == "map":
        mspec = cc.map_entry(cfg, name)
        _stage(lambda: stages.map_orbits(mspec, name), Path(layout.path("map", out, name=name)),
               layout.path("log", out, job=f"map/{name}"), f"map {name}")
        return 0
    if section == "homoclinic":
        hspec = cc.homoclinic(cfg, name)
        _stage(lambda: stages.homoclinic_solution(hspec, name), Path(layout.path("homoclinic", out, name=name)),
               layout.path("log", out, job=f"homoclinic/{name}"), f"homoclinic {name}")
        return 0
    spec = cc.scene(cfg, name)
    outs, homoclinic = {}, None
    if isinstance(spec.initial, Breather):
        hname = spec.initial.homoclinic
        hspec = cc.homoclinic(cfg, hname)
        homoclinic = lambda: stages.homoclinic_solution(hspec, hname)  # noqa: E731
        outs["homoclinic"] = Path(layout.path("homoclinic", out, name=hname))
    outs.update({part: Path(p) for part, p in layout.scene_paths(name, out).items()})
    _may_write(outs, {**dict.fromkeys(layout.SCENE_PARTS, name), "homoclinic": spec.initial.homoclinic
                      if isinstance(spec.initial, Breather) else ""}, overwrite)
    print(f"{PROG}: {budget.spec_estimate(spec, name).describe()}", file=sys.stderr)  # within budget (validated)
    log = layout.path("log", out, job=f"sim/{name}")
    try:
        run_scene(spec, name, outs, log, homoclinic=homoclinic)
    except StageFailure as err:
        raise CliError(f"{name}: {err} (none of the scene's files written; what was computed is kept for "
                       f"diagnosis, see {log})") from None
    print(f"{name}: {', '.join(str(p) for p in outs.values())}")
    return 0
