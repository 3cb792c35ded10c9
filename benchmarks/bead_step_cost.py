"""Measure the wall time per bead-step of the lattice integrators (the constants of
cradle.pipeline.budget.COST_PER_BEAD_STEP_S).

For each method: a travelling wave (q = 4 pi / 5, omega_tw = 1.1, the fft106 initial data) on
N beads, integrated to t_end (a tenth of it for the scipy methods) after a warm-up call (numba
compilation and cache loads are not counted); prints seconds / (n_steps * N) for every method and
the steps per unit of simulated time at the default step or tolerance. Run:

    PYTHONPATH=src python benchmarks/bead_step_cost.py
"""
import json
import sys
import time

import numpy as np

from cradle.integrators import integrate_lattice
from cradle.models import initial

N = int(sys.argv[1]) if len(sys.argv) > 1 else 200
T = float(sys.argv[2]) if len(sys.argv) > 2 else 100.0
d = initial.travelling_wave(N, 4 * np.pi / 5, 1.5, omega_tw=1.1)
out = {"N": N, "t_end": T}
for method in ("srkn6c", "srkn4c", "srkn6", "srkn4", "strang", "dop853_numba", "dop853", "rk45"):
    Tm = T if method not in ("dop853", "rk45") else T / 10  # scipy's Python step loop: a shorter run
    integrate_lattice(d.x0, d.v0, np.array([0.0, 1.0]), alpha=1.5, method=method)  # warm-up
    best = None
    for _ in range(3):
        t0 = time.perf_counter()
        sol = integrate_lattice(d.x0, d.v0, np.array([0.0, Tm]), alpha=1.5, method=method)
        wall = time.perf_counter() - t0
        best = wall if best is None else min(best, wall)
    out[method] = {"t_end": Tm, "wall_s": best, "n_steps": sol.n_steps, "steps_per_time_unit": sol.n_steps / Tm,
                   "per_bead_step_s": best / (sol.n_steps * N)}
print(json.dumps(out, indent=1))
