"""The commands on result files: ``cradle describe`` (parameters, checks, provenance), ``cradle extend``
(continue a finished exact run of (nc) to a later time) and ``cradle verify`` (every output's checksums);
describe and verify also say which files are not what the config expects (:mod:`cradle.pipeline.identity`)."""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from cradle.pipeline import layout
from cradle.pipeline.cli.common import CliError, expectations, identity_line

if TYPE_CHECKING:
    import argparse

    import xarray as xr

#: global attributes that are checks of the result (accuracy, convergence, failure)
CHECKS = ("energy_drift", "max_energy_drift_allowed", "max_l2_drift", "max_dps_energy_drift", "residual",
          "converged", "symmetry_error", "E_max", "E_final", "n_steps", "n_force_evals", "wall_time_s", "failure")
CF_KEYS = ("title", "Conventions", "source", "references", "history")


def _fmt(value: Any) -> str:
    import numpy as np

    if isinstance(value, (float, np.floating)):
        return f"{float(value):.6g}"
    if isinstance(value, np.ndarray):
        return "[" + ", ".join(_fmt(v) for v in value.tolist()) + "]"
    return str(value)


def _describe_variables(heading: str, ds: xr.Dataset) -> list[str]:
    """One line per variable of ``ds``: name, dims with sizes, long name and units."""
    out = ["", heading]
    for name in list(ds.coords) + list(ds.data_vars):
        var = ds[name]
        dims = f"({', '.join(f'{d}={ds.sizes[d]}' for d in var.dims)})"
        out.append(f"  {name:<16} {dims:<22} {var.attrs.get('long_name', '')} [{var.attrs.get('units', '?')}]")
    return out


def cmd_describe(args: argparse.Namespace) -> int:
    import xarray as xr

    from cradle.data.digests import read_record, sidecar
    from cradle.data.io import DamagedOutput, verify_file
    from cradle.data.provenance import KEYS as PROV

    path = Path(args.file)
    if not path.exists():
        raise CliError(f"no such file {str(path)!r}")
    expect = expectations(args.config)
    # identity first: another entry's file copied here is said as such, not compared with the sidecar of the file
    # this path held (docs/recovery.md)
    other = expect.check_file(path) if expect is not None else None
    try:
        # every checksum, in bounded memory: a damaged file is not described as fine
        bare = verify_file(path, digest=other is None)
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
        out.append(f"  {'digest':<{width}} " + (
            f"not compared: another entry's file (identity below), {sidecar(path).name} is that of the file this "
            f"path held" if other is not None else
            f"values and attributes as written (recorded in {sidecar(path).name})" if read_record(path) is not None
            else f"none recorded (no {sidecar(path).name}: written before digests, or copied without it; rebuild to "
                 "protect it)"))
        out.append(f"  {'identity':<{width}} {identity_line(expect, path, attrs)}")
        out += ["", "provenance:"]
        out += [f"  {k:<{width}} {_fmt(attrs[k])}" for k in PROV + ("history", "Conventions") if k in attrs]
        out += _describe_variables("variables:", ds)
    with xr.open_datatree(path) as tree:   # the groups of an analysis file (xarray.open_datatree)
        for node in list(tree.subtree)[1:]:
            out += _describe_variables(f"group {node.path}:", node.to_dataset(inherit=False))
    print("\n".join(out))
    return 0


def _workflow_scene_of(path: Path) -> str | None:
    """The scene whose workflow outputs ``path`` belongs to (``.../sim/SCENE/exact.nc`` beside its
    ``dps.nc``), or None for a standalone exact run."""
    if path.parent.parent.name == "sim" and (path.parent / "dps.nc").exists():
        return path.parent.name
    return None


def _may_extend_into(path: Path, out: Path, overwrite: bool) -> None:
    """Refuse ``--out`` when it is a workflow output or an existing file that is not an exact run of the same
    scene (:func:`cradle.pipeline.destinations.check`), before any work."""
    from cradle.pipeline.destinations import Refused, check, holds

    kind, name = holds(path)
    try:
        check(out, command="cradle extend", identity=(kind or "exact", name or "?"), overwrite=overwrite)
    except Refused as err:
        raise CliError(str(err)) from None


def default_extend_out(path: Path, t_end: float) -> Path:
    """Where ``cradle extend FILE --t-end T`` writes without ``--out``: ``FILE-tT.nc`` beside ``cradle run``'s
    outputs. A file of the workflow's ``results/`` is continued into the same place under :data:`RUN_OUT`
    (``results/sim/S/exact.nc`` -> ``cradle-runs/sim/S/exact-tT.nc``): a file written there outside Snakemake would
    sit among the files Snakemake owns. Any other file is continued beside itself."""
    from cradle.pipeline.cli.run import RUN_OUT

    name = f"{path.stem}-t{t_end:g}.nc"
    full = path.resolve()
    root = next((p for p in full.parents if p.name == layout.ROOT), None)
    if root is None:
        return path.with_name(name)
    return Path(RUN_OUT) / full.parent.relative_to(root) / name


def cmd_extend(args: argparse.Namespace) -> int:
    import math
    import sys

    from cradle.data.io import DamagedOutput
    from cradle.pipeline.budget import Budget
    from cradle.pipeline.cli.common import PROG, load_config
    from cradle.pipeline.extend import estimate, extend

    path = Path(args.file)
    if not path.exists():
        raise CliError(f"no such file {str(path)!r}")
    if path.is_dir():
        raise CliError(f"{path}: a folder, not a netCDF file (give an exact run, results/sim/SCENE/exact.nc)")
    if not math.isfinite(args.t_end):
        raise CliError(f"--t-end {args.t_end!r}: must be a finite time")
    if args.every is not None and not (math.isfinite(args.every) and args.every > 0):
        raise CliError(f"--every {args.every!r}: must be a finite time > 0")
    # the budget of the config (as the workflow's), or the declared one when there is no config file
    budget = Budget.from_config(load_config(args.config)) if Path(args.config).exists() else Budget()
    if args.in_place and args.out:
        raise CliError("give --out FILE or --in-place, not both")
    out = path if args.in_place else Path(args.out) if args.out else default_extend_out(path, args.t_end)
    if out.resolve() == path.resolve():
        scene = _workflow_scene_of(path)
        if scene is not None:
            raise CliError(f"refusing to extend {path} in place: the DpS run {path.parent / 'dps.nc'}, the metrics "
                           f"and the config would stay at the old t_end. Set scenes.{scene}.t_end: {args.t_end:g} in "
                           f"the config and run `snakemake {path}` (all four files of the scene, consistently), "
                           f"or drop --in-place to write a new file")
    if out.resolve() != path.resolve():
        _may_extend_into(path, out, getattr(args, "overwrite", False))
    try:
        cost = estimate(path, args.t_end, every=args.every, budget=budget)   # refused here, before any work
        print(f"{PROG}: {cost.describe()}", file=sys.stderr)
        s = extend(path, args.t_end, out=out, every=args.every, budget=budget)
    except DamagedOutput as err:
        raise CliError(str(err)) from None
    except ValueError as err:
        raise CliError(str(err)) from None
    print(f"{s['path']}: t = {s['t_from']:g} -> {s['t_end']:g}, {s['rows_added']} stored times added, "
          f"{s['n_steps']} steps (dt = {s['dt']:.6g}), energy drift {s['energy_drift']:.3e}, "
          f"{s['wall_time_s']:.2f} s")
    return 0


def cmd_verify(args: argparse.Namespace) -> int:
    from cradle.data.digests import read_record, sidecar
    from cradle.data.io import DamagedOutput, rebuild_hint, stale_temporaries, verify_file

    root = Path(args.root)
    if not root.exists():
        raise CliError(f"no such folder or file {str(root)!r}")
    files = [root] if root.is_file() else sorted(p for p in root.rglob("*.nc")
                                                 if not p.name.startswith(".") and "failed" not in p.parts)
    damaged, bare, unrecorded = [], [], []
    for p in files:
        try:
            if verify_file(p):
                bare.append(p)
            elif read_record(p) is None:
                unrecorded.append(p)
        except (DamagedOutput, OSError) as err:
            damaged.append(" ".join(str(err).split()))
    expect = expectations(args.config)  # what the config expects of each file: kind, name, parameters
    mismatched = [line for p in files if expect is not None and (line := expect.check_file(p))]
    for line in damaged:
        print(f"DAMAGED {line}")
    for line in mismatched:
        print(f"MISMATCH {line}")
    for p in bare:
        print(f"note    {p}: readable, but written before checksums; {rebuild_hint(p)} to protect it")
    for p in unrecorded:
        print(f"note    {p}: readable, but no digest recorded (no {sidecar(p).name}: written before digests, or "
              f"copied without it), so an edit would not show; {rebuild_hint(p)} to protect it")
    stale = [] if root.is_file() else stale_temporaries(root)
    for p in stale:
        print(f"note    stale temporary file {p} (a killed write; delete it)")
    print(f"{len(files)} files checked: {len(files) - len(damaged) - len(bare) - len(unrecorded)} verified, "
          f"{len(bare)} without checksums, " + (f"{len(unrecorded)} without a digest, " if unrecorded else "")
          + f"{len(damaged)} to rebuild" + (f"; {len(stale)} stale temporary files" if stale else ""))
    if mismatched:
        print(f"{len(mismatched)} files not what {expect.source} expects (another entry's, or older parameters): "  # type: ignore[union-attr]  # none mismatch without expect
              "rebuild them")
    return 1 if damaged or mismatched else 0
