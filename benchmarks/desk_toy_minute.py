"""The CPU time of a desk toy watched for a minute: the table of docs/analyses/desk-toy-minute.md.

    python benchmarks/desk_toy_minute.py [--no-docs] [--duration 60] [--repeats 3]

1 cm steel balls on 10 cm strings released from 20 degrees, one ball lifted (cradle.analyses.desk_toy_minute):
(ncdamped) with Kuwabara-Kono contacts (e = 0.9 and 0.98 at 0.3 m/s, the analysis's assumed bracket) and the lower
(Stokes) drag rate, integrated by dop853_numba at the analysis's rtol (1e-12), stored 16 times per swing period.
CPU time (time.process_time) of the integration alone, after the kernel is compiled (or loaded from its cache): the
median of ``--repeats`` runs. Rows: the 5-ball cradle over ``--duration`` seconds (the minute), its scaling in the
number of balls N (3 to 20) and in the length of the run (a quarter, half, one and two durations). A timing:
run it on a quiet machine (nothing else building).
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from cradle.analyses import desk_toy_minute as dm  # noqa: E402
from cradle.analyses.protocol import FULL, form_spec  # noqa: E402
from cradle.models import desk_toy as dt  # noqa: E402
from cradle.specs.declare import from_plain  # noqa: E402
from doctable import publish  # noqa: E402

CHAINS = (3, 5, 7, 10, 20)
LENGTHS = (0.25, 0.5, 1.0, 2.0)   # times --duration


def cpu_of(N: int, duration: float, e: float, repeats: int) -> tuple[float, int]:
    """(median CPU seconds, steps) of one run of N balls, one lifted, over ``duration`` seconds."""
    spec = form_spec(from_plain(dm.DeskToyMinute, {"restitution": [e]}), FULL)
    (_, A), = dm.contacts(spec)
    rate = dm.drag_rates(spec)[0]
    x0, _, s = dt.desk_toy_initial(dt.desk_toy(N, 1, spec.angle_deg, dm.DEFAULT_CRADLE))
    t = dm.time_grid(duration / s.T, spec.samples)
    damping = dm.damping_of(A, rate, s)
    times, steps = [], 0
    for _ in range(repeats):
        c0 = time.process_time()
        run = dm.minute_run(x0, t, damping, spec.rtol)
        times.append(time.process_time() - c0)
        steps = int(run.n_steps)
    return statistics.median(times), steps


def table(duration: float, repeats: int) -> str:
    c0 = time.process_time()
    dm.warm_up()
    compile_s = time.process_time() - c0
    rows = []
    for e in (0.9, 0.98):
        for N in CHAINS:
            cpu, steps = cpu_of(N, duration, e, repeats)
            rows.append(f"| N = {N} | {duration:g} | {e:g} | {steps} | {cpu:.3f} | {cpu / duration * 60:.3f} |")
        for f in LENGTHS:
            if f == 1.0:
                continue
            cpu, steps = cpu_of(5, f * duration, e, repeats)
            per_minute = cpu / (f * duration) * 60
            rows.append(f"| N = 5 | {f * duration:g} | {e:g} | {steps} | {cpu:.3f} | {per_minute:.3f} |")
    rtol = form_spec(from_plain(dm.DeskToyMinute, {}), FULL).rtol
    head = (f"One lifted ball, (ncdamped) by dop853_numba at rtol = {rtol:g}, Stokes drag; CPU time of the integration "
            f"(median of {repeats}), after the kernel is compiled or loaded ({compile_s:.1f} s of CPU here). "
            f"Target: a minute of the 5-ball cradle in under a minute of CPU.")
    columns = "| cradle | real time (s) | e at 0.3 m/s | steps | CPU (s) | CPU per real minute (s) |"
    return "\n".join([head, "", columns, "|---|---|---|---|---|---|", *rows])


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-docs", action="store_true", help="print the table only")
    ap.add_argument("--duration", type=float, default=60.0, help="real time of the reference run (s, default 60)")
    ap.add_argument("--repeats", type=int, default=3, help="runs per row, the median reported (default 3)")
    args = ap.parse_args(argv)
    text = table(args.duration, args.repeats)
    print(text)
    if not args.no_docs:
        publish("analyses/desk-toy-minute.md", "desk-toy-minute-cost", text)


if __name__ == "__main__":
    main()
