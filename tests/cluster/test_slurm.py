"""The workflow through a real Slurm (tests/cluster/slurm-up.sh), both ways: the whole build in one Slurm job
(`cradle slurm TARGET`) and every rule instance submitted (grouped) by
`snakemake --workflow-profile profiles/slurm`; the data of every netCDF output bitwise equal to a local
`snakemake -j2` build of the same target (built first, once).

Run it after tests/cluster/slurm-up.sh (it skips, saying why, when `sbatch`, `sinfo` or `sacct` do not
answer; the rule-instance test also when the executor plugin is missing)::

    tests/cluster/slurm-up.sh && python -m pytest -m slurm tests/cluster -s; tests/cluster/slurm-down.sh

``CRADLE_SLURM_TARGET`` (default ``paper``) chooses what the builds make. Each test writes what it measured
(wall time of its build and of the local one, jobs, Slurm jobs, per-job times from sacct) to
``results/slurm-overhead.json`` of its build and prints it; benchmarks/slurm.py times the three ways back to
back, repeated, and writes the table.
"""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from conftest import run_snakemake
from cradle.pipeline.workdir import copy_workflow

pytestmark = pytest.mark.slurm

ROOT = Path(__file__).resolve().parents[2]
TARGET = os.environ.get("CRADLE_SLURM_TARGET", "paper")
# attributes that record when, where and how long a file was made, not what it holds
VOLATILE = re.compile(r"(^|_)(history|date_created|wall_time_s|command|hostname|host|created|"
                      r"startup_s|time_s)$")


def _answers(*cmd) -> str | None:
    """None if ``cmd`` runs and exits 0 within 10 s, else why not."""
    if shutil.which(cmd[0]) is None:
        return f"no {cmd[0]} on PATH (install Slurm: tests/cluster/slurm-up.sh)"
    try:
        proc = subprocess.run(cmd, check=False, capture_output=True, text=True, timeout=10)
    except subprocess.TimeoutExpired:
        return f"`{' '.join(cmd)}` did not answer in 10 s"
    if proc.returncode != 0:
        return (f"`{' '.join(cmd)}` failed: {' '.join(proc.stderr.split())[:200]} "
                "(start Slurm: tests/cluster/slurm-up.sh)")
    return None


@pytest.fixture(scope="module")
def slurm():
    for cmd in (("sbatch", "--version"), ("sinfo", "-h", "-o", "%T"), ("sacct", "-n", "-X", "-S", "now")):
        why = _answers(*cmd)
        if why:
            pytest.skip(why)


def _workdir(path: Path) -> Path:
    return copy_workflow(ROOT, path)


def _build(work: Path, *args) -> float:
    t0 = time.perf_counter()
    proc = run_snakemake(work, *args, TARGET, timeout=3 * 3600)
    wall = time.perf_counter() - t0
    (work / "snakemake.out").write_text(proc.stdout + proc.stderr)
    assert proc.returncode == 0, (proc.stdout + proc.stderr)[-3000:]
    return wall


def _same_data(a: Path, b: Path) -> list[str]:
    """Differences between two netCDF files (every group): variables bitwise, attributes but the volatile ones."""
    import netCDF4

    out = []

    def walk(ga, gb, prefix):
        for name in sorted(set(ga.variables) | set(gb.variables)):
            if name not in ga.variables or name not in gb.variables:
                out.append(f"{prefix}{name}: in one file only")
                continue
            va, vb = ga.variables[name], gb.variables[name]
            va.set_auto_mask(False)
            vb.set_auto_mask(False)
            xa, xb = np.asarray(va[...]), np.asarray(vb[...])
            # variable-length strings come back as arrays of Python objects, whose bytes are addresses
            same = xa.tolist() == xb.tolist() if xa.dtype == object else xa.tobytes() == xb.tobytes()
            if xa.shape != xb.shape or xa.dtype != xb.dtype or not same:
                out.append(f"{prefix}{name}: data differ")
            if {k: str(va.getncattr(k)) for k in va.ncattrs()} != {k: str(vb.getncattr(k)) for k in vb.ncattrs()}:
                out.append(f"{prefix}{name}: attributes differ")
        for key in sorted(set(ga.ncattrs()) | set(gb.ncattrs())):
            if VOLATILE.search(key):
                continue
            here = str(ga.getncattr(key)) if key in ga.ncattrs() else None
            there = str(gb.getncattr(key)) if key in gb.ncattrs() else None
            if here != there:
                out.append(f"{prefix}@{key}: {here!r} against {there!r}")
        for name in sorted(set(ga.groups) | set(gb.groups)):
            if name in ga.groups and name in gb.groups:
                walk(ga.groups[name], gb.groups[name], f"{prefix}{name}/")
            else:
                out.append(f"{prefix}{name}/: in one file only")

    with netCDF4.Dataset(a) as na, netCDF4.Dataset(b) as nb:
        walk(na, nb, "")
    return out


def _sacct(job_ids) -> list[dict]:
    fields = "JobID,JobName,State,Submit,Start,End,ElapsedRaw,ReqCPUS,ReqMem"
    proc = subprocess.run(["sacct", "-n", "-X", "-P", "-j", ",".join(job_ids), "-o", fields],
                          check=False, capture_output=True, text=True, timeout=60)
    return [dict(zip(fields.split(","), line.split("|"), strict=False)) for line in proc.stdout.splitlines() if line]


@pytest.fixture(scope="module")
def local_build(slurm, tmp_path_factory):
    """The target built by a local ``snakemake -j2`` (the reference), and its wall time."""
    local = _workdir(tmp_path_factory.mktemp("builds") / "local")
    return local, _build(local, "-j2")


def _differences(local: Path, other: Path) -> tuple[int, dict]:
    """How many netCDF files the local build wrote, and what differs in ``other``'s copies of them."""
    files = sorted(p.relative_to(local / "results") for p in (local / "results").rglob("*.nc"))
    assert files, "the local build wrote no netCDF file"
    problems = {}
    for rel in files:
        there = other / "results" / rel
        diff = ["missing"] if not there.exists() else _same_data(local / "results" / rel, there)
        if diff:
            problems[str(rel)] = diff
    return len(files), problems


def _rule_jobs(work: Path) -> int | None:
    steps = re.findall(r"(\d+) of \1 steps \(100%\) done", (work / "snakemake.out").read_text())
    return int(steps[-1]) if steps else None


def _report(work: Path, report: dict) -> None:
    (work / "results" / "slurm-overhead.json").write_text(json.dumps(report, indent=1))
    print(json.dumps({k: v for k, v in report.items() if k != "sacct"}))


def test_one_allocation_equals_local_build(local_build, tmp_path):
    """``cradle slurm TARGET``: one Slurm job running the local executor (its jobs forked from the warm process)."""
    local, wall_local = local_build
    work = _workdir(tmp_path / "allocation")
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "cradle", "slurm", "--directory", str(work), TARGET],
                          check=False, capture_output=True, text=True, timeout=3 * 3600)
    wall = time.perf_counter() - t0
    (work / "snakemake.out").write_text(proc.stdout + proc.stderr)
    assert proc.returncode == 0, (proc.stdout + proc.stderr)[-3000:]
    job_ids = re.findall(r"Slurm job (\d+) submitted", proc.stderr)
    assert len(job_ids) == 1, proc.stderr[-2000:]
    jobs = _sacct(job_ids)
    assert [j["State"] for j in jobs] == ["COMPLETED"], jobs
    forked = len(re.findall(r"forked job: peak resident memory", "".join(
        p.read_text(errors="replace") for p in (work / "results" / "logs").rglob("*.log"))))
    n_files, problems = _differences(local, work)
    _report(work, {"target": TARGET, "mode": "one allocation (cradle slurm)", "wall_slurm_s": round(wall, 1),
                   "wall_local_j2_s": round(wall_local, 1), "ratio": round(wall / wall_local, 2),
                   "slurm_jobs": 1, "rule_jobs": _rule_jobs(work), "forked_jobs": forked,
                   "netcdf_files_compared": n_files, "sacct": jobs})
    assert not problems, problems


def test_rule_instances_through_slurm_equal_local_build(local_build, tmp_path):
    """``snakemake --workflow-profile profiles/slurm``: the rule instances submitted (grouped) to Slurm."""
    pytest.importorskip("snakemake_executor_plugin_slurm",
                        reason="snakemake-executor-plugin-slurm is not installed: pip install -e '.[slurm]'")
    local, wall_local = local_build
    on_slurm = _workdir(tmp_path / "slurm")
    wall_slurm = _build(on_slurm, "--workflow-profile", "profiles/slurm")
    log = (on_slurm / "snakemake.out").read_text()
    job_ids = sorted(set(re.findall(r"submitted with SLURM jobid (\d+)", log)), key=int)
    assert job_ids, "no job was submitted to Slurm"
    jobs = _sacct(job_ids)
    assert len(jobs) == len(job_ids) and all(j["State"] == "COMPLETED" for j in jobs), jobs
    n_files, problems = _differences(local, on_slurm)
    _report(on_slurm, {"target": TARGET, "mode": "rule instances (profiles/slurm)",
                       "wall_slurm_s": round(wall_slurm, 1), "wall_local_j2_s": round(wall_local, 1),
                       "ratio": round(wall_slurm / wall_local, 2),
                       "slurm_jobs": len(job_ids), "rule_jobs": _rule_jobs(local), "netcdf_files_compared": n_files,
                       "sacct": jobs})
    assert not problems, problems
