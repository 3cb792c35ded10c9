"""A scene's job in bounded memory: the (nc) and DpS runs and their metrics, block by block.

The in-memory job (:func:`cradle.pipeline.runner.run_chain` of
:mod:`cradle.scenes.stages`) holds every stored time of both runs until its four files are
written; its peak memory grows with N x (number of stored times). This job computes the same
four files in blocks of stored times (:func:`cradle.data.appending.chunk_rows` of
``chunk_bytes``) and appends each block to its file, so what it holds is one block plus a few
numbers per stored time, whatever the store:

* the exact run continues from block to block with the run's step and energy reference
  (``integrate_lattice(..., t0=, energy0=, dt=)``: a fixed-step splitting covers each interval
  between stored times with the same steps either way); when the compression exceeds the one the
  default step was set for, the run restarts with a larger one, as ``integrate_lattice`` reruns;
* the DpS run continues with the stepper's state (:func:`cradle.integrators.dps_solver.iter_dps`);
* the metrics of every stored time are those of :func:`cradle.scenes.stages.metrics` on the
  block (with the row t = 0 in front, from which they take their scale, site and core); the ones
  over the whole run are accumulated: the peak compression per breather period, the merging
  time and outcome of a pair, a breather's frequencies and half-period shift, E_max and E_final.

So the files hold bitwise the values of the in-memory job (``tests/pipeline/test_streamed.py``);
only their HDF5 chunking, ``wall_time_s`` and the ``streamed`` attribute differ. The four files
are renamed into place only after all blocks succeeded (the initial data last): a failure or an
interrupt leaves none of them. Which job a scene gets is decided by
:func:`cradle.pipeline.budget.streams`.
"""
from __future__ import annotations

import logging
import time
from collections.abc import Callable
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from cradle.data.appending import DEFAULT_CHUNK_BYTES, Appender, chunk_rows
from cradle.data.io import GLOBAL_KEYS, make_dataset, write_netcdf
from cradle.data.provenance import provenance
from cradle.measurements import breathers, interactions
from cradle.models import lattice
from cradle.scenes import stages
from cradle.scenes.failure import StageFailure
from cradle.scenes.spec import Scene
from cradle.specs.declare import plain

#: float64 arrays of N values held per stored time of a block (both runs, their forces, the
#: metrics' spectra and FFTs): the block size follows from ``chunk_bytes``
BLOCK_ARRAYS = 16

#: metrics variables without t that this job computes over the whole run (the others are per stored time)
WHOLE_RUN = ("breather_omega", "peak_compression_exact", "peak_compression_dps", "merging_time_exact",
             "merging_time_dps", "first_coalescence_exact", "first_coalescence_dps", "outcome_exact", "outcome_dps",
             "breather_site", "omega_exact", "omega_approx", "half_shift_periods")


class _Peaks:
    """Running peak compression max |f_n| per breather period [t_0 + k period, t_0 + (k+1) period)
    (:func:`cradle.measurements.breathers.peak_compression`'s windows, over the whole run)."""

    def __init__(self, times: np.ndarray, period: float, N: int) -> None:
        self.t0, self.period = float(times[0]), float(period)
        self.K = int(np.floor((times[-1] - times[0]) / period + 1e-9))
        self.starts: np.ndarray = self.t0 + period * np.arange(self.K)
        self.P: NDArray[np.float64] = np.full((self.K, N), np.nan)

    def add(self, t: np.ndarray, force: np.ndarray) -> None:
        k = np.floor((np.asarray(t) - self.t0) / self.period + 1e-9).astype(int)
        f = np.abs(force)
        for i in np.unique(k[k < self.K]):
            rows = f[k == i].max(axis=0)
            self.P[i] = np.where(np.isnan(self.P[i]), rows, np.maximum(self.P[i], rows))


class _Run:
    """The exact and DpS runs of one attempt, block by block, and the three files they fill."""

    def __init__(self, spec: Scene, init_ds: xr.Dataset, name: str, outs: dict, rows: int, dt: float,
                 c_assumed: float | str) -> None:
        self.spec, self.init_ds, self.name, self.outs = spec, init_ds, name, outs
        self.rows, self.dt, self.c_assumed = rows, dt, c_assumed
        self.files: dict[str, Appender] = {}

    def abort(self) -> None:
        for f in self.files.values():
            f.abort()


def simulate_streamed(spec: Scene, init_ds: xr.Dataset, name: str, outs: dict, *,
                      chunk_bytes: int = DEFAULT_CHUNK_BYTES, progress: Callable[[float, float], None] | None = None,
                      log: logging.Logger | None = None) -> dict:
    """Write the scene's four files (``outs``: initial, exact, dps, metrics paths) block by block.

    ``init_ds``: the scene's initial data (:func:`cradle.scenes.stages.initial_data`). The exact
    method must be a fixed-step splitting and the DpS method ``dop853_numba``
    (:func:`cradle.pipeline.budget.streams` says which scenes qualify). ``progress(t, t_end)`` is
    called after every block. Returns the run's summary (rows, blocks, energy drift, wall time).
    Raises :class:`~cradle.pipeline.runner.StageFailure` (nothing written) on a blow-up or an energy
    drift above ``max_energy_drift``.
    """
    from cradle.integrators import MAX_RERUNS, compression_bounds, default_dt
    from cradle.models.lattice import DEFAULT_DT_FACTOR

    wall0 = time.perf_counter()
    method = spec.exact.method
    x0, v0 = init_ds["x0"].values, init_ds["v0"].values
    fac = spec.exact.dt_factor or DEFAULT_DT_FACTOR[method]
    c_assumed, c_energy = compression_bounds(x0, v0, spec.alpha, spec.bc)
    rows = chunk_rows(spec.N, chunk_bytes, BLOCK_ARRAYS)
    n_reruns = 0
    while True:  # as integrate_lattice: rerun with a larger compression while the assumed one is exceeded
        run = _Run(spec, init_ds, name, outs, rows, default_dt(c_assumed, spec.alpha, method, fac), c_assumed)
        try:
            # this attempt's c_assumed and n_reruns, bound
            summary = _attempt(run, progress,
                               lambda cmax, c_assumed=c_assumed, n_reruns=n_reruns:  # type: ignore[misc]
                               not (cmax <= c_assumed * (1.0 + 1e-12) or c_assumed >= c_energy
                                    or n_reruns >= MAX_RERUNS))
        except BaseException:
            run.abort()
            raise
        if summary.get("restart"):
            run.abort()
            c_assumed = min(1.5 * summary["restart"], c_energy)
            n_reruns += 1
            if log is not None:
                log.info("%s: compression %.4g above the assumed one: restarting with c = %.4g", name,
                         summary["restart"], c_assumed)
            continue
        break
    try:
        for key in ("exact", "dps", "metrics"):
            run.files[key].commit()
        write_netcdf(init_ds, outs["initial"])  # last: the job is done only when its initial data is there
    except BaseException:
        run.abort()
        raise
    summary.update({"n_reruns": n_reruns, "wall_time_s": time.perf_counter() - wall0})
    return summary


def _attempt(run: _Run, progress: Callable[[float, float], None] | None, exceeded: Callable[[float], bool]) -> dict:
    """Integrate both models block by block into ``run.files``; returns the summary, or
    {"restart": cmax} as soon as ``exceeded(cmax)`` says the default step was set too large."""
    from cradle.integrators import integrate_lattice
    from cradle.integrators.dps_solver import iter_dps

    spec, init_ds, name = run.spec, run.init_ds, run.name
    params = plain(spec)
    alpha, bc, N = spec.alpha, spec.bc, spec.N
    times = np.asarray(spec.times, dtype=float)
    eps = float(init_ds.attrs["eps"])
    A0 = init_ds["A0_re"].values + 1j * init_ds["A0_im"].values
    dps_blocks = iter_dps(A0, eps ** (alpha - 1.0) * times, run.rows, alpha=alpha, bc=bc,
                          rtol=spec.dps.rtol)
    kind = init_ds.attrs.get("initial_kind")
    localised = kind in stages.LOCALISED_KINDS
    if localised:
        omega = float(init_ds.attrs["omega_sw"]) if "omega_sw" in init_ds.attrs else stages.PACKET_OMEGA
        peaks = {m: _Peaks(times, 2.0 * np.pi / omega, N) for m in ("exact", "dps")}
        site_peaks = {m: _Peaks(times, 2.0 * np.pi / omega, N) for m in ("exact", "dps")}  # max_t |x_n| (pairs)
    x, v = init_ds["x0"].values.copy(), init_ds["v0"].values.copy()
    H0, t_cur = None, float(times[0])
    stats = {"energy_drift": 0.0, "n_steps": 0, "n_force_evals": 0, "max_compression": 0.0,
             "n_onset_corrections": 0, "wall_time_s": 0.0}
    dps_stats = {"n_steps": 0, "wall_time_s": 0.0}
    E_max = -np.inf
    site_series: dict[str, list[np.ndarray]] = {"exact": [], "dps": []}
    first: dict[str, xr.Dataset] = {}
    for start in range(0, times.size, run.rows):
        tb = times[start:start + run.rows]
        sol = integrate_lattice(x, v, tb, alpha=alpha, bc=bc, method=spec.exact.method, dt=run.dt,
                                t0=t_cur, energy0=H0)
        if exceeded(sol.max_compression):
            return {"restart": sol.max_compression}
        H0 = float(sol.energy[0]) if H0 is None else H0
        stats["energy_drift"] = max(stats["energy_drift"], sol.energy_drift)
        stats["max_compression"] = max(stats["max_compression"], sol.max_compression)
        for k in ("n_steps", "n_force_evals", "n_onset_corrections"):
            stats[k] += int(getattr(sol, k))
        stages.check_finite(name, "exact", {"x": sol.x, "v": sol.v}, None, start)
        exact_ds = make_dataset({"x": sol.x, "v": sol.v, "force": lattice.bond_forces(sol.x, alpha, bc),
                                 "energy": sol.energy}, coords={"t": tb, "n": np.arange(N)},
                                attrs=dict(init_ds.attrs), params=params, title=stages.exact_title(name),
                                identity=("exact", name))
        dsol = next(dps_blocks)
        stages.check_finite(name, "dps", {"A": dsol.A}, None, start)
        stats["wall_time_s"] += sol.wall_time_s
        dps_stats["n_steps"] += dsol.n_steps
        dps_stats["wall_time_s"] += dsol.wall_time_s
        dps_ds = stages.dps_dataset(spec, init_ds, name, tb, dsol)
        if start == 0:
            first = {"exact": exact_ds.isel(t=[0]), "dps": dps_ds.isel(t=[0])}
        # per stored time: the in-memory metrics on the block, after the row t = 0 (scale, site, core)
        with_first = {m: (ds if start == 0 else xr.concat([first[m], ds], dim="t", data_vars="minimal",
                                                          coords="minimal", compat="override",
                                                          combine_attrs="override"))
                      for m, ds in (("exact", exact_ds), ("dps", dps_ds))}
        met = stages.metrics(spec, with_first["exact"], with_first["dps"], name)
        if start:
            met = met.isel(t=slice(1, None))
        E_max = max(E_max, float(np.max(met["E"].values)))
        if localised:
            for m, ds in (("exact", exact_ds), ("dps", dps_ds)):
                peaks[m].add(tb, ds["force"].values)
                if kind == "pair":
                    site_peaks[m].add(tb, ds["x"].values)
            if kind == "breather":
                site = int(np.argmax(np.abs(first["exact"]["x"].values[0])))
                for m, ds in (("exact", exact_ds), ("dps", dps_ds)):
                    site_series[m].append(ds["x"].values[:, site])
        for key, ds in (("exact", exact_ds), ("dps", dps_ds), ("metrics", met)):
            if key in run.files:
                run.files[key].append_block(ds)
            else:  # the variables over the whole run get their final shape now, their values at the end
                run.files[key] = Appender(run.outs[key],
                                          _whole_run_shapes(ds, peaks) if localised and key == "metrics" else ds)
        x, v, t_cur = sol.x[-1].copy(), sol.v[-1].copy(), float(tb[-1])
        if progress is not None:
            progress(t_cur, float(times[-1]))
    # whole-run values: exact and DpS statistics, then the metrics over every stored time
    streamed = f"block by block, {run.rows} stored times per block (cradle.scenes.streamed)"
    exact_attrs = stages.exact_attrs(spec, init_ds, spec.exact.method, stages.steps_taken(times, run.dt)[0],
                                     run.dt, None, None, stats)
    exact_attrs.update({"streamed": streamed, "c_assumed": run.c_assumed})
    run.files["exact"].set_attrs({k: v for k, v in exact_attrs.items() if k not in GLOBAL_KEYS})
    run.files["dps"].set_attrs({"max_l2_drift": dsol.max_l2_drift, "max_dps_energy_drift": dsol.max_energy_drift,
                                **dps_stats, "streamed": streamed})
    values: dict[str, Any] = {}
    attrs = {"E_max": E_max, "E_final": float(met["E"].values[-1]), "t_final": float(times[-1]), "streamed": streamed}
    if localised:
        period = peaks["exact"].period
        for m in ("exact", "dps"):
            values[f"peak_compression_{m}"] = peaks[m].P
        if kind == "pair":
            periodic = spec.bc == "periodic"
            for m in ("exact", "dps"):
                oc = interactions.classify_peaks(site_peaks[m].starts, site_peaks[m].P, periodic=periodic)
                values[f"merging_time_{m}"] = oc.merge_period
                values[f"first_coalescence_{m}"] = oc.first_coalescence
                values[f"outcome_{m}"] = np.int64(oc.code)
        elif kind == "breather":
            sh = breathers.half_period_shift(times, np.concatenate(site_series["exact"]),
                                             np.concatenate(site_series["dps"]), 2.0 * np.pi / period)
            values.update({"omega_exact": sh["omega_exact"], "omega_approx": sh["omega_approx"],
                           "half_shift_periods": sh["half_shift_periods"]})
    unknown = [str(k) for k in met.data_vars if "t" not in met[k].dims and k not in WHOLE_RUN]
    if unknown:  # a metric over the whole run that this job does not accumulate: refuse rather than mislead
        raise StageFailure(f"scene '{name}': the streamed job cannot compute {', '.join(unknown)} over the run")
    run.files["metrics"].set_values(values)
    run.files["metrics"].set_attrs(attrs)
    prov = provenance(params)
    for f in run.files.values():
        f.set_attrs(prov)
    if not stats["energy_drift"] <= spec.max_energy_drift:
        raise StageFailure(f"scene '{name}' (exact): relative energy drift {stats['energy_drift']:.3e} exceeds "
                           f"max_energy_drift = {spec.max_energy_drift:.1e} ({spec.exact.method}, "
                           f"dt={exact_attrs['dt']})")
    return {"rows": int(times.size), "blocks": -(-times.size // run.rows), "rows_per_block": run.rows,
            "energy_drift": stats["energy_drift"]}


def _whole_run_shapes(met: xr.Dataset, peaks: dict) -> xr.Dataset:
    """The first block's metrics with the peak compression over the whole run's periods (NaN until
    :meth:`Appender.set_values` writes them at the end)."""
    out = met.drop_dims("t_window")
    starts = peaks["exact"].starts
    out = out.assign_coords(t_window=("t_window", starts, met["t_window"].attrs))
    for m in ("exact", "dps"):
        name = f"peak_compression_{m}"
        out[name] = (met[name].dims, np.full((starts.size,) + met[name].shape[1:], np.nan), met[name].attrs)
    return out
