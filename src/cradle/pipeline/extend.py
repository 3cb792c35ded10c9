"""Long lattice runs streamed to disk, and extending a finished exact run.

:func:`stream_lattice` integrates (nc) in chunks of output times and appends
each chunk to a netCDF file whose ``t`` dimension is unlimited, so the
memory held is one chunk (``chunk_bytes``), whatever t_end and the number of
stored times. The file is written under a temporary name beside the target
and renamed at the end (as :func:`cradle.data.io.write_netcdf`): an interrupted
run leaves nothing at the target. Its variables and attributes are those of
:func:`cradle.scenes.stages.exact_run` (``x``, ``v``, ``force``, ``energy`` on
``(t, n)``).

:func:`extend` continues a finished ``exact.nc`` (it stores x and v at the
last time in float64, the integrator and its step ``dt``) to a later
``t_end`` and appends. With a fixed-step splitting (every default method),
continuing from the state at T with the same dt and the same later output
times takes exactly the steps of one run to the later time: the result is
bitwise that of the single run, energy drift included (measured from the
energy at t = 0, passed as ``energy0``). ``cradle extend FILE --t-end T``.

Chunk boundaries are output times, and the step grid depends only on
consecutive output times (``integrate_lattice`` covers each interval by
ceil(length/dt) equal steps), which is why chunking changes no bit either.
"""
from __future__ import annotations

import datetime as _dt
import math
import os
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import xarray as xr

from cradle.data.appending import DEFAULT_CHUNK_BYTES, Appender, chunk_rows
from cradle.data.io import check_is_netcdf, make_dataset, verify_file
from cradle.models import lattice

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from cradle.integrators.lattice_solver import LatticeSolution
    from cradle.pipeline.budget import Budget, Estimate

TIME_TOL = 1e-9
VARS = ("x", "v", "force", "energy")


def _fields(sol: LatticeSolution, alpha: float, bc: str) -> dict[str, np.ndarray]:
    return {"x": sol.x, "v": sol.v, "force": lattice.bond_forces(sol.x, alpha, bc), "energy": sol.energy}


def stream_lattice(x0: ArrayLike, v0: ArrayLike, t_out: ArrayLike, path: str | os.PathLike, *, alpha: float,
                   bc: str = "periodic", method: str = "srkn6c", dt: float | None = None, t0: float | None = None,
                   energy0: float | None = None, attrs: dict | None = None,
                   title: str = "exact solution of (nc), streamed", params: Any = None,
                   chunk_bytes: int = DEFAULT_CHUNK_BYTES, progress: Callable[[float, float], None] | None = None,
                   prefix: xr.Dataset | None = None) -> dict:
    """Integrate (nc) from (x0, v0) at time t0 (default t_out[0]) to t_out[-1], appending every chunk of
    output times to ``path`` (netCDF, unlimited t; temporary name, renamed at the end).

    ``dt``: the splitting step; default :func:`cradle.integrators.default_dt` at the compression of
    :func:`cradle.integrators.compression_bounds` (no reruns: the chunks are already on disk; the
    attribute ``max_compression`` > ``c_assumed`` tells). ``prefix``: an xarray Dataset of earlier rows
    (same variables) copied first, chunk by chunk (used by :func:`extend`). Returns the run's summary
    (also written as global attributes): energy_drift, n_steps, n_force_evals, max_compression, dt,
    wall_time_s, rows.
    """
    from cradle.integrators import SPLITTING_METHODS, compression_bounds, default_dt, integrate_lattice

    wall0 = time.perf_counter()
    if method not in SPLITTING_METHODS:
        raise ValueError(f"streaming needs a fixed-step splitting method {SPLITTING_METHODS}, got method={method!r}")
    x = np.array(x0, dtype=float)
    v = np.array(v0, dtype=float)
    N = x.size
    t_out = np.asarray(t_out, dtype=float)
    t_cur = float(t_out[0]) if t0 is None else float(t0)
    summary: dict[str, Any] = {"c_assumed": "none"}
    if dt is None:
        c, _ = compression_bounds(x, v, alpha, bc)
        dt = default_dt(c, alpha, method)
        summary["c_assumed"] = c
    H0 = float(lattice.hamiltonian(x, v, alpha, bc)) if energy0 is None else float(energy0)
    rows = chunk_rows(N, chunk_bytes)
    drift, n_steps, nfev, cmax, ncorr = 0.0, 0, 0, 0.0, 0
    app = None
    try:
        if prefix is not None:
            first = prefix.isel(t=slice(0, min(rows, prefix.sizes["t"]))).load()
            app = Appender(path, first)
            for i in range(first.sizes["t"], prefix.sizes["t"], rows):
                part = prefix.isel(t=slice(i, i + rows)).load()
                app.append(part["t"].values, {k: part[k].values for k in VARS})
        todo = t_out[t_out > t_cur + TIME_TOL] if (prefix is not None or t_out[0] != t_cur) else t_out
        start = 0
        while start < todo.size:
            times = todo[start:start + rows]
            sol = integrate_lattice(x, v, times, alpha=alpha, bc=bc, method=method, dt=dt, t0=t_cur,
                                    energy0=H0, progress=progress)
            drift = max(drift, sol.energy_drift)
            n_steps += sol.n_steps
            nfev += sol.n_force_evals
            cmax = max(cmax, sol.max_compression)
            ncorr += sol.n_onset_corrections
            f = _fields(sol, alpha, bc)
            if app is None:
                ds = make_dataset(f, coords={"t": times, "n": np.arange(N)}, attrs=attrs, title=title,
                                  params=params)
                app = Appender(path, ds)
            else:
                app.append(times, f)
            x, v, t_cur = sol.x[-1].copy(), sol.v[-1].copy(), float(times[-1])
            start += times.size
        summary.update({"integrator": method, "dt": _largest_step(t_out, dt, t0), "dt_nominal": float(dt),
                        "energy_drift": drift, "n_steps": n_steps,
                        "n_force_evals": nfev, "max_compression": cmax, "n_onset_corrections": ncorr,
                        "wall_time_s": time.perf_counter() - wall0, "rows": app.rows if app else 0,
                        "chunk_rows": rows, "t_end": t_cur})
        if app is None:
            raise ValueError(f"nothing to integrate: no output time after t0={t_cur!r}")
        app.set_attrs(summary)
        app.commit()
    except BaseException:
        if app is not None:
            app.abort()
        raise
    return summary


def _largest_step(t_out: np.ndarray, dt: float, t0: float | None) -> float:
    from cradle.scenes.stages import steps_taken

    return steps_taken(t_out, float(dt), None if t0 is None else float(t0))[0]


def _infer_every(t: np.ndarray) -> float:
    d = np.diff(np.asarray(t, dtype=float))
    if d.size == 0:
        raise ValueError("cannot infer the storage step from a file with one stored time; give every")
    return float(np.round(np.median(d), 9))


def estimate(path: str | os.PathLike, t_end: float, every: float | None = None,
             budget: Budget | None = None) -> Estimate:
    """What extending the exact run in ``path`` to ``t_end`` will cost (:func:`cradle.pipeline.budget.extend_estimate`),
    from its header alone, before any work: ValueError (one line naming the value) for a t_end beyond a
    scene's longest run (a limit of float64) or past the file's last time, an adaptive integrator, or an
    estimate (memory, output, time: a grid of many stored times among them) over ``budget`` (a
    :class:`cradle.pipeline.budget.Budget`; default: the declared one)."""
    from cradle.integrators import SPLITTING_METHODS
    from cradle.pipeline import budget as costs
    from cradle.scenes.times import grid_size
    from cradle.specs.values import MAX_T_END, T_END_WHY

    path = Path(path)
    t_end = float(t_end)
    if not math.isfinite(t_end):
        raise ValueError(f"t_end={t_end!r}: must be a finite time")
    if not t_end <= MAX_T_END:
        raise ValueError(f"t_end={t_end!r}: must be <= {MAX_T_END:.0f}, a scene's longest run ({T_END_WHY})")
    if every is not None and not (math.isfinite(float(every)) and float(every) > 0):
        raise ValueError(f"every={every!r}: must be a finite time > 0")
    with xr.open_dataset(check_is_netcdf(path)) as ds:   # another kind of file: one line, not xarray's
        missing = [k for k in VARS if k not in ds]
        if missing:
            raise ValueError(f"{path}: not an exact run of (nc) (no {', '.join(missing)}): cannot extend it")
        a = ds.attrs
        method = a.get("integrator")
        if method not in SPLITTING_METHODS:
            raise ValueError(f"{path}: integrator={method!r} is adaptive; extending needs a fixed-step splitting "
                             f"{SPLITTING_METHODS} (rerun the scene to the later t_end instead)")
        dt = float(a.get("dt_nominal", a["dt"]))
        t = ds["t"].values
        N = int(ds.sizes["n"])
    t_last = float(t[-1])
    if not t_end > t_last + TIME_TOL:
        raise ValueError(f"t_end={t_end!r} must be > the last stored time t={t_last!r} of {path}")
    every = _infer_every(t) if every is None else float(every)
    n = grid_size(None, every, t_end)   # the grid k * every on [0, t_end] is built whole: the estimate holds it
    added = min(n, int((t_end - t_last) / every) + 2)
    e = costs.extend_estimate(str(path), N, str(method), dt, t_last, t_end, added, int(t.size))
    over = costs.exceeds(e, budget if budget is not None else costs.Budget())
    if over is not None:
        raise ValueError(f"{over} (a shorter t_end or a coarser every, or a larger budget: in config.yaml's "
                         f"budget: with --config)")
    return e


def extend(path: str | os.PathLike, t_end: float, out: str | os.PathLike | None = None, every: float | None = None,
           chunk_bytes: int = DEFAULT_CHUNK_BYTES, progress: Callable[[float, float], None] | None = None,
           budget: Budget | None = None) -> dict:
    """Continue the exact run stored in ``path`` to ``t_end`` and append (to ``out``, default ``path``).

    New output times: the grid k * ``every`` (default: the median spacing of the stored times,
    rounded to 1e-9 as :func:`cradle.pipeline.config.store_times` rounds) beyond the last stored time, and
    t_end. The step is the file's ``dt`` and the drift reference its energy at t = 0, so with a
    splitting method the result equals one run to t_end bitwise (same grid). Attributes updated:
    t_end, energy_drift (max over both parts), n_steps, n_force_evals, max_compression, wall_time_s,
    n_onset_corrections; ``extended`` records the history. Raises ValueError naming the value for
    an adaptive integrator, t_end <= the last stored time, a file without x/v, or a cost over ``budget``
    (:func:`estimate`, checked before any work).
    """
    from cradle.integrators import SPLITTING_METHODS
    from cradle.scenes.times import store_times

    path = Path(path)
    out = path if out is None else Path(out)
    verify_file(path)  # every checksum, before anything is written (DamagedOutput: one line)
    estimate(path, t_end, every, budget)   # every bound and the budget, from the header, before any work
    with xr.open_dataset(path) as ds:
        missing = [k for k in VARS if k not in ds]
        if missing:
            raise ValueError(f"{path}: not an exact run of (nc) (no {', '.join(missing)}): cannot extend it")
        a: dict[str, Any] = dict(ds.attrs)
        method = a.get("integrator")
        if method not in SPLITTING_METHODS:
            raise ValueError(f"{path}: integrator={method!r} is adaptive; extending needs a fixed-step splitting "
                             f"{SPLITTING_METHODS} (rerun the scene to the later t_end instead)")
        dt = float(a.get("dt_nominal", a["dt"]))  # the step bound the run was made with
        alpha, bc = float(a["alpha"]), str(a["bc"])
        t = ds["t"].values
        t_last = float(t[-1])
        if not t_end > t_last + TIME_TOL:
            raise ValueError(f"t_end={t_end!r} must be > the last stored time t={t_last!r} of {path}")
        every = _infer_every(t) if every is None else float(every)
        if not every > 0:
            raise ValueError(f"every must be > 0, got every={every!r}")
        grid = np.asarray(store_times(None, every, t_end), dtype=float)
        new = np.concatenate(([t_last], grid[grid > t_last + TIME_TOL]))
        x, v = ds["x"].values[-1], ds["v"].values[-1]
        H0 = float(ds["energy"].values[0])
        prefix = ds[list(VARS)]
        s = stream_lattice(x, v, new, out if out != path else path.with_name(path.name + ".extending"),
                           alpha=alpha, bc=bc, method=method, dt=dt, t0=t_last, energy0=H0, prefix=prefix,
                           chunk_bytes=chunk_bytes, progress=progress)
    # the old run's statistics and the new part's combine into those of one run
    stamp = _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds")
    attrs = {k: val for k, val in a.items()}
    attrs.update({
        "t_end": float(new[-1]),
        "dt": max(float(a["dt"]), s["dt"]) if isinstance(a.get("dt"), (int, float, np.floating)) else s["dt"],
        "dt_nominal": dt,
        "energy_drift": max(float(a.get("energy_drift", 0.0)), s["energy_drift"]),
        "n_steps": int(a.get("n_steps", 0)) + s["n_steps"],
        "n_force_evals": int(a.get("n_force_evals", 0)) + s["n_force_evals"],
        "max_compression": max(float(a.get("max_compression", 0.0)), s["max_compression"]),
        "wall_time_s": float(a.get("wall_time_s", 0.0)) + s["wall_time_s"],
        "n_onset_corrections": int(a.get("n_onset_corrections", 0)) + s["n_onset_corrections"],
        "extended": (str(a.get("extended", "")) + f"; {stamp} t={t_last!r} -> {float(new[-1])!r} "
                     f"({s['n_steps']} steps, dt={dt!r})").lstrip("; "),
        "history": str(a.get("history", "")) + f"\n{stamp} cradle extend {path.name} --t-end {t_end!r}",
    })
    import netCDF4

    tmp = path.with_name(path.name + ".extending") if out == path else out
    with netCDF4.Dataset(tmp, "a") as nc:
        for k in list(nc.ncattrs()):
            nc.delncattr(k)
        from cradle.data.io import _attr_value

        for k, val in attrs.items():
            nc.setncattr(k, _attr_value(val))
    from cradle.data import digests

    digests.record(path if out == path else out, tmp)  # the attributes above changed the file the appender recorded
    if out == path:
        os.replace(tmp, path)
        digests.discard(tmp)
    allowed = a.get("max_energy_drift_allowed")
    summary = {**s, "energy_drift": attrs["energy_drift"], "t_from": t_last, "t_end": float(new[-1]),
               "rows_added": int(new.size - 1), "path": str(out)}
    if isinstance(allowed, (int, float, np.floating)) and not attrs["energy_drift"] <= float(allowed):
        raise ValueError(f"{out}: written, but the relative energy drift {attrs['energy_drift']:.3e} exceeds "
                         f"max_energy_drift_allowed = {float(allowed):.1e}")
    return summary
