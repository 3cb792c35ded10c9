"""Homoclinic solutions of (dpsstn) (figure bcsc) and breather data (ansatzapproxst2)."""
import numpy as np
import pytest

from cradle import homoclinic, initial


@pytest.fixture(scope="module")
def solutions():
    return {kind: homoclinic.solve(homoclinic.initial_guess(50, kind, 1.5), 1.5) for kind in ("site", "bond", "double")}


@pytest.mark.parametrize("kind", ["site", "bond", "double"])
def test_homoclinics_are_nontrivial_localised_and_solve_dpsstn(solutions, kind):
    sol = solutions[kind]
    a = sol.a
    assert sol.converged
    assert np.max(np.abs(a)) > 0.04          # never the trivial a = 0
    assert sol.residual < 1e-15
    assert np.max(np.abs(homoclinic.residual(a, 1.5))) < 1e-15
    # localised: tails (first and last 10 sites) far below 1e-12
    assert np.max(np.abs(np.r_[a[:10], a[-10:]])) < 1e-12
    # sum a_n^2 = sum |a_{n+1}-a_n|^(alpha+1) (section 2.2)
    s2, sd = homoclinic.energy_balance(a, 1.5)
    assert s2 == pytest.approx(sd, rel=1e-12)


def test_symmetries(solutions):
    assert homoclinic.symmetry_error(solutions["site"].a, "site") < 1e-15
    assert homoclinic.symmetry_error(solutions["bond"].a, "bond") < 1e-15


def test_site_centred_decays_super_exponentially(solutions):
    # log|a_n| falls faster than linearly: successive ratios |a_{n+1}/a_n| shrink
    a = np.abs(solutions["site"].a)
    c = int(np.argmax(a))
    ratios = a[c + 2:c + 9] / a[c + 1:c + 8]
    assert np.all(np.diff(ratios) < 0)
    assert ratios[-1] < 1e-4


def test_mu_scaling():
    # a solution of (dpsst) with mu is mu^(1/(alpha-1)) times the mu = 1 one
    s1 = homoclinic.solve(homoclinic.initial_guess(50, "bond", 1.5), 1.5)
    s2 = homoclinic.solve(homoclinic.initial_guess(50, "bond", 1.5), 1.5, mu=0.4)
    assert np.allclose(s2.a, 0.4**2 * s1.a, rtol=1e-12, atol=1e-20)
    assert s2.residual < 1e-16


@pytest.mark.parametrize("alpha, start", [(1.5, 0.1), (2.0, 0.3), (3.0, 0.5)])
def test_free_end_breather_of_fini(alpha, start):
    # the homoclinic loop grows with alpha (like the period-2 orbit 2^((alpha+1)/(1-alpha))),
    # so the start does too; from 0.1 at alpha = 3 hybr falls to a = 0
    sol = homoclinic.solve(homoclinic.initial_guess(10, "bond", alpha, amplitude=start, centre=4), alpha, bc="free")
    assert sol.converged and sol.residual < 1e-14
    assert np.max(np.abs(sol.a)) > 0.01
    s2, sd = homoclinic.energy_balance(sol.a, alpha, bc="free")
    assert s2 == pytest.approx(sd, rel=1e-10)


def test_breather_initial_data(solutions):
    a = solutions["bond"].a
    data = initial.breather(a, 1.5, omega_sw=1.1)
    mu = (1.1 - 1) * 2**1.5 * 1.5450622310844766
    assert data.x0 == pytest.approx(mu**2 * a, rel=1e-12, abs=1e-30)
    assert np.all(data.v0 == 0.0)    # standing wave: zero initial velocities
    back = initial.breather(a, 1.5, amplitude=float(np.max(np.abs(data.x0))))
    assert back.info["omega_sw"] == pytest.approx(1.1, rel=1e-12)


def test_bad_mu_raises():
    with pytest.raises(ValueError, match="mu=-1"):
        homoclinic.solve(np.zeros(10), 1.5, mu=-1)
