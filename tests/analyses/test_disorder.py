"""The disorder analysis: its measurements on closed forms, the first-order detuning shift of a DpS breather, the
scale invariance of (dpsimperfect) through the analysis's own runs, and its spec's checks."""
from __future__ import annotations

import math

import numpy as np
import pytest

from cradle.analyses import disorder as dis
from cradle.analyses.protocol import FULL, form_spec
from cradle.measurements import disorder as md
from cradle.specs.declare import from_plain


def test_plane_wave_measures():
    """A plane wave: F = 1 against any phase-rotated copy, carrier share 1, xi = N, participation 1; a state on one
    bead: xi = 1 (every mode holds 1/N of the norm), participation 1/N."""
    N, k = 24, 5
    A = 0.7 * np.exp(-2j * np.pi * k * np.arange(N) / N)
    assert md.fidelity(A, A * np.exp(1.3j)) == pytest.approx(1.0, abs=1e-14)
    assert md.carrier_fraction(A, -k) == pytest.approx(1.0, abs=1e-14)
    assert md.correlation_length(A) == pytest.approx(N, rel=1e-13)
    assert md.participation(A) == pytest.approx(1.0, abs=1e-14)
    B = np.zeros(N, complex)
    B[3] = 2.0
    assert md.correlation_length(B) == pytest.approx(1.0, rel=1e-13)
    assert md.participation(B) == pytest.approx(1.0 / N, rel=1e-13)
    # orthogonal plane waves: F = 0
    C = np.exp(-2j * np.pi * (k + 1) * np.arange(N) / N)
    assert md.fidelity(A, C) == pytest.approx(0.0, abs=1e-13)


def test_correlation_length_is_the_summed_squared_autocorrelation():
    """xi = N sum_k P_k^2 equals sum_r |C(r)|^2 computed directly on the ring (Wiener-Khinchin)."""
    rng = np.random.default_rng(7)
    N = 17
    A = rng.standard_normal(N) + 1j * rng.standard_normal(N)
    C = np.array([np.sum(np.roll(A, -r) * np.conj(A)) for r in range(N)]) / np.sum(np.abs(A) ** 2)
    assert md.correlation_length(A) == pytest.approx(float(np.sum(np.abs(C) ** 2)), rel=1e-12)


def test_first_below_and_crossover_are_exact_on_their_interpolants():
    """first_below is exact on a linear series; crossover on a survival linear in log(sigma); the censorings."""
    t = np.linspace(0.0, 10.0, 11)
    assert md.first_below(t, 1.0 - 0.07 * t, 0.5) == pytest.approx(0.5 / 0.07, rel=1e-13)
    assert math.isnan(md.first_below(t, np.ones_like(t), 0.5))
    sigma = np.array([0.0, 0.001, 0.003, 0.01, 0.03, 0.1])
    a, b = 0.2, -0.1   # S = a + b ln(sigma): S = 0.5 at sigma = exp((0.5 - a) / b)
    S = np.where(sigma > 0, a + b * np.log(np.where(sigma > 0, sigma, 1.0)), 1.0)
    star, cens = md.crossover(sigma, S, 0.5)
    assert cens == 0 and star == pytest.approx(math.exp((0.5 - a) / b), rel=1e-12)
    assert md.crossover(sigma, np.ones(6), 0.5) == (pytest.approx(float("nan"), nan_ok=True), 1)
    assert md.crossover(sigma, np.r_[1.0, np.zeros(5)], 0.5)[1] == -1


def test_energy_centre_travel_and_retention():
    """A bump moving one bead per unit t around a ring: travel = the distance moved (unwrapped past the seam),
    velocity 1; retention counts the beads within the window."""
    N = 12
    t = np.arange(30.0)
    e = np.zeros((t.size, N))
    e[np.arange(t.size), (3 + np.arange(t.size)) % N] = 1.0
    path, dist, vel = md.travel(t, e)
    assert dist == pytest.approx(29.0, abs=1e-12)
    assert vel == pytest.approx(1.0, abs=1e-12)
    f = np.ones(N)
    assert md.retention(f, 0.0, 2.0) == pytest.approx(5.0 / N)   # beads 10, 11, 0, 1, 2


def test_overlap_frequency_of_a_rigid_and_of_a_sloshing_state():
    """A_n = a_n(t) e^{i w t}: w whether the shape a_n(t) is fixed or moves its norm between two beads."""
    t = np.linspace(0.0, 40.0, 801)
    w = 0.37
    a = np.zeros((t.size, 6))
    a[:, 2], a[:, 3] = np.cos(0.1 * t), np.sin(0.1 * t)      # the norm moves between beads 2 and 3
    A = a * np.exp(1j * w * t)[:, None]
    assert md.overlap_frequency(t, A) == pytest.approx(w, rel=1e-12)


def test_detuning_shift_of_a_dps_breather_is_first_order():
    """A stationary breather of (dfnls) under detunings delta_n of (dpsimperfect): its frequency moves by exactly delta
    for a uniform detuning (A -> A e^{i delta tau}), and by sum w_n delta_n / sum w_n + O(delta^2) for random ones:
    the residual over delta falls about tenfold when delta does."""
    from cradle.integrators import integrate_dps
    from cradle.models import homoclinic
    from cradle.models.dps_sites import DpsSites

    N, alpha = 16, 1.5
    sol = homoclinic.solve(homoclinic.initial_guess(N, "site", alpha, 0.1, centre=N // 2), alpha, "periodic")
    assert sol.converged
    A0 = np.asarray(sol.a).astype(complex)
    tau = np.linspace(0.0, 50.0, 2001)
    w0 = md.overlap_frequency(tau, integrate_dps(A0, tau, alpha=alpha, rtol=1e-11).A)
    one, zero = np.ones(N), np.zeros(N)
    uniform = integrate_dps(A0, tau, alpha=alpha, rtol=1e-11, sites=DpsSites(np.full(N, 0.3), one, one, zero, zero))
    assert md.overlap_frequency(tau, uniform.A) - w0 == pytest.approx(0.3, abs=1e-10)
    z = np.random.default_rng(3).standard_normal(N)
    residual = []
    for s in (1e-2, 1e-3):
        det = s * w0 * z
        run = integrate_dps(A0, tau, alpha=alpha, rtol=1e-11, sites=DpsSites(det, one, one, zero, zero))
        shift = md.overlap_frequency(tau, run.A) - w0
        residual.append(abs(shift - md.detuning_shift(np.abs(A0) ** 2, det)) / (s * w0))
    assert residual[1] < 0.05
    assert residual[0] / residual[1] > 5.0


def test_seed_statistics():
    v = np.array([[1.0, 2.0, 3.0, np.nan], [np.nan] * 4])
    st = md.seed_statistics(v)
    assert st[0].tolist() == [2.0, 1.0, 1.5, 2.0, 2.5, 3.0]
    assert np.isnan(st[1, :5]).all() and st[1, 5] == 0


TINY = {"N": 8, "wave_mode": 1, "mi_mode": 3, "sigmas": [0.0, 0.02, 0.04], "shifts": [0.2, 0.4], "seeds": 1,
        "slow_periods": 1.0, "samples": 128, "split": False}


def test_dps_results_depend_on_sigma_over_delta_only():
    """(dpsimperfect) with delta_n = (omega_n - 1) eps^(1-alpha) is invariant under A -> l A, tau -> l^(1-alpha) tau
    with sigma scaled as the frequency shift: the analysis's DpS wave at (sigma, Delta) = (0.02, 0.2) and (0.04, 0.4)
    (same seed, both grids 128 samples per slow period) gives the same fidelity series and coherence measures."""
    spec = form_spec(from_plain(dis.Disorder, TINY), FULL)
    a = dis.family_batch(spec, "wave", 0.2)
    b = dis.family_batch(spec, "wave", 0.4)
    dps = dis.MODELS.index("dps")
    assert np.allclose(a["series"][dps, 1], b["series"][dps, 2], atol=1e-7)
    assert a["measures"]["correlation_length"][dps, 1] == pytest.approx(b["measures"]["correlation_length"][dps, 2],
                                                                       rel=1e-6)
    # the lattice is DpS's leading order only: the same comparison is not exact there
    assert not np.allclose(a["series"][0, 1], b["series"][0, 2], atol=1e-7)


def test_a_case_is_what_its_batch_stores():
    """run_case, the case of a batch (the one the sweep benchmark times), gives bitwise the measures and fidelity
    series family_batch stores at that (sigma, seed), against the homogeneous pair run the same way."""
    spec = form_spec(from_plain(dis.Disorder, TINY), FULL)
    shift, (i, sigma), seed = 0.4, list(enumerate(spec.sigmas))[-1], dis.seeds_of(spec)[0]
    batch = dis.family_batch(spec, "wave", shift)
    t = dis.time_grid(spec, shift)
    run0, res0 = dis.run_case(spec, "wave", shift, t, 0.0, seed, None, None)
    run, res = dis.run_case(spec, "wave", shift, t, sigma, seed, None, dict(run0, measures=res0))
    s_grid = np.linspace(0.0, spec.slow_periods, dis.SERIES_POINTS)
    for m, model in enumerate(dis.MODELS):
        for k in dis.MEASURES["wave"]:
            assert np.array_equal(batch["measures"][k][m, i, 0], res[model][k], equal_nan=True), (model, k)
        series = np.interp(s_grid, t / (2.0 * np.pi / shift), res[model]["_series"])
        assert np.array_equal(batch["series"][m, i, 0], series), model
    assert (batch["drift"][i, 0], batch["l2"][i, 0]) == (run["drift"], run["l2"])


@pytest.mark.parametrize(("key", "value", "why"), [
    ("sigmas", [0.01, 0.1], "must start with 0"),
    ("shifts", [0.1, 0.05], "must be strictly increasing"),
    ("mi_mode", 20, "must be below N / 2"),
])
def test_check_refuses(key, value, why):
    from cradle.specs.values import Errors

    spec = from_plain(dis.Disorder, {key: value})
    out = Errors()
    spec.check(["beyond", "disorder"], None, out)
    assert len(out.lines) == 1 and f"beyond.disorder.{key}" in out.lines[0] and why in out.lines[0]
