"""breather-interactions: runs whose outcome is fixed by symmetry, the DpS n -> -n invariance (a symmetric pair
stays centred), the tiny sweep bitwise reproducible, and its config."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from cradle.analyses import breather_interactions as B, pair_runs
from cradle.analyses.protocol import FULL, form_spec
from cradle.measurements.interactions import OUTCOMES
from cradle.models import pairs
from cradle.pipeline import config as cc
from cradle.specs.declare import from_plain

ROOT = Path(__file__).resolve().parents[2]
N, ALPHA = 50, 1.5
TINY = {"N": N, "alpha": ALPHA, "amplitude": 0.01, "pairs": ["site-site"], "spacings": [2, 6], "n_theta": 2,
        "refine": 0, "n_seeds": 1, "noise": 0.01, "seed_base": 20261122, "periods": 100.0, "ratios": [1.0],
        "amplitudes": [0.01], "amplitude_thetas": [0.0], "chunks": 1}


def _spec(**changes):
    """The typed spec of a sweep given as plain values (the full form: no reduced overrides)."""
    return form_spec(from_plain(B.BreatherInteractions, {**TINY, **changes}), FULL)


def _pair(spacing, theta, prof=("site", "site")):
    return pairs.two_breathers(N, ALPHA, profiles=prof, centres=pairs.symmetric_centres(N, prof, spacing),
                               theta=theta)


def test_two_breathers_data_are_the_copies_with_the_carrier_phase():
    d = _pair(20, 0.0)
    e, c0, _ = pairs.envelope_profile(N, "site", ALPHA)
    # x_n(0) = 2 Re A_n(0): each copy (-1)^n e_{n - c} scaled to peak 0.01, at c = 15 and 35
    sign = (-1.0) ** np.arange(N)
    want = 0.01 / e.max() * sign * (np.roll(e, 15 - int(c0)) + np.roll(e, 35 - int(c0)))
    assert np.max(np.abs(d.x0 - want)) <= 1e-15
    assert np.max(np.abs(d.x0[:25])) == pytest.approx(0.01, rel=1e-6)
    assert np.max(np.abs(d.v0)) == 0.0
    assert np.sign(d.x0[15]) == np.sign(d.x0[35])           # in phase: same sign at sites of equal parity
    anti = _pair(20, np.pi)
    assert np.sign(anti.x0[15]) == -np.sign(anti.x0[35])
    # theta = pi, spacing 2: a node between the two cores (x_n(0) = 0 at the middle site)
    node = _pair(2, np.pi)
    assert node.x0[25] == pytest.approx(0.0, abs=1e-18)
    # theta = pi/2: a complex A_n(0), hence the ansatz velocities of (ansatzapproxst2)
    assert np.max(np.abs(_pair(8, np.pi / 2).v0)) > 0


def test_antiphase_pair_one_node_apart_repels_in_both_models():
    res = pair_runs.run_pair(_pair(2, np.pi), 120 * 2 * np.pi / 1.106, ALPHA)
    for m in pair_runs.MODELS:
        oc = res[m]["outcome"]
        assert oc.outcome == "repel"
        assert 0.1 < oc.separation_velocity < 0.3     # sites per period (docs/loc1-readings.md: ~0.2)


def test_a_symmetric_pair_stays_centred_in_dps():
    """(dfnls) is invariant under A_n -> A_{-n}: a pair symmetric about site 25 stays symmetric, and what
    it merges into does not drift (velocity 0 to round-off)."""
    d = _pair(6, 0.0)
    T = 2 * np.pi / d.info["omega_sw"]
    res = pair_runs.run_pair(d, 200 * T, ALPHA, models=("dps",), keep=True)
    oc = res["dps"]["outcome"]
    assert oc.outcome == "merge"
    assert abs(oc.drift_velocity) < 1e-12
    x = res["dps"]["x"]        # x_n(t) = x_{50-n}(t) (the mirror about site 25) at every stored time
    mirror = x[:, (2 * 25 - np.arange(N)) % N]
    assert np.max(np.abs(x - mirror)) <= 1e-12 * np.max(np.abs(x))


def test_the_tiny_sweep_runs_in_seconds_and_is_bitwise_reproducible():
    assert B.ANALYSIS.batches.keys(_spec()) == []        # one job: the sweep runs in the analysis job
    a = B.ANALYSIS.compute(_spec(), {})
    b = B.ANALYSIS.compute(_spec(), {})
    ca, cb = a["cases"].to_dataset(), b["cases"].to_dataset()
    assert ca.sizes["case"] == 4
    for k in ca.data_vars:
        assert np.array_equal(ca[k].values, cb[k].values, equal_nan=ca[k].dtype.kind == "f"), k
    # theta = pi at spacing 2 (node between the cores) repels; theta = 0 at spacing 2 is one hump
    oc = {(float(s), float(t)): int(o) for s, t, o in zip(ca["spacing"].values, ca["theta"].values,
                                                          ca["outcome_exact"].values, strict=True)}
    assert oc[(2.0, float(np.pi))] == OUTCOMES.index("repel")
    assert oc[(2.0, 0.0)] == OUTCOMES.index("none")
    assert float(a.attrs["wall_time_s"]) < 60


def test_config_of_both_forms_and_a_bad_value():
    cfg = cc.load(ROOT / "config.yaml")
    red = cc.analysis_spec(cfg, "breather-interactions", "reduced")
    full = cc.analysis_spec(cfg, "breather-interactions", "full")
    assert red.pairs == ["site-site"] and full.n_theta == 24 and full.n_seeds == 8
    assert len(B.chunk_batches(full, 0)) + len(B.chunk_batches(full, 1)) + len(B.chunk_batches(full, 2)) \
        + len(B.chunk_batches(full, 3)) == len(B.batches(full)) == 15
    # only the full form has batch jobs, one per chunk; the reduced one runs in the analysis job
    assert B.ANALYSIS.batches.keys(full) == ["0", "1", "2", "3"] and B.ANALYSIS.batches.keys(red) == []
    assert list(B.ANALYSIS.reads_of(full)) == ["batch/0", "batch/1", "batch/2", "batch/3"]
    bad = {**cfg, "beyond": {**cfg["beyond"], "breather-interactions": {**cfg["beyond"]["breather-interactions"],
                                                                         "spacings": [4, 4]}}}
    with pytest.raises(cc.ConfigError, match=r"beyond\.breather-interactions\.spacings.*distinct"):
        cc.validate(bad)


def test_batches_gathered_equal_the_sweep_in_one_job(tmp_path):
    """The full form's path: batch files written by its batch jobs, read back and gathered, give the same
    cases as the sweep run in one job."""
    import xarray as xr

    spec = _spec(chunks=2, periods=40.0)
    files = {}
    for key in B.ANALYSIS.batches.keys(spec):
        path = tmp_path / f"{key}.nc"
        B.ANALYSIS.batches.run(spec, key, {}).to_netcdf(path)
        files[f"batch/{key}"] = xr.open_dataset(path)
    assert sorted(files) == ["batch/0", "batch/1"]
    gathered = B.ANALYSIS.compute(spec, files)["cases"].to_dataset()
    direct = B.ANALYSIS.compute(_spec(periods=40.0), {})["cases"].to_dataset()
    order = np.lexsort((direct["theta"].values, direct["spacing"].values))
    for k in direct.data_vars:
        a, b = direct[k].values[order], gathered[k].values
        assert np.array_equal(a, b, equal_nan=a.dtype.kind == "f"), k
