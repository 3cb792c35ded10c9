"""Cost per bead and force evaluation of the conservative lattice with every damping term off: a checkout
from before the damping terms ("before") against this one ("now"), measured in one run.

The same call (the fft106 travelling wave of benchmarks/bead_step_cost.py, q = 4 pi / 5, omega_tw = 1.1,
N beads to t_end; srkn6c at its default step and dop853_numba at rtol = 1e-10, no ``damping``
argument) is timed in fresh subprocesses whose PYTHONPATH is the ``src`` of each checkout, alternating
before and now, ``REPEATS`` times each; in each process the best of ``CALLS`` calls after a warm-up
call (compilation and cache loads not counted), in CPU time of the process (``time.process_time``:
the machine is shared, and wall time counts the other jobs' turns). This checkout is also timed with
``damping=Damping()`` (every term off, given explicitly). Also checks that both checkouts give bitwise
the same final state.

Writes docs/damping-off-cost.md. Run from this checkout, BEFORE_SRC the src of a checkout of the commit before
the damping terms (e.g. ``git worktree add /tmp/before 89f9fe2``):

    PYTHONPATH=src python benchmarks/damping_off_cost.py BEFORE_SRC [N] [T]

"""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

from doctable import cost_rows

ROOT = Path(__file__).resolve().parents[1]
MAIN_SRC = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("/tmp/before/src")
N = int(sys.argv[2]) if len(sys.argv) > 2 else 200
T = float(sys.argv[3]) if len(sys.argv) > 3 else 50.0
REPEATS = 7
CALLS = 7
METHODS = {"srkn6c": {}, "dop853_numba": {"rtol": 1e-10}}
OUT = ROOT / "docs" / "damping-off-cost.md"

CHILD = r"""
import hashlib, json, sys, time
import numpy as np
from cradle.integrators import integrate_lattice
from cradle.models import initial
N, T, method, rtol, explicit = int(sys.argv[1]), float(sys.argv[2]), sys.argv[3], json.loads(sys.argv[4]), sys.argv[5]
kw = dict(rtol) if rtol else {}
if explicit == "1":
    from cradle.models.damping import Damping
    kw["damping"] = Damping()
d = initial.travelling_wave(N, 4 * np.pi / 5, 1.5, omega_tw=1.1)
integrate_lattice(d.x0, d.v0, np.array([0.0, 1.0]), alpha=1.5, method=method, **kw)   # warm-up
best = None
for _ in range(int(sys.argv[6])):
    t0 = time.process_time()
    sol = integrate_lattice(d.x0, d.v0, np.array([0.0, T]), alpha=1.5, method=method, **kw)
    wall = time.process_time() - t0
    best = wall if best is None else min(best, wall)
state = np.concatenate([sol.x[-1], sol.v[-1]])
print(json.dumps({"per_bead_eval_s": best / (sol.n_force_evals * N), "evals": sol.n_force_evals,
                  "sha256": hashlib.sha256(state.tobytes()).hexdigest()}))
"""


def child(src: Path, method: str, explicit: bool) -> dict:
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(src)
    proc = subprocess.run([sys.executable, "-c", CHILD, str(N), repr(T), method, json.dumps(METHODS[method]),
                           "1" if explicit else "0", str(CALLS)], env=env, capture_output=True, text=True, check=True)
    return json.loads(proc.stdout.strip().splitlines()[-1])


def main() -> None:
    branch_src = ROOT / "src"
    lines = []
    for method in METHODS:
        runs: dict[str, list[dict]] = {"before": [], "now": [], "now, damping=Damping()": []}
        for _ in range(REPEATS):   # alternating, so that a slower moment of the machine hits both
            runs["before"].append(child(MAIN_SRC, method, False))
            runs["now"].append(child(branch_src, method, False))
            runs["now, damping=Damping()"].append(child(branch_src, method, True))
        for line in cost_rows(method, runs):
            lines.append(line)
            print(line, flush=True)
    text = "\n".join([
        "# Cost of the conservative lattice with every damping term off: before the damping terms and now",
        "",
        f"Written by `benchmarks/damping_off_cost.py`: the fft106 travelling wave, N = {N} beads to t = {T:g}, "
        f"{REPEATS} fresh processes per row alternating before ({MAIN_SRC}: the code before the damping terms) and "
        f"now (this checkout), best of {CALLS} calls "
        "in each, CPU time; ns per bead and force evaluation (median, min, max over the processes), the median's and "
        "the minimum's difference from before's (the machine is shared: the minimum is the least disturbed), "
        "and whether every process gave bitwise the same final state and "
        "number of force evaluations.",
        "",
        "| method | code | median ns | min ns | max ns | median vs before | min vs before | bitwise same |",
        "|---|---|---|---|---|---|---|---|",
        *lines,
        "",
    ])
    OUT.write_text(text)
    print(f"wrote {OUT}", file=sys.stderr)


if __name__ == "__main__":
    main()
