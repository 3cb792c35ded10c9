"""Cost per bead and force evaluation of the lattice (nc) with every term of the imperfect cradle off: the code
before the terms ("before") against this checkout ("now"), measured in one run; and, for information, the cost of
kind 4 (the general right-hand side of (ncimperfect)) against kind 0.

The same call (the fft106 travelling wave of benchmarks/bead_step_cost.py, q = 4 pi / 5, omega_tw = 1.1,
N beads to t_end; srkn6c at its default step and dop853_numba at rtol = 1e-10, no ``terms`` argument) is timed
in fresh subprocesses whose PYTHONPATH is the ``src`` of each checkout, alternating before and now, ``REPEATS``
times each; in each process the best of ``CALLS`` calls after a warm-up call (compilation and cache loads not
counted), in CPU time of the process (``time.process_time``: the machine is shared). This checkout is also timed
with ``terms=Terms()`` (every term off, given explicitly). Every process must give bitwise the same final state.

Kind 4 (informative): in the "now" processes of dop853_numba, the same wave through
``lattice_adaptive.run_dop853_terms`` with trivial terms (every coefficient 1: bitwise kind 0's steps, so the
ratio is the cost of the general right-hand side and energy), and with active terms (sigma = 0.05, masses,
stiffnesses, delta0 = 0.05, quartic beta = 0.1; its own steps, so per evaluation).

Writes docs/terms-off-cost.md. Run from this checkout, BEFORE_SRC the src of a checkout of the commit before the
terms (``git -C /work/main worktree add /tmp/before25 9d0ea5d``):

    PYTHONPATH=src python benchmarks/terms_off_cost.py BEFORE_SRC [N] [T]
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

from doctable import cost_rows

ROOT = Path(__file__).resolve().parents[1]
BEFORE_SRC = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("/tmp/before25/src")
N = int(sys.argv[2]) if len(sys.argv) > 2 else 200
T = float(sys.argv[3]) if len(sys.argv) > 3 else 50.0
REPEATS = int(os.environ.get("REPEATS", 7))
CALLS = 7
METHODS = {"srkn6c": {}, "dop853_numba": {"rtol": 1e-10}}
OUT = ROOT / "docs" / "terms-off-cost.md"

CHILD = r"""
import hashlib, json, sys, time
import numpy as np
from cradle.integrators import integrate_lattice
from cradle.models import initial
N, T, method, rtol, variant, calls = (int(sys.argv[1]), float(sys.argv[2]), sys.argv[3], json.loads(sys.argv[4]),
                                      sys.argv[5], int(sys.argv[6]))
kw = dict(rtol) if rtol else {}
if variant != "plain":
    from cradle.models.lattice_terms import Terms
    kw["terms"] = Terms()
d = initial.travelling_wave(N, 4 * np.pi / 5, 1.5, omega_tw=1.1)


def best_of(run):
    run(1.0)   # warm-up: compilation and cache loads
    best = None
    for _ in range(calls):
        t0 = time.process_time()
        out = run(T)
        spent = time.process_time() - t0
        best = spent if best is None else min(best, spent)
    return best, out


best, sol = best_of(lambda t: integrate_lattice(d.x0, d.v0, np.array([0.0, t]), alpha=1.5, method=method, **kw))
state = np.concatenate([sol.x[-1], sol.v[-1]])
res = {"per_bead_eval_s": best / (sol.n_force_evals * N), "evals": sol.n_force_evals,
       "sha256": hashlib.sha256(state.tobytes()).hexdigest()}
if variant == "kind4":
    from cradle.integrators.lattice_adaptive import run_dop853_terms
    from cradle.models.inhomogeneity import Inhomogeneity, homogeneous, sites
    from cradle.models.onsite import OnSite
    from cradle.models.precompression import Precompression
    atol = sol.atol
    for name, terms in (("trivial", Terms()), ("active", Terms(
            inhomogeneity=Inhomogeneity(sigma=0.05, mass_sigma=0.05, seed=1, stiffness=tuple(1.0 + 0.05 * np.cos(
                np.arange(N)))), precompression=Precompression(delta0=0.05),
            onsite=OnSite(potential="quartic", beta=0.1)))):
        s = homogeneous(N) if name == "trivial" else sites(terms.inhomogeneity, N)
        b, out = best_of(lambda t: run_dop853_terms(d.x0, d.v0, np.array([0.0, t]), 1e-10, atol, 1.5, 0, True,
                                                    terms, s, None, None))
        res[name] = {"per_bead_eval_s": b / (out[6] * N), "evals": int(out[6]),
                     "same_as_kind0": bool(np.array_equal(out[0][-1], sol.x[-1])
                                           and np.array_equal(out[1][-1], sol.v[-1]))}
print(json.dumps(res))
"""


def child(src: Path, method: str, variant: str) -> dict:
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(src)
    proc = subprocess.run([sys.executable, "-c", CHILD, str(N), repr(T), method, json.dumps(METHODS[method]),
                           variant, str(CALLS)], env=env, capture_output=True, text=True, check=True)
    return json.loads(proc.stdout.strip().splitlines()[-1])


def main() -> None:
    branch_src = ROOT / "src"
    lines = []
    kind4: list[dict] = []
    for method in METHODS:
        runs: dict[str, list[dict]] = {"before": [], "now": [], "now, terms=Terms()": []}
        for _ in range(REPEATS):   # alternating, so that a slower moment of the machine hits both
            runs["before"].append(child(BEFORE_SRC, method, "plain"))
            runs["now"].append(child(branch_src, method, "kind4" if method == "dop853_numba" else "plain"))
            runs["now, terms=Terms()"].append(child(branch_src, method, "terms"))
        kind4 += [r for r in runs["now"] if "trivial" in r]
        for line in cost_rows(method, runs):
            lines.append(line)
            print(line, flush=True)
    k0 = np.array([r["per_bead_eval_s"] for r in kind4])
    rows4 = [f"| kind 0 (now) | {np.median(k0) * 1e9:.2f} | {k0.min() * 1e9:.2f} | 1.00 | {kind4[0]['evals']} | - |"]
    for name in ("trivial", "active"):
        t = np.array([r[name]["per_bead_eval_s"] for r in kind4])
        same = {r[name]["same_as_kind0"] for r in kind4}
        rows4.append(f"| kind 4, {name} terms | {np.median(t) * 1e9:.2f} | {t.min() * 1e9:.2f} | "
                     f"{np.median(t / k0):.2f} | {kind4[0][name]['evals']} | {'yes' if same == {True} else 'no'} |")
    text = "\n".join([
        "# Cost of the lattice (nc) with every term of the imperfect cradle off: before the terms and now",
        "",
        f"Written by `benchmarks/terms_off_cost.py`: the fft106 travelling wave, N = {N} beads to t = {T:g}, "
        f"{REPEATS} fresh processes per row alternating before ({BEFORE_SRC}: the code before the terms, 9d0ea5d) "
        f"and now (this checkout), best of {CALLS} calls in each, CPU time; ns per bead and force evaluation "
        "(median, min, max over the processes), the median's and the minimum's difference from before's (the "
        "machine is shared: the minimum is the least disturbed), and whether every process gave bitwise the same "
        "final state and number of force evaluations. Target: within 5 %.",
        "",
        "| method | code | median ns | min ns | max ns | median vs before | min vs before | bitwise same |",
        "|---|---|---|---|---|---|---|---|",
        *lines,
        "",
        "## Kind 4 against kind 0 (informative)",
        "",
        "dop853_numba at rtol = 1e-10 on the same wave in the \"now\" processes: kind 0 (`integrate_lattice`), and "
        "kind 4 (`lattice_adaptive.run_dop853_terms`, the general right-hand side of (ncimperfect) with its site "
        "coefficients read from `par`) with trivial terms (every coefficient 1: kind 0's floats, so its steps and "
        "final state, checked) and with active ones (sigma = 0.05, mass_sigma = 0.05, stiffnesses 1 + 0.05 cos n, "
        "delta0 = 0.05, quartic beta = 0.1: its own steps). ns per bead and force evaluation, median and min over "
        "the processes, and the median of the per-process ratio to kind 0.",
        "",
        "| right-hand side | median ns | min ns | ratio to kind 0 | evaluations | bitwise kind 0 |",
        "|---|---|---|---|---|---|",
        *rows4,
        "",
    ])
    OUT.write_text(text)
    print(f"wrote {OUT}", file=sys.stderr)


if __name__ == "__main__":
    main()
