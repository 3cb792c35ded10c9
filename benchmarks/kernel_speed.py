"""Speed of every integrator and every combination of model terms a scene uses: this checkout against another.

Each case is one call of the public API (``integrate_lattice`` / ``integrate_dps``) on the fft106 travelling wave
(q = 4 pi/5, omega_tw = 1.1, N beads; for the DpS cases its slow amplitudes), the terms given as a scene gives them
(``terms=Terms(...)``, ``damping=Damping(...)``, ``sites=...``). A child process imports one checkout's ``src``,
makes a warm-up call (compilation and cache loads are not counted), then times ``CALLS`` calls in CPU time of the
process (``time.process_time``: the machine is shared) and keeps the best; it prints that time and a SHA-256 of the
final state. The parent alternates the two checkouts ``--repeats`` times per case (before, now, before, now, ...) and
reports the median of the paired ratios now/before, and whether every process of both checkouts gave the same bits.

    python benchmarks/kernel_speed.py BEFORE_SRC [--repeats 5] [--cases srkn6c,dop853_numba] [--table FILE]

The floor: a bare compiled loop of the Hertz force (alpha = 3/2) and its assembly into net forces, per bead and
evaluation, measured in the "now" child; a method's cost per bead and force evaluation over that floor is its ratio
to the floor (srkn6c: forces of several stages per step; dop853_numba: 12 stages per step plus error control).
"""
from __future__ import annotations

import argparse
import datetime as dt
import json
import os
import platform
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: case -> (model, method, keyword arguments as Python source evaluated in the child, t_end)
CASES: dict[str, tuple[str, str, str, float]] = {
    # the paper's lattice (nc): every integrator
    "srkn6c": ("nc", "srkn6c", "{}", 3000.0),
    "srkn4c": ("nc", "srkn4c", "{}", 2000.0),
    "srkn6": ("nc", "srkn6", "{}", 250.0),
    "srkn4": ("nc", "srkn4", "{}", 150.0),
    "strang": ("nc", "strang", "{}", 50.0),
    "dop853_numba": ("nc", "dop853_numba", "{'rtol': 1e-10}", 750.0),
    "scipy-dop853": ("nc", "dop853", "{'rtol': 1e-8}", 100.0),
    "scipy-rk45": ("nc", "rk45", "{'rtol': 1e-6}", 500.0),
    "scipy-lsoda": ("nc", "lsoda", "{'rtol': 1e-8}", 150.0),
    "scipy-radau": ("nc", "radau", "{'rtol': 1e-6}", 3.0),
    "smooth-srkn6c": ("nc", "srkn6c", "{'potential': 'smooth'}", 2000.0),
    "alpha2-srkn6c": ("nc2", "srkn6c", "{}", 300.0),
    # damping (ncdamped): the dissipation and desk-toy analyses
    "damped-onsite": ("nc", "dop853_numba", "{'rtol': 1e-10, 'damping': Damping(onsite=1e-3)}", 500.0),
    "damped-contact": ("nc", "dop853_numba", "{'rtol': 1e-10, 'damping': Damping(contact=1e-2)}", 400.0),
    "damped-both": ("nc", "dop853_numba", "{'rtol': 1e-10, 'damping': Damping(onsite=1e-3, contact=1e-2)}", 400.0),
    # the imperfect cradle (ncimperfect): jkc-variants, disorder, trapping
    "terms-quartic": ("nc", "dop853_numba",
                      "{'rtol': 1e-10, 'terms': Terms(onsite=OnSite(potential='quartic', beta=-1.0))}", 400.0),
    "terms-pendulum": ("nc", "dop853_numba",
                       "{'rtol': 1e-10, 'terms': Terms(onsite=OnSite(potential='pendulum', scale=0.1))}", 250.0),
    "terms-precompression": ("nc", "dop853_numba",
                             "{'rtol': 1e-10, 'terms': Terms(precompression=Precompression(delta0=0.05))}", 1500.0),
    "terms-disorder": ("nc", "dop853_numba",
                       "{'rtol': 1e-10, 'terms': Terms(inhomogeneity=Inhomogeneity(sigma=0.05, seed=1))}", 100.0),
    "terms-disorder-damped": ("nc", "dop853_numba",
                              "{'rtol': 1e-10, 'terms': Terms(inhomogeneity=Inhomogeneity(sigma=0.05, seed=1)), "
                              "'damping': Damping(onsite=1e-3, contact=1e-2)}", 50.0),
    # the DpS equation (dfnls) and its variants
    "dps-dop853_numba": ("dps", "dop853_numba", "{}", 800.0),
    "dps-scipy-dop853": ("dps", "dop853", "{}", 400.0),
    "dps-damped": ("dps", "dop853_numba", "{'damping': DpsDamping(gamma=1e-2, eta=1e-2)}", 2000.0),
    "dps-sites": ("dps", "dop853_numba", "{'sites': dps_sites(*_disorder(N), alpha=1.5, eps=eps)}", 200.0),
}

CHILD = r"""
import hashlib, json, sys, time
import numpy as np
from cradle.integrators import integrate_dps, integrate_lattice
from cradle.models import initial
from cradle.models.damping import Damping
from cradle.models.dps_damped import DpsDamping
from cradle.models.dps_sites import dps_sites
from cradle.models.inhomogeneity import Inhomogeneity, sites as _sites
from cradle.models.lattice_terms import Terms
from cradle.models.onsite import OnSite
from cradle.models.precompression import Precompression

model, method, kwargs, T, N, calls, floor = (sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4]),
                                             int(sys.argv[5]), int(sys.argv[6]), sys.argv[7] == "1")


def _disorder(n):
    s = _sites(Inhomogeneity(sigma=0.05, seed=1), n)
    return s.mass, s.omega, s.stiffness


alpha = 2.0 if model == "nc2" else 1.5
d = initial.travelling_wave(N, 4 * np.pi / 5, alpha, omega_tw=1.1)
eps = float(np.max(np.abs(d.x0))) / 2.0
kw = eval(kwargs)
if model == "dps":
    A0 = (d.x0 - 1j * d.v0) / (2.0 * eps)
    run = lambda t: integrate_dps(A0, np.array([0.0, t]), alpha=alpha, method=method, **kw)
    final = lambda s: s.A[-1]
else:
    run = lambda t: integrate_lattice(d.x0, d.v0, np.array([0.0, t]), alpha=alpha, method=method, **kw)
    final = lambda s: np.concatenate([s.x[-1], s.v[-1]])
run(min(1.0, T))   # warm-up: compilation and cache loads
best = None
for _ in range(calls):
    t0 = time.process_time()
    sol = run(T)
    spent = time.process_time() - t0
    best = spent if best is None else min(best, spent)
evals = getattr(sol, "n_force_evals", None) or getattr(sol, "n_rhs_evals", None)
out = {"cpu_s": best, "sha256": hashlib.sha256(np.ascontiguousarray(final(sol)).tobytes()).hexdigest(),
       "evals": int(evals) if evals else None}
if floor:
    from numba import njit

    @njit(cache=False)
    def loop(x, f, F, reps):
        n = x.shape[0]
        for _ in range(reps):
            for i in range(n - 1):
                c = max(x[i] - x[i + 1], 0.0)
                f[i] = -c * np.sqrt(c)
            c = max(x[n - 1] - x[0], 0.0)
            f[n - 1] = -c * np.sqrt(c)
            F[0] = f[0] - f[n - 1]
            for i in range(1, n):
                F[i] = f[i] - f[i - 1]
        return F[0]

    x = np.ascontiguousarray(d.x0)
    f = np.empty(N)
    F = np.empty(N)
    loop(x, f, F, 1)
    reps = 200_000
    fl = None
    for _ in range(5):
        t0 = time.process_time()
        loop(x, f, F, reps)
        spent = time.process_time() - t0
        fl = spent if fl is None else min(fl, spent)
    out["floor_ns_per_bead_eval"] = fl / (reps * N) * 1e9
print(json.dumps(out))
"""


def child(src: Path, case: str, N: int, calls: int, floor: bool) -> dict:
    model, method, kwargs, T = CASES[case]
    env = dict(os.environ, PYTHONPATH=str(src), NUMBA_NUM_THREADS="1", OMP_NUM_THREADS="1")
    done = subprocess.run([sys.executable, "-c", CHILD, model, method, kwargs, str(T), str(N), str(calls),
                           "1" if floor else "0"], env=env, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise SystemExit(f"{case} with {src}: the child failed:\n{done.stderr[-2000:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("before", type=Path, help="the src folder of the checkout to compare against")
    ap.add_argument("--now", type=Path, default=ROOT / "src", help="the src folder measured (default: this one)")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--calls", type=int, default=3)
    ap.add_argument("--N", type=int, default=200)
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--table", type=Path, help="write the markdown table here (default: print it)")
    args = ap.parse_args()
    cases = args.cases.split(",")
    unknown = [c for c in cases if c not in CASES]
    if unknown:
        raise SystemExit(f"--cases: unknown {', '.join(unknown)} (known: {', '.join(CASES)})")
    rows = []
    floor = None
    for case in cases:
        before, now, hashes = [], [], set()
        for _ in range(args.repeats):
            b = child(args.before, case, args.N, args.calls, False)
            n = child(args.now, case, args.N, args.calls, floor is None and case in ("srkn6c", "dop853_numba"))
            floor = n.get("floor_ns_per_bead_eval", floor)
            before.append(b["cpu_s"])
            now.append(n["cpu_s"])
            hashes |= {b["sha256"], n["sha256"]}
        ratios = [x / y for x, y in zip(now, before, strict=True)]
        per = statistics.median(now) / (n["evals"] * args.N) * 1e9 if n["evals"] else None
        rows.append((case, statistics.median(before), statistics.median(now), statistics.median(ratios),
                     min(ratios), max(ratios), len(hashes) == 1, per))
        print(f"{case}: before {rows[-1][1]:.4f} s, now {rows[-1][2]:.4f} s, now/before median "
              f"{rows[-1][3]:.3f} [{rows[-1][4]:.3f}, {rows[-1][5]:.3f}], bitwise {rows[-1][6]}", flush=True)
    lines = [f"`python benchmarks/kernel_speed.py` ({dt.date.today()}, {platform.machine()}, "
             f"{os.cpu_count()} cores, Python {platform.python_version()}; N = {args.N}, best of {args.calls} calls "
             f"per process in CPU time, {args.repeats} alternating process pairs per case)", "",
             "| case | before [s] | now [s] | now/before (median of pairs) | min-max | same bits | "
             "ns / (bead x eval) | / floor |", "|---|---:|---:|---:|---|---|---:|---:|"]
    for case, b, n, r, lo, hi, same, per in rows:
        ratio = f"{per / floor:.2f}" if per and floor else ""
        lines.append(f"| {case} | {b:.4f} | {n:.4f} | {r:.3f} | {lo:.3f}-{hi:.3f} | {'yes' if same else 'NO'} | "
                     f"{per:.2f} | {ratio} |" if per else
                     f"| {case} | {b:.4f} | {n:.4f} | {r:.3f} | {lo:.3f}-{hi:.3f} | {'yes' if same else 'NO'} | | |")
    if floor:
        lines += ["", f"Floor: a bare compiled Hertz force loop with its net-force assembly, {floor:.2f} ns per bead "
                      "and evaluation in the same kind of process."]
    text = "\n".join(lines) + "\n"
    if args.table:
        args.table.write_text(text)
    print(text)
    return 0 if all(r[6] for r in rows) else 1


if __name__ == "__main__":
    raise SystemExit(main())
