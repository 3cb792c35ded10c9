"""The config fuzz at every extreme: every leaf of config.yaml, and of the keys a scene may add, given each value of
every type and extreme; each case validated or refused in one line naming the key, in under a second of CPU.

The leaves are those of tests/pipeline/test_config_fuzz.py (every key the schema declares, followed into the
entries config.yaml gives and the defaults it fills in, one representative per shape; with ``--every``, all of
them), over config.yaml plus one scene of a real cradle that gives what a scene may add: ``cradle:`` (SI units),
``damping:`` and ``terms:`` (inhomogeneity, precompression, an on-site potential). Every analysis section of
``beyond:`` is in the filled config (its declared defaults), so its keys are fuzzed too. The values (:data:`VALUES`):
0, +-1e-300, +-1e300, nan, +-inf, a string, a list of 1e6 numbers, a nested mapping, null, true.

A case runs what the Snakefile runs before any job (cradle.pipeline.config.validate, then the planning of the
analysis whose section it is in) in this process; CPU time per case (``time.process_time``: the machine is
shared). Writes the counts and the slowest cases between the markers of docs/extremes.md::

    python benchmarks/config_fuzz.py [--every]
"""
from __future__ import annotations

import copy
import datetime as dt
import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "tests"), str(ROOT / "tests" / "pipeline")]

from cradle.pipeline import config as cc  # noqa: E402
from cradle.specs.values import key_path  # noqa: E402
from doctable import publish  # noqa: E402
from test_config_fuzz import _alarm, cases, leaves, run_case  # noqa: E402

#: the values each leaf is given
VALUES = {"zero": 0, "tiny": 1e-300, "-tiny": -1e-300, "huge": 1e300, "-huge": -1e300, "nan": math.nan,
          "inf": math.inf, "-inf": -math.inf, "string": "fuzz", "list of 1e6": [1.5] * 1_000_000,
          "nested mapping": {"a": {"b": [1, {"c": None}]}}, "null": None, "true": True}
#: what a mapping (a section, an entry, an object) is given: any number is the same wrong type there
NOT_MAPPINGS = ("zero", "string", "list of 1e6", "null", "nan")
#: scenes that give every key a scene may add (docs/physical-units.md, docs/imperfect-cradles.md): a real cradle in
#: SI with damping, and an imperfect cradle (damping and terms do not go together)
EXTRA_SCENES = {
    "fuzz-si": {"N": 16, "bc": "free", "cradle": {"material": "steel", "radius": 0.01, "length": 0.1}, "units": "si",
                "initial": {"kind": "packet", "amplitude": 1.0e-9, "width": 6},
                "damping": {"onsite": 0.05, "contact": 1.0e-6},
                "exact": {"method": "dop853_numba", "rtol": 1.0e-12}, "t_end": 0.5, "store": {"every": 0.01}},
    "fuzz-terms": {"N": 16, "bc": "periodic", "initial": {"kind": "packet", "amplitude": 0.1, "width": 6},
                   "terms": {"inhomogeneity": {"sigma": 0.01, "mass_sigma": 0.01, "seed": 1},
                             "precompression": {"delta0": 0.1}, "onsite": {"potential": "quartic", "beta": 0.1}},
                   "exact": {"method": "dop853_numba", "rtol": 1.0e-12}, "t_end": 10.0, "store": {"every": 0.5}}}
LIMIT_S = 1.0


def main(argv: list[str]) -> int:
    raw = yaml.safe_load((ROOT / "config.yaml").read_text())
    raw["scenes"].update(copy.deepcopy(EXTRA_SCENES))
    filled = cc.validate(raw)
    paths = leaves(raw, filled, every="--every" in argv)
    signal.signal(signal.SIGALRM, _alarm)   # run_case's watchdog
    counts: dict[str, int] = {}
    failures, times = [], []
    start = time.process_time()
    for path, label, value in cases(filled, paths, VALUES, NOT_MAPPINGS):
        t0 = time.process_time()
        outcome, problem = run_case(raw, filled, path, value)
        took = time.process_time() - t0
        case = f"{key_path(list(path))} = {label}"
        counts[outcome] = counts.get(outcome, 0) + 1
        times.append((took, case, outcome))
        if problem is not None or took > LIMIT_S:
            failures.append(f"{case}: {outcome}, {took:.2f} s: {problem}")
    cpu = time.process_time() - start
    times.sort(reverse=True)
    commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, check=False).stdout.strip() or "?"
    stamp = dt.datetime.now(dt.UTC).strftime("%Y-%m-%d %H:%M UTC")
    lines = [f"`python benchmarks/config_fuzz.py` at commit {commit}, {stamp} (load average "
             f"{os.getloadavg()[0]:.1f}: the 2 cores are shared): {len(paths)} leaves of config.yaml and of two scenes "
             f"giving `cradle:`, `damping:` and `terms:` (mappings included) x {len(VALUES)} values "
             f"({len(NOT_MAPPINGS)} for a mapping) = {sum(counts.values())} cases: "
             f"{', '.join(f'{n} {k}' for k, n in sorted(counts.items()))}; {cpu:.0f} s of CPU in all; "
             f"{len(failures)} cases over {LIMIT_S:g} s of CPU or not one line naming the key.", "",
             "| slowest cases | outcome | CPU [s] |", "|---|---|---:|"]
    lines += [f"| `{case}` | {outcome} | {took:.3f} |" for took, case, outcome in times[:8]]
    if failures:
        lines += ["", "Failing cases:", ""] + [f"* `{f[:230]}{'...' if len(f) > 230 else ''}`" for f in failures[:40]]
    text = "\n".join(lines)
    print(text)
    publish("extremes.md", "config-fuzz", text)
    return 1 if failures else 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
