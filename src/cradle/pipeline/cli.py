"""The ``cradle`` command (also ``python -m cradle``).

::

    cradle scenes   [--config config.yaml]                 # scenes, figures and what each needs
    cradle run      SCENE [--out results] [--config ...]   # one scene without Snakemake
    cradle describe FILE.nc                                # parameters, checks, provenance of a result
    cradle extend   FILE.nc --t-end T [--every DT] [--out FILE.nc]   # continue a finished exact run

``cradle run`` computes a scene's initial data, exact and DpS runs and
metrics with :mod:`cradle.pipeline.stages` and :func:`cradle.pipeline.runner.run` (atomic
writes, failed runs kept under ``failed/``, progress every ~2 s on the
terminal and in ``OUT/logs/...``), into the same layout as the workflow:
``OUT/initial/SCENE.nc``, ``OUT/sim/SCENE/{exact,dps}.nc``,
``OUT/metrics/SCENE.nc``. A breather scene's homoclinic solution is computed
first (``OUT/homoclinic/NAME.nc``). A ``map`` or ``homoclinic`` name computes
that entry alone.

Every error is one line on stderr, ``cradle: error: ...``, exit status 2,
no traceback.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from cradle import __version__

PROG = "cradle"


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


def cmd_scenes(args) -> int:
    cfg = _load(args.config)
    out = [f"{args.config}: {len(cfg.get('scenes') or {})} scenes, {len(cfg.get('homoclinic') or {})} homoclinic, "
           f"{len(cfg.get('map') or {})} map, {len(cfg.get('figures') or {})} figures", "", "scenes:"]
    for name, spec in (cfg.get("scenes") or {}).items():
        out.append(_scene_line(name, spec))
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


def cmd_run(args) -> int:
    from cradle.pipeline import config as cc
    from cradle.pipeline import stages
    from cradle.pipeline.runner import Progress

    cfg = _load(args.config)
    name, out = args.scene, Path(args.out)
    section = _section_of(cfg, name)
    if section is None:
        raise CliError(f"unknown scene {name!r} (known: {_known(cfg)})")
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
    hom = None
    if spec["initial"]["kind"] == "breather":
        hname = spec["initial"]["homoclinic"]
        hspec = cc.resolved_homoclinic(cfg, hname)
        hom = _stage(lambda: stages.homoclinic_solution(hspec, hname), out / "homoclinic" / f"{hname}.nc",
                     logs / "homoclinic" / f"{hname}.log", f"homoclinic {hname}")
    init = _stage(lambda: stages.initial_data(spec, name, hom), out / "initial" / f"{name}.nc",
                  logs / "initial" / f"{name}.log", f"initial {name}")
    sim = out / "sim" / name
    ex = _stage(lambda: stages.exact_run(spec, init, name, progress=Progress(f"exact {name}")), sim / "exact.nc",
                logs / "sim" / name / "exact.log", f"exact {name}")
    ap = _stage(lambda: stages.dps_run(spec, init, name, progress=Progress(f"dps {name}")), sim / "dps.nc",
                logs / "sim" / name / "dps.log", f"dps {name}")
    _stage(lambda: stages.metrics(spec, ex, ap, name), out / "metrics" / f"{name}.nc",
           logs / "metrics" / f"{name}.log", f"metrics {name}")
    print(f"{name}: {out / 'initial' / (name + '.nc')}, {sim / 'exact.nc'}, {sim / 'dps.nc'}, "
          f"{out / 'metrics' / (name + '.nc')}")
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


def cmd_describe(args) -> int:
    import xarray as xr

    from cradle.pipeline.provenance import KEYS as PROV

    path = Path(args.file)
    if not path.exists():
        raise CliError(f"no such file {str(path)!r}")
    try:
        ds = xr.open_dataset(path)
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
        out += ["", "provenance:"]
        out += [f"  {k:<{width}} {_fmt(attrs[k])}" for k in PROV + ("history", "Conventions") if k in attrs]
        out += ["", "variables:"]
        for name in list(ds.coords) + list(ds.data_vars):
            var = ds[name]
            dims = f"({', '.join(f'{d}={ds.sizes[d]}' for d in var.dims)})"
            out.append(f"  {name:<16} {dims:<22} {var.attrs.get('long_name', '')} [{var.attrs.get('units', '?')}]")
    print("\n".join(out))
    return 0


# ------------------------------------------------------------------ extend

def cmd_extend(args) -> int:
    from cradle.pipeline.extend import extend

    path = Path(args.file)
    if not path.exists():
        raise CliError(f"no such file {str(path)!r}")
    try:
        s = extend(path, args.t_end, out=args.out, every=args.every)
    except ValueError as err:
        raise CliError(str(err)) from None
    print(f"{s['path']}: t = {s['t_from']:g} -> {s['t_end']:g}, {s['rows_added']} stored times added, "
          f"{s['n_steps']} steps (dt = {s['dt']:.6g}), energy drift {s['energy_drift']:.3e}, "
          f"{s['wall_time_s']:.2f} s")
    return 0


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
    r.add_argument("--out", default="results", help="output folder (default: results)")
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
    e.add_argument("--out", default=None, help="write here instead of replacing FILE.nc")
    e.set_defaults(func=cmd_extend)
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
        if os.environ.get("CRADLE_DEBUG"):
            raise
        text = f"{type(err).__name__}: {' '.join(str(err).split())} (CRADLE_DEBUG=1 shows the traceback)"
    finally:
        provenance.set_command(None)
    print(f"{PROG}: error: {text}", file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
