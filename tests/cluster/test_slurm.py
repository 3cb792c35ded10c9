"""The workflow through a real Slurm (tests/cluster/slurm-up.sh): every job submitted with sbatch by
`snakemake --workflow-profile profiles/slurm`, and the data of every netCDF output bitwise equal to a
local `snakemake -j2` build of the same target.

Run it after tests/cluster/slurm-up.sh (it skips, saying why, when `sbatch`, `sinfo` or `sacct` do not
answer, or the executor plugin is missing)::

    tests/cluster/slurm-up.sh && python -m pytest -m slurm tests/cluster -s; tests/cluster/slurm-down.sh

``CRADLE_SLURM_TARGET`` (default ``paper``) chooses what both builds make. The test writes what it measured
(wall time of each build, jobs, Slurm jobs, per-job times from sacct) to ``results/slurm-overhead.json`` of
the Slurm build and prints it.
"""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import time
from pathlib import Path

import numpy as np
import pytest

from conftest import run_snakemake

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
    pytest.importorskip("snakemake_executor_plugin_slurm",
                        reason="snakemake-executor-plugin-slurm is not installed: pip install -e '.[slurm]'")
    for cmd in (("sbatch", "--version"), ("sinfo", "-h", "-o", "%T"), ("sacct", "-n", "-X", "-S", "now")):
        why = _answers(*cmd)
        if why:
            pytest.skip(why)


def _workdir(path: Path) -> Path:
    path.mkdir(parents=True)
    for name in ("Snakefile", "config.yaml"):
        shutil.copy(ROOT / name, path)
    for name in ("workflow", "profiles"):
        shutil.copytree(ROOT / name, path / name)
    (path / "src").symlink_to(ROOT / "src")
    return path


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


def test_workflow_through_slurm_equals_local_build(slurm, tmp_path):
    on_slurm, local = _workdir(tmp_path / "slurm"), _workdir(tmp_path / "local")
    wall_slurm = _build(on_slurm, "--workflow-profile", "profiles/slurm")
    wall_local = _build(local, "-j2")
    log = (on_slurm / "snakemake.out").read_text()
    job_ids = sorted(set(re.findall(r"submitted with SLURM jobid (\d+)", log)), key=int)
    assert job_ids, "no job was submitted to Slurm"
    jobs = _sacct(job_ids)
    assert len(jobs) == len(job_ids) and all(j["State"] == "COMPLETED" for j in jobs), jobs
    steps = re.findall(r"(\d+) of \1 steps \(100%\) done", (local / "snakemake.out").read_text())
    rule_jobs = int(steps[-1]) if steps else None

    files = sorted(p.relative_to(local / "results") for p in (local / "results").rglob("*.nc"))
    assert files, "the local build wrote no netCDF file"
    problems = {}
    for rel in files:
        other = on_slurm / "results" / rel
        if not other.exists():
            problems[str(rel)] = ["missing from the Slurm build"]
            continue
        diff = _same_data(local / "results" / rel, other)
        if diff:
            problems[str(rel)] = diff
    report = {"target": TARGET, "wall_slurm_s": round(wall_slurm, 1), "wall_local_j2_s": round(wall_local, 1),
              "slurm_jobs": len(job_ids), "netcdf_files_compared": len(files), "rule_jobs": rule_jobs,
              "sacct": jobs}
    (on_slurm / "results" / "slurm-overhead.json").write_text(json.dumps(report, indent=1))
    print(json.dumps({k: v for k, v in report.items() if k != "sacct"}))
    assert not problems, problems
