"""solitary-wave (cradle.analyses.solitary_wave): the stored file and the desk toy's first impact.

Checked from physics: every SI value is the chain's value times its scale (speed c D omega_0, velocity
v X omega_0); the pulse of a long line settles onto the exact solitary wave at its own peak velocity (the
local speed approaches it monotonically, and ends nearer to it than Nesterenko's long-wave speed is); the
pendulum force is negligible during the impact: (nc) and the Hertz chain alone differ in the peak velocities
by less than the on-site force can change a velocity over the window, (omega_0 t_window)^2 of the impact
speed.
"""
from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pytest
import yaml

from cradle.analyses import solitary_wave as sw
from cradle.models.physical import scales
from cradle.pipeline import config as cc
from cradle.specs.declare import from_plain


def _tiny(**over):
    plain = {"speeds": [0.5, 1.0, 2.0], "points": 16, "length": 32.0, "tail_stop": 12.0, "launch_time": 2.0,
             "chains": [5, 16], "samples": 1600, "rtol": 1e-12, **over}
    return from_plain(sw.SolitaryWaveRuns, plain)


@pytest.fixture(scope="module")
def tiny():
    spec = _tiny()
    return spec, sw.compute(spec, {})


def test_exponent_residual_and_launch(tiny):
    _, tree = tiny
    assert abs(float(tree.attrs["speed_exponent"]) - 0.2) < 1e-6
    assert float(tree.attrs["residual_max"]) < 1e-11
    assert float(tree.attrs["launch_strain_error"]) < 1e-9


def test_si_values_are_the_chain_values_times_the_scales(tiny):
    spec, tree = tiny
    s = scales(sw.DEFAULT_CRADLE)
    D = 2.0 * sw.DEFAULT_CRADLE.radius
    # the law in SI: a wave of the chain (c, v_m) is one of the cradle at (v_m X omega_0, c D omega_0)
    sp, law = tree["speeds"], tree["law"]
    i = list(spec.speeds).index(1.0)
    c, vm = float(sp["c"].values[i]), float(sp["velocity_max"].values[i])
    v_si = np.asarray(law["v_m"].values)
    assert np.allclose(law["speed_exact"].values, c * (v_si / (vm * s.V)) ** 0.2 * D * s.omega0, rtol=1e-13)
    assert np.allclose(law["speed_exact"].values, float(tree.attrs["speed_constant_si"]) * v_si**0.2, rtol=1e-13)
    g = tree["impact/n5"]
    assert float(g.attrs["impact_speed_m_per_s"]) == pytest.approx(
        0.1 * np.sin(np.radians(20.0)) * s.omega0, rel=1e-12)   # (nc)'s small-angle pendulum: L sin(theta) omega_0
    for path in ("wave", "speeds", "law", "tail", "nesterenko", "impact/n5"):
        for var in tree[path].to_dataset(inherit=False).variables.values():
            assert "long_name" in var.attrs and "units" in var.attrs
    assert tree["nesterenko"]["quantity"].dtype == object


def test_pulse_settles_onto_the_exact_wave(tiny):
    _, tree = tiny
    g = tree["impact/n16"]
    ratio = np.asarray(g["speed"].values) / np.asarray(g["speed_exact"].values)
    mid = int(g.attrs["settled_bead"])
    gap = np.abs(ratio[2: mid + 1] - 1.0)
    assert np.all(np.diff(gap) < 0.0)
    nest = np.asarray(g["speed_nesterenko"].values)[mid] / np.asarray(g["speed_exact"].values)[mid] - 1.0
    assert gap[-1] < abs(nest)


def test_pendulum_force_negligible_during_the_impact(tiny):
    _, tree = tiny
    s = scales(sw.DEFAULT_CRADLE)
    for name in ("n5", "n16"):
        g = tree[f"impact/{name}"]
        window = float(np.asarray(g["t"].values)[-1]) * s.omega0
        N = int(g.attrs["n_beads"])
        diff = np.abs(np.asarray(g["nc_difference"].values)[: N - 1])
        assert np.all(diff < window**2)


def test_figure_draws_from_the_tiny_run(tiny, tmp_path):
    from cradle.figures import draw_analysis

    paths = draw_analysis("solitary_wave", tiny[1], tmp_path / "solitary-wave", note="test")
    assert len(paths) == 2 and all(p.stat().st_size > 0 for p in paths)


def test_config_refuses_speeds_without_one_and_a_launch_off_the_grid():
    raw = yaml.safe_load((Path(__file__).resolve().parents[2] / "config.yaml").read_text())
    bad = copy.deepcopy(raw)
    bad["beyond"]["solitary-wave"] = {"speeds": [0.5, 2.0]}
    with pytest.raises(cc.ConfigError, match=r"beyond\.solitary-wave\.speeds = \[0\.5, 2\.0\]: must include 1"):
        cc.analysis_spec(bad, "solitary-wave", "full")
    bad["beyond"]["solitary-wave"] = {"launch_time": 1.01, "points": 64}
    with pytest.raises(cc.ConfigError, match=r"beyond\.solitary-wave\.launch_time = 1\.01: must be a whole number"):
        cc.analysis_spec(bad, "solitary-wave", "full")
    spec = cc.analysis_spec(raw, "solitary-wave", "reduced")
    assert spec.chains == [5, 20] and spec.points == 32
