"""The ``cradle`` command (also ``python -m cradle``).

::

    cradle scenes   [--config config.yaml]                 # scenes, figures and what each needs
    cradle run      SCENE [--out cradle-runs] [--config ...]   # one scene without Snakemake
    cradle describe FILE.nc                                # parameters, checks, provenance of a result
    cradle extend   FILE.nc --t-end T [--every DT] [--out FILE.nc | --in-place]   # continue an exact run
    cradle verify   [results]                              # every output's checksums; what to rebuild

``cradle run`` computes a scene's initial data, exact and DpS runs and
metrics with :mod:`cradle.pipeline.stages` and
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

``cradle extend`` writes a new file by default (``FILE-tT.nc`` beside the
input); ``--in-place`` replaces the input, and is refused for a scene's
exact run next to its DpS run (a workflow output): extending it alone would
leave the DpS run, the metrics and the config at the old t_end.

Every error is one line on stderr, ``cradle: error: ...``, exit status 2,
no traceback. ``cradle verify`` exits 1 when an output must be rebuilt.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from cradle import __version__

PROG = "cradle"
#: where ``cradle run`` writes by default: its own folder, not the workflow's results/
RUN_OUT = "cradle-runs"


class CliError(Exception):
    """An error reported as one line, exit status 2."""


def _load(path):
    from cradle.pipeline import config as cc

    path = Path(path)
    if not path.exists():
        raise CliError(f"no config file {str(path)!r} (give one with --config)")
    return cc.load(path)


def _section_of(cfg, name):
    for section in ("scenes", "homoclinic", "map"):
        if name in (cfg.get(section) or {}):
            return section
    return None


def _known(cfg):
    names = [n for s in ("scenes", "homoclinic", "map") for n in (cfg.get(s) or {})]
    return ", ".join(names) or "none"


# ------------------------------------------------------------------ scenes

def _scene_line(name, spec) -> str:
    from cradle.pipeline import config as cc

    ini = spec["initial"]
    kind = ini["kind"]
    what = kind
    if kind == "travelling":
        what += f" q={ini.get('q')}" + "".join(f" {k}={ini[k]}" for k in ("a", "omega_tw") if ini.get(k) is not None)
        if ini.get("noise"):
            what += f" +{ini['noise'].get('kind')} noise"
    elif kind == "breather":
        what += f" from homoclinic '{ini['homoclinic']}'"
    if kind in ("breather", "packet", "pair") and ini.get("amplitude") is not None:
        what += f" amplitude={ini['amplitude']:g}"
    times = cc.store_times(spec["store"], spec["t_end"])
    return f"  {name:<16} N={spec['N']:<4} {spec['bc']:<8} t_end={spec['t_end']:<8g} {len(times):>6} stored times  {what}"


def _cost_line(cfg, name) -> str:
    """The scene's estimated job cost (cradle.pipeline.budget), under its line of ``cradle scenes``."""
    from cradle.pipeline import budget

    e = budget.scene_estimate(cfg, name)
    return (f"  {'':<16} estimated: peak memory {budget.fmt_bytes(e.memory_bytes)}, "
            f"writes {budget.fmt_bytes(e.disk_bytes)}, about {budget.fmt_duration(e.seconds)}")


def cmd_scenes(args) -> int:
    cfg = _load(args.config)
    out = [f"{args.config}: {len(cfg.get('scenes') or {})} scenes, {len(cfg.get('homoclinic') or {})} homoclinic, "
           f"{len(cfg.get('map') or {})} map, {len(cfg.get('figures') or {})} figures", "", "scenes:"]
    for name, spec in (cfg.get("scenes") or {}).items():
        out.append(_scene_line(name, spec))
        out.append(_cost_line(cfg, name))
        if spec["initial"]["kind"] == "breather":
            out.append(f"  {'':<16} needs homoclinic/{spec['initial']['homoclinic']}.nc")
        out.append(f"  {'':<16} makes initial/{name}.nc, sim/{name}/exact.nc, sim/{name}/dps.nc, metrics/{name}.nc")
    out += ["", "homoclinic:"]
    for name, spec in (cfg.get("homoclinic") or {}).items():
        out.append(f"  {name:<16} N={spec['N']:<4} {spec['bc']:<8} guess={spec['guess']:<8} makes homoclinic/{name}.nc")
    out += ["", "map:"]
    for name, spec in (cfg.get("map") or {}).items():
        out.append(f"  {name:<16} iterations={spec['iterations']} box={spec['box']}  makes map/{name}.nc")
    out += ["", "figures (label: the entries it reads, the times it shows):"]
    for label, fig in (cfg.get("figures") or {}).items():
        reads = [name if _section_of(cfg, name) == "scenes" else f"{name} ({_section_of(cfg, name)})"
                 for name in fig["scenes"]]
        times = f"  at t = {', '.join(f'{t:g}' for t in fig['times'])}" if fig.get("times") else ""
        out.append(f"  {label:<12} {', '.join(reads)}{times}")
    print("\n".join(out))
    return 0


# ------------------------------------------------------------------ run

def _stage(compute, out, log, label):
    """runner.run (atomic write, log, failed/ on StageFailure) of ``compute``; the stage functions
    record the hash of their parameters themselves (``params_sha256``)."""
    from cradle.pipeline.runner import StageFailure, run

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


def cmd_run(args) -> int:
    from cradle.pipeline import budget, config as cc
    from cradle.pipeline import stages
    from cradle.pipeline.runner import Progress, StageFailure, run_chain

    cfg = _load(args.config)  # validate: an over-budget job is refused here, before any work
    name, out = args.scene, Path(args.out)
    section = _section_of(cfg, name)
    if section is None:
        raise CliError(f"unknown scene {name!r} (known: {_known(cfg)})")
    _note_workflow_results(out, args.config)
    logs = out / "logs"
    if section == "map":
        mspec = cc.resolved_map(cfg, name)
        _stage(lambda: stages.map_orbits(mspec, name), out / "map" / f"{name}.nc",
               logs / "map" / f"{name}.log", f"map {name}")
        return 0
    if section == "homoclinic":
        hspec = cc.resolved_homoclinic(cfg, name)
        _stage(lambda: stages.homoclinic_solution(hspec, name), out / "homoclinic" / f"{name}.nc",
               logs / "homoclinic" / f"{name}.log", f"homoclinic {name}")
        return 0
    spec = cc.resolved_scene(cfg, name)
    print(f"{PROG}: {budget.spec_estimate(spec).describe()}", file=sys.stderr)  # within budget (validated)
    steps, outs = [], {}
    if spec["initial"]["kind"] == "breather":
        hname = spec["initial"]["homoclinic"]
        hspec = cc.resolved_homoclinic(cfg, hname)
        steps.append(("homoclinic", lambda done: stages.homoclinic_solution(hspec, hname)))
        outs["homoclinic"] = out / "homoclinic" / f"{hname}.nc"
    sim = out / "sim" / name
    steps += [
        ("initial", lambda done: stages.initial_data(spec, name, done.get("homoclinic"))),
        ("exact", lambda done: stages.exact_run(spec, done["initial"], name, progress=Progress(
            f"exact {name}", estimate=budget.long_run(spec)))),
        ("dps", lambda done: stages.dps_run(spec, done["initial"], name, progress=Progress(f"dps {name}"))),
        ("metrics", lambda done: stages.metrics(spec, done["exact"], done["dps"], name)),
    ]
    outs.update({"initial": out / "initial" / f"{name}.nc", "exact": sim / "exact.nc", "dps": sim / "dps.nc",
                  "metrics": out / "metrics" / f"{name}.nc"})
    try:
        run_chain(steps, outs, str(logs / "sim" / f"{name}.log"), label=name)
    except StageFailure as err:
        raise CliError(f"{name}: {err} (none of the scene's files written; what was computed is kept for "
                       f"diagnosis, see {logs / 'sim' / (name + '.log')})") from None
    print(f"{name}: {', '.join(str(p) for p in outs.values())}")
    return 0


# ------------------------------------------------------------------ describe

#: global attributes that are checks of the result (accuracy, convergence, failure)
CHECKS = ("energy_drift", "max_energy_drift_allowed", "max_l2_drift", "max_dps_energy_drift", "residual",
          "converged", "symmetry_error", "E_max", "E_final", "n_steps", "n_force_evals", "wall_time_s", "failure")
CF_KEYS = ("title", "Conventions", "source", "references", "history")


def _fmt(value) -> str:
    import numpy as np

    if isinstance(value, (float, np.floating)):
        return f"{float(value):.6g}"
    if isinstance(value, np.ndarray):
        return "[" + ", ".join(_fmt(v) for v in value.tolist()) + "]"
    return str(value)


def _describe_variables(heading: str, ds) -> list[str]:
    """One line per variable of ``ds``: name, dims with sizes, long name and units."""
    out = ["", heading]
    for name in list(ds.coords) + list(ds.data_vars):
        var = ds[name]
        dims = f"({', '.join(f'{d}={ds.sizes[d]}' for d in var.dims)})"
        out.append(f"  {name:<16} {dims:<22} {var.attrs.get('long_name', '')} [{var.attrs.get('units', '?')}]")
    return out


def cmd_describe(args) -> int:
    import xarray as xr

    from cradle.pipeline.provenance import KEYS as PROV

    from cradle.pipeline.io import DamagedOutput, verify_file

    path = Path(args.file)
    if not path.exists():
        raise CliError(f"no such file {str(path)!r}")
    try:
        bare = verify_file(path)  # every checksum, in bounded memory: a damaged file is not described as fine
        ds = xr.open_dataset(path)
    except DamagedOutput as err:
        raise CliError(str(err)) from None
    except Exception as err:  # noqa: BLE001 - any unreadable file is one line
        raise CliError(f"cannot read {str(path)!r} as netCDF: {' '.join(str(err).split())}") from None
    with ds:
        attrs = dict(ds.attrs)
        width = max([len(k) for k in attrs] + [12])
        out = [f"{path}: {attrs.get('title', '(no title)')}", "", "parameters:"]
        out += [f"  {k:<{width}} {_fmt(v)}" for k, v in attrs.items() if k not in CHECKS + CF_KEYS + PROV]
        out += ["", "checks:"]
        out += [f"  {k:<{width}} {_fmt(attrs[k])}" for k in CHECKS if k in attrs]
        for name in ("residual_n", "l2_drift", "dps_energy_drift", "P_drift", "E"):
            if name in ds:
                out.append(f"  {'max|' + name + '|':<{width}} {float(abs(ds[name]).max()):.6g}")
        out.append(f"  {'checksums':<{width}} " + ("verified (every variable)" if not bare else
                   f"verified; no checksum on {', '.join(bare)} (written before checksums: rebuild to protect)"))
        out += ["", "provenance:"]
        out += [f"  {k:<{width}} {_fmt(attrs[k])}" for k in PROV + ("history", "Conventions") if k in attrs]
        out += _describe_variables("variables:", ds)
    with xr.open_datatree(path) as tree:   # the groups of an analysis file (xarray.open_datatree)
        for node in list(tree.subtree)[1:]:
            out += _describe_variables(f"group {node.path}:", node.to_dataset(inherit=False))
    print("\n".join(out))
    return 0


# ------------------------------------------------------------------ extend

def _workflow_scene_of(path: Path) -> str | None:
    """The scene whose workflow outputs ``path`` belongs to (``.../sim/SCENE/exact.nc`` beside its
    ``dps.nc``), or None for a standalone exact run."""
    if path.parent.parent.name == "sim" and (path.parent / "dps.nc").exists():
        return path.parent.name
    return None


def cmd_extend(args) -> int:
    import math

    from cradle.pipeline.extend import extend
    from cradle.pipeline.io import DamagedOutput

    path = Path(args.file)
    if not path.exists():
        raise CliError(f"no such file {str(path)!r}")
    if not math.isfinite(args.t_end):
        raise CliError(f"--t-end {args.t_end!r}: must be a finite time")
    if args.every is not None and not (math.isfinite(args.every) and args.every > 0):
        raise CliError(f"--every {args.every!r}: must be a finite time > 0")
    if args.in_place and args.out:
        raise CliError("give --out FILE or --in-place, not both")
    out = path if args.in_place else Path(args.out) if args.out else path.with_name(f"{path.stem}-t{args.t_end:g}.nc")
    if out.resolve() == path.resolve():
        scene = _workflow_scene_of(path)
        if scene is not None:
            raise CliError(f"refusing to extend {path} in place: the DpS run {path.parent / 'dps.nc'}, the metrics "
                           f"and the config would stay at the old t_end. Set scenes.{scene}.t_end: {args.t_end:g} in "
                           f"the config and run `snakemake {path}` (all four files of the scene, consistently), "
                           f"or drop --in-place to write a new file")
    try:
        s = extend(path, args.t_end, out=out, every=args.every)
    except DamagedOutput as err:
        raise CliError(str(err)) from None
    except ValueError as err:
        raise CliError(str(err)) from None
    print(f"{s['path']}: t = {s['t_from']:g} -> {s['t_end']:g}, {s['rows_added']} stored times added, "
          f"{s['n_steps']} steps (dt = {s['dt']:.6g}), energy drift {s['energy_drift']:.3e}, "
          f"{s['wall_time_s']:.2f} s")
    return 0


# ------------------------------------------------------------------ verify

def cmd_verify(args) -> int:
    from cradle.pipeline.io import DamagedOutput, rebuild_hint, verify_file

    root = Path(args.root)
    if not root.exists():
        raise CliError(f"no such folder or file {str(root)!r}")
    files = [root] if root.is_file() else sorted(p for p in root.rglob("*.nc")
                                                 if not p.name.startswith(".") and "failed" not in p.parts)
    damaged, bare = [], []
    for p in files:
        try:
            if verify_file(p):
                bare.append(p)
        except (DamagedOutput, OSError) as err:
            damaged.append(" ".join(str(err).split()))
    for line in damaged:
        print(f"DAMAGED {line}")
    for p in bare:
        print(f"note    {p}: readable, but written before checksums; {rebuild_hint(p)} to protect it")
    print(f"{len(files)} files checked: {len(files) - len(damaged) - len(bare)} verified, {len(bare)} without "
          f"checksums, {len(damaged)} to rebuild")
    return 1 if damaged else 0


# ------------------------------------------------------------------ main

class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, exit 2 (argparse would print the usage first)
        raise CliError(message)


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
    r.set_defaults(func=cmd_run)
    d = sub.add_parser("describe", help="print a result's parameters, checks and provenance")
    d.add_argument("file", metavar="FILE.nc")
    d.set_defaults(func=cmd_describe)
    e = sub.add_parser("extend", help="continue a finished exact run (exact.nc) to a later time and append; "
                                      "bitwise the same as one longer run for splitting methods")
    e.add_argument("file", metavar="FILE.nc", help="an exact run (sim/SCENE/exact.nc)")
    e.add_argument("--t-end", type=float, required=True, dest="t_end", help="new final time (> the last stored t)")
    e.add_argument("--every", type=float, default=None,
                   help="storage step of the new times (default: the file's median spacing)")
    e.add_argument("--out", default=None, help="write here (default: FILE-tT.nc beside FILE.nc)")
    e.add_argument("--in-place", action="store_true", dest="in_place",
                   help="replace FILE.nc (refused for a workflow scene's exact run: change t_end in the config)")
    e.set_defaults(func=cmd_extend)
    v = sub.add_parser("verify", help="read every output's data against its checksums; list what to rebuild "
                                      "(exit 1 if any)")
    v.add_argument("root", nargs="?", default="results", metavar="RESULTS",
                   help="a folder of outputs (every *.nc below it) or one file (default: results)")
    v.set_defaults(func=cmd_verify)
    return p


def main(argv=None) -> int:
    """Run the command line ``argv`` (default ``sys.argv[1:]``); returns the exit status."""
    import os

    from cradle.pipeline import provenance
    from cradle.pipeline.config import ConfigError

    argv = sys.argv[1:] if argv is None else list(argv)
    try:
        args = parser().parse_args(argv)
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
        io = sys.modules.get("cradle.pipeline.io")  # a damaged input can only come from the readers there
        if io is not None and isinstance(err, io.DamagedOutput):
            text = " ".join(str(err).split())
        elif os.environ.get("CRADLE_DEBUG"):
            raise
        else:
            text = f"{type(err).__name__}: {' '.join(str(err).split())} (CRADLE_DEBUG=1 shows the traceback)"
    finally:
        provenance.set_command(None)
    print(f"{PROG}: error: {text}", file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
