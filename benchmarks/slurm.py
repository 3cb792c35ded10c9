"""The paper through a real Slurm against a local build, back to back: the wall times and what each way writes.

    tests/cluster/slurm-up.sh                      # a single-node Slurm on this machine
    python benchmarks/slurm.py [--target paper] [--repeats 2] [--rule-instances] [--no-docs]

Each repeat builds the target from scratch in fresh folders (Snakefile, config, workflow, profiles copied from
this checkout; its ``src`` linked), in turn: a local ``snakemake -j2``; ``cradle slurm TARGET`` (one Slurm job
running ``snakemake --cores 2`` with the local executor, its jobs forked from the warm process); and with
``--rule-instances``, ``snakemake --workflow-profile profiles/slurm`` (every rule instance submitted, grouped;
in the first repeat only: it takes minutes).
One untimed local build first loads the compiled kernels into the shared cache, so that no way pays for
compiling. Wall time is from the command's start to its exit, as a researcher waits for it. Every netCDF file
of each Slurm build is compared with the first local build's (benchmarks/compare_outputs.py: every variable,
bitwise). The table goes into docs/usage.md ("Cluster") unless ``--no-docs``.
"""
from __future__ import annotations

import argparse
import datetime as _dt
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from compare_outputs import compare_folders
from cradle.pipeline.workdir import copy_workflow
from doctable import git_commit, publish

ROOT = Path(__file__).resolve().parents[1]
WAYS = {
    "local": "local `snakemake -j2`",
    "allocation": "`cradle slurm` (one Slurm job, local executor inside)",
    "rule-instances": "`--workflow-profile profiles/slurm` (rule instances as Slurm jobs, grouped)",
}


def build(way: str, work: Path, target: str, env: dict) -> dict:
    cmd = {"local": [sys.executable, "-m", "snakemake", "-j2", target],
           "allocation": [sys.executable, "-m", "cradle", "slurm", "--quiet", target],
           "rule-instances": [sys.executable, "-m", "snakemake", "--workflow-profile", "profiles/slurm", target]}[way]
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, cwd=work, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    out = proc.stdout + proc.stderr
    (work / "build.out").write_text(out)
    if proc.returncode:
        sys.exit(f"{way} build failed in {work}:\n{out[-3000:]}")
    ids = set(re.findall(r"Slurm job (\d+) submitted|submitted with SLURM jobid (\d+)", out))
    logs = "".join(p.read_text(errors="replace") for p in (work / "results" / "logs").rglob("*.log"))
    return {"wall": wall, "slurm_jobs": len(ids), "forked": logs.count("forked job: peak resident memory"),
            "jobs": sum(1 for _ in (work / "results" / "logs").rglob("*.log"))}


def differing(reference: Path, other: Path) -> tuple[int, int]:
    """(netCDF files compared, files with any variable not bitwise equal or missing)."""
    reports, only_old, _ = compare_folders(reference, other)
    return len(reports) + len(only_old), len(only_old) + sum(bool(r.differences) for r in reports)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--target", default="paper")
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--rule-instances", action="store_true", dest="rule_instances",
                    help="also build through profiles/slurm, in the first repeat (several minutes)")
    ap.add_argument("--no-docs", action="store_true", help="do not write the table into docs/usage.md")
    args = ap.parse_args(argv)
    for cmd in ("sbatch", "squeue", "sacct"):
        if shutil.which(cmd) is None:
            sys.exit(f"no {cmd} on PATH: start Slurm first (tests/cluster/slurm-up.sh)")
    ways = ["local", "allocation"] + (["rule-instances"] if args.rule_instances else [])
    commit = git_commit()
    started = _dt.datetime.now(_dt.UTC)
    runs: dict[str, list[dict]] = {w: [] for w in ways}
    with tempfile.TemporaryDirectory(prefix="cradle-slurm-bench-") as tmp:
        env = dict(os.environ, CRADLE_KERNEL_CACHE=str(Path(tmp) / "kernel-cache"),
                   PYTHONPATH=f"{ROOT / 'src'}{os.pathsep}{os.environ.get('PYTHONPATH', '')}")
        build("local", copy_workflow(ROOT, Path(tmp) / "warm-up"), args.target, env)   # kernels compiled once, untimed
        reference = None
        for k in range(args.repeats):
            for way in ways if k == 0 else [w for w in ways if w != "rule-instances"]:
                work = copy_workflow(ROOT, Path(tmp) / f"{way}-{k}")
                run = build(way, work, args.target, env)
                if reference is None:
                    reference = work / "results"
                run["files"], run["differ"] = differing(reference, work / "results")
                runs[way].append(run)
                print(f"{way} {k}: {run['wall']:.1f} s", file=sys.stderr)
    local = statistics.median(r["wall"] for r in runs["local"])
    rows = ["| way | wall [s], each repeat | median [s] | / local | Slurm jobs | rule instances forked | "
            "netCDF files bitwise equal to the local build's |", "|---|---|---:|---:|---:|---:|---:|"]
    for way in ways:
        walls = [r["wall"] for r in runs[way]]
        med = statistics.median(walls)
        last = runs[way][-1]
        equal = sum(r["files"] - r["differ"] for r in runs[way])
        total = sum(r["files"] for r in runs[way])
        rows.append(f"| {WAYS[way]} | {', '.join(f'{w:.1f}' for w in walls)} | {med:.1f} | **{med / local:.2f}** "
                    f"| {last['slurm_jobs']} | {last['forked']} of {last['jobs']} | {equal} of {total} |")
    ended = _dt.datetime.now(_dt.UTC)
    text = (f"`python benchmarks/slurm.py --target {args.target} --repeats {args.repeats}"
            f"{' --rule-instances' if args.rule_instances else ''}` at commit {commit}, {started:%Y-%m-%d %H:%M}-"
            f"{ended:%H:%M} UTC, single-node Slurm of tests/cluster/slurm-up.sh on this machine ({os.cpu_count()} "
            f"cores; load average {os.getloadavg()[0]:.1f} at the end); the ways in turn within each repeat, "
            f"every build from scratch in a fresh folder, kernels compiled beforehand\n\n" + "\n".join(rows) + "\n")
    print(text)
    if not args.no_docs:
        publish("usage.md", f"slurm-{args.target}", text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
