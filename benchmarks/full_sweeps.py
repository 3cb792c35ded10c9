"""The full sweeps' wall times, the code before against now, from fresh clones: one record line per build.

    python benchmarks/full_sweeps.py measure breather_interactions_full --before 9d0ea5d [--records FILE]
    python benchmarks/full_sweeps.py compare breather_interactions_full BEFORE_CLONE NOW_CLONE [--records FILE]
    python benchmarks/full_sweeps.py table [--records FILE] [--no-docs]

``measure`` clones this repository twice (``--before REV`` and HEAD; HEAD only without ``--before``), each with
its own compiled-kernel cache, runs ``snakemake -j2 TARGET`` in each (now first, then before), times it from
the command's start to its exit, and appends one line per build to the records; then ``compare`` on the two
clones. ``compare`` pairs every netCDF file the two builds wrote under the target's folder
(benchmarks/compare_outputs.py: every variable, bitwise) and appends one line. ``table`` writes the records as
the table ``full-sweeps`` of docs/sweep-cases.md. A record line is ``LABEL key=value ...`` (``build`` or
``compare``), so a build timed by hand the same way (clone, ``snakemake -j2``, wall from start to exit) is one
line in the same form.
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from datetime import UTC, datetime
from pathlib import Path

from compare_outputs import compare_folders
from doctable import git_commit, publish

ROOT = Path(__file__).resolve().parents[1]
RECORDS = ROOT / "results" / "benchmarks" / "full-sweeps.txt"


def record(path: Path, label: str, **fields) -> str:
    line = label + " " + " ".join(f"{k}={v}" for k, v in fields.items())
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "a") as fh:
        fh.write(line + "\n")
    return line


def read_records(path: Path) -> list[dict]:
    out = []
    for line in path.read_text().splitlines():
        if line.strip():
            label, *pairs = line.split()
            out.append({"label": label, **dict(p.split("=", 1) for p in pairs)})
    return out


def _commit(clone: Path) -> str:
    return git_commit(repo=clone)


def build(clone: Path, target: str, cores: int, records: Path, role: str) -> None:
    env = dict(os.environ, PYTHONPATH=str(clone / "src"), CRADLE_KERNEL_CACHE=str(clone / ".kernel-cache"))
    start, load0 = datetime.now(UTC), os.getloadavg()[0]
    t0 = time.perf_counter()
    with open(clone / f"{target}.log", "w") as log:
        rc = subprocess.run([sys.executable, "-m", "snakemake", f"-j{cores}", target], cwd=clone, env=env,
                            stdout=log, stderr=subprocess.STDOUT).returncode
    wall = time.perf_counter() - t0
    print(record(records, "build", role=role, target=target, rc=rc, start=f"{start:%Y-%m-%dT%H:%M:%S}",
                 end=f"{datetime.now(UTC):%H:%M:%S}", wall=f"{wall:.1f}", cores=cores, load_start=f"{load0:.2f}",
                 load_end=f"{os.getloadavg()[0]:.2f}", commit=_commit(clone)))
    if rc:   # recorded, but a failed build's wall time says nothing: stop here
        sys.exit(f"snakemake -j{cores} {target} failed in {clone} (log: {clone / f'{target}.log'})")


def compare(target: str, before: Path, now: Path, records: Path) -> None:
    """Every netCDF file of the target's folder in both clones' results, bitwise."""
    folder = target.removesuffix("_full").replace("_", "-")
    a, b = before / "results" / folder, now / "results" / folder
    reports, only_old, only_new = compare_folders(a, b)
    print(record(records, "compare", target=target, before=_commit(before), now=_commit(now), files=len(reports),
                 variables=sum(r.compared for r in reports), differ=sum(bool(r.differences) for r in reports),
                 only_before=len(only_old), only_now=len(only_new)))


def _build_cells(build: dict) -> list[str]:
    """A build's commit and wall time, as two cells of the table."""
    wall = float(build["wall"])
    return [build["commit"], f"{wall:.0f} ({wall / 60:.1f} min)"]


def table(records: Path) -> str:
    recs = read_records(records)
    rows = ["| target | before: commit | before: wall [s] | now: commit | now: wall [s] | now / before | "
            "load average (start-end) | netCDF files bitwise equal |", "|---|---|---:|---|---:|---:|---|---|"]
    for target in dict.fromkeys(r["target"] for r in recs):
        builds = {r["role"]: r for r in recs if r["label"] == "build" and r["target"] == target}
        cmp = [r for r in recs if r["label"] == "compare" and r["target"] == target]
        now, before = builds.get("now"), builds.get("before")
        if now is None:
            continue
        ratio = f"**{float(now['wall']) / float(before['wall']):.2f}**" if before else "-"
        loads = "; ".join(f"{b['load_start']}-{b['load_end']}" for b in (before, now) if b)
        equal = (f"{int(cmp[-1]['files']) - int(cmp[-1]['differ'])} of {cmp[-1]['files']} "
                 f"({cmp[-1]['variables']} variables)" if cmp else "not compared")
        if cmp and int(cmp[-1]["only_now"]):
            equal += f"; {cmp[-1]['only_now']} files only in now's build"
        cells = [f"`{target}`", *(_build_cells(before) if before else ["-", "-"]), *_build_cells(now), ratio,
                 loads, equal]
        rows.append("| " + " | ".join(cells) + " |")
    days = sorted({r["start"][:10] for r in recs if r["label"] == "build"})
    return (f"`snakemake -j2 TARGET` from fresh clones, {', '.join(days)} ({os.cpu_count()} cores), the builds one "
            f"after another; wall time from the command's start to its exit (records: `benchmarks/full_sweeps.py`)"
            "\n\n" + "\n".join(rows) + "\n")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    m = sub.add_parser("measure")
    m.add_argument("targets", nargs="+")
    m.add_argument("--before", metavar="REV")
    m.add_argument("--cores", type=int, default=2)
    m.add_argument("--work", type=Path, default=Path("/tmp/cradle-full-sweeps"))
    c = sub.add_parser("compare")
    c.add_argument("target")
    c.add_argument("before", type=Path)
    c.add_argument("now", type=Path)
    t = sub.add_parser("table")
    t.add_argument("--no-docs", action="store_true")
    for p in (m, c, t):
        p.add_argument("--records", type=Path, default=RECORDS)
    args = ap.parse_args(argv)
    if args.cmd == "compare":
        compare(args.target, args.before, args.now, args.records)
        return 0
    if args.cmd == "measure":
        for target in args.targets:
            clones = {}
            for role, rev in (("now", "HEAD"), ("before", args.before)):
                if rev is None:
                    continue
                clone = args.work / f"{target}-{role}"
                subprocess.run(["git", "clone", "-q", str(ROOT), str(clone)], check=True)
                subprocess.run(["git", "checkout", "-q", rev], cwd=clone, check=True)
                build(clone, target, args.cores, args.records, role)
                clones[role] = clone
            if "before" in clones:
                compare(target, clones["before"], clones["now"], args.records)
    text = table(args.records)
    print(text)
    if not getattr(args, "no_docs", False):
        publish("sweep-cases.md", "full-sweeps", text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
