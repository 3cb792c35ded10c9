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

    python benchmarks/config_fuzz.py [--every] [--real 30 [--seed S] [--below 20]]

``--real N``: then N of the accepted cases, drawn with a recorded seed among those whose changed value reaches a job
that ``cradle run`` runs (a scene, homoclinic or map entry: the entries whose resolved parameters differ from
config.yaml's) and whose estimate (:mod:`cradle.pipeline.budget`) is under ``--below`` seconds, are run for real:
``cradle run NAME`` of the case's config, in a subprocess, into a scratch folder. Its CPU time (the machine is
shared; the estimate is of a quiet machine's wall time, which on one core is the CPU time) and the bytes it wrote are
set against the estimate's seconds and bytes; a ratio outside [1/10, 10] is a failing case. Writes the table
``config-fuzz-real`` of docs/extremes.md.
"""
from __future__ import annotations

import argparse
import copy
import datetime as dt
import math
import os
import random
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "tests"), str(ROOT / "tests" / "pipeline")]

from cradle.pipeline import config as cc  # noqa: E402
from cradle.specs.values import key_path  # noqa: E402
from doctable import git_commit, publish  # noqa: E402
from test_config_fuzz import _alarm, cases, leaves, run_case, substituted  # noqa: E402

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


#: the sections whose entries ``cradle run`` runs, by the prefix of their estimate's key
RUNNABLE = ("scenes", "homoclinic", "map")
#: the ratios of actual to estimated cost a sampled run must lie within
WITHIN = 10.0


def jobs_of(before: object, after: object) -> list[tuple[str, str]]:
    """(section, name) of every entry ``cradle run`` runs whose resolved parameters differ between the typed
    configs ``before`` and ``after`` (a case's changed value reaches those jobs)."""
    from cradle.specs.declare import plain

    out = []
    for section in RUNNABLE:
        old, new = getattr(before, section), getattr(after, section)
        out += [(section, name) for name in new if name not in old or plain(new[name]) != plain(old[name])]
    return out


def _sampled(raw: dict, filled: dict, accepted: list[tuple[tuple, str, object]], count: int, seed: int,
             below: float) -> tuple[list[dict], int]:
    """``count`` accepted cases drawn with ``seed`` among those reaching a job ``cradle run`` runs whose estimate
    is under ``below`` seconds, each with its job, its config and the estimate; and how many were eligible."""
    from cradle.pipeline import budget

    base = cc.typed(raw)
    eligible = []
    for path, label, value in accepted:
        cfg = substituted(raw, filled, path, value)
        typed = cc.typed(cfg)
        by_key = {e.key: e for e in budget.estimates(typed)}
        jobs = [(s, n) for s, n in jobs_of(base, typed) if f"{s}.{n}" in by_key]
        jobs = [j for j in jobs if by_key[f"{j[0]}.{j[1]}"].seconds < below]
        if jobs:
            section, name = min(jobs, key=lambda j: by_key[f"{j[0]}.{j[1]}"].seconds)
            eligible.append({"case": f"{key_path(list(path))} = {label}", "config": cfg, "section": section,
                             "name": name, "estimate": by_key[f"{section}.{name}"]})
    return random.Random(seed).sample(eligible, min(count, len(eligible))), len(eligible)


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run_for_real(case: dict, scratch: Path) -> dict:
    """``cradle run`` of the case's job from its config, in a subprocess: CPU and wall seconds, bytes written, exit
    status and the last line it printed."""
    folder = scratch / f"case-{len(list(scratch.iterdir()))}"
    folder.mkdir()
    config = folder / "config.yaml"
    config.write_text(yaml.safe_dump(case["config"], sort_keys=False))
    cpu0, wall0 = _children_cpu(), time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "cradle", "run", case["name"], "--config", str(config), "--out",
                           str(folder / "out")], cwd=folder, capture_output=True, text=True, check=False)
    cpu, wall = _children_cpu() - cpu0, time.perf_counter() - wall0
    written = sum(p.stat().st_size for p in (folder / "out").rglob("*") if p.is_file() and p.suffix == ".nc")
    lines = (done.stdout + done.stderr).strip().splitlines()
    shutil.rmtree(folder)
    return {"cpu": cpu, "wall": wall, "bytes": written, "status": done.returncode, "last": lines[-1] if lines else ""}


def real_table(sample: list[dict], eligible: int, accepted: int, seed: int, below: float,
               scratch: Path) -> tuple[str, int]:
    """Run every sampled case for real (:func:`run_for_real`); the table of estimates against actual costs, and the
    number of cases outside :data:`WITHIN`."""
    from cradle.pipeline.budget import fmt_bytes

    rows, bad = [], 0
    for case in sample:
        got = run_for_real(case, scratch)
        e = case["estimate"]
        first = ""
        if got["status"] == 0 and got["cpu"] > WITHIN * e.seconds:
            # once more: the estimate is of a run whose kernels are compiled (cradle.integrators._cache)
            first, got = f" (first run {got['cpu']:.3g} s, compiling)", run_for_real(case, scratch)
        t_ratio, b_ratio = got["cpu"] / e.seconds, got["bytes"] / max(e.disk_bytes, 1.0)
        ok = got["status"] == 0 and 1 / WITHIN <= t_ratio <= WITHIN and 1 / WITHIN <= b_ratio <= WITHIN
        bad += not ok
        rows.append(f"| `{case['case']}` | {case['section']}.{case['name']} | {e.seconds:.3g} | "
                    f"{got['cpu']:.3g}{first} | "
                    f"{got['wall']:.3g} | {t_ratio:.2f} | {fmt_bytes(e.disk_bytes)} | {fmt_bytes(got['bytes'])} | "
                    f"{b_ratio:.2f} | {'yes' if ok else 'NO: ' + got['last'][:120].replace('|', '/')} |")
        print(rows[-1], flush=True)
    head = [f"`python benchmarks/config_fuzz.py --real {len(sample)} --seed {seed} --below {below:g}` at commit "
            f"{git_commit()}, {_stamp()} (load average {os.getloadavg()[0]:.1f}): {len(sample)} of the {eligible} "
            f"accepted cases (of {accepted}) whose changed value reaches a job `cradle run` runs with an estimate "
            f"under {below:g} s, each run for real (`cradle run NAME` of the case's config, its own process); CPU "
            f"time of that process against the estimate's seconds, bytes of its netCDF files against the estimate's; "
            f"{len(sample) - bad} within {WITHIN:g}x both ways, {bad} not.", "",
            "| case | job | estimate [s] | CPU [s] | wall [s] | CPU / estimate | estimated output | written | "
            "written / estimate | within 10x |",
            "|---|---|---:|---:|---:|---:|---:|---:|---:|---|"]
    return "\n".join(head + rows), bad


def _stamp() -> str:
    return dt.datetime.now(dt.UTC).strftime("%Y-%m-%d %H:%M UTC")


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--every", action="store_true", help="every entry and list item, not one per shape")
    ap.add_argument("--real", type=int, default=0, metavar="N", help="then run N accepted cases for real")
    ap.add_argument("--seed", type=int, default=20261128, help="seed of the draw of --real's cases")
    ap.add_argument("--below", type=float, default=20.0, help="--real draws among jobs estimated under this [s]")
    args = ap.parse_args(argv)
    raw = yaml.safe_load((ROOT / "config.yaml").read_text())
    raw["scenes"].update(copy.deepcopy(EXTRA_SCENES))
    filled = cc.validate(raw)
    paths = leaves(raw, filled, every=args.every)
    signal.signal(signal.SIGALRM, _alarm)   # run_case's watchdog
    counts: dict[str, int] = {}
    failures, times, accepted = [], [], []
    start = time.process_time()
    for path, label, value in cases(filled, paths, VALUES, NOT_MAPPINGS):
        t0 = time.process_time()
        outcome, problem = run_case(raw, filled, path, value)
        took = time.process_time() - t0
        case = f"{key_path(list(path))} = {label}"
        counts[outcome] = counts.get(outcome, 0) + 1
        times.append((took, case, outcome))
        if outcome == "accepted" and problem is None:
            accepted.append((path, label, value))
        if problem is not None or took > LIMIT_S:
            failures.append(f"{case}: {outcome}, {took:.2f} s: {problem}")
    cpu = time.process_time() - start
    times.sort(reverse=True)
    lines = [f"`python benchmarks/config_fuzz.py` at commit {git_commit()}, {_stamp()} (load average "
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
    bad = 0
    if args.real:
        signal.signal(signal.SIGALRM, signal.SIG_DFL)
        sample, eligible = _sampled(raw, filled, accepted, args.real, args.seed, args.below)
        scratch = Path(tempfile.mkdtemp(prefix="config-fuzz-real-"))
        try:
            real, bad = real_table(sample, eligible, len(accepted), args.seed, args.below, scratch)
        finally:
            shutil.rmtree(scratch, ignore_errors=True)
        publish("extremes.md", "config-fuzz-real", real)
    return 1 if failures or bad else 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
