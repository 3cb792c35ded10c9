"""Scan dt_factor of the splittings on the paper's travelling-wave scenes.

Prints, per method and dt_factor, the relative energy drift (max over every
step) and wall time on each scene; used to set
cradle.integrators.DEFAULT_DT_FACTOR (target: drift <= 1e-8 on every scene).

    python benchmarks/tune_dt_factor.py [method ...]
"""
from __future__ import annotations

import sys

import numpy as np

from cradle.dps import omega_tw
from cradle.integrators import DEFAULT_DT_FACTOR, integrate_lattice

ALPHA = 1.5

# (label, N, q, a, omega_tw, t_final)
SCENES = [
    ("N50 q=pi/5 w=1.01", 50, np.pi / 5, 0.02118, 1.01, 621.95),
    ("N50 q=pi/5 w=1.1", 50, np.pi / 5, 2.118, 1.1, 621.95),
    ("N50 q=pi/5 w=1.5", 50, np.pi / 5, 52.95, 1.5, 621.95),
    ("N200 q=4pi/5 w=1.1", 200, 4 * np.pi / 5, 2 * 0.003835, omega_tw(2 * 0.003835, 4 * np.pi / 5, ALPHA), 913.7),
]


def wave(N, q, a, om):
    """Travelling wave (ansatzapprox) at t = 0: x_n = a cos(qn), v_n = a omega sin(qn)."""
    n = np.arange(N)
    return a * np.cos(q * n), a * om * np.sin(q * n)


def main(methods):
    for method in methods:
        base = DEFAULT_DT_FACTOR[method]
        print(f"== {method} (default dt_factor {base})")
        for fac in base * np.array([2.0, 1.5, 1.0, 0.75, 0.5]):
            cells = []
            for label, N, q, a, om, tf in SCENES:
                x0, v0 = wave(N, q, a, om)
                s = integrate_lattice(x0, v0, np.array([0.0, tf]), alpha=ALPHA, method=method, dt_factor=fac)
                cells.append(f"{s.energy_drift:8.1e} {s.wall_time_s:6.3f}s")
            print(f"dt_factor={fac:8.5f} | " + " | ".join(cells))
    print("scenes:", " | ".join(s[0] for s in SCENES))


if __name__ == "__main__":
    main(sys.argv[1:] or ["srkn6", "srkn4", "strang"])
