"""Time `snakemake -j2 paper` from a fresh clone, cold then warm, and say where the time goes.

    python benchmarks/rebuild.py [--target paper] [--cores 2] [--before REV] [--out results/benchmarks/rebuild.md]

1. ``git clone`` of this repository's HEAD into a temporary folder (uncommitted
   changes are not included: this is what a newcomer gets);
2. **cold**: ``snakemake -j2 paper`` there, with an empty compiled-kernel cache
   (``CRADLE_KERNEL_CACHE`` pointed into the temporary folder: numba compiles
   each kernel on first use; see docs/compiled-kernels.md);
3. **warm**: ``results/`` removed, the same command again (the cache now warm).

The clone's ``src/`` is put first on PYTHONPATH, so the installed ``cradle``
(an editable install of this folder) is shadowed by the clone's and no install
is timed. Each job's log (``results/logs``) starts with the process start-up
time (interpreter, Snakemake's script preamble, imports; see
:func:`cradle.pipeline.runner.process_age`) and its steps' times; the outputs record the
integrators' own wall time. From these the table splits the job time into:

* start-up: process start to the first line of cradle code, summed over jobs;
* integration: the integrators' wall time (``wall_time_s`` of exact.nc, dps.nc);
* kernel loads, initial data, I/O: the rest of the simulate jobs (compiling,
  in the cold run);
* figures: drawing + saving (PDF and PNG), and loading their inputs;
* other jobs: homoclinic, map orbits, the claims table;

and compares their sum over 2 cores with the wall time (the rest is Snakemake:
DAG building, job scheduling and bookkeeping, and cores left idle). The *compute floor* is
the sum of the jobs' times less their start-up, over the cores: what the build's work needs.
A job forked from the warm process (:mod:`cradle.pipeline.warm`) counts its start-up from the
start of its own process (interpreter, Snakemake's preamble, the hand-over, the fork).
``--before REV`` builds that commit too, in its own folder, alternating with HEAD.
"""
from __future__ import annotations

import argparse
import datetime as _dt
import os
import platform
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from doctable import git_commit, publish

ROOT = Path(__file__).resolve().parents[1]
STAMP = re.compile(r"^(\d{4}-\d\d-\d\d \d\d:\d\d:\d\d,\d{3}) (.*)$")


def _lines(path: Path):
    for line in path.read_text().splitlines():
        m = STAMP.match(line)
        if m:
            yield _dt.datetime.strptime(m.group(1), "%Y-%m-%d %H:%M:%S,%f").timestamp(), m.group(2)


def job_times(results: Path) -> dict:
    """Per job (one log file): start-up, total and the logged step times, by job kind."""
    jobs = []
    for log in sorted((results / "logs").rglob("*.log")):
        lines = list(_lines(log))
        if not lines:
            continue
        kind = log.relative_to(results / "logs").parts[0]
        startup = next((float(m.group(1)) for _, text in lines
                        if (m := re.match(r"process start-up [^:]*: ([\d.]+) s", text))), 0.0)
        forked = any("(forked from the warm process)" in text for _, text in lines)
        job = {"kind": kind, "name": log.stem, "startup": startup, "forked": forked, "start": lines[0][0] - startup,
               "end": lines[-1][0], "total": startup + lines[-1][0] - lines[0][0], "draw": 0.0, "save": 0.0}
        for _, text in lines:
            if m := re.match(r"figure \S+: drawn in ([\d.]+) s, saved in ([\d.]+) s", text):
                job["draw"], job["save"] = float(m.group(1)), float(m.group(2))
        jobs.append(job)
    return jobs


def integration_time(results: Path) -> float:
    """Sum of the integrators' own wall time over the exact and DpS outputs."""
    import xarray as xr

    total = 0.0
    for path in sorted((results / "sim").rglob("*.nc")):
        with xr.open_dataset(path) as ds:
            total += float(ds.attrs.get("wall_time_s", 0.0))
    return total


def breakdown(results: Path, wall: float, cores: int) -> dict:
    jobs = job_times(results)
    sim = [j for j in jobs if j["kind"] == "sim"]
    fig = [j for j in jobs if j["kind"] == "figures"]
    rest = [j for j in jobs if j["kind"] not in ("sim", "figures")]
    integ = integration_time(results)
    out = {
        "wall": wall,
        "jobs": len(jobs),
        "start-up (all jobs)": sum(j["startup"] for j in jobs),
        "integration (exact + DpS)": integ,
        "kernel loads, initial data, I/O (simulate)": sum(j["total"] - j["startup"] for j in sim) - integ,
        "figures: drawing": sum(j["draw"] for j in fig),
        "figures: saving PDF + PNG": sum(j["save"] for j in fig),
        "figures: loading inputs": sum(j["total"] - j["startup"] - j["draw"] - j["save"] for j in fig),
        "other jobs: stage 1, claims table, analyses": sum(j["total"] - j["startup"] for j in rest),
    }
    out["sum of job times"] = sum(j["total"] for j in jobs)
    out["Snakemake and idle cores"] = wall - out["sum of job times"] / cores
    # what the build's computations need on these cores: the jobs' time without their start-up
    out["compute floor"] = (out["sum of job times"] - out["start-up (all jobs)"]) / cores
    out["wall / compute floor"] = wall / out["compute floor"]
    out["jobs forked from the warm process"] = sum(j["forked"] for j in jobs)
    # from the first job's start to the last job's end: how long 0, 1, 2... jobs ran at once
    events = sorted([(j["start"], 1) for j in jobs] + [(j["end"], -1) for j in jobs])
    running, last, spans = 0, events[0][0], {}
    for t, step in events:
        spans[running] = spans.get(running, 0.0) + t - last
        running, last = running + step, t
    out["no job running: DAG before, wrap-up after"] = wall - (events[-1][0] - events[0][0])
    for k in range(cores + 1):
        out[f"{k} job{'s' if k != 1 else ''} running"] = spans.get(k, 0.0)
    out[f"more than {cores} running"] = sum(v for k, v in spans.items() if k > cores)
    return out


def run(clone: Path, target: str, cores: int) -> float:
    env = dict(os.environ, PYTHONPATH=f"{clone / 'src'}{os.pathsep}{os.environ.get('PYTHONPATH', '')}",
               CRADLE_KERNEL_CACHE=str(clone.parent / "kernel-cache"))
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "snakemake", f"-j{cores}", target, "--quiet", "all"],
                          cwd=clone, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if proc.returncode:
        sys.exit(f"snakemake failed in {clone}:\n{proc.stderr[-3000:]}")
    return wall


def table(runs: dict, cores: int) -> str:
    keys = list(next(iter(runs.values())))
    head = "| | " + " | ".join(runs) + " |\n|---|" + "---:|" * len(runs) + "\n"
    rows = []
    for key in keys:
        cells = [f"{r[key]:.0f}" if key.startswith("jobs") else f"**{r[key]:.2f}**" if key.startswith("wall /")
                 else f"{r[key]:.1f} s" for r in runs.values()]
        if key.startswith("no job running"):
            rows.append("| *timeline* |" + " |" * len(runs))
        label = (f"**{key}**" if key in ("wall", "wall / compute floor") else
                 f"{key} (wall - sum/{cores})" if key.startswith("Snake") else
                 f"{key} ((sum - start-up)/{cores})" if key == "compute floor" else key)
        rows.append(f"| {label} | " + " | ".join(cells) + " |")
    return head + "\n".join(rows) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--target", default="paper")
    ap.add_argument("--cores", type=int, default=2)
    ap.add_argument("--out", type=Path, help="also write the table (markdown) here")
    ap.add_argument("--no-docs", action="store_true", help="do not write the table into docs/performance.md")
    ap.add_argument("--before", metavar="REV", help="also build this commit, alternating with HEAD, for a "
                    "before/after measured in the same session")
    args = ap.parse_args(argv)
    commit = git_commit()
    revs = {"": "HEAD"}
    if args.before:
        before = git_commit(args.before)
        revs = {f"{before}: ": before, "": "HEAD"}
    with tempfile.TemporaryDirectory(prefix="cradle-rebuild-") as tmp:
        clones = {}
        for prefix, rev in revs.items():   # each its own folder and compiled-kernel cache
            clones[prefix] = Path(tmp) / (f"before-{rev}" if prefix else "now") / "cradle"
            subprocess.run(["git", "clone", "-q", str(ROOT), str(clones[prefix])], check=True)
            subprocess.run(["git", "checkout", "-q", rev], cwd=clones[prefix], check=True)
        runs = {}
        for label in ("cold", "warm"):   # before and now alternate: both measured in the same minutes
            for prefix, clone in clones.items():
                shutil.rmtree(clone / "results", ignore_errors=True)
                wall = run(clone, args.target, args.cores)
                runs[prefix + label] = breakdown(clone / "results", wall, args.cores)
                print(f"{prefix}{label}: {wall:.1f} s", file=sys.stderr)
    ended = _dt.datetime.now(_dt.UTC)
    text = (f"`snakemake -j{args.cores} {args.target}` from a fresh clone of {commit}"
            + (f" and of {before} (columns `{before}: ...`, the code before; runs alternating)" if args.before else "")
            + f", {_dt.date.today()}, {platform.machine()} with {os.cpu_count()} cores, "
            f"Python {platform.python_version()}, load average {os.getloadavg()[0]:.1f} at the end"
            f" ({ended:%H:%M} UTC)\n\n" + table(runs, args.cores))
    print(text)
    if not args.no_docs:
        publish("performance.md", f"rebuild-{args.target}", text)
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
