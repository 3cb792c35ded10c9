"""Homoclinic solutions of (dpsstn) (figure bcsc) and breather data (ansatzapproxst2)."""
import numpy as np
import pytest

from cradle.models import homoclinic, homoclinic_tails, initial


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


def _relative_residuals(signs, log10a, alpha, digits=40):
    """(dpsstn) residual / |a_n| at interior tail sites, in 40-digit decimal arithmetic
    (decimal's exponent range reaches 1e-999999, so nothing underflows): an
    independent check of the log-variable tail."""
    from decimal import Decimal, localcontext

    with localcontext() as ctx:
        ctx.prec = digits
        al = Decimal(repr(alpha))
        a = [int(sg) * Decimal(10) ** Decimal(repr(float(L))) for sg, L in zip(signs, log10a, strict=True)]

        def g(x):
            return (abs(x) ** al).copy_sign(x) if x != 0 else Decimal(0)

        return [float(abs(g(a[n + 1] - a[n]) - g(a[n] - a[n - 1]) + a[n]) / abs(a[n]))
                for n in range(1, len(a) - 1)]


@pytest.mark.parametrize("alpha, start", [(1.5, 0.1), (2.0, 0.3), (3.0, 0.5)])
def test_tails_below_machine_precision_follow_dpsstn(alpha, start):
    # the log-variable continuation of (dpsstn), started where |a_n| ~ 1e-9 max|a|, agrees with the
    # double-precision Newton solution where that one still resolves the tail, solves (dpsstn) to
    # ~1e-10 relative at sites down to 1e-1000 and beyond (checked in 40-digit decimal arithmetic),
    # and follows the decay law (dpsstn) implies: ln|a_{n+1}| / ln|a_n| -> alpha, signs alternating
    sol = homoclinic.solve(homoclinic.initial_guess(50, "site", alpha, amplitude=start), alpha)
    a = sol.a
    log10a = homoclinic_tails.log10_abs(a, alpha)
    c = int(np.argmax(np.abs(a)))
    resolved = (np.abs(a) > 1e-40) & (np.abs(a) < 1e-12 * np.max(np.abs(a)))
    assert resolved.sum() >= 2
    assert np.allclose(log10a[resolved], np.log10(np.abs(a[resolved])), rtol=1e-8)
    assert np.min(log10a) < -300
    j = c + int(np.flatnonzero(np.abs(a[c:]) > 1e-9 * np.max(np.abs(a)))[-1])
    signs, L = homoclinic_tails.log_tail(a[j], alpha, 12)
    assert np.all(signs[1:] == -signs[:-1])
    assert L[-1] / np.log(10) < -300
    assert max(_relative_residuals(signs, L / np.log(10), alpha)) < 1e-9
    ratios = L[-4:] / L[-5:-1]
    assert np.allclose(ratios, alpha, rtol=1e-9)


@pytest.mark.parametrize("N, kind, bc, centre", [(200, "bond", "periodic", 3), (150, "bond", "free", 20),
                                                  (150, "double", "periodic", 70), (40, "site", "periodic", None)])
def test_zero_at_says_where_the_job_s_profile_is_0(N, kind, bc, centre):
    """A long chain's profile solved on a window around its core is 0 exactly where the whole chain's is (its
    tails underflow a few sites out; a ring's core across site 0, a core near a free end)."""
    from cradle.models.homoclinic_continuation import solve_kind, zero_at

    a = solve_kind(N, kind, 1.5, bc, centre=centre).a
    said = [zero_at(k, N, kind, 1.5, bc, centre=centre) for k in range(N)]
    assert said == [bool(v == 0) for v in a]
    assert 0 < sum(v != 0 for v in a) < N   # both kinds of site are there


def test_zero_at_cannot_say_for_tails_wider_than_its_window():
    from cradle.models.homoclinic_continuation import zero_at

    assert zero_at(0, 120, "site", 1.1) is None   # alpha = 1.1: the tails fill the window


def test_guess_off_chain_names_the_seeds_a_free_chain_lacks():
    from cradle.models.homoclinic import guess_off_chain

    assert guess_off_chain(10, "bond", "free", 8) is None and guess_off_chain(10, "bond", "periodic", 9) is None
    assert "the centre must be <= N-2 = 8" in str(guess_off_chain(10, "bond", "free", 9))
    assert "humps at -1 and 8" in str(guess_off_chain(20, "double", "free", 3, 9))
