"""What reading and validating config.yaml costs: the table ``validation-cost`` of docs/performance.md.

    python benchmarks/validation_cost.py [--repeats 9] [--no-docs]

Each repeat is a fresh process that imports :mod:`cradle.pipeline.config` (not counted), then times in CPU time
(``time.process_time``) the bounded YAML read (``read_yaml``) and the one validation pass with the budget and the
checks across keys (``validate``), as the Snakefile runs them before any job, on a config validated for the first time
in that process (no remembered entry). Twice: cold (what validation imports on its way -- scipy.optimize for the
homoclinic entries solved at validation -- counted), and with that module imported first (the pass itself). And the
whole command ``python -m cradle.pipeline.config config.yaml`` (interpreter, imports, read, validation) as the
CPU time of its process; the bytecode of every module written before the first timed process, as a user's Python
reads it. The median and the range over the repeats; target: validation under 0.2 s of
CPU (issue "One validator, one kernel per model"). A timing: run it on a quiet machine.
"""
from __future__ import annotations

import argparse
import datetime as dt
import json
import os
import resource
import statistics
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from doctable import git_commit, publish  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]

CHILD = """
import json, sys, time
from cradle.pipeline import config as cc
t0 = time.process_time()
raw = cc.read_yaml(sys.argv[1])
t1 = time.process_time()
if sys.argv[2] == "warm":   # what validation imports on its way (numba, scipy), imported first
    import cradle.models.homoclinic_continuation, scipy.optimize
t2 = time.process_time()
cc.validate(raw)
t3 = time.process_time()
print(json.dumps({"read": t1 - t0, "imports": t2 - t1, "validate": t3 - t2}))
"""


#: the children as a user's Python runs them: compiled bytecode written once and read after (a sandbox may set
#: PYTHONDONTWRITEBYTECODE, which makes every import compile its source)
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def one(path: Path, imports: str) -> dict[str, float]:
    out = subprocess.run([sys.executable, "-c", CHILD, str(path), imports], capture_output=True, text=True,
                         check=True, cwd=ROOT, env=ENV)
    return json.loads(out.stdout.strip().splitlines()[-1])


def whole(path: Path) -> float:
    """CPU seconds of the process ``python -m cradle.pipeline.config path``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sys.executable, "-m", "cradle.pipeline.config", str(path)], capture_output=True, check=True,
                   cwd=ROOT, env=ENV)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=9)
    ap.add_argument("--no-docs", action="store_true", help="print the table only")
    args = ap.parse_args(argv)
    whole(ROOT / "config.yaml")   # untimed: writes the bytecode every later process reads
    cold = [one(ROOT / "config.yaml", "cold") for _ in range(args.repeats)]
    warm = [one(ROOT / "config.yaml", "warm") for _ in range(args.repeats)]
    process = [{"process": whole(ROOT / "config.yaml")} for _ in range(args.repeats)]
    head = git_commit()
    steps = (("read", cold, "`read_yaml` (bounded YAML read)"),
             ("validate", cold, "`validate` in a fresh process (the modules it imports on its way included)"),
             ("imports", warm, "of which: importing scipy.optimize (the homoclinic entries solved at validation)"),
             ("validate", warm, "`validate` with it imported (the pass, the budget, the checks)"),
             ("process", process, "the whole command `python -m cradle.pipeline.config config.yaml`"))
    rows = []
    for key, runs, what in steps:
        xs = [r[key] for r in runs]
        rows.append(f"| {what} | {statistics.median(xs) * 1e3:.0f} | {min(xs) * 1e3:.0f}-{max(xs) * 1e3:.0f} |")
    text = (f"`python benchmarks/validation_cost.py` at commit {head}, "
            f"{dt.datetime.now(dt.UTC):%Y-%m-%d %H:%M} UTC (load average {os.getloadavg()[0]:.1f}): "
            f"config.yaml, {args.repeats} fresh processes each way, CPU time; target: validation under 200 ms\n\n"
            "| step | median [ms] | range [ms] |\n|---|---:|---:|\n" + "\n".join(rows) + "\n")
    print(text)
    if not args.no_docs:
        publish("performance.md", "validation-cost", text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
