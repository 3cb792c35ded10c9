"""Extremes at full size (issue 6): long runs, big chains, alpha -> 1+, tiny and huge amplitudes.

Each case runs in its own subprocess, so that its peak resident memory
(resource.getrusage ru_maxrss, numba and the libraries included) is its own,
and prints one JSON line; the parent prints a table. Lattice runs use the
default method srkn6c with its default step, stream their 100 stored times
to a netCDF file with an unlimited t (cradle.pipeline.extend.stream_lattice, 64 MiB
chunks), then delete it.

Cases:
  long-t      t = 1e4, N = 200, travelling wave q = pi/5, omega_tw = 1.1 (plot6-7 data), 100 snapshots
  extend      the same run to t = 5e3 written as exact.nc, extended to 1e4: bitwise equal to long-t?
  big-N       N = 1e4, t = 1e3, q = pi/5, omega_tw = 1.1, 100 snapshots
  hom-1.01    alpha = 1.01 site homoclinic, ring N chosen from its decay (16 decades), residual, width
  breather-1.01  alpha = 1.01 breather (amplitude 0.01) from that homoclinic, N = its ring, t = 1e3
  tiny-a      a = 1e-8, N = 50, q = pi/5, t = 1e3: drift and E(t) = |x_app - x|_inf / a against DpS
  omega-1.5   omega_tw = 1.5 (a = 52.9), N = 50, q = pi/5, t = 1e3 (plot1v5st runs to ~100)
  dense-memory   N = 1e4, t = 100, 2001 stored times (every 0.05) held in memory as stages.exact_run
                 does (x, v, force: 480 MB of float64)
  dense-stream   the same streamed in 64 MiB chunks (stream_lattice)

Run time ~1.5 min on one core (the dense cases write a 458 MiB file to the temporary folder):
    python benchmarks/extremes.py [--only CASE ...]
"""
from __future__ import annotations

import argparse
import datetime as _dt
import json
import os
import platform
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

from doctable import publish

HERE = os.path.dirname(os.path.abspath(__file__))
CASES = ("long-t", "extend", "big-N", "hom-1.01", "breather-1.01", "tiny-a", "omega-1.5", "dense-memory",
         "dense-stream")


def _peak_mib() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0   # Linux: KiB


def _tw_stream(N, t_end, omega_tw=None, a=None, q=np.pi / 5, alpha=1.5, keep=None):
    from cradle.models import initial
    from cradle.pipeline.extend import stream_lattice

    d = initial.travelling_wave(N, q, alpha, a=a, omega_tw=omega_tw)
    t = np.linspace(0.0, t_end, 101)
    with tempfile.TemporaryDirectory() as tmp:
        path = keep or os.path.join(tmp, "exact.nc")
        t0 = time.perf_counter()
        s = stream_lattice(d.x0, d.v0, t, path, alpha=alpha, attrs={"alpha": alpha, "bc": "periodic", "N": N})
        wall = time.perf_counter() - t0
        size = os.path.getsize(path) / 2**20
    return d, s, wall, size


def case_long_t():
    d, s, wall, size = _tw_stream(200, 1e4, omega_tw=1.1)
    return {"drift": s["energy_drift"], "steps": s["n_steps"], "dt": s["dt"], "wall_s": wall, "file_MiB": size}


def case_extend():
    """Run to 5e3 (exact.nc), extend to 1e4 with cradle.pipeline.extend.extend, compare with one run to 1e4."""
    from cradle.data import io
    from cradle.models import initial
    from cradle.pipeline.extend import extend, stream_lattice

    d = initial.travelling_wave(200, np.pi / 5, 1.5, omega_tw=1.1)
    t = np.linspace(0.0, 1e4, 101)
    with tempfile.TemporaryDirectory() as tmp:
        one = stream_lattice(d.x0, d.v0, t, os.path.join(tmp, "one.nc"), alpha=1.5,
                             attrs={"alpha": 1.5, "bc": "periodic"})
        half = os.path.join(tmp, "half.nc")
        stream_lattice(d.x0, d.v0, t[:51], half, alpha=1.5, dt=one["dt"],
                       attrs={"alpha": 1.5, "bc": "periodic"})
        t0 = time.perf_counter()
        s = extend(half, 1e4, every=100.0)
        wall = time.perf_counter() - t0
        a, b = io.open_dataset(half), io.open_dataset(os.path.join(tmp, "one.nc"))
        same = bool(np.array_equal(a["x"].values, b["x"].values) and np.array_equal(a["v"].values, b["v"].values))
        return {"drift": float(a.attrs["energy_drift"]), "drift_one_run": one["energy_drift"], "bitwise": same,
                "wall_s": wall, "steps": s["n_steps"]}


def case_big_n():
    d, s, wall, size = _tw_stream(10_000, 1e3, omega_tw=1.1)
    return {"drift": s["energy_drift"], "steps": s["n_steps"], "dt": s["dt"], "wall_s": wall, "file_MiB": size}


def case_hom():
    from cradle.models import homoclinic, homoclinic_continuation, homoclinic_tails

    t0 = time.perf_counter()
    sol, N = homoclinic_continuation.solve_sized("site", 1.01, decades=16)
    wall = time.perf_counter() - t0
    L = homoclinic_tails.log10_abs_scaled(sol)
    a = sol.a
    res = float(np.max(np.abs(homoclinic.residual(a, 1.01)))) / float(np.max(np.abs(a)))
    return {"N": N, "residual": res, "profile_residual": sol.residual, "nu": sol.nu,
            "log10_max_a": sol.log10_scale, "width8": homoclinic_tails.decay_sites(L, 8),
            "width16": homoclinic_tails.decay_sites(L, 16), "log10_tail_min": float(np.min(L)), "wall_s": wall}


def case_breather():
    from cradle.models import homoclinic_continuation, initial
    from cradle.pipeline.extend import stream_lattice

    sol, N = homoclinic_continuation.solve_sized("site", 1.01, decades=16)
    d = initial.breather(sol.profile, 1.01, amplitude=0.01)
    t = np.linspace(0.0, 1e3, 101)
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        s = stream_lattice(d.x0, d.v0, t, os.path.join(tmp, "b.nc"), alpha=1.01,
                           attrs={"alpha": 1.01, "bc": "periodic"})
        wall = time.perf_counter() - t0
    return {"N": N, "drift": s["energy_drift"], "steps": s["n_steps"], "omega_sw": d.info["omega_sw"],
            "wall_s": wall}


def case_tiny():
    from cradle.integrators import integrate_dps, integrate_lattice
    from cradle.measurements import compare
    from cradle.models import initial, lattice

    d = initial.travelling_wave(50, np.pi / 5, 1.5, a=1e-8)
    t = np.linspace(0.0, 1e3, 101)
    t0 = time.perf_counter()
    s = integrate_lattice(d.x0, d.v0, t, alpha=1.5, method="srkn6c")
    wall = time.perf_counter() - t0
    A = integrate_dps(d.A0, d.eps**0.5 * t, alpha=1.5).A
    E = compare.relative_error(s.x, compare.approximate_displacement(A, t, d.eps), 1e-8)
    return {"drift": s.energy_drift, "E_max": float(E.max()), "E_max/a^0.5": float(E.max() / 1e-4),
            "max_force": float(np.max(np.abs(lattice.bond_forces(s.x, 1.5)))), "steps": s.n_steps, "wall_s": wall}


def case_omega15():
    d, s, wall, size = _tw_stream(50, 1e3, omega_tw=1.5)
    return {"a": d.info["a"], "drift": s["energy_drift"], "steps": s["n_steps"], "dt": s["dt"],
            "max_compression": s["max_compression"], "wall_s": wall}


def case_dense_memory():
    from cradle.integrators import integrate_lattice
    from cradle.models import initial, lattice

    d = initial.travelling_wave(10_000, np.pi / 5, 1.5, omega_tw=1.1)
    t = np.round(np.arange(2001) * 0.05, 9)
    t0 = time.perf_counter()
    s = integrate_lattice(d.x0, d.v0, t, alpha=1.5, method="srkn6c")
    force = lattice.bond_forces(s.x, 1.5)
    wall = time.perf_counter() - t0
    return {"drift": s.energy_drift, "stored_MiB": (s.x.nbytes + s.v.nbytes + force.nbytes) / 2**20, "wall_s": wall}


def case_dense_stream():
    from cradle.models import initial
    from cradle.pipeline.extend import stream_lattice

    d = initial.travelling_wave(10_000, np.pi / 5, 1.5, omega_tw=1.1)
    t = np.round(np.arange(2001) * 0.05, 9)
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "dense.nc")
        t0 = time.perf_counter()
        s = stream_lattice(d.x0, d.v0, t, path, alpha=1.5, attrs={"alpha": 1.5, "bc": "periodic"})
        wall = time.perf_counter() - t0
        size = os.path.getsize(path) / 2**20
    return {"drift": s["energy_drift"], "file_MiB": size, "chunk_rows": s["chunk_rows"], "wall_s": wall}


RUN = {"long-t": case_long_t, "extend": case_extend, "big-N": case_big_n, "hom-1.01": case_hom,
       "breather-1.01": case_breather, "tiny-a": case_tiny, "omega-1.5": case_omega15,
       "dense-memory": case_dense_memory, "dense-stream": case_dense_stream}


def child(name):
    t0 = time.perf_counter()
    out = RUN[name]()
    out["total_s"] = time.perf_counter() - t0
    out["peak_RSS_MiB"] = _peak_mib()
    print(json.dumps({"case": name, **out}, default=float))


def fmt(v):
    if isinstance(v, bool):
        return str(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return f"{v:.3g}"
    return str(v)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--only", nargs="*", choices=CASES)
    p.add_argument("--child", choices=CASES, help=argparse.SUPPRESS)
    p.add_argument("--no-docs", action="store_true", help="do not write the table into docs/extremes.md")
    args = p.parse_args(argv)
    if args.child:
        child(args.child)
        return 0
    rows = []
    for name in args.only or CASES:
        r = subprocess.run([sys.executable, __file__, "--child", name], capture_output=True, text=True)
        if r.returncode != 0:
            rows.append({"case": name, "error": r.stderr.strip().splitlines()[-1] if r.stderr else "failed"})
        else:
            rows.append(json.loads(r.stdout.strip().splitlines()[-1]))
        print(f"{name}: " + ", ".join(f"{k}={fmt(v)}" for k, v in rows[-1].items() if k != "case"), flush=True)
    lines = [f"`python benchmarks/extremes.py`: {_dt.date.today()}, {platform.machine()} with {os.cpu_count()} cores, "
             f"Python {platform.python_version()}, each case in its own process", "",
             "| case | drift / residual | peak RSS (MiB) | wall (s) | other |", "|---|---|---|---|---|"]
    for r in rows:
        acc = r.get("drift", r.get("residual", r.get("error")))
        other = ", ".join(f"{k}={fmt(v)}" for k, v in r.items()
                          if k not in ("case", "drift", "residual", "peak_RSS_MiB", "total_s", "error"))
        rss, wall = fmt(r.get("peak_RSS_MiB", "")), fmt(r.get("total_s", ""))
        lines.append(f"| {r['case']} | {fmt(acc)} | {rss} | {wall} | {other} |")
    print("\n" + "\n".join(lines))
    if not (args.only or args.no_docs):  # a partial run does not replace the published table
        publish("extremes.md", "extremes", "\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
