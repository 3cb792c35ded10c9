"""The pipeline: stages write self-describing netCDF, failures leave nothing at the
target, and a small Snakemake run on a tiny config builds, is idempotent and
replans only what a changed parameter touches."""
from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import numpy as np
import pytest
import yaml

from conftest import run_snakemake
from cradle.data.io import open_dataset, write_netcdf
from cradle.data.variables import VARIABLES
from cradle.pipeline import config as cc
from cradle.pipeline.runner import failed_path, run, run_chain
from cradle.pipeline.workdir import copy_workflow
from cradle.scenes import stages
from cradle.specs.values import DRIFT_FLOOR

ROOT = Path(__file__).resolve().parents[2]

TINY = {
    "defaults": {"alpha": 1.5, "exact": {"method": "srkn6"}, "dps": {"method": "dop853", "rtol": 1e-9}},
    "map": {"traj3": {"box": 0.1, "iterations": 40, "marks": False, "starts": [[0.0, 1.0e-13]]}},
    "homoclinic": {
        "site": {"guess": "site", "N": 20, "bc": "periodic"},
        "bond": {"guess": "bond", "N": 20, "bc": "periodic"},
        "double": {"guess": "double", "N": 30, "bc": "periodic", "separation": 9},
    },
    "scenes": {
        "tw-weak": {"N": 20, "bc": "periodic", "initial": {"kind": "travelling", "q": "pi/5", "omega_tw": 1.01},
                    "t_end": 20.0, "store": {"snapshots": [7.5, 20.0], "every": 0.5}},
        "tw-weak-noise": {"N": 20, "bc": "periodic",
                          "initial": {"kind": "travelling", "q": "pi/5", "omega_tw": 1.01,
                                      "noise": {"kind": "uniform", "amplitude": 0.5, "seed": 3}},
                          "t_end": 20.0, "store": {"snapshots": [20.0]}},
    },
    "figures": {
        "traj3": {"scenes": ["traj3"]},
        "bcsc": {"scenes": ["site", "bond", "double"]},
        "plot4-5": {"scenes": ["tw-weak"], "times": [20.0]},
        "plotcomplin": {"scenes": ["tw-weak-noise", "tw-weak"], "times": [20.0, 7.5]},
    },
}


def _run_scene(cfg, name, tmp_path):
    spec = cc.scene(cfg, name)
    init = stages.initial_data(spec, name)
    ex = stages.exact_run(spec, init, name)
    ap = stages.dps_run(spec, init, name)
    m = stages.metrics(spec, ex, ap, name)
    paths = {}
    for part, ds in (("initial", init), ("exact", ex), ("dps", ap), ("metrics", m)):
        paths[part] = write_netcdf(ds, tmp_path / f"{name}-{part}.nc")
    return spec, paths


def test_outputs_are_self_describing(tmp_path):
    cfg = cc.validate(TINY)
    spec, paths = _run_scene(cfg, "tw-weak-noise", tmp_path)
    ex = open_dataset(paths["exact"])
    for key in ("alpha", "N", "bc", "q", "omega_tw", "a", "eps", "noise", "noise_amplitude", "seed",
                "integrator", "dt", "energy_drift", "wall_time_s", "cradle_version"):
        assert key in ex.attrs, key
    assert ex.attrs["noise"] == "uniform" and ex.attrs["seed"] == 3
    assert ex.attrs["a"] == pytest.approx(2.118e-2, rel=5e-4)
    assert ex.attrs["energy_drift"] < 1e-8
    assert tuple(ex["t"].values) == spec.times
    for part in ("initial", "exact", "dps", "metrics"):
        ds = open_dataset(paths[part])
        for name in list(ds.data_vars) + list(ds.coords):
            assert ds[name].attrs["units"] == VARIABLES[name].units
            assert ds[name].attrs["long_name"] == VARIABLES[name].long_name
    init = open_dataset(paths["initial"])
    assert {"x0", "v0", "A0_re", "A0_im", "rho1", "rho2"} <= set(init.data_vars)
    ap = open_dataset(paths["dps"])
    assert ap["tau"].values == pytest.approx(ap.attrs["eps"] ** 0.5 * ap["t"].values)
    # stored only at the declared times: 0 and t_end
    assert ex.sizes["t"] == 2


def test_same_config_gives_bitwise_same_arrays(tmp_path):
    cfg = cc.validate(TINY)
    _, p1 = _run_scene(cfg, "tw-weak-noise", tmp_path / "a")
    _, p2 = _run_scene(cfg, "tw-weak-noise", tmp_path / "b")
    for part in ("initial", "exact", "dps"):
        d1, d2 = open_dataset(p1[part]), open_dataset(p2[part])
        for name in d1.data_vars:
            assert np.array_equal(d1[name].values, d2[name].values), (part, name)


def test_failed_stage_leaves_nothing_at_target(tmp_path):
    cfg = cc.validate(TINY)
    spec = dataclasses.replace(cc.scene(cfg, "tw-weak"), max_energy_drift=1e-30)  # impossible bound: it must fail
    init = stages.initial_data(spec, "tw-weak")
    out = tmp_path / "results" / "sim" / "tw-weak" / "exact.nc"
    with pytest.raises(stages.StageFailure, match="energy drift"):
        run(lambda: stages.exact_run(spec, init, "tw-weak"), out)
    assert not out.exists()
    kept = failed_path(out)
    assert kept == tmp_path / "results" / "failed" / "sim" / "tw-weak" / "exact.nc"
    assert "exceeds max_energy_drift" in open_dataset(kept).attrs["failure"]
    assert not list(out.parent.glob("*.tmp"))



def test_failed_step_of_a_chain_writes_no_target_and_keeps_the_finished_steps(tmp_path):
    """simulate's run_chain: the exact run fails its drift bound, so neither initial.nc nor exact.nc
    is written at its target; both go to results/failed/ with the reason."""
    cfg = cc.validate(TINY)
    spec = dataclasses.replace(cc.scene(cfg, "tw-weak"), max_energy_drift=1e-30)
    root = tmp_path / "results"
    outs = {"initial": root / "initial" / "tw-weak.nc", "exact": root / "sim" / "tw-weak" / "exact.nc"}
    with pytest.raises(stages.StageFailure, match="energy drift"):
        run_chain([("initial", lambda done: stages.initial_data(spec, "tw-weak")),
                   ("exact", lambda done: stages.exact_run(spec, done["initial"], "tw-weak"))], outs)
    assert not any(path.exists() for path in outs.values())
    assert "the later step 'exact' failed" in open_dataset(failed_path(outs["initial"])).attrs["failure"]
    assert "exceeds max_energy_drift" in open_dataset(failed_path(outs["exact"])).attrs["failure"]

def _tiny_workflow(tmp_path):
    """A copy of the workflow (the sources linked) running the TINY config."""
    return copy_workflow(ROOT, tmp_path / "cradle", config=yaml.safe_dump(TINY), profiles=False)


def _snakemake(workdir, *args):
    return run_snakemake(workdir, "--cores", "2", *args)


def _job_counts(text):
    table = text.split("Job stats:")[1] if "Job stats:" in text else ""
    return {m.group(1): int(m.group(2)) for m in re.finditer(r"^(\w+)\s+(\d+)$", table, re.M)}


@pytest.mark.slow
def test_snakemake_end_to_end_on_tiny_config(tmp_path, monkeypatch):
    work = _tiny_workflow(tmp_path)
    tiny = (work / "config.yaml").read_text()

    built = _snakemake(work, "paper")      # the paper's figures and claims table (all adds slow analyses)
    assert built.returncode == 0, built.stderr[-3000:]
    for label in TINY["figures"]:
        for ext in ("pdf", "png"):
            assert (work / "results" / "figures" / f"{label}.{ext}").stat().st_size > 1000
    ex = open_dataset(work / "results" / "sim" / "tw-weak" / "exact.nc")
    assert ex.attrs["energy_drift"] < 1e-8

    again = _snakemake(work, "-n", "paper")
    assert again.returncode == 0
    assert "Nothing to be done" in again.stdout + again.stderr

    # the same values in another key order: a job's params are the sorted plain values, nothing replans
    cfg = yaml.safe_load((work / "config.yaml").read_text())
    cfg["scenes"] = {n: dict(reversed(list(s.items()))) for n, s in cfg["scenes"].items()}
    cfg["homoclinic"] = {n: dict(reversed(list(h.items()))) for n, h in cfg["homoclinic"].items()}
    (work / "config.yaml").write_text(yaml.safe_dump(cfg, sort_keys=False))
    reordered = _snakemake(work, "-n", "paper")
    assert reordered.returncode == 0 and "Nothing to be done" in reordered.stdout + reordered.stderr

    # change q of one scene: only that scene's chain and the figures reading it replan
    cfg["scenes"]["tw-weak"]["initial"]["q"] = "2pi/5"
    (work / "config.yaml").write_text(yaml.safe_dump(cfg))
    plan = _snakemake(work, "-n", "paper")
    assert plan.returncode == 0, plan.stderr[-2000:]
    counts = _job_counts(plan.stdout + plan.stderr)
    assert counts.get("simulate") == 1   # initial data, exact, dps and metrics: one job
    assert counts.get("figure") == 2   # plot4-5 and plotcomplin
    assert "homoclinic" not in counts and "map_orbits" not in counts

    # a bad value stops the run before any work, naming key and value
    cfg["scenes"]["tw-weak"]["N"] = 1
    (work / "config.yaml").write_text(yaml.safe_dump(cfg))
    bad = _snakemake(work, "-n", "paper")
    assert bad.returncode != 0
    assert "scenes.tw-weak.N = 1" in bad.stdout + bad.stderr

    # the jobs that started once the warm process was ready were forked from it (cradle.pipeline.warm); the
    # scene's job run again in its own process writes the same values, bit for bit
    starts = [line for log in (work / "results" / "logs").rglob("*.log") for line in log.read_text().splitlines()
              if "process start-up" in line]
    assert any(line.endswith("(forked from the warm process)") for line in starts), starts
    (work / "config.yaml").write_text(tiny)
    sim = sorted((work / "results" / "sim" / "tw-weak").glob("*.nc"))
    forked = {path.name: open_dataset(path).load() for path in sim}
    monkeypatch.setenv("CRADLE_WARM", "0")
    own = _snakemake(work, "--force", str(sim[0].relative_to(work)))   # the scene's job: all its files
    assert own.returncode == 0, own.stderr[-3000:]
    log = (work / "results" / "logs" / "sim" / "tw-weak.log").read_text()
    assert "(forked from the warm process)" not in log and "(own process)" in log
    for path in sim:
        again = open_dataset(path).load()
        assert set(again.variables) == set(forked[path.name].variables)
        for name, var in again.variables.items():
            assert np.array_equal(var.values, forked[path.name][name].values, equal_nan=var.dtype.kind == "f"), name


@pytest.mark.slow
def test_a_failed_forced_rerun_restores_the_previous_outputs(tmp_path):
    """Every rule's outputs are update(): `--forcerun simulate` failing at run time (here an energy bound
    no run meets) leaves the scene's four files as they were, with their modification times, and says so
    for each."""
    import hashlib

    work = _tiny_workflow(tmp_path)
    target = "results/sim/tw-weak/exact.nc"
    built = _snakemake(work, target)
    assert built.returncode == 0, built.stderr[-3000:]
    files = sorted((work / "results").glob("**/tw-weak.nc")) + sorted((work / "results/sim/tw-weak").glob("*.nc"))
    assert len(files) == 4
    before = {f: hashlib.sha256(f.read_bytes()).hexdigest() for f in files}
    times = {f: f.stat().st_mtime_ns for f in files}

    # the floor of the bound (validation refuses a smaller one): this run's drift is some 1e-12
    (work / "fail.yaml").write_text(yaml.safe_dump({"scenes": {"tw-weak": {"max_energy_drift": DRIFT_FLOOR}}}))
    failed = _snakemake(work, target, "--forcerun", "simulate", "--configfile", "fail.yaml")
    assert failed.returncode != 0
    assert failed.stderr.count("Restored previous version of results/") == 4
    assert {f: hashlib.sha256(f.read_bytes()).hexdigest() for f in files} == before
    # and with their old times (the Snakefile's onerror, cradle.pipeline.restored): their readers stay up to date
    assert {f: f.stat().st_mtime_ns for f in files} == times
