"""The ``cradle`` command (also ``python -m cradle``).

::

    cradle scenes   [--config config.yaml]                 # scenes, figures and what each needs
    cradle run      SCENE [--out cradle-runs] [--config ...]   # one scene without Snakemake
    cradle describe FILE.nc [--config config.yaml]         # parameters, checks, provenance of a result
    cradle extend   FILE.nc --t-end T [--every DT] [--out FILE.nc | --in-place]   # continue an exact run
    cradle verify   [results] [--config config.yaml]       # every output's checksums and identity; what to rebuild
    cradle animate  SCENE [--results results] [--gif] [--fps F --duration S]   # a movie of the stored runs
    cradle animate  n5-lifted1 --desk-toy results/desk-toy/desk-toy.nc          # a desk toy of that analysis
    cradle slurm    [TARGET...] [--cpus N --mem-mb MB --time MIN] [-- SNAKEMAKE_ARGS]   # the build in one Slurm job
    cradle scale    --material steel --radius R (--length L | --omega0 W) [--amplitude A] [--angle DEG]
                                                           # (nc)'s units in SI for a real cradle

``cradle run`` computes a scene's initial data, exact and DpS runs and
metrics with :mod:`cradle.scenes.stages` and
:func:`cradle.pipeline.runner.run_chain`, as the workflow's ``simulate`` job
does: all four files are written only after every step succeeded (a failure
writes none of them; what was computed goes under ``failed/``), into the
workflow's layout under its own folder (default ``cradle-runs/``, never the
workflow's ``results/`` unless asked): ``OUT/initial/SCENE.nc``,
``OUT/sim/SCENE/{exact,dps}.nc``, ``OUT/metrics/SCENE.nc``, log in
``OUT/logs/sim/SCENE.log``. A breather scene's homoclinic solution is
computed first (``OUT/homoclinic/NAME.nc``). A ``map`` or ``homoclinic``
name computes that entry alone. The config is refused before any work if a
job is over budget (:mod:`cradle.pipeline.budget`).

``cradle run``, ``cradle extend`` and ``cradle animate`` refuse a destination that is another job's output or an
existing file they did not make (:mod:`cradle.pipeline.destinations`), unless given ``--overwrite``.

``cradle extend`` writes a new file by default, ``FILE-tT.nc``, beside
``cradle run``'s outputs: a file of the workflow's ``results/`` is continued
under ``cradle-runs/`` (``results/sim/S/exact.nc`` ->
``cradle-runs/sim/S/exact-tT.nc``), any other file beside itself. It writes
into the workflow's ``results/`` only when told: ``--out`` there, or
``--in-place``, which replaces the input and is refused for a scene's exact
run next to its DpS run (a workflow output): extending it alone would leave
the DpS run, the metrics and the config at the old t_end.

Every error is one line on stderr, ``cradle: error: ...``, exit status 2,
no traceback. ``cradle verify`` exits 1 when an output must be rebuilt: damaged (``DAMAGED``), or not the
file the config expects there (``MISMATCH``: another scene's, or made from other parameters than the config
resolves to now; :mod:`cradle.pipeline.identity`). ``describe`` says the same of one file and goes on.
Both check the files of the ``results/`` folder beside the config (``--config``, default ``config.yaml``:
when there is none, identities are not checked).

``cradle animate`` draws a movie from a scene's stored runs only
(:mod:`cradle.figures.movie`): ``RESULTS/movies/SCENE.mp4`` (and ``.gif``).

``cradle scale`` prints the SI value of one unit of (nc)'s time, length, velocity, force and energy for
spheres of a named material on pendulum strings (or stiff oscillators), what a dimensionless amplitude is
in metres and what a release angle is in (nc)'s units (:mod:`cradle.models.physical`, docs/physical-units.md).

``cradle slurm`` submits one Slurm job that runs ``snakemake --cores CPUS TARGET...`` in the workflow's
folder, its jobs forked from the warm process as in a local build (:mod:`.slurm`; the per-rule way is
``snakemake --workflow-profile profiles/slurm``).

This package holds the parser and :func:`main`; the commands are in
:mod:`.scenes`, :mod:`.run`, :mod:`.files` (describe, extend, verify), :mod:`.animate`, :mod:`.scale` and
:mod:`.slurm`,
what they share in :mod:`.common`.
"""
from __future__ import annotations

import argparse
import sys
from typing import NoReturn

from cradle.data.provenance import VERSION as __version__
from cradle.pipeline.cli.animate import cmd_animate
from cradle.pipeline.cli.common import PROG, CliError
from cradle.pipeline.cli.files import cmd_describe, cmd_extend, cmd_verify
from cradle.pipeline.cli.run import RUN_OUT, cmd_run
from cradle.pipeline.cli.scale import cmd_scale
from cradle.pipeline.cli.scenes import cmd_scenes
from cradle.pipeline.cli.slurm import add_parser as add_slurm_parser, split_snakemake_args

#: the flag of every command that writes: replace a destination that is another job's or that it did not make
OVERWRITE_HELP = ("write even over a workflow output of another scene or rule, or a file this command did not "
                  "make (refused otherwise)")


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:  # one line, exit 2 (argparse would print the usage first)
        raise CliError(message)


def _finite(text: str) -> float:
    """A command-line number that is finite (argparse's float takes 'nan' and 'inf')."""
    import math

    value = float(text)
    if not math.isfinite(value):
        raise ValueError(text)
    return value


_finite.__name__ = "finite number"  # argparse names the type in its message: "invalid finite number value"


def parser() -> argparse.ArgumentParser:
    p = _Parser(prog=PROG, description="Newton's cradle and the discrete p-Schroedinger equation (G. James 2011), "
                                       "rebuilt: list, run and describe scenes outside Snakemake.")
    p.add_argument("--version", action="version", version=f"{PROG} {__version__}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    s = sub.add_parser("scenes", help="list scenes, homoclinic and map entries, figures and what each needs")
    s.add_argument("--config", default="config.yaml", help="config file (default: config.yaml)")
    s.set_defaults(func=cmd_scenes)
    r = sub.add_parser("run", help="compute one scene (initial, exact, dps, metrics) without Snakemake")
    r.add_argument("scene", metavar="SCENE", help="a name under scenes: (or homoclinic:, map:) of the config")
    r.add_argument("--out", default=RUN_OUT, help=f"output folder (default: {RUN_OUT}; not the workflow's results)")
    r.add_argument("--config", default="config.yaml", help="config file (default: config.yaml)")
    r.add_argument("--overwrite", action="store_true", help=OVERWRITE_HELP)
    r.set_defaults(func=cmd_run)
    d = sub.add_parser("describe", help="print a result's parameters, checks and provenance")
    d.add_argument("file", metavar="FILE.nc")
    d.add_argument("--config", default=None, help="the config whose results/ the file should match "
                                                  "(default: config.yaml, if there is one)")
    d.set_defaults(func=cmd_describe)
    e = sub.add_parser("extend", help="continue a finished exact run (exact.nc) to a later time and append; "
                                      "bitwise the same as one longer run for splitting methods")
    e.add_argument("file", metavar="FILE.nc", help="an exact run (sim/SCENE/exact.nc)")
    e.add_argument("--t-end", type=float, required=True, dest="t_end", help="new final time (> the last stored t)")
    e.add_argument("--every", type=float, default=None,
                   help="storage step of the new times (default: the file's median spacing)")
    e.add_argument("--out", default=None, help=f"write here (default: FILE-tT.nc, under {RUN_OUT}/ for a file of the "
                                               f"workflow's results/, e.g. {RUN_OUT}/sim/SCENE/exact-tT.nc; beside "
                                               "FILE.nc for any other file)")
    e.add_argument("--overwrite", action="store_true", help=OVERWRITE_HELP)
    e.add_argument("--in-place", action="store_true", dest="in_place",
                   help="replace FILE.nc (refused for a workflow scene's exact run: change t_end in the config)")
    e.add_argument("--config", default="config.yaml",
                   help="config whose budget: the run must fit (default: config.yaml; the declared budget without one)")
    e.set_defaults(func=cmd_extend)
    v = sub.add_parser("verify", help="read every output's data against its checksums; list what to rebuild "
                                      "(exit 1 if any)")
    v.add_argument("root", nargs="?", default="results", metavar="RESULTS",
                   help="a folder of outputs (every *.nc below it) or one file (default: results)")
    v.add_argument("--config", default=None, help="the config whose results/ the files should match "
                                                  "(default: config.yaml, if there is one)")
    v.set_defaults(func=cmd_verify)
    a = sub.add_parser("animate", help="a movie (MP4, optionally GIF) of a scene's stored exact and DpS runs")
    a.add_argument("scene", metavar="SCENE", help="a scene whose runs are stored under RESULTS/sim/SCENE/")
    a.add_argument("--results", default="results", help="the results folder to read (default: results)")
    a.add_argument("--out", default=None, help="the MP4 to write (default: RESULTS/movies/SCENE.mp4)")
    a.add_argument("--gif", action="store_true", help="also write a small GIF beside the MP4")
    a.add_argument("--overwrite", action="store_true", help=OVERWRITE_HELP)
    a.add_argument("--fps", type=int, default=None, help="frames per second (default: movies.fps of the config)")
    a.add_argument("--duration", type=float, default=None, help="seconds of movie (default: movies.duration)")
    a.add_argument("--width", type=int, default=None, help="frame width in pixels, even")
    a.add_argument("--height", type=int, default=None, help="frame height in pixels, even")
    a.add_argument("--gif-fps", type=int, default=None, dest="gif_fps", help="frames per second of the GIF")
    a.add_argument("--t-start", type=float, default=None, dest="t_start", help="first time shown (default: 0)")
    a.add_argument("--t-end", type=float, default=None, dest="t_end", help="last time shown (default: the run's end)")
    a.add_argument("--config", default="config.yaml", help="config whose movies: section gives the defaults")
    a.add_argument("--desk-toy", default=None, dest="desk_toy", metavar="FILE.nc",
                   help="draw the desk toy SCENE (e.g. n5-lifted1) of this desk-toy analysis file instead of a scene")
    a.add_argument("--hard", type=int, default=1, help="with --desk-toy: the hard-sphere model index drawn beside "
                                                       "(default 1: the first restitution coefficient)")
    a.set_defaults(func=cmd_animate)
    c = sub.add_parser("scale", help="(nc)'s units in SI for a cradle of given spheres and strings; what an amplitude "
                                     "or a release angle means")
    c.add_argument("--material", required=True, help="sphere material: steel, brass, glass or ptfe")
    c.add_argument("--radius", type=_finite, required=True, help="sphere radius R (m)")
    o = c.add_mutually_exclusive_group(required=True)
    o.add_argument("--length", type=_finite, help="pendulum length L, pivot to the sphere's centre (m)")
    o.add_argument("--omega0", type=_finite, help="angular frequency of a stiff on-site oscillator (rad/s)")
    c.add_argument("--amplitude", type=_finite, default=None,
                   help="a dimensionless amplitude of (nc), printed in metres")
    c.add_argument("--angle", type=_finite, default=None,
                   help="a pendulum released from this angle (degrees, in (0, 90)), printed in (nc)'s units")
    c.set_defaults(func=cmd_scale)
    add_slurm_parser(sub)
    return p


def _numbers_attached(argv: list[str]) -> list[str]:
    """``--radius -1e-300`` as ``--radius=-1e-300``: argparse takes a negative number with an exponent for an
    option and says only "expected one argument"; attached, the value reaches its check and its one line."""
    import re

    out: list[str] = []
    for token in argv:
        prev = out[-1] if out else ""
        if re.fullmatch(r"-(\d|\.\d|inf|nan)\S*", token, re.IGNORECASE) and prev.startswith("--") and "=" not in prev:
            out[-1] = f"{prev}={token}"
        else:
            out.append(token)
    return out


def main(argv: list[str] | None = None) -> int:
    """Run the command line ``argv`` (default ``sys.argv[1:]``); returns the exit status."""
    import os

    from cradle.data import provenance
    from cradle.pipeline.config import ConfigError

    argv = sys.argv[1:] if argv is None else list(argv)
    try:
        own, snakemake_args = split_snakemake_args(argv) if argv[:1] == ["slurm"] else (argv, [])
        args = parser().parse_args(_numbers_attached(own))
        if snakemake_args:
            args.snakemake_args = snakemake_args
        if not getattr(args, "func", None):
            parser().print_help()
            return 2
        provenance.set_command(" ".join([PROG, *argv]))
        return args.func(args)
    except CliError as err:
        text = " ".join(str(err).split())
    except ConfigError as err:
        lines = [line.strip() for line in str(err).splitlines() if line.strip()]
        text = "; ".join(line.removeprefix("config error: ") for line in lines)
        text = f"{getattr(args, 'config', 'config')}: {text}"
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted", file=sys.stderr)
        return 130
    except Exception as err:  # noqa: BLE001 - one line for the user; CRADLE_DEBUG=1 shows the traceback
        io = sys.modules.get("cradle.data.io")  # a damaged input or a full disk: only from the io there
        if io is not None and isinstance(err, (io.DamagedOutput, io.DiskFull)):
            text = " ".join(str(err).split())
        elif os.environ.get("CRADLE_DEBUG"):
            raise
        else:
            text = f"{type(err).__name__}: {' '.join(str(err).split())} (CRADLE_DEBUG=1 shows the traceback)"
    finally:
        provenance.set_command(None)
    print(f"{PROG}: error: {text}", file=sys.stderr)
    return 2
