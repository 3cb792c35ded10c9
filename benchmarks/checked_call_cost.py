"""What ``@checked`` (cradle.specs.checked) adds to a call of a public function: integrate_lattice's arguments as
the scene job passes them, to a function that returns at once, against the same function undecorated.

Per call, the best of ``ROUNDS`` rounds of ``CALLS`` calls each (wall time, ``time.perf_counter``: a call is a
few microseconds, below the resolution of CPU time; the best round is the one the shared machine least
disturbed). Writes the table between its markers in docs/performance.md (section "Checked arguments")::

    python benchmarks/checked_call_cost.py
"""
from __future__ import annotations

import datetime as dt
import math
import os
import time
from pathlib import Path

from cradle.specs.checked import checked
from doctable import git_commit, publish

ROOT = Path(__file__).resolve().parents[1]
ROUNDS = int(os.environ.get("ROUNDS", 5))
CALLS = int(os.environ.get("CALLS", 20000))
TARGET_S = 20e-6   # what a checked call may add: far below any integration it guards


def plain(x0, v0, t_out, *, alpha, bc="periodic", method="srkn6c", dt=None, dt_factor=None, rtol=None,
          atol=None, potential="hertz"):
    return alpha


def per_call(f) -> float:
    """Best seconds per call of ``f`` over the rounds."""
    best = math.inf
    for _ in range(ROUNDS):
        t0 = time.perf_counter()
        for _ in range(CALLS):
            f(None, None, None, alpha=1.5, bc="periodic", method="srkn6c", dt=0.01)
        best = min(best, (time.perf_counter() - t0) / CALLS)
    return best


def main() -> int:
    wrapped = checked(method="latticeMethod")(plain)
    bare, with_checks = per_call(plain), per_call(wrapped)
    extra = with_checks - bare
    commit = git_commit()
    stamp = dt.datetime.now(dt.UTC).strftime("%Y-%m-%d %H:%M UTC")
    text = "\n".join([
        f"`python benchmarks/checked_call_cost.py` at commit {commit}, {stamp}; wall time per call, best of "
        f"{ROUNDS} rounds of {CALLS} calls (load average {os.getloadavg()[0]:.1f})", "",
        "| call | per call [us] |", "|---|---:|",
        f"| undecorated | {bare * 1e6:.2f} |", f"| `@checked(method=\"latticeMethod\")` | {with_checks * 1e6:.2f} |",
        f"| added by the checks | **{extra * 1e6:.2f}** |", "",
        f"Target: under {TARGET_S * 1e6:.0f} us added per call ({'met' if extra < TARGET_S else 'NOT met'})."])
    print(text)
    publish("performance.md", "checked-call", text)
    return 0 if extra < TARGET_S else 1


if __name__ == "__main__":
    raise SystemExit(main())
