"""Scan dt_factor of the splittings on every scene of config.yaml (the paper's runs, full t_end).

Prints, per method and dt_factor, the relative energy drift (max over every
step) and the wall time of each scene, and the worst drift; used to set
cradle.integrators.DEFAULT_DT_FACTOR (target: drift <= 1e-8 on every paper
scene, with a margin). Initial data are built in-process from the config
(breathers: the homoclinic solution is solved first), exactly as the
pipeline's `initial` rule does.

    python benchmarks/tune_dt_factor.py [--methods srkn6c srkn6] [--factors 0.02 0.01] [--scenes tw-weak ...]
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

from cradle.integrators import DEFAULT_DT_FACTOR, integrate_lattice
from cradle.pipeline import config as cc
from cradle.scenes import stages
from cradle.scenes.spec import Breather

ROOT = Path(__file__).resolve().parents[1]


def paper_initial_data(cfg, names=None):
    """{scene: (x0, v0, spec)} for the scenes of a validated config (all of them by default)."""
    out = {}
    homs = {}
    for name in names or list(cfg["scenes"]):
        spec = cc.scene(cfg, name)
        hom = None
        if isinstance(spec.initial, Breather):
            hname = spec.initial.homoclinic
            if hname not in homs:
                homs[hname] = stages.homoclinic_solution(cc.homoclinic(cfg, hname), hname)
            hom = homs[hname]
        init = stages.initial_data(spec, name, hom)
        out[name] = (init["x0"].values, init["v0"].values, spec)
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--config", default=str(ROOT / "config.yaml"))
    parser.add_argument("--methods", nargs="+", default=["srkn6c"])
    parser.add_argument("--factors", nargs="+", type=float, default=None,
                        help="dt_factor values (default: the method's default x [2, 1.5, 1, 0.5])")
    parser.add_argument("--scenes", nargs="+", default=None)
    args = parser.parse_args(argv)
    cfg = cc.load(args.config)
    data = paper_initial_data(cfg, args.scenes)
    x0, v0, spec = next(iter(data.values()))
    integrate_lattice(x0[:8], v0[:8], [0.0, 0.1], alpha=spec.alpha, method="srkn6c")  # JIT cache
    for method in args.methods:
        base = DEFAULT_DT_FACTOR[method]
        factors = args.factors or [base * f for f in (2.0, 1.5, 1.0, 0.5)]
        print(f"== {method} (default dt_factor {base}); cells: energy drift / wall time [s]")
        print(f"{'scene':16s} " + " ".join(f"{f:>18.5g}" for f in factors))
        worst = {f: (0.0, "") for f in factors}
        total = {f: 0.0 for f in factors}
        for name, (x0, v0, spec) in data.items():
            cells = []
            for fac in factors:
                t0 = time.perf_counter()
                s = integrate_lattice(x0, v0, [0.0, spec.t_end], alpha=spec.alpha, bc=spec.bc,
                                      method=method, dt_factor=fac)
                total[fac] += time.perf_counter() - t0
                if s.energy_drift > worst[fac][0]:
                    worst[fac] = (s.energy_drift, name)
                cells.append(f"{s.energy_drift:9.2e} /{s.wall_time_s:6.2f}")
            print(f"{name:16s} " + " ".join(f"{c:>18s}" for c in cells), flush=True)
        print(f"{'worst':16s} " + " ".join(f"{worst[f][0]:9.2e} {worst[f][1]:>8.8s}" for f in factors))
        print(f"{'total wall [s]':16s} " + " ".join(f"{total[f]:18.2f}" for f in factors))


if __name__ == "__main__":
    main()
