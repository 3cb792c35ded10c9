"""A run killed mid-integration (SIGKILL: no clean-up at all) leaves nothing at its target
paths (`cradle run` writes a scene's four files only once all are computed), and running it
again completes with the same numbers as a run never interrupted."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import yaml

from cradle.data.io import open_dataset

CONFIG = {
    "scenes": {
        "long": {"N": 128, "bc": "periodic", "initial": {"kind": "travelling", "q": "pi/4", "omega_tw": 1.1},
                 "t_end": 1500.0, "store": {"every": 15.0}},
    },
    "figures": {},
}


def _run(config: Path, out: Path) -> subprocess.Popen:
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    return subprocess.Popen([sys.executable, "-m", "cradle", "run", "long", "--config", str(config),
                             "--out", str(out)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)


def test_killed_run_leaves_nothing_and_rerun_matches(tmp_path):
    config = tmp_path / "config.yaml"
    config.write_text(yaml.safe_dump(CONFIG))
    out = tmp_path / "out"
    exact_log = out / "logs" / "sim" / "long.log"       # one log for the scene's four steps

    proc = _run(config, out)
    deadline = time.monotonic() + 120.0
    while not (exact_log.exists() and "exact long: start" in exact_log.read_text()):
        assert proc.poll() is None, "the run ended before its lattice integration started"
        assert time.monotonic() < deadline, "the lattice integration never started"
        time.sleep(0.05)
    time.sleep(0.3)                      # well inside the integration (seconds long)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()

    sim = out / "sim" / "long"
    assert not (out / "initial" / "long.nc").exists()      # all or nothing: computed, never written
    assert not (sim / "exact.nc").exists() and not (sim / "dps.nc").exists()
    assert not (out / "metrics" / "long.nc").exists()
    assert not sim.exists() or not list(sim.glob("*.nc"))  # at most a hidden .tmp of a write cut short

    assert _run(config, out).wait() == 0                    # the same command again completes
    clean = tmp_path / "clean"
    assert _run(config, clean).wait() == 0                  # and a run never interrupted
    for rel in ("sim/long/exact.nc", "sim/long/dps.nc", "metrics/long.nc"):
        a, b = open_dataset(out / rel), open_dataset(clean / rel)
        for name in a.data_vars:
            np.testing.assert_array_equal(a[name].values, b[name].values, err_msg=f"{rel}:{name}")
    assert open_dataset(out / "sim/long/exact.nc").attrs["energy_drift"] < 1e-8
