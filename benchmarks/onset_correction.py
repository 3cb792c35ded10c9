"""The contact-onset correction (srkn6c/srkn4c): does it pay, and which variant.

1. Local error of one step across a contact onset (two-bead free chain,
   onset at theta h, exact reference): order 2.5 plain, 5 corrected.
2. Global error at t = 100 (max_n |x_n - x_ref| / a, reference srkn6c at
   dt_factor 2e-4), energy drift and wall time against dt_factor on three
   config scenes (tw-weak, fft106, tw-strong), for the plain splittings and
   the corrected ones with the options of cradle.integrators._onset
   (variant 1 "difference" / 2 "replace", n_iter refinements of the model,
   `near` margin of the screen). Observed orders are fitted per row.

    python benchmarks/onset_correction.py [--t-end 100]
"""
from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

from cradle.integrators import integrate_lattice, lattice_splitting as LS
from cradle.pipeline import config as cc
from cradle.scenes import stages

ROOT = Path(__file__).resolve().parents[1]
FACTORS = [0.064, 0.032, 0.016, 0.008, 0.004]
OPTIONS = [("srkn6", None), ("srkn6c", (2, 0, 4 / 27)), ("srkn6c", (1, 0, 4 / 27)), ("srkn6c", (2, 1, 4 / 27)),
           ("srkn6c", (2, 0, 0.08)), ("srkn6c", (2, 0, 0.5)), ("srkn6c", (2, 0, 0.0)), ("srkn4", None),
           ("srkn4c", (2, 0, 4 / 27))]


def local_orders():
    alpha, u = 1.5, 1.0
    hs = np.array([0.2, 0.1, 0.05, 0.025])
    print("1. one step across an onset at theta h (two-bead chain): local error, fitted order")
    for theta in (0.3, 0.7):
        for method in ("srkn6", "srkn6c", "srkn4c"):
            errs = []
            for h in hs:
                r0, w0 = u * np.sin(theta * h), -u * np.cos(theta * h)
                s = integrate_lattice([-r0 / 2, r0 / 2], [-w0 / 2, w0 / 2], [0.0, h], alpha=alpha, bc="free",
                                      method=method, dt=h)
                ref = solve_ivp(lambda _t, y: [y[1], -y[0] + 2.0 * max(-y[0], 0.0) ** alpha],
                                (0.0, (1 - theta) * h), [0.0, -u], method="DOP853", rtol=1e-13, atol=1e-18).y[:, -1]
                errs.append(max(abs(s.x[-1, 1] - s.x[-1, 0] - ref[0]), abs(s.v[-1, 1] - s.v[-1, 0] - ref[1])))
            p = np.polyfit(np.log(hs), np.log(errs), 1)[0]
            print(f"   theta={theta} {method:7s} order {p:.2f}  errors " + " ".join(f"{e:.1e}" for e in errs))


def global_table(t_end):
    cfg = cc.load(ROOT / "config.yaml")
    print(f"\n2. error at t = {t_end:g} / energy drift / wall [s] against dt_factor {FACTORS}")
    for name in ("tw-weak", "fft106", "tw-strong"):
        spec = cc.scene(cfg, name)
        init = stages.initial_data(spec, name)
        x0, v0, a = init["x0"].values, init["v0"].values, float(init.attrs["a"])
        LS.ONSET_OPTIONS = (2, 0, 4 / 27)
        ref = integrate_lattice(x0, v0, [0.0, t_end], alpha=1.5, method="srkn6c", dt_factor=2e-4)
        print(f"== {name} (N = {x0.size}); reference srkn6c dt_factor 2e-4, energy drift {ref.energy_drift:.1e}")
        for method, opt in OPTIONS:
            LS.ONSET_OPTIONS = opt or (2, 0, 4 / 27)
            cells, errs = [], []
            for fac in FACTORS:
                s = integrate_lattice(x0, v0, [0.0, t_end], alpha=1.5, method=method, dt_factor=fac)
                err = max(np.abs(s.x[-1] - ref.x[-1]).max(), np.abs(s.v[-1] - ref.v[-1]).max()) / a
                errs.append(err)
                cells.append(f"{err:.1e}/{s.energy_drift:.0e}/{s.wall_time_s:.3f}")
            p = np.polyfit(np.log(FACTORS[1:]), np.log(errs[1:]), 1)[0]
            label = method + ("" if opt is None else f" v{opt[0]} it{opt[1]} near={opt[2]:.2f}")
            print(f"   {label:30s} order {p:4.1f} | " + "  ".join(cells), flush=True)
    LS.ONSET_OPTIONS = (2, 0, 4 / 27)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--t-end", type=float, default=100.0)
    args = parser.parse_args(argv)
    integrate_lattice(np.zeros(8) + 0.1, np.zeros(8), [0.0, 0.1], alpha=1.5, method="srkn6c")
    local_orders()
    global_table(args.t_end)


if __name__ == "__main__":
    main()
