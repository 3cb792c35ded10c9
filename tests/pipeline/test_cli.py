"""The `cradle` command line: scenes, run (outside Snakemake), describe, one-line errors."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from cradle.data.io import open_dataset
from cradle.data.provenance import params_hash
from cradle.pipeline.cli import main
from cradle.pipeline.config import load, scene
from cradle.pipeline.outputs import open_scene
from cradle.specs.declare import plain

ROOT = Path(__file__).resolve().parents[2]

TINY_CLI = {
    "defaults": {"alpha": 1.5, "exact": {"method": "srkn6"}, "dps": {"method": "dop853", "rtol": 1e-9}},
    "map": {"traj3": {"box": 0.1, "iterations": 20, "starts": [[0.0, 1.0e-13]]}},
    "homoclinic": {"bond": {"guess": "bond", "N": 20, "bc": "periodic"}},
    "scenes": {
        "tw": {"N": 20, "bc": "periodic", "initial": {"kind": "travelling", "q": "pi/5", "omega_tw": 1.01},
               "t_end": 5.0, "store": {"every": 1.0}},
        "br": {"N": 20, "bc": "periodic", "initial": {"kind": "breather", "homoclinic": "bond", "amplitude": 9.7e-3},
               "t_end": 3.0, "store": {"snapshots": [3.0]}},
    },
    "figures": {"traj3": {"scenes": ["traj3"]}, "plot4-5": {"scenes": ["tw"], "times": [5.0]}},
}


@pytest.fixture
def tiny_config(tmp_path):
    path = tmp_path / "tiny.yaml"
    path.write_text(yaml.safe_dump(TINY_CLI, sort_keys=False))
    return path


def test_scenes_lists_scenes_figures_and_needs(tiny_config, capsys):
    assert main(["scenes", "--config", str(tiny_config)]) == 0
    out = capsys.readouterr().out
    for word in ("tw", "br", "bond", "traj3", "plot4-5", "needs homoclinic/bond.nc", "sim/tw/exact.nc"):
        assert word in out, word


def test_run_scene_then_describe(tiny_config, tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["run", "br", "--out", str(out), "--config", str(tiny_config)]) == 0
    for rel in ("homoclinic/bond.nc", "initial/br.nc", "sim/br/exact.nc", "sim/br/dps.nc", "metrics/br.nc",
                "logs/sim/br.log"):
        assert (out / rel).exists(), rel
    ex = open_dataset(out / "sim" / "br" / "exact.nc")
    assert ex.attrs["command"].startswith("cradle run br")
    assert ex.attrs["params_sha256"] == params_hash(plain(scene(load(tiny_config), "br")))
    log = (out / "logs" / "sim" / "br.log").read_text()   # one log, as the workflow's simulate job
    assert "exact br: t = 3 / 3 (100.0%)" in log and "exact br: done" in log  # progress reaches the log
    ds = open_scene("br", root=out)
    assert list(ds["model"].values) == ["exact", "dps"]
    capsys.readouterr()
    assert main(["describe", str(out / "sim" / "br" / "exact.nc")]) == 0
    text = capsys.readouterr().out
    for word in ("energy_drift", "cradle_version", "software_versions", "parameters:", "checks:", "provenance:"):
        assert word in text, word


@pytest.mark.parametrize("argv, message", [
    (["run", "nope"], "unknown scene 'nope' (known: tw, br, bond, traj3)"),
    (["describe", "missing.nc"], "no such file"),
    (["frobnicate"], "invalid choice"),
])
def test_errors_are_one_line_exit_2(tiny_config, tmp_path, capsys, argv, message):
    if argv[0] == "run":
        argv = argv + ["--config", str(tiny_config), "--out", str(tmp_path)]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("cradle: error: ") and message in err and err.count("\n") == 1, err


def test_config_error_is_one_line(tmp_path, capsys):
    bad = tmp_path / "bad.yaml"
    bad.write_text(yaml.safe_dump({**TINY_CLI, "defaults": {"alpha": 0.5}}))
    assert main(["scenes", "--config", str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("cradle: error: ") and "alpha" in err and err.count("\n") == 1, err


def test_python_dash_m_entry_point(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "cradle", "run", "nope", "--config", str(tmp_path / "none.yaml")],
                          capture_output=True, text=True, env={**os.environ, "PYTHONWARNINGS": "ignore"})
    assert proc.returncode == 2
    assert proc.stderr.strip().splitlines() == [f"cradle: error: no config file '{tmp_path / 'none.yaml'}' "
                                                "(give one with --config)"]
    assert "Traceback" not in proc.stderr
