"""The instability windows of the DpS travelling breathers along c on one ring: docs/analyses/travelling-breathers.md.

    python benchmarks/tb_windows.py N C_FROM C_TO [STEP]        e.g. python benchmarks/tb_windows.py 24 0.10 0.14

The family of cradle.analyses.travelling_breathers (its full form's defaults: alpha = 3/2, unit norm, rtol 1e-13)
computed on a ring of N sites, then continued from its member nearest C_FROM in steps of STEP (default 0.001) up to
C_TO (cradle.integrators.dps_travelling.continue_family, tangent predictor); one line per member: c, theta, the
growth rate ln max|mu| / T of the non-trivial multipliers modulo shift and the verdict (U above the analysis's
stability_threshold). The continuation stops where a step cannot be completed (the family ends or turns there).
A few seconds to a minute of CPU.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from cradle.analyses import travelling_breathers as tb  # noqa: E402
from cradle.analyses.protocol import FULL, form_spec  # noqa: E402
from cradle.analyses.travelling_breathers import dps_family  # noqa: E402
from cradle.integrators import dps_travelling as DT  # noqa: E402
from cradle.specs.declare import from_plain  # noqa: E402


def main(argv: list[str]) -> None:
    N, c_from, c_to = int(argv[0]), float(argv[1]), float(argv[2])
    step = float(argv[3]) if len(argv) > 3 else 1e-3
    spec = form_spec(from_plain(tb.TravellingBreathers, {}), FULL)
    members, _ = dps_family.family(spec, N, spec.rtol)
    start = min(members, key=lambda b: abs(b.c - c_from))
    cs = np.round(np.arange(c_from, c_to + step / 2, step), 9)
    fam, last = DT.continue_family(start, cs[cs >= start.c], spec.newton_tol, spec.rtol)
    print(f"ring of {N}: c, theta, growth rate, verdict")
    for b in fam:
        _, rate, unstable, _ = dps_family.verdict(b, spec.stability_threshold)
        print(f"{b.c:.5f} {b.theta:+.5f} {rate:.2e} {'U' if unstable else 'S'}")
    if fam and fam[-1].c < cs[-1] - step / 2:
        print(f"the continuation stopped after c = {last:.5g}")


if __name__ == "__main__":
    main(sys.argv[1:])
