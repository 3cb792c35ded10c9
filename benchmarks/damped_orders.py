"""Observed convergence order of DOP853 ("dop853_numba") on the damped lattice (ncdamped), each damping term.

For each scene and damping, runs at rtol = 1e-6 ... 1e-12 and a reference at rtol = 1e-14 (the
closed form when the scene has one); the error is max |x - x_ref|, |v - v_ref| at the final time over
the largest initial |x|, |v|. The observed order is the slope p of log(error) against log(steps)
(error ~ steps^-p; DOP853's nominal order is 8), fitted over the runs whose error is above 1e-13,
and the slope q of log(error) against log(rtol). Also the drift of H + D (stored plus dissipated
energy) from H(0), the integrator's error on the energy balance.

Scenes (units of (nc)):
* ``oscillator``: two beads with the same state (no contact ever), on-site damping; exact reference
  e^(-gamma t/2) [x0 cos(w t) + (v0 + gamma x0/2)/w sin(w t)];
* ``collisions``: two beads on free ends colliding repeatedly (contact onsets and releases);
* ``loc1``: figure loc1's localised binary oscillation, 50 beads on a ring.

Writes docs/damped-orders.md. Run: ``PYTHONPATH=src python benchmarks/damped_orders.py``.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from cradle.integrators import integrate_lattice
from cradle.models.damping import Damping
from cradle.models.initial import packet

RTOLS = [1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12]
RTOL_REF = 1e-14
FLOOR = 1e-13   # errors below this are roundoff, left out of the fits

OUT = Path(__file__).resolve().parents[1] / "docs" / "damped-orders.md"


def oscillator(gamma):
    x0, v0, T = 1.0, -0.4, 20.0
    w = np.sqrt(1.0 - gamma**2 / 4.0)
    b = (v0 + gamma * x0 / 2.0) / w
    e = np.exp(-gamma * T / 2.0)
    x = e * (x0 * np.cos(w * T) + b * np.sin(w * T))
    v = -gamma / 2.0 * x + e * (-x0 * w * np.sin(w * T) + b * w * np.cos(w * T))
    return np.array([x0, x0]), np.array([v0, v0]), T, "free", (np.array([x, x]), np.array([v, v]))


def collisions(_):
    return np.array([-0.05, 0.05]), np.array([0.5, -0.5]), 10.0, "free", None


def loc1(_):
    data = packet(50, 1.5, amplitude=0.2, width=8.0)
    return data.x0, data.v0, 30.0, "periodic", None


CASES = [
    ("oscillator", oscillator, None),
    ("oscillator", oscillator, Damping(onsite=0.3)),
    ("collisions", collisions, None),
    ("collisions", collisions, Damping(onsite=0.1)),
    ("collisions", collisions, Damping(contact=0.5)),
    ("collisions", collisions, Damping(onsite=0.1, contact=0.5)),
    ("loc1", loc1, None),
    ("loc1", loc1, Damping(onsite=0.01)),
    ("loc1", loc1, Damping(contact=0.05)),
    ("loc1", loc1, Damping(onsite=0.01, contact=0.05)),
]


def run(x0, v0, T, bc, damping, rtol):
    return integrate_lattice(x0, v0, [0.0, T], alpha=1.5, bc=bc, method="dop853_numba", rtol=rtol, damping=damping)


def slope(a, b):
    keep = b > FLOOR
    if keep.sum() < 2:
        return float("nan")
    return float(np.polyfit(np.log(a[keep]), np.log(b[keep]), 1)[0])


def main() -> None:
    rows = []
    summary = []
    for scene, build, damping in CASES:
        gamma = damping.onsite if damping is not None else 0.0
        x0, v0, T, bc, exact = build(gamma)
        if exact is None:
            ref = run(x0, v0, T, bc, damping, RTOL_REF)
            exact = (ref.x[-1], ref.v[-1])
        amp = max(np.abs(x0).max(), np.abs(v0).max())
        steps, errors, drifts = [], [], []
        for rtol in RTOLS:
            sol = run(x0, v0, T, bc, damping, rtol)
            err = max(np.abs(sol.x[-1] - exact[0]).max(), np.abs(sol.v[-1] - exact[1]).max()) / amp
            steps.append(sol.n_steps)
            errors.append(err)
            drifts.append(sol.energy_drift)
            label = "off" if damping is None else f"gamma={damping.onsite:g}, eta={damping.contact:g}"
            rows.append(f"| {scene} | {label} | {rtol:.0e} | {sol.n_steps} | {err:.2e} | {sol.energy_drift:.2e} | "
                        f"{sol.dissipated[-1] / sol.energy[0]:.3f} |")
            print(rows[-1], flush=True)
        s, e, d = np.array(steps, float), np.array(errors), np.array(drifts)
        p = -slope(s, e)
        q = slope(np.array(RTOLS), e)
        label = "off" if damping is None else f"gamma={damping.onsite:g}, eta={damping.contact:g}"
        summary.append(f"| {scene} | {label} | {p:.2f} | {q:.2f} | {d.min():.1e} .. {d.max():.1e} |")
    text = "\n".join([
        "# Observed orders of DOP853 on the damped lattice (ncdamped)",
        "",
        "Written by `benchmarks/damped_orders.py` (method `dop853_numba`, alpha = 3/2; the runs, the "
        "reference and the fits are described in its docstring). p: slope of -log(error) against "
        "log(steps) (nominal 8); q: slope of log(error) against log(rtol); fits over the runs with error "
        f"> {FLOOR:g}. Damping `off` is the conservative (nc) on the same scene, for comparison.",
        "",
        "| scene | damping | order p (steps) | q (rtol) | drift of H + D over the rtols |",
        "|---|---|---|---|---|",
        *summary,
        "",
        "Every run: error at the final time (relative to the largest initial |x|, |v|), the drift "
        "max |H + D - H(0)| / |H(0)| over every step, and D / H(0) at the final time.",
        "",
        "| scene | damping | rtol | steps | error | drift of H + D | D / H(0) |",
        "|---|---|---|---|---|---|---|",
        *rows,
        "",
    ])
    OUT.write_text(text)
    print(f"wrote {OUT}", file=sys.stderr)


if __name__ == "__main__":
    main()
