"""continuum-limit (cradle.analyses.continuum_limit): the Gaussians of alpha -> 1+ and the distances to them.

Checked from mathematics: the expansion g(s) = s |s|^eps = s (1 + eps ln|s| + ...) term by term; the Gaussians of
:mod:`cradle.models.continuum` solve the lattice equations up to the order the expansion neglects (the staggered
(dpsstn) with nu = 4 + eps (4 ln 2 - 2) up to O(eps^2), (sw) with c^2 = 1 + eps (ln A - 1/2) up to O(eps^3)), so
the residual's measured power is 2 and 3; the breathers and waves are solutions (residuals); the distance vanishes
as the first power of eps, within the fit's own uncertainty; (nu - 4)/eps tends to 4 ln 2 - 2.
"""
from __future__ import annotations

import copy
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from cradle.analyses import continuum_limit as cl
from cradle.analyses.protocol import REDUCED, form_spec
from cradle.models import continuum as C
from cradle.models.homoclinic import RESIDUAL_TOL
from cradle.pipeline import config as cc
from cradle.specs.declare import from_plain


@pytest.fixture(scope="module")
def reduced():
    spec = form_spec(from_plain(cl.ContinuumLimit, {}), REDUCED)
    return spec, cl.compute(spec, {})


def test_g_series_is_the_taylor_expansion():
    s = np.array([-3.0, -0.2, 1e-3, 0.5, 2.0, 7.0])
    for eps in (0.3, 0.01):
        # to high order the series is g itself (|eps ln s| < 1 here: the terms fall factorially)
        assert np.allclose(C.g_series(s, eps, 30), s * np.abs(s) ** eps, rtol=1e-14, atol=0)
    # the first-order remainder is eps^2 s ln^2|s| / 2 (1 + eps ln|s| / 3 + ...)
    for eps in (1e-2, 1e-3):
        rem = (s * np.abs(s) ** eps - C.g_series(s, eps, 1)) / (eps**2 * s * np.log(np.abs(s)) ** 2 / 2)
        assert np.all(np.abs(rem - 1.0) <= eps * np.abs(np.log(np.abs(s))))
    assert C.g_series(np.array([0.0]), 0.1, 3)[0] == 0.0


def _power(res_of, eps=(1e-2, 1e-3)):
    r = [res_of(e) for e in eps]
    return math.log(r[0] / r[1]) / math.log(eps[0] / eps[1])


def test_the_log_nls_gaussian_solves_the_staggered_dps_to_second_order():
    def residual(eps):
        n = np.arange(-int(12 / math.sqrt(eps)), int(12 / math.sqrt(eps)) + 1, dtype=float)
        b = C.dps_gaussian(n, 0.0, eps)
        g = C.g_series(b[1:-1] + b[2:], eps, 40) + C.g_series(b[1:-1] + b[:-2], eps, 40)
        return float(np.max(np.abs(C.nu_limit(eps) * b[1:-1] - g)))
    # the neglected terms are O(eps^2) (models.continuum): the first correction, O(eps) relative, moves the
    # measured power by about log10(1 + O(10) eps) <= 0.05 at eps <= 1e-2
    assert _power(residual) == pytest.approx(2.0, abs=0.05)


def test_the_log_kdv_gaussian_solves_the_travelling_wave_equation_to_third_order():
    def residual(eps):
        A = 1.7
        xi = np.linspace(-12 / math.sqrt(eps), 12 / math.sqrt(eps), 2001)
        R = lambda x: A * C.kdv_gaussian(x, eps)       # noqa: E731
        k = C.KDV_KAPPA * eps
        R2 = (4 * k**2 * xi**2 - 2 * k) * R(xi)
        f = lambda x: R(x) ** (1 + eps)                # noqa: E731
        return float(np.max(np.abs(C.kdv_speed_squared(eps, A) * R2 - (f(xi + 1) - 2 * f(xi) + f(xi - 1)))))
    # the Gaussian balances the O(eps^2) terms; what it leaves is O(eps^3)
    assert _power(residual) == pytest.approx(3.0, abs=0.05)


def test_breathers_and_waves_are_solutions(reduced):
    _, tree = reduced
    for key in ("dps_site", "dps_bond"):
        assert np.all(tree[key]["residual"].values <= RESIDUAL_TOL)
    # (sw) in its differential form, R'' by Fourier differentiation: the rounding of the transforms
    assert np.all(tree["hertz"]["residual"].values <= 1e-12)
    # every breather is staggered: its envelope positive above the rounding
    for key in ("dps_site", "dps_bond"):
        for k in range(tree[key]["eps"].size):
            assert float(tree[f"{key}/e{k:02d}"]["envelope"].min()) > -1e-15


def test_the_distance_vanishes_as_the_first_power(reduced):
    _, tree = reduced
    for key in ("dps_site", "dps_bond", "hertz"):
        p, u = float(tree.attrs[f"{key}_power"]), float(tree.attrs[f"{key}_power_uncertainty"])
        assert 0 < u < 0.05, key
        assert abs(p - 1.0) <= 3 * u, (key, p, u)
    assert list(tree["claims"]["verdict"].values)[:3] == ["agrees"] * 3


def test_first_order_constants(reduced):
    _, tree = reduced
    m = C.LOG_NLS_M
    for key in ("dps_site", "dps_bond"):
        e = np.asarray(tree[key]["eps"].values)
        q = np.asarray(tree[key]["nu_first_order"].values)
        i, j = np.argsort(e)[:2]
        # (nu - 4)/eps = m + m2 eps + O(eps^2): Richardson's extrapolation from the two smallest eps removes m2 eps
        ext = (e[j] * q[i] - e[i] * q[j]) / (e[j] - e[i])
        assert abs(ext - m) < abs(q[i] - m) / 5, key
    la = np.asarray(tree["hertz"]["log_amplitude"].values)
    e = np.asarray(tree["hertz"]["eps"].values)
    assert np.all(np.abs(la - 0.5) < e)               # ln max R = 1/2 + O(eps) at c = 1
    assert np.all(np.diff(np.abs(la - 0.5)[np.argsort(e)]) > 0)


def test_config_refuses_a_fit_range_without_four_points():
    raw = yaml.safe_load((Path(__file__).resolve().parents[2] / "config.yaml").read_text())
    bad = copy.deepcopy(raw)
    bad["beyond"]["continuum-limit"] = {"fit_below": 0.003}
    with pytest.raises(cc.ConfigError, match=r"beyond\.continuum-limit\.hertz_eps = \[.*\]: needs at least 4 values <= "
                       r"beyond\.continuum-limit\.fit_below = 0\.003"):
        cc.analysis_spec(bad, "continuum-limit", "full")
    bad["beyond"]["continuum-limit"] = {"fit_below": 1e-300}   # neither list reaches it: the line names fit_below
    with pytest.raises(cc.ConfigError, match=r"beyond\.continuum-limit\.fit_below = 1e-300: leaves fewer than 4 "
                       r"values of dps_eps and of hertz_eps"):
        cc.analysis_spec(bad, "continuum-limit", "full")
    spec = cc.analysis_spec(raw, "continuum-limit", "reduced")
    assert spec.dps_eps == [0.1, 0.05, 0.02, 0.01, 0.005] and spec.fit_below == 0.1


# ----------------------------------------------------------------- mobility


def test_the_site_breather_is_unstable_and_the_growing_mode_is_real():
    from cradle.models.dps_mobility import unstable_site

    br = unstable_site(3.0, 48)
    assert br.residual <= RESIDUAL_TOL
    assert br.lam > 0.1 and br.lam == pytest.approx(br.lam_max, rel=1e-8)
    assert float(np.max(np.abs(br.phi))) == 0.5


def test_norm_and_hamiltonian_drifts_fall_with_the_tolerance():
    from cradle.integrators.dps_solver import integrate_dps
    from cradle.models.dps_mobility import start, unstable_site

    br = unstable_site(2.0, 48)
    tau = np.linspace(0.0, 10.0 / br.lam, 3)
    drifts = []
    for rtol in (1e-8, 1e-10):
        sol = integrate_dps(start(br, 1e-2), tau, alpha=2.0, rtol=rtol)
        drifts.append((sol.max_l2_drift, sol.max_energy_drift))
    # DOP853 is of order 8: a tolerance 100 times smaller cuts the drift of a conserved quantity at least tenfold
    for before, after in zip(drifts[0], drifts[1], strict=True):
        assert after < before / 10


def test_peak_position_unwraps_round_the_ring():
    from cradle.measurements.travel import displacement, peak_position

    N = 16
    n = np.arange(N)
    # a peak moving 1.25 sites per row, twice round the ring: a symmetric profile puts the parabola's vertex at
    # the centre exactly when it is a parabola on the three sites, as |A|^2 = 1 - (n - c)^2 / 4 is
    centres = 3.0 + 1.25 * np.arange(26)
    A = np.array([np.sqrt(np.maximum(1.0 - ((n - c + N / 2) % N - N / 2) ** 2 / 4.0, 0.0)) for c in centres])
    assert np.allclose(peak_position(A) - peak_position(A)[0], centres - centres[0], atol=1e-12)
    assert displacement(A) == pytest.approx(31.25)


def test_crossover_is_read_along_the_alphas():
    assert cl.crossover([1.5, 2.0, 2.5, 3.0], [True, True, False, False]) == 2.25
    assert cl.crossover([1.5, 2.0, 2.5], [True, True, True]) == 2.5
    assert math.isnan(cl.crossover([1.5, 2.0], [False, False]))


def test_mobility_verdicts_of_the_reduced_form(reduced):
    spec, tree = reduced
    mob = tree["mobility"]
    # the integrator's drift of the norm and of H is a thousandth of the smallest perturbation studied, at most
    for key in ("mobility_max_l2_drift", "mobility_max_energy_drift"):
        assert float(tree.attrs[key]) < 1e-3 * min(spec.deltas), key
    # the growth rate rises with alpha (the instability vanishes as alpha -> 1+)
    assert np.all(np.diff(mob["growth_rate"].values) > 0)
    for t in spec.thresholds:
        assert int(tree.attrs[f"verdicts_unchanged_N_doubled_threshold_{t:g}"]) == 1
        assert int(tree.attrs[f"verdicts_unchanged_rtol_over_10_threshold_{t:g}"]) == 1


def test_a_lattice_run_through_the_ansatz_conserves_the_energy():
    spec = from_plain(cl.ContinuumLimit, {"lattice_alphas": [3.0], "lattice_eps": 0.3, "mobility_N": 32,
                                          "deltas": [1e-2], "growth_times": 10.0})
    data, coords = cl.lattice_runs(spec, lambda *a: None)
    from cradle.models.dps_mobility import unstable_site

    lam = unstable_site(3.0, 32).lam
    assert data["t_end"][0] == pytest.approx((math.log(100.0) + 10.0) / lam / 0.3**2, rel=1e-12)
    # srkn6c is symplectic: the energy error stays at the level of its local truncation, far below the
    # perturbation delta^2 = 1e-4 of the energy the start carries
    assert data["energy_drift"][0] < 1e-8
    assert coords["lattice_alpha"] == [3.0] and np.isfinite(data["displacement"][0])


# ----------------------------------------------------------------- compactons and the lattice's pinning mode


def test_the_distances_to_the_compactons_vanish_as_the_first_power(reduced):
    spec, tree = reduced
    for key in ("compacton_A_site", "compacton_B_site", "compacton_C_site", "compacton_A_bond", "compacton_B_bond",
                "compacton_C_bond", "compacton_hertz"):
        p, u = float(tree.attrs[f"{key}_power"]), float(tree.attrs[f"{key}_power_uncertainty"])
        # the distance vanishes (the power is resolved well above 0) as the first power; B's distance, a tenth of the
        # others, carries a relatively larger eps^2 term, so its fit over the reduced form's eps is the loosest
        assert p - 3 * u > 0.5 and abs(p - 1.0) <= 3 * u, (key, p, u)
    comp = tree["compacton_dps"]
    # nu of each compacton agrees with the breather's to O(eps^2): (nu_c - nu) / eps^2 stays bounded and settles
    err = np.asarray(comp["nu_error"].values)
    assert np.all(np.abs(err) < 3.0)
    assert np.all(np.abs(np.diff(err[:, -2:], axis=1)) < 0.05 * np.abs(err[:, -1:]))
    # the two compacton rows of the claims (James 2018, James and Pelinovsky 2014) follow the fitted powers
    assert list(tree["claims"]["verdict"].values)[-2:] == ["agrees"] * 2
    # the support grows as 1/eps: pi (1 + eps) / (2 eps) for form A
    e = np.asarray(comp["eps"].values)
    assert np.allclose(np.asarray(comp["half_width"].values)[0], 0.5 * math.pi * (1 + e) / e, rtol=1e-14)


def test_the_lattice_pinning_mode_tends_to_the_dps_one(reduced):
    spec, tree = reduced
    st = tree["lattice_stability"]
    assert np.all(np.asarray(st["converged"].values) == 1)
    assert np.all(np.asarray(st["residual"].values) < 1e-9)
    # the trivial pair sits at +1 within the accuracy of the monodromy (the tolerance of the shooting integrator)
    assert np.all(np.asarray(st["trivial"].values) < 1e-4)
    e = np.asarray(st["stability_eps"].values)
    for i, alpha in enumerate(np.asarray(st["stability_alpha"].values)):
        S = np.asarray(st["sigma_ratio"].values)[i]
        # DpS is the limit eps -> 0: sigma / lambda^2 -> 1 with a correction linear in eps^(alpha - 1); Richardson's
        # extrapolation from the two smallest amplitudes removes it
        a, b = np.argsort(e)[:2]
        x_a, x_b = e[a] ** (alpha - 1), e[b] ** (alpha - 1)
        ext = (x_b * S[a] - x_a * S[b]) / (x_b - x_a)
        assert abs(ext - 1.0) < abs(S[a] - 1.0) / 5, (alpha, S)
        assert np.all(np.asarray(st["amplitude"].values)[i] == pytest.approx(e, rel=0.1))


# ----------------------------------------------------------------- travelling breathers near alpha = 1


def test_the_travelling_breathers_are_solutions_and_c_0_is_the_static_comparison(reduced):
    from cradle.measurements.continuum import sup_distance

    spec, tree = reduced
    tb = tree["travelling"]
    assert np.all(np.asarray(tb["residual"].values) <= 1e-10)          # the shift-map residual (issue 37)
    eps = np.asarray(tb["tb_eps"].values)
    models = [str(m) for m in np.asarray(tb["model"].values)]
    Ds = np.asarray(tb["static_distance"].values)
    for i, e in enumerate(eps):
        # the measurement at c = 0 on the static site breather is the static comparison's, on the same ring
        b = C.dps_breather(float(e), "site", spec.tb_decades)
        assert Ds[models.index("gaussian"), i] == pytest.approx(sup_distance(b.envelope, b.gaussian), rel=1e-12)
        for base in ("gaussian", "A", "B", "C"):                               # the same profile at c = 0
            assert Ds[models.index(base + " carrier"), i] == Ds[models.index(base), i]


def test_the_carrier_gaussian_is_the_static_distance_away(reduced):
    # the lattice's dispersion at the carrier narrows the TB (models.travelling_continuum): against the Gaussian
    # narrowed so, the TB is about as far as the static breather is from its Gaussian, nearer than the boost's
    # (the same for each compacton)
    _, tree = reduced
    tb = tree["travelling"]
    models = [str(m) for m in np.asarray(tb["model"].values)]
    D = np.asarray(tb["distance"].values)
    Ds = np.asarray(tb["static_distance"].values)
    for base in ("gaussian", "A", "B", "C"):
        S = Ds[models.index(base)][:, None]
        assert np.all(np.abs(D[models.index(base + " carrier")] - S) < np.abs(D[models.index(base)] - S)), base


def test_theta_of_the_travelling_breathers_tends_to_the_boosts(reduced):
    _, tree = reduced
    tb = tree["travelling"]
    eps = np.asarray(tb["tb_eps"].values)
    err = np.abs(np.asarray(tb["theta_error"].values))
    order = np.argsort(eps)
    # O(eps^(3/2)) (docs): at least the first power between the two smallest eps
    i, j = order[0], order[1]
    assert np.all(err[i] / err[j] < eps[i] / eps[j])


def test_config_refuses_bad_boosts():
    raw = yaml.safe_load((Path(__file__).resolve().parents[2] / "config.yaml").read_text())
    bad = copy.deepcopy(raw)
    bad["beyond"]["continuum-limit"] = {"tb_boosts": [1.0, 0.5]}
    with pytest.raises(cc.ConfigError, match=r"beyond\.continuum-limit\.tb_boosts = \[1\.0, 0\.5\]: must increase"):
        cc.analysis_spec(bad, "continuum-limit", "full")
    bad["beyond"]["continuum-limit"] = {"tb_boosts": [0.5, 2.5]}
    with pytest.raises(cc.ConfigError, match=r"beyond\.continuum-limit\.tb_boosts = \[0\.5, 2\.5\]: times "
                       r"sqrt\(max beyond\.continuum-limit\.tb_eps\) must be < 1"):
        cc.analysis_spec(bad, "continuum-limit", "full")
