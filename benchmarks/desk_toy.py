"""The desk-toy experiments in (nc) and in the ideal hard-sphere cradle: the tables of docs/desk-toy.md.

    python benchmarks/desk_toy.py [--no-docs] [--periods 20]

1 cm steel balls on 10 cm strings (cradle.models.physical), 5 balls with 1, 2 or 3 lifted and 10 balls with 1
lifted, released from 20 degrees (cradle.models.desk_toy). (nc) is integrated at the desk toy's own amplitude
(about 3.7e17 in (nc)'s units) with dop853_numba, free ends; the same cradle at two moderate amplitudes shows
what the homogeneity of (nc) makes of the amplitude. The hard-sphere cradle (cradle.models.hard_spheres) runs
at e = 1 and e = 0.95. Every number is measured by cradle.measurements.desk_toy; wall times on this machine.
"""
from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from cradle.integrators import integrate_lattice  # noqa: E402
from cradle.measurements import desk_toy as m  # noqa: E402
from cradle.models import desk_toy as dt, physical as ph  # noqa: E402
from cradle.models.hard_spheres import hard_sphere_run  # noqa: E402
from cradle.models.restitution_data import STEEL_ASSUMED  # noqa: E402
from doctable import publish  # noqa: E402

STEEL = ph.real_cradle("steel", 0.01, length=0.1)
ANGLE = 20.0
CASES = [(5, 1), (5, 2), (5, 3), (10, 1)]
THRESHOLDS = (0.9, 0.5)
#: restitution of two steel balls: the assumed value of cradle.models.restitution_data (not a measured one)
STEEL_E = STEEL_ASSUMED.e
RTOL = 1e-14
SAMPLES = 256   # stored times per swing period 2 pi


def nc(x0, t, rtol=RTOL):
    return integrate_lattice(x0, np.zeros_like(x0), t, alpha=1.5, bc="free", method="dop853_numba", rtol=rtol)


def measure(t, x, v, lifted, cascade):
    """The measurements of one run: shares, holds, break-up (velocities after the first cascade, gaps at pi)."""
    times, f = m.out_fractions(t, x, v, lifted)
    holds = [m.pattern_hold(t, x, v, lifted, th) for th in THRESHOLDS]
    _, E = m.energy_per_swing(t, x, v)
    H0 = E[0].sum()
    return {"f": f, "holds": holds, "E": E / H0, "cascade": cascade}


def nc_cascade(x0):
    """Velocities just after the first cascade and gaps at t = pi, from a run stored densely around the impact."""
    t = np.unique(np.concatenate([np.linspace(0, math.pi, 101), math.pi / 2 + np.linspace(0, 0.05, 5001)]))
    run = nc(x0, t)
    t0, t_end, i = m.cascade_end(t, run.x)
    _, gaps, _ = m.line_state(t, run.x, run.v, math.pi)
    return {"t_end": t_end, "v": run.v[i] if i >= 0 else np.full(x0.size, np.nan), "gaps": gaps}


def hs_cascade(run, A):
    """The same for the hard-sphere cradle: velocities just after the first instant of collisions."""
    t = np.array([math.pi / 2 + 1e-12, math.pi])
    r = hard_sphere_run(run[0], np.zeros_like(run[0]), t, restitution=run[1])
    return {"t_end": float(r.collision_t[0]) if r.collision_t.size else math.nan, "v": r.v[0], "gaps": np.diff(r.x[1])}


def fmt_holds(holds):
    return " | ".join(f"{h.swings}" + (" (held)" if math.isnan(h.t_break) else "") for h in holds)


def run_all(periods: int):
    t = (np.arange(periods * SAMPLES + 1) + 0.5) * (2 * math.pi / SAMPLES)
    nc(np.array([-1.0, 0.0]), np.array([0.0, 0.1]))   # load the compiled kernels before timing
    rows, timing, energy_rows, breakup_rows, scale_rows, tol_rows = [], [], [], [], [], []
    for n, lifted in CASES:
        spec = dt.desk_toy(n, lifted, ANGLE, STEEL)
        x0, _, s = dt.desk_toy_initial(spec)
        A = -x0[0]
        label = f"{n} balls, {lifted} lifted"
        w0 = time.perf_counter()
        run = nc(x0, t)
        wall = time.perf_counter() - w0
        timing.append(f"| {label} | {A:.4g} | {dt.collision_fraction(spec):.3g} | {periods} | {run.n_steps} | "
                      f"{run.n_steps / periods:.0f} | {run.energy_drift:.2g} | {wall:.2f} |")
        results = {"(nc)": measure(t, run.x, run.v, lifted, nc_cascade(x0))}
        # the same run at a looser tolerance: what of it is converged
        loose = nc(x0, t, rtol=100 * RTOL)
        cells = []
        for r in (loose, run):
            meas = measure(t, r.x, r.v, lifted, None)
            cells.append(f"{fmt_holds(meas['holds'])} | {meas['f'][-1]:.3f} | {r.energy_drift:.2g}")
        tol_rows.append(f"| {label} | " + " | ".join(cells) + " |")
        for e in (1.0, STEEL_E):
            hs = hard_sphere_run(x0, np.zeros(n), t, restitution=e)
            results[f"hard spheres e = {e:g}"] = measure(t, hs.x, hs.v, lifted, hs_cascade((x0, e), A))
        for model, r in results.items():
            f = r["f"]
            rows.append(f"| {label} | {model} | " + " ".join(f"{v:.3f}" for v in f[:6]) + f" | {f[-1]:.3f} | "
                        f"{fmt_holds(r['holds'])} |")
            E = r["E"]
            energy_rows.append(f"| {label} | {model} | " + " ".join(f"{v:.3f}" for v in E[0]) + " | "
                               + " ".join(f"{v:.3f}" for v in E[-1]) + f" | {E[-1].sum():.4f} |")
            c = r["cascade"]
            stay = slice(0, n - lifted)          # every ball but the out group: they should end at rest
            line = slice(0, n - lifted - 1)      # the bonds between them
            vm = " ".join(f"{v / A:+.4f}" for v in c["v"][stay])
            gaps = c["gaps"][line]
            breakup_rows.append(f"| {label} | {model} | {vm or '-'} | "
                                + (" ".join(f"{g / A:.4f}" for g in gaps) or "-") + " | "
                                + (" ".join(f"{g * s.X * 1e3:.3f}" for g in gaps) or "-") + " |")
        # the homogeneity of (nc): the same release at moderate amplitudes
        if (n, lifted) == (5, 1):
            for amp in (1e6, 1e10, A):
                x = np.zeros(n)
                x[:lifted] = -amp
                run = nc(x, t)
                meas = measure(t, run.x, run.v, lifted, nc_cascade(x))
                frac = dt.collision_time_nc(amp) / (2 * math.pi)
                g = meas["cascade"]["gaps"][: n - lifted - 1]
                scale_rows.append(f"| {amp:.4g} | {frac:.3g} | " + " ".join(f"{v:.3f}" for v in meas["f"][:4])
                                  + f" | {fmt_holds(meas['holds'])} | " + " ".join(f"{v / amp:.4f}" for v in g) + " |")
    return rows, timing, energy_rows, breakup_rows, scale_rows, tol_rows


def tables(periods: int) -> dict[str, str]:
    w0 = time.process_time()
    rows, timing, energy_rows, breakup_rows, scale_rows, tol_rows = run_all(periods)
    cpu = time.process_time() - w0
    th = " | ".join(f"holds (f >= {x:g})" for x in THRESHOLDS)
    return {
        "desk-toy-cost": "\n".join([
            f"1 cm steel balls on 10 cm strings released from {ANGLE:g} degrees; (nc) by dop853_numba, rtol = "
            f"{RTOL:g}, free ends, over {periods} swing periods 2 pi (wall times after compilation; the whole "
            f"benchmark took {cpu:.1f} s of CPU).", "",
            "| cradle | amplitude A (nc) | t_c / 2 pi | periods | steps | steps per period | energy drift | "
            "wall (s) |", "|---|---|---|---|---|---|---|---|", *timing]),
        "desk-toy-pattern": "\n".join([
            "f_k: share of the energy carried by the `lifted` outermost balls at the far end at t = k pi "
            "(k odd: the end opposite the release; k even: the release end); holds: out-swings in a row from the "
            f"first with f_k above the threshold (of {2 * periods} measured).", "",
            f"| cradle | model | f_1 .. f_6 | f_{2 * periods} | {th} |", "|---|---|---|---|---|---|", *rows]),
        "desk-toy-breakup": "\n".join([
            "Just after the first cascade (nc: the first stored time, on a grid of 1e-5, after the first "
            "compression with no bond compressed; hard spheres: just after the first instant of collisions): the "
            "velocities of the balls that should stay at rest (all but the out group: beads 0 .. N-1-lifted), over the "
            "impact speed A; the gaps between them at "
            "the first largest swing, t = pi, over A and in millimetres.", "",
            "| cradle | model | velocities / A, beads 0 .. N-1-lifted | gaps at t = pi / A | gaps at t = pi (mm) |",
            "|---|---|---|---|---|", *breakup_rows]),
        "desk-toy-energy": "\n".join([
            "Each bead's energy averaged over the first and the last swing period, over the energy of the first "
            "(the last column: the total in the last period, below 1 where collisions dissipate).", "",
            "| cradle | model | first period, beads 0 .. N-1 | last period, beads 0 .. N-1 | total, last |",
            "|---|---|---|---|---|", *energy_rows]),
        "desk-toy-scaling": "\n".join([
            "5 balls, 1 lifted: (nc) at moderate amplitudes and at the desk toy's own, on the same grid.", "",
            f"| A (nc) | t_c / 2 pi | f_1 .. f_4 | {th} | gaps at t = pi / A |", "|---|---|---|---|---|---|",
            *scale_rows]),
        "desk-toy-tolerance": "\n".join([
            f"(nc) at the desk toy's amplitude at two tolerances of dop853_numba: the holds, the last share f_"
            f"{2 * periods} and the energy drift max |H(t) - H(0)| / H(0).", "",
            f"| cradle | rtol {100 * RTOL:g}: holds (0.9) | holds (0.5) | f_{2 * periods} | drift | rtol {RTOL:g}: "
            f"holds (0.9) | holds (0.5) | f_{2 * periods} | drift |", "|---|---|---|---|---|---|---|---|---|",
            *tol_rows]),
    }


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-docs", action="store_true", help="print the tables only")
    ap.add_argument("--periods", type=int, default=20, help="swing periods 2 pi to integrate (default 20)")
    args = ap.parse_args(argv)
    out = tables(args.periods)
    for name, text in out.items():
        print(f"## {name}\n{text}\n")
        if not args.no_docs:
            publish("desk-toy.md", name, text)


if __name__ == "__main__":
    main()
