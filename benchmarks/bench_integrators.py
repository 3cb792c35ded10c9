"""Wall time and accuracy: scipy DOP853 (numpy RHS) vs the splittings srkn6 and srkn6c (numba).

Scenes (periodic, alpha = 3/2, travelling-wave initial data (ansatzapprox)
x_n = a cos(qn), v_n = a omega_tw sin(qn)):

* plot4-5 : N = 50,  q = pi/5,  a = 0.02118 (omega_tw = 1.01), t = 621.95
* q=4pi/5 : N = 200, q = 4pi/5, a = 0.00767 (omega_tw = 1.1),  t = 913.7

Rows: ``solve_ivp(method="DOP853", rtol=1e-10)`` with the vectorised numpy
right-hand side :func:`cradle.models.lattice.acceleration` (the plain baseline,
energy checked at the 1001 outputs only); ``integrate_lattice(method="dop853")``
(same solver, numba RHS, energy after every step); "dop853_numba" (same
pair and controller, whole loop in numba); srkn6 with its default
step and with a 10x coarser one; srkn6c (contact-onset correction) with its
default step. "err" is max_n |x_n(t_f) - x_ref_n(t_f)| / a with x_ref from
srkn6c at dt_factor = 2e-4. One process, JIT warmed up first. For the
matched-accuracy comparison with scipy see bench_vs_scipy.py.

    python benchmarks/bench_integrators.py
"""
from __future__ import annotations

import time

import numpy as np
from scipy.integrate import solve_ivp

from cradle.integrators import DEFAULT_DT_FACTOR, integrate_lattice
from cradle.models import lattice as L

ALPHA = 1.5
SCENES = [
    ("plot4-5 N=50 q=pi/5 a=0.02118", 50, np.pi / 5, 0.02118, 1.01, 621.95),
    ("N=200 q=4pi/5 a=0.00767", 200, 4 * np.pi / 5, 0.00767, 1.1, 913.7),
]
N_OUT = 1001
BUDGET_S = 180.0


def wave(N, q, a, om):
    n = np.arange(N)
    return a * np.cos(q * n), a * om * np.sin(q * n)


def dop853_numpy(x0, v0, t, rtol):
    N = x0.size
    nfev = [0]

    def fun(_t, y):
        nfev[0] += 1
        return np.concatenate((y[N:], L.acceleration(y[:N], ALPHA)))

    amp = max(np.abs(x0).max(), np.abs(v0).max())
    t0 = time.perf_counter()
    sol = solve_ivp(fun, (0.0, t[-1]), np.concatenate((x0, v0)), method="DOP853", t_eval=t,
                    rtol=rtol, atol=rtol * amp)
    wall = time.perf_counter() - t0
    X, V = sol.y[:N].T, sol.y[N:].T
    H = L.hamiltonian(X, V, ALPHA)
    return X, float(np.abs(H - H[0]).max() / H[0]), wall, nfev[0], sol.t.size


def main():
    integrate_lattice(*wave(8, 1.0, 0.1, 1.0), [0.0, 1.0], alpha=ALPHA)  # JIT / cache load
    integrate_lattice(*wave(8, 1.0, 0.1, 1.0), [0.0, 1.0], alpha=ALPHA, method="srkn6c")
    integrate_lattice(*wave(8, 1.0, 0.1, 1.0), [0.0, 1.0], alpha=ALPHA, method="dop853")
    integrate_lattice(*wave(8, 1.0, 0.1, 1.0), [0.0, 1.0], alpha=ALPHA, method="dop853_numba")
    start = time.perf_counter()
    print(f"{'scene':32s} {'method':30s} {'wall [s]':>9s} {'ratio':>7s} {'f-evals':>9s} "
          f"{'ns/bead/feval':>13s} {'energy drift':>12s} {'err/a':>9s}")
    for label, N, q, a, om, tf in SCENES:
        if time.perf_counter() - start > BUDGET_S / 2:
            print(f"{label}: skipped (time budget)")
            continue
        x0, v0 = wave(N, q, a, om)
        t = np.linspace(0.0, tf, N_OUT)
        ref = integrate_lattice(x0, v0, t[[0, -1]], alpha=ALPHA, method="srkn6c", dt_factor=2e-4)
        rows = []
        X, drift, wall, nfev, _ = dop853_numpy(x0, v0, t, 1e-10)
        rows.append(("scipy DOP853 numpy rtol=1e-10", wall, nfev, drift, X[-1]))
        s = integrate_lattice(x0, v0, t, alpha=ALPHA, method="dop853", rtol=1e-10)
        rows.append(("dop853 numba-RHS rtol=1e-10", s.wall_time_s, s.n_force_evals, s.energy_drift, s.x[-1]))
        for rtol in (1e-10, 1e-13):
            s = integrate_lattice(x0, v0, t, alpha=ALPHA, method="dop853_numba", rtol=rtol)
            rows.append((f"dop853_numba rtol={rtol:.0e}", s.wall_time_s, s.n_force_evals, s.energy_drift, s.x[-1]))
        for method, fac, name in (("srkn6", None, "srkn6 default"),
                                  ("srkn6", 10 * DEFAULT_DT_FACTOR["srkn6"], "srkn6 dt_factor x10"),
                                  ("srkn6c", None, "srkn6c default")):
            s = integrate_lattice(x0, v0, t, alpha=ALPHA, method=method, dt_factor=fac)
            rows.append((f"{name} (dt={s.dt:.2g})", s.wall_time_s, s.n_force_evals, s.energy_drift, s.x[-1]))
        base = rows[0][1]
        for name, wall, nfev, drift, xf in rows:
            err = np.abs(xf - ref.x[-1]).max() / a
            print(f"{label:32s} {name:30s} {wall:9.3f} {base / wall:7.1f} {nfev:9d} "
                  f"{wall / nfev / N * 1e9:13.2f} {drift:12.2e} {err:9.1e}")
    print(f"total wall time {time.perf_counter() - start:.1f} s "
          "(ratio = scipy DOP853 numpy wall / row wall)")


if __name__ == "__main__":
    main()
