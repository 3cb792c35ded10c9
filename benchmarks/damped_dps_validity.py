"""The sup error of the damped DpS (dpsdamped) against the damped lattice (ncdamped), as dps-validity defines it,
for a few eps at one damping; writes the table of docs/damped-dps.md. Run:

    PYTHONPATH=src python benchmarks/damped_dps_validity.py [eps ...]

The lattice is scipy's DOP853 on cradle.models.damping.acceleration (rtol 1e-11): the compiled damped lattice
integrators are measured once they are in.
"""
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

from cradle.integrators import integrate_dps
from cradle.measurements.damped_validity import sup_error
from cradle.models import damping as D, dps_damped as DD
from doctable import publish

ALPHA, N, GAMMA_SLOW, ETA, T = 1.5, 16, 1.0, 0.1, [0.5, 1.0, 2.0]
EPS = [float(e) for e in sys.argv[1:]] or [0.01, 0.0025]
n = np.arange(N)
A0 = (1.0 + 0.3 * np.cos(2 * np.pi * n / N)) * np.exp(-1j * np.pi / 4 * n)
A0 /= np.max(np.abs(A0))

rows = []
for eps in EPS:
    c0 = time.perf_counter()
    lattice_damping = D.Damping(onsite=GAMMA_SLOW * eps ** (ALPHA - 1), contact=ETA)
    slow = DD.slow_damping(lattice_damping, eps, ALPHA)
    x0, v0 = DD.lattice_state(A0, eps, ALPHA, slow)
    t_end = max(T) * eps ** (1 - ALPHA)
    t = np.linspace(0.0, t_end, int(np.ceil(t_end / 0.05)) + 1)

    def f(_t, y, damping=lattice_damping):
        return np.concatenate([y[N:], D.acceleration(y[:N], y[N:], ALPHA, damping)])

    r = solve_ivp(f, (0.0, t_end), np.concatenate([x0, v0]), method="DOP853", t_eval=t, rtol=1e-11,
                  atol=1e-13 * eps)
    x, v = r.y[:N].T, r.y[N:].T
    damped = integrate_dps(A0, eps ** (ALPHA - 1) * t, alpha=ALPHA, rtol=1e-11, damping=slow)
    m = sup_error(t, x, damped.A, eps, ALPHA, T, v=v)
    mu = sup_error(t, x, integrate_dps(A0, eps ** (ALPHA - 1) * t, alpha=ALPHA, rtol=1e-11).A, eps, ALPHA, T)
    for i, Ti in enumerate(m["T"]):
        rows.append((eps, lattice_damping.onsite, Ti, m["abs_error"][i], m["abs_error"][i] / eps**ALPHA,
                     m["rel_error"][i], m["envelope_error"][i], m["velocity_abs_error"][i], mu["abs_error"][i],
                     damped.max_l2_drift))
    print(f"eps = {eps}: {time.perf_counter() - c0:.1f} s", flush=True)

head = ("| eps | gamma | T | E_abs | E_abs / eps^alpha | E_rel = E_abs/(2 eps) | E_env | velocity E_abs | "
        "E_abs, undamped DpS | DpS l2 balance residual |\n|---|---|---|---|---|---|---|---|---|---|\n")
body = "".join(f"| {e:g} | {g:.4g} | {Ti:g} | {a:.3e} | {a_s:.3f} | {rel:.3e} | {env:.3e} | {ve:.3e} | {u:.3e} | "
               f"{bal:.1e} |\n" for e, g, Ti, a, a_s, rel, env, ve, u, bal in rows)
p = np.log(rows[len(T) - 1][3] / rows[-1][3]) / np.log(EPS[0] / EPS[-1]) if len(EPS) > 1 else float("nan")
text = head + body + (f"\nPower of eps between eps = {EPS[0]:g} and {EPS[-1]:g} at T = {T[-1]:g}: {p:.3f} "
                      f"(alpha = {ALPHA}).\n")
print(text)
publish("damped-dps.md", "damped-dps-validity", text)
