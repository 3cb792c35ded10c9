"""dps-validity (cradle.analyses.dps_validity): the DpS approximation error of (ansatz) against eps.

The numbers checked are fixed by the multi-scale expansion of (ansatz) and by numerical analysis:
the error of x_app = eps (A e^{it} + c.c.) on t <= T eps^(1-alpha) scales as eps^alpha (the
non-resonant harmonics of V0'(eps (...)) = eps^alpha V0'(...)), so the error ratio at two
amplitudes is their ratio to the power alpha; the lattice run's own error (dt halved) is far below
that error; a least-squares power fit of an exact power law returns its power.
"""
from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pytest
import yaml

from cradle.analyses import dps_validity as dv
from cradle.pipeline import config as cc
from cradle.specs.declare import from_plain

ALPHA = 1.5
SPEC = from_plain(dv.DpsValidity, {"N_wave": 10, "N_breather": 32, "N_noise": 50, "noise_amplitude": 0.01,
                                   "seed": 20261122})
RUN = {"sample_every": 0.2, "dt_factor": 0.01, "rtol": 1e-11}


def _err(family, eps, T=(1.0,), alpha=ALPHA, check=False):
    A0, _, _ = dv.family_amplitude(family, alpha, SPEC)
    return dv.sup_error(A0, eps, alpha, list(T), check=check, **RUN)


def test_power_fit_of_an_exact_power_law():
    eps = np.geomspace(1e-5, 1e-1, 7)
    p, se, c = dv.power_fit(eps, 0.3 * eps**1.7)
    assert p == pytest.approx(1.7, abs=1e-12) and se < 1e-10 and np.exp(c) == pytest.approx(0.3, rel=1e-10)
    assert np.allclose(dv.local_exponents(eps, eps**2.5), 2.5)


@pytest.mark.parametrize("family", ["tw-pi5", "breather-bond"])
def test_error_ratio_at_two_amplitudes_matches_the_fitted_law(family):
    """Fit E_abs ~ C eps^p on eps = 1e-6, 1e-5, 1e-4 (T = 1); at two other amplitudes (3e-6, 3e-5) the
    measured ratio equals 10^p, and p is the consistency order alpha of (ansatz). The next order of
    (ansatz) is relative eps^(alpha-1) (1e-2 here): the local power approaches alpha that slowly (the
    breather's is 1.477 over 1e-5..1e-3), hence the small amplitudes."""
    fit_eps = np.array([1e-6, 1e-5, 1e-4])
    p, se, _ = dv.power_fit(fit_eps, [_err(family, e)["abs_error"][0] for e in fit_eps])
    assert abs(p - ALPHA) < 0.02, (p, se)
    e_lo, e_hi = _err(family, 3e-6)["abs_error"][0], _err(family, 3e-5)["abs_error"][0]
    assert e_hi / e_lo == pytest.approx(10.0**p, rel=0.03)


@pytest.mark.parametrize("family,alpha,eps", [("tw-pi5", 1.5, 1e-5), ("breather-bond", 1.5, 1e-5),
                                              ("tw-pi5", 2.0, 1e-3)])
def test_lattice_integration_error_below_one_percent_of_the_dps_error(family, alpha, eps):
    """At the smallest amplitude, halving the srkn6c step changes x by < 1 % of the sup |x - x_app|."""
    r = _err(family, eps, T=(2.0,), alpha=alpha, check=True)
    assert r["halving_deviation"][-1] < 0.01 * r["abs_error"][-1]
    assert r["energy_drift"] < 1e-9


def test_running_sup_is_monotone_in_T_and_chunking_changes_nothing():
    A0, _, _ = dv.family_amplitude("tw-4pi5", ALPHA, SPEC)
    one = dv.sup_error(A0, 1e-2, ALPHA, [0.5, 1.0, 2.0], **RUN)
    chunked = dv.sup_error(A0, 1e-2, ALPHA, [0.5, 1.0, 2.0], chunk=37, **RUN)
    assert np.all(np.diff(one["abs_error"]) >= 0)
    # the splitting continues bitwise; the DpS restarts its step control at each chunk (rtol 1e-11)
    assert np.allclose(chunked["abs_error"], one["abs_error"], rtol=1e-7, atol=0)


def test_noise_family_is_reproducible_from_its_seed():
    a, _, info = dv.family_amplitude("mi-4pi5-noise", ALPHA, SPEC)
    b, _, _ = dv.family_amplitude("mi-4pi5-noise", ALPHA, SPEC)
    assert np.array_equal(a, b) and info["seed"] == SPEC.seed + 150


def test_dps_growth_of_the_families():
    """(ansatz3): q = pi/5 <= pi/2 is stable, q = 4 pi/5 unstable on the ring's sidebands."""
    assert dv.dps_growth("tw-pi5", ALPHA, 10) == 0.0
    assert dv.dps_growth("breather-bond", ALPHA, 32) == 0.0
    assert dv.dps_growth("tw-4pi5", ALPHA, 10) > 0.1


def _tiny(families):
    return from_plain(dv.DpsValidity, {"N_wave": 10, "N_breather": 32, "N_noise": 50, "noise_amplitude": 0.01,
                                       "seed": 20261122, "alpha": [1.5], "eps_min": [1e-3], "eps_max": 1e-2,
                                       "n_eps": 3, "T": [1.0, 2.0], "families": families, "sample_every": 0.2,
                                       "dt_factor": 0.01, "dps_rtol": 1e-11, "chunk": 20000})


def test_tiny_end_to_end_run():
    tree = dv.compute(_tiny(["tw-pi5", "breather-bond"]), {})
    err, fits, checks = tree["errors"], tree["fits"], tree["checks"]
    eps = err["eps"].values[0]
    assert np.allclose(err["rel_error"].values, err["abs_error"].values / (2 * eps[None, None, :, None]))
    assert np.allclose(err["law_ratio"].values, err["rel_error"].values / eps[None, None, :, None] ** 0.5)
    # the wave q = pi/5 is in the asymptotic regime already at eps = 1e-3..1e-2; the breather is not yet
    # at T = 2 (p = 1.39: its phase drift's next order, relative eps^(alpha-1), is 10 % at eps = 1e-2)
    assert np.all(np.abs(fits["exponent"].values[0] - 1.5) < 0.02)
    assert np.all(np.isfinite(fits["exponent"].values)) and np.all(fits["exponent_stderr"].values > 0)
    assert np.all(checks["halving_ratio"].values < 0.01)
    for node in tree.subtree:
        for name, var in node.to_dataset(inherit=False).data_vars.items():
            assert "long_name" in var.attrs and "units" in var.attrs, name


def test_figure_draws_from_the_tiny_run(tmp_path):
    from cradle.figures import draw_analysis

    tree = dv.compute(_tiny(["tw-pi5", "mi-4pi5-noise"]), {})
    paths = draw_analysis("dps_validity", tree, tmp_path / "dps-validity", note="test")
    assert len(paths) == 2 and all(p.stat().st_size > 0 for p in paths)


def test_config_one_eps_min_per_alpha():
    raw = yaml.safe_load((Path(__file__).resolve().parents[2] / "config.yaml").read_text())
    bad = copy.deepcopy(raw)
    bad["beyond"].setdefault("dps-validity", {})["eps_min"] = [1e-5, 1e-5]
    with pytest.raises(cc.ConfigError, match=r"beyond\.dps-validity\.eps_min .*one value per alpha"):
        cc.analysis_spec(bad, "dps-validity", "full")
    spec = cc.analysis_spec(raw, "dps-validity", "reduced")
    assert isinstance(spec, dv.DpsValidity) and spec.reduced is None
    assert spec.alpha == [1.5] and spec.n_eps == 3 and spec.T == [1.0, 2.0]
    assert cc.analysis_spec(raw, "dps-validity", "full").n_eps == 9


# ----------------------------------------------------------------- the batches (one job per alpha)


def _two_alphas():
    """Two alphas (two batches), a family with noise (its seed per alpha) and one without."""
    return from_plain(dv.DpsValidity, {"N_wave": 10, "N_breather": 32, "N_noise": 50, "noise_amplitude": 0.01,
                                       "seed": 20261122, "alpha": [1.5, 2.0], "eps_min": [1e-3, 1e-2],
                                       "eps_max": 3e-2, "n_eps": 3, "T": [2.0, 1.0], "families":
                                       ["tw-4pi5", "mi-4pi5-noise"], "sample_every": 0.2, "dt_factor": 0.01,
                                       "dps_rtol": 1e-11, "chunk": 20000})


def _one_job(spec):
    """The form computed in one job, as dps-validity did before its batches: the loop over families x alphas x
    eps of :func:`cradle.analyses.dps_validity.compute` then, its results handed to tree_of_runs."""
    import time

    t_start = time.perf_counter()
    alphas = [float(a) for a in spec.alpha]
    fams = list(spec.families)
    Ts = np.sort(np.asarray(spec.T, dtype=float))
    n_eps = spec.n_eps
    E = np.full((len(fams), len(alphas), n_eps, Ts.size), np.nan)
    eps_all = np.array([dv.eps_grid(spec, ia) for ia in range(len(alphas))])
    dts, drifts, nsamp = (np.full((len(fams), len(alphas), n_eps), np.nan) for _ in range(3))
    halving, growth = np.full((len(fams), len(alphas), Ts.size), np.nan), np.zeros((len(fams), len(alphas)))
    seeds = {}
    for jf, fam in enumerate(fams):
        for ia, al in enumerate(alphas):
            A0, N, info = dv.family_amplitude(fam, al, spec)
            if "seed" in info:
                seeds[f"{fam}_alpha{al:g}"] = info["seed"]
            growth[jf, ia] = dv.dps_growth(fam, al, N)
            for ie, eps in enumerate(eps_all[ia]):
                r = dv.sup_error(A0, eps, al, Ts, sample_every=spec.sample_every, dt_factor=spec.dt_factor,
                                 rtol=spec.dps_rtol, chunk=spec.chunk, check=ie == 0)
                E[jf, ia, ie] = r["abs_error"]
                dts[jf, ia, ie], drifts[jf, ia, ie], nsamp[jf, ia, ie] = r["dt"], r["energy_drift"], r["n_samples"]
                if ie == 0:
                    halving[jf, ia] = r["halving_deviation"]
    runs = {"abs_error": E, "dt": dts, "energy_drift": drifts, "n_samples": nsamp, "halving_deviation": halving,
            "dps_growth_rate": growth, "noise_seeds": seeds}
    return dv.tree_of_runs(spec, runs, t_start)


def _assert_same_tree(new, old):
    """Same groups, variables, dims, dtypes and bits; same attributes but the measured wall time and the
    creation time (history)."""
    assert {n.path for n in new.subtree} == {n.path for n in old.subtree}
    for node in old.subtree:
        a, b = new[node.path].to_dataset(inherit=False), node.to_dataset(inherit=False)
        assert set(a.variables) == set(b.variables), node.path
        for name in b.variables:
            x, y = a[name], b[name]
            assert x.dims == y.dims and x.dtype == y.dtype and x.attrs == y.attrs, (node.path, name)
            assert np.ascontiguousarray(x.values).tobytes() == np.ascontiguousarray(y.values).tobytes(), \
                (node.path, name)
        skip = {"wall_time_s", "history"}
        assert {k: v for k, v in a.attrs.items() if k not in skip} == \
            {k: v for k, v in b.attrs.items() if k not in skip}, node.path


def test_batched_form_is_bitwise_the_one_job_form(tmp_path):
    """One batch per alpha, written to netCDF and read back (as the pipeline hands them to compute), run in
    either order: the tree is bitwise the one the one-job loop gives, on every variable of every group;
    compute(spec) with no batches runs them itself, to the same bits."""
    from cradle.data.io import open_dataset, write_netcdf

    spec = _two_alphas()
    keys = dv.batch_keys(spec)
    assert keys == ["alpha0-1.5", "alpha1-2"]
    reference = _one_job(spec)
    for order in (keys, keys[::-1]):
        inputs = {f"batch/{key}": open_dataset(write_netcdf(dv.run_batch(spec, key, {}),
                                                            tmp_path / f"{'-'.join(order)}-{key}.nc"))
                  for key in order}
        _assert_same_tree(dv.compute(spec, inputs), reference)
    _assert_same_tree(dv.compute(spec), reference)
    b = inputs[f"batch/{keys[1]}"]
    assert b.attrs["noise_seeds"] == f"mi-4pi5-noise_alpha2={spec.seed + 200}" and b.attrs["wall_time_s"] > 0
    for name, var in b.variables.items():
        assert var.dims == dv.BATCH_VARIABLES[name].dims and var.attrs["long_name"] and var.attrs["units"], name
    with pytest.raises(ValueError, match=r"^dps-validity: no batch alpha1-2 among the inputs \(given: alpha0-1.5\)$"):
        dv.compute(spec, {f"batch/{keys[0]}": inputs[f"batch/{keys[0]}"]})


def test_batch_keys_are_unique_and_an_unknown_key_is_refused():
    spec = from_plain(dv.DpsValidity, {"alpha": [1.5, 1.5, 3.0], "eps_min": [1e-3, 1e-3, 1e-2]})
    assert dv.batch_keys(spec) == ["alpha0-1.5", "alpha1-1.5", "alpha2-3"]
    assert dv.ANALYSIS.batches is not None and dv.ANALYSIS.batches.keys(spec) == dv.batch_keys(spec)
    for key in ("alpha3-1.5", "alpha1-3", "alpha0-1.50", "N200-exact-0"):
        with pytest.raises(ValueError, match=rf"^dps-validity: no batch '{key}' in this form \(batches: "
                                             r"alpha0-1.5, alpha1-1.5, alpha2-3\)$"):
            dv.run_batch(spec, key, {})
