"""One instability window of the DpS travelling breathers resolved and read as a Krein collision
(docs/analyses/travelling-breathers.md, "robustness in the limit").

    python benchmarks/tb_bubble.py N C_FROM C_TO STEP ANGLE [SPAN]     e.g. ... 24 0.11920 0.11936 2e-6 1.31

The family of cradle.analyses.travelling_breathers on the ring of N (full form's defaults) continued to C_FROM
and over C_FROM..C_TO in steps of STEP (bubble_scan); the bubble is the longest run of points where the largest
ln |mu| exceeds the stability threshold times T with its multiplier within 0.05 of ANGLE; the two-mode model
(cradle.measurements.floquet_bubbles.collision_fit) is fitted to the pair's splitting over SPAN (default 2e-5)
on either side of it, and its height g and width 4 g / s are printed against the measured largest ln |mu| and
width. A few seconds of CPU on the ring of 24.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from cradle.analyses import travelling_breathers as tb  # noqa: E402
from cradle.analyses.protocol import FULL, form_spec  # noqa: E402
from cradle.analyses.travelling_breathers import dps_family, fine_scan  # noqa: E402
from cradle.integrators import dps_travelling as DT  # noqa: E402
from cradle.measurements import floquet_bubbles as FB  # noqa: E402
from cradle.specs.declare import from_plain  # noqa: E402


def main(argv: list[str]) -> None:
    N, c_from, c_to, step, angle = int(argv[0]), float(argv[1]), float(argv[2]), float(argv[3]), float(argv[4])
    span = float(argv[5]) if len(argv) > 5 else 2e-5
    spec = form_spec(from_plain(tb.TravellingBreathers, {}), FULL)
    first = dps_family.first_member(spec, N, spec.rtol)
    lead, _ = DT.continue_family(first, np.arange(first.c, c_from, 0.005)[1:].tolist() + [c_from], spec.newton_tol,
                                 spec.rtol, min_step=fine_scan.LIMIT_MIN_STEP)
    r = fine_scan.bubble_scan(spec, lead[-1], np.round(np.arange(c_from, c_to + step / 2, step), 12)[1:], angle, 0.05)
    fit = FB.bubble(r, spec.stability_threshold, angle, span)
    for k, v in fit.items():
        print(f"{k}: {v:.6g}")


if __name__ == "__main__":
    main(sys.argv[1:])
