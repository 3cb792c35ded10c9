"""desk-toy (cradle.analyses.desk_toy): the desk-toy experiments in SI, (nc) against the hard-sphere cradle.

The numbers checked are fixed by physics: the energy (ham) of the conservative (nc) is conserved (to its
integrator's tolerance); the hard-sphere cradle with e = 1 keeps exactly ``lifted`` balls out, the others at
rest, and loses no energy; with damping, stored plus dissipated energy is conserved; every stored SI value is
(nc)'s value times the cradle's scale (:func:`cradle.models.physical.to_si`), and the released balls start at
L sin(theta) from the line.
"""
from __future__ import annotations

import copy
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from cradle.analyses import desk_toy as dk
from cradle.models.physical import scales, to_si
from cradle.pipeline import config as cc
from cradle.specs.declare import from_plain


def _tiny(**over):
    plain = {"chains": [4], "lifted": [1, 2], "swings": 2, "samples": 64, "restitution": [1.0, 0.9],
             "rtol": 1e-12, "thresholds": [0.9, 0.5], **over}
    return from_plain(dk.DeskToyRuns, plain)


@pytest.fixture(scope="module")
def tiny():
    return _tiny(), dk.compute(_tiny(), {})


def test_groups_and_si_values_are_to_si_of_the_nc_runs(tiny):
    spec, tree = tiny
    s = scales(dk.DEFAULT_CRADLE)
    assert str(tree.attrs["desk_toys"]) == "n4-lifted1, n4-lifted2"
    for lifted in (1, 2):
        g = tree[dk.label(4, lifted)]
        r = dk.desk_toy_runs(spec, 4, lifted)
        assert np.array_equal(g["t"].values, to_si(r["t"], "time", s))
        for m, run in enumerate(r["models"]):
            assert np.array_equal(g["x"].values[m], to_si(run["x"], "displacement", s))
            assert np.array_equal(g["energy"].values[m], to_si(run["energy"], "energy", s))
        assert g.attrs["X_m"] == s.X and g.attrs["T_s"] == s.T and g.attrs["E_J"] == s.E
        # the released balls: L sin(theta) from the line, in metres
        assert g["x"].values[0, 0, 0] == pytest.approx(-0.1 * math.sin(math.radians(20.0)), rel=1e-12)
        for node_var in g.to_dataset(inherit=False).data_vars.values():
            assert "long_name" in node_var.attrs and "units" in node_var.attrs


def test_nc_energy_conserved(tiny):
    """(ham) is conserved by (nc): its stored drift is at most the integrator's own (its max over every step),
    and below 1e-6, far below what moves a share f_k reported to three digits (measured: 1.9e-9 at rtol 1e-12;
    dop853's error control is local, so the drift grows with the steps through the collisions)."""
    _, tree = tiny
    for lifted in (1, 2):
        g = tree[dk.label(4, lifted)]
        H = g["energy"].values[0]
        drift = np.max(np.abs(H - H[0])) / H[0]
        assert drift <= g.attrs["nc_energy_drift"] * (1 + 1e-6) and g.attrs["nc_energy_drift"] < 1e-6
        assert np.all(g["dissipated"].values[0] == 0.0)       # conservative (nc): nothing dissipated


def test_hard_spheres_e1_keep_exactly_lifted_balls_out(tiny):
    _, tree = tiny
    for lifted in (1, 2):
        g = tree[dk.label(4, lifted)]
        assert g["restitution"].values[1] == 1.0
        assert np.all(g["share"].values[1] == 1.0)                     # f_k = 1 at every out-swing, exactly
        assert np.all(g["hold_swings"].values[1] == g.sizes["swing"])   # held through the run
        assert np.all(np.isnan(g["hold_time"].values[1]))
        assert np.all(g["cascade_velocity"].values[1, : 4 - lifted] == 0.0)   # the rest stay at rest
        assert np.all(g["gap_at_pi"].values[1, : 4 - lifted - 1] == 0.0)
        H = g["energy"].values[1]
        assert np.allclose(H, H[0], rtol=1e-13, atol=0) and np.all(g["dissipated"].values[1] == 0.0)
        # e < 1: stored + dissipated energy is the initial energy
        Hd = g["energy"].values[2] + g["dissipated"].values[2]
        assert np.allclose(Hd, Hd[0], rtol=1e-13, atol=0) and g["dissipated"].values[2, -1] > 0.0


def test_damped_runs_conserve_stored_plus_dissipated():
    spec = _tiny(lifted=[1], restitution=[1.0], damping={"onsite": 0.05})
    g = dk.compute(spec, {})[dk.label(4, 1)]
    H, D = g["energy"].values[0], g["dissipated"].values[0]
    assert D[-1] > 0.1 * H[0]                  # gamma = 0.05 over 2 periods: exp(-0.05 * 4 pi) of it is left
    # the integrator's drift of H + D (its max over every step) bounds the stored one; below 1e-6 (measured 9e-9)
    assert np.max(np.abs(H + D - H[0])) / H[0] <= g.attrs["nc_energy_drift"] * (1 + 1e-6) < 1e-6
    # linear on-site damping of a pendulum, x'' + gamma x' + x = 0: E(t) = E(0) exp(-gamma t) up to an oscillating
    # term of relative size O(gamma) (5 %); the instantaneous collisions exchange energy and dissipate none
    t_nc = g["t"].values / g.attrs["T_s"]
    assert H[-1] / H[0] == pytest.approx(math.exp(-0.05 * t_nc[-1]), rel=0.05)


def test_figure_draws_from_the_tiny_run(tiny, tmp_path):
    from cradle.figures import draw_analysis

    paths = draw_analysis("desk_toy", tiny[1], tmp_path / "desk-toy", note="test")
    assert len(paths) == 2 and all(p.stat().st_size > 0 for p in paths)


def test_config_refuses_a_lifted_count_past_a_chain():
    raw = yaml.safe_load((Path(__file__).resolve().parents[2] / "config.yaml").read_text())
    bad = copy.deepcopy(raw)
    bad["beyond"]["desk-toy"] = {"lifted": [1, 5], "chains": [5, 10]}
    with pytest.raises(cc.ConfigError, match=r"beyond\.desk-toy\.lifted\[1\] = 5: must be < every chain length"):
        cc.analysis_spec(bad, "desk-toy", "full")
    spec = cc.analysis_spec(raw, "desk-toy", "reduced")
    assert spec.chains == [5] and spec.reduced is None and spec.lifted == [1, 2, 3]
    assert cc.analysis_spec(raw, "desk-toy", "full").chains == [5, 10]


@pytest.mark.slow
def test_cradle_animate_draws_a_desk_toy_of_a_file_from_its_spec(tiny, tmp_path, capsys):
    """`cradle animate n4-lifted1 --desk-toy FILE.nc`: the movie's own run of the file's spec (its cradle, angle,
    tolerance) with the `movies.desk_toy` settings of the config, one frame per stored state; a name the file
    does not hold is one line."""
    imageio_ffmpeg = pytest.importorskip("imageio_ffmpeg")
    from cradle.data.io import write_netcdf
    from cradle.pipeline.cli import main

    path = tmp_path / "desk-toy.nc"
    write_netcdf(tiny[1], path)
    cfg = tmp_path / "c.yaml"
    scene = {"N": 4, "bc": "free", "initial": {"kind": "kick", "site": 0, "velocity": 1.0}, "t_end": 1.0,
             "store": {"every": 0.5}}
    cfg.write_text(yaml.safe_dump({"defaults": {"alpha": 1.5}, "scenes": {"s": scene}, "movies": {
        "width": 256, "height": 144, "fps": 10, "desk_toy": {"swings": 1, "per_contact": 2, "margin": 0.0,
                                                              "ramp": 10.0, "slowdown": 0.1}}}))
    args = ["animate", "n4-lifted1", "--desk-toy", str(path), "--results", str(tmp_path / "r"), "--config", str(cfg)]
    assert main(args) == 0
    out = capsys.readouterr().out
    frames = int(out.split(": ")[1].split()[0])
    reader = imageio_ffmpeg.read_frames(str(tmp_path / "r" / "movies" / "desk-toy-n4-lifted1.mp4"))
    assert next(reader)["size"] == (256, 144) and len(list(reader)) == frames
    assert "largest contact force" in out and " N)" in out
    assert main([*args[:1], "n9-lifted1", *args[2:]]) == 2
    assert "n9-lifted1: not a desk toy of" in capsys.readouterr().err
    assert main([*args, "--t-end", "1", "--duration", "3"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("cradle: error: --duration, --t-end: not with --desk-toy") and err.count("\n") == 1
