"""Modulational instability measured (cradle.analyses.mi_growth, cradle.analyses.mi_statistics): the growth fit
and its window on synthetic series, a direct DpS run against mi_diagram.growth_rate, crossing times and the threshold
estimator on synthetic data, determinism, and a tiny sweep through its batches (cradle.analyses.protocol)."""
import copy

import numpy as np
import pytest

from cradle.analyses import mi_diagram as MI, mi_growth as MG, mi_statistics as MS
from cradle.models import dps, initial
from cradle.pipeline import config as cc

# ---------------------------------------------------------------- growth fit

def test_fit_recovers_a_known_rate_from_exponential_plus_noise():
    rng = np.random.default_rng(1)
    t = np.arange(0.0, 400.0, 0.5)
    rate = 0.0173
    y = 3e-3 * np.exp(rate * t) * np.exp(rng.normal(0.0, 0.03, t.size))   # 3 % multiplicative noise
    y = np.minimum(y, 0.8)                                                 # saturation
    i_a, i_b, saturated, full = MG.growth_window(t, y, saturation=0.2, decades=1.0)
    assert saturated and full
    assert 0.2 <= y[i_b] < 0.3 and y[i_a] <= y[i_b] / 10 < y[i_a + 1]
    r, se, r2 = MG.fit_log_linear(t[i_a:i_b + 1], y[i_a:i_b + 1])
    assert abs(r / rate - 1) < 0.02 and se < 0.01 * rate and r2 > 0.99


def test_measure_picks_the_fastest_pair_and_skips_excluded_bins():
    t = np.arange(0.0, 600.0, 1.0)
    rates = np.array([0.0, 0.004, 0.011, 0.020, 0.007])       # m = 0..4; m = 3 excluded (a "harmonic")
    S = 1e-3 * np.exp(rates[None, :] * t[:, None])
    S[:, 3] = 0.05 + 0.0 * t                                   # a constant harmonic, above the noise
    r = MG.measure(t, S, exclude_m=[3], saturation=0.2, decades=1.0)
    assert r["m_star"] == 2 and abs(r["rate"] - 0.011) < 1e-9 and r["exponential"]
    np.testing.assert_allclose(r["rate_p"][[1, 2, 4]], rates[[1, 2, 4]], rtol=1e-9)


def test_measure_claims_no_exponential_growth_without_saturation():
    t = np.arange(0.0, 500.0, 1.0)
    S = np.column_stack([np.full(t.size, np.nan), 0.01 + 1e-5 * t, 0.01 + 0.0 * t])
    r = MG.measure(t, S, saturation=0.2, decades=1.0)
    assert not r["saturated"] and not r["exponential"]


def test_pair_spectrum_of_a_plane_wave_with_two_sidebands():
    N, k_q, m = 64, 20, 5
    n = np.arange(N)
    q, p = 2 * np.pi * k_q / N, 2 * np.pi * m / N
    A = np.exp(-1j * q * n) * (1.0 + 0.03 * np.exp(1j * p * n) + 0.04 * np.exp(-1j * p * n))
    S = MG.pair_spectrum(A[None, :], k_q)[0]
    assert abs(S[m] - 0.05) < 1e-12 and np.nanmax(np.delete(S, m)) < 1e-12
    # the lattice amplitude (x - i v) e^{-it} / (2 eps) of x = eps (A e^{it} + c.c.)
    eps, t = 0.01, np.array([0.7])
    x = 2 * eps * np.real(A * np.exp(1j * t[0]))
    v = 2 * eps * np.real(1j * A * np.exp(1j * t[0]))
    np.testing.assert_allclose(MG.lattice_amplitude(x[None], v[None], t, eps)[0], A, atol=1e-14)


def test_direct_dps_run_growth_matches_linear_theory():
    """A plane wave (R = 1) plus a 1e-6 noise-free sideband pair, q = 0.8 pi, N = 50: the fitted rate of
    the pair (per unit tau here, eps = 1) agrees with modulational.growth_rate to 0.1 %."""
    from cradle.integrators import integrate_dps

    alpha, N, k_q, m = 1.5, 50, 20, 6
    q, p = 2 * np.pi * k_q / N, 2 * np.pi * m / N
    lam = float(MI.growth_rate(q, p, alpha))
    n = np.arange(N)
    A0 = np.exp(-1j * q * n) * (1.0 + 1e-6 * np.cos(p * n))
    tau = np.linspace(0.0, np.log(2e5) / lam, 301)
    sol = integrate_dps(A0, tau, alpha=alpha, method="dop853_numba", rtol=1e-11)
    S = MG.pair_spectrum(sol.A, k_q)
    r = MG.measure(tau, S, saturation=0.05, decades=3.0, r2_min=0.999)
    assert r["m_star"] == m and r["exponential"]
    assert abs(r["rate"] / lam - 1.0) < 1e-3, (r["rate"], lam)   # measured: 3e-5


# ---------------------------------------------------------------- statistics

def test_crossing_time_interpolates_in_log_and_flags_no_crossing():
    t = np.arange(0.0, 100.0, 1.0)
    r = 0.01 * np.exp(0.05 * t)
    tc = MS.crossing_time(t, r, 0.5)
    assert abs(tc - np.log(50.0) / 0.05) < 1e-9
    assert np.isnan(MS.crossing_time(t, np.full(t.size, 0.2), 0.5))
    assert MS.crossing_time(t, np.full(t.size, 0.7), 0.5) == 0.0


def test_threshold_estimator_on_synthetic_fractions():
    q = np.arange(10) * 0.1
    n = 16
    frac = np.array([0, 0, 0, 0, 4, 12, 16, 16, 16, 16]) / n        # crosses 1/2 between q = 0.4 and 0.5
    u = np.arange(n)[None, :] < (frac * n)[:, None]
    th = MS.threshold(q, u)
    assert th["status"] == "ok" and abs(th["estimate"] - 0.45) < 1e-12
    # Wilson 95 %: 4/16 has upper bound 0.49 < 1/2, 12/16 lower bound 0.51 > 1/2
    assert th["low"] == pytest.approx(0.4) and th["high"] == pytest.approx(0.5)
    lo, hi = MS.wilson_interval(np.array([0, 16, 8]), 16)
    assert hi[0] < 0.2 and lo[1] > 0.8 and lo[2] < 0.5 < hi[2]
    # a sharp step: the estimate is the midpoint, the interval the two grid points
    u = np.repeat((q >= 0.55)[:, None], n, axis=1)
    th = MS.threshold(q, u)
    assert th["estimate"] == pytest.approx(0.55) and (th["low"], th["high"]) == pytest.approx((0.5, 0.6))
    assert MS.threshold(q, np.ones((10, n), bool))["status"] == "below_grid"
    assert MS.threshold(q, np.zeros((10, n), bool))["status"] == "above_grid"


def _tiny_spec(raw_config):
    cfg = copy.deepcopy(raw_config)
    ms = cfg["beyond"].setdefault("mi-statistics", {})
    ms["reduced"] = {"N": [40], "q_over_pi": {"start": 0.6, "stop": 0.8, "count": 2}, "n_seeds": 2, "chunks": 1}
    ms.update(t_end=60.0, fraction=0.02, sample_every=2.0)
    return cc.analysis_spec(cfg, "mi-statistics", "reduced")


@pytest.fixture(scope="module")
def raw():
    from pathlib import Path

    import yaml

    return yaml.safe_load((Path(__file__).resolve().parents[2] / "config.yaml").read_text())


def test_tiny_batch_end_to_end_and_deterministic(raw, tmp_path):
    spec = _tiny_spec(raw)
    assert MS.q_indices(spec, 40) == [12, 16]
    keys = MS.ANALYSIS.batches.keys(spec)
    assert keys == ["N40-exact-0", "N40-dps-0"]
    bs = [MS.ANALYSIS.batches.run(spec, key, {}) for key in keys]
    again = MS.batch(spec, 40, "dps", 0)
    np.testing.assert_array_equal(again["ratio"].values, bs[1]["ratio"].values)    # same seed, same numbers
    with pytest.raises(ValueError, match="no batch 'N40-exact-1'"):
        MS.ANALYSIS.batches.run(spec, "N40-exact-1", {})
    tree = MS.aggregate(bs[::-1], spec)                                            # any order
    gathered = MS.ANALYSIS.compute(spec, {f"batch/{k}": b for k, b in zip(keys, bs, strict=True)})
    for name, var in tree["runs"].data_vars.items():
        np.testing.assert_array_equal(gathered["runs"][name].values, var.values)
    ds, runs = tree.to_dataset(), tree["runs"]
    assert runs["ratio"].dims == ("N", "model", "q", "seed", "t") and runs["ratio"].shape == (1, 2, 2, 2, 31)
    assert list(ds["model"].values) == ["exact", "dps"] and [str(b["model"].values[0]) for b in bs] == ["exact", "dps"]
    r = runs["ratio"].values
    assert np.all(np.isfinite(r)) and np.all(r[..., 0] < 0.1)
    tc, crossed = runs["crossing_time"].values, runs["crossed"].values
    assert np.array_equal(np.isfinite(tc), crossed == 1)
    assert set(runs["seed"].values) == {spec.seed0, spec.seed0 + 1}
    np.testing.assert_array_equal(ds["fraction_unstable"].values, crossed.mean(axis=-1))
    assert ds.attrs["fraction"] == 0.02 and ds.attrs["exact_integrator"] == "srkn6c"
    # the ratio at t = 0 is the noise of (perturb), the same realisation in both models (x(0) is shared)
    np.testing.assert_allclose(r[0, 0, :, :, 0], r[0, 1, :, :, 0], rtol=1e-6)
    d = initial.travelling_wave(40, 2 * np.pi * 12 / 40, 1.5, omega_tw=1.1, noise_kind="gaussian",
                                noise_amplitude=0.05, seed=spec.seed0)
    assert ds["a"].values[0, 0] == pytest.approx(d.info["a"])
    assert dps.omega_tw(d.info["a"], 2 * np.pi * 12 / 40, 1.5) == pytest.approx(1.1)
    # written, read back and drawn
    from cradle.data.io import open_dataset, open_tree, write_netcdf
    from cradle.figures import save_figure
    from cradle.figures.mi_statistics import draw

    back = open_tree(write_netcdf(tree, tmp_path / "mis.nc"))
    np.testing.assert_array_equal(back["runs"]["crossed"].values, crossed)
    # the models by name, in the file as in the batches
    np.testing.assert_array_equal(back["runs"]["crossed"].sel(model="exact").values, crossed[:, 0])
    np.testing.assert_array_equal(back["threshold"].sel(model="dps").values, ds["threshold"].values[:, 1])
    batch_back = open_dataset(write_netcdf(bs[1], tmp_path / "batch.nc"))
    np.testing.assert_array_equal(batch_back["ratio"].sel(model="dps").values, r[:, 1])
    assert back["runs"]["crossed"].encoding["fletcher32"] and back["threshold"].encoding["fletcher32"]
    drawn = save_figure(draw(back), tmp_path / "mis")
    assert all(p.stat().st_size > 0 for p in drawn)


def test_config_rejects_a_q_grid_off_the_ring(raw):
    bad = copy.deepcopy(raw)
    bad["beyond"].setdefault("mi-statistics", {})["q_over_pi"] = {"start": 0.45, "stop": 0.65, "count": 20}
    with pytest.raises(cc.ConfigError, match=r"beyond\.mi-statistics\.q_over_pi.*not|must be an integer"):
        cc.validate(bad)
    bad = copy.deepcopy(raw)
    bad["beyond"]["mi-growth"]["scenes"] = ["fftseuil-5"]
    with pytest.raises(cc.ConfigError, match=r"beyond\.mi-growth\.scenes\[0\] = 'fftseuil-5': unknown scene.*did "
                                             r"you mean 'fftseuil-5"):
        cc.validate(bad)
    bad["beyond"]["mi-growth"]["scenes"] = ["loc1-pair"]
    with pytest.raises(cc.ConfigError, match=r"beyond\.mi-growth\.scenes\[0\] = 'loc1-pair'"):
        cc.validate(bad)


def test_mi_growth_tiny_end_to_end_names_its_scenes_and_models(tmp_path):
    """mi-growth on one short unstable scene: computed, written, read back; rows selected by scene and model name."""
    from cradle.data.io import open_tree, write_netcdf
    from cradle.scenes import stages
    from cradle.specs.declare import from_plain

    name = "mi-tiny"
    cfg = cc.validate({"defaults": {"alpha": 1.5},
                       "scenes": {name: {"N": 20, "bc": "periodic",
                                         "initial": {"kind": "travelling", "q": "4*pi/5", "omega_tw": 1.1,
                                                     "noise": {"kind": "uniform", "amplitude": 0.01, "seed": 1}},
                                         "t_end": 30.0, "store": {"every": 1.0}}}})
    sc = cc.scene(cfg, name)
    init = stages.initial_data(sc, name)
    inputs = {f"{name}/initial": init, f"{name}/exact": stages.exact_run(sc, init, name),
              f"{name}/dps": stages.dps_run(sc, init, name)}
    spec = from_plain(MG.MIGrowth, {"scenes": [name], "sample_every": 1.0})
    tree = open_tree(write_netcdf(MG.compute(spec, inputs), tmp_path / "mi-growth.nc"))
    ds = tree.to_dataset()
    assert list(ds["scene"].values) == [name] and list(ds["model"].values) == ["exact", "dps"]
    assert ds["growth"].dims == ("scene", "model")
    np.testing.assert_array_equal(ds["growth"].sel(scene=name, model="exact").values, ds["growth"].values[0, 0])
    np.testing.assert_array_equal(tree["series"]["pair"].sel(model="dps").values, tree["series"]["pair"].values[:, 1])
    assert float(ds["sim_check"].sel(model="exact").max()) < 1e-12   # the rerun is the stored run
