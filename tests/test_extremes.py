"""Extremes (issue 6): alpha in {1.01, 1.1, 1.5, 2, 3}, amplitudes from 1e-8 to omega_tw = 1.5,
N = 2 (periodic: the binary oscillation (inteq); free: the two-bead reduction), DpS with N = 2.

Every test asserts a number. The full sizes (t = 1e4, N = 1e4, peak memory) are in
benchmarks/extremes.py; extending a finished run is tested in tests/test_extend.py.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import gamma

from cradle.analyses import theorem1
from cradle.integrators import integrate_dps, integrate_lattice
from cradle.measurements import compare
from cradle.models import dps, homoclinic, homoclinic_continuation, homoclinic_tails, initial, lattice

ALPHAS = [1.01, 1.1, 1.5, 2.0, 3.0]


# ------------------------------------------------------------------ tau0 and the plane waves of (dfnls)

@pytest.mark.parametrize("alpha", ALPHAS)
def test_tau0_closed_form_log_gamma_and_quadrature(alpha):
    """tau0 of (tau0) three ways: the paper's Gamma formula, the log-Gamma one of dps.tau0, and
    2^(1-alpha) / c_alpha with c_alpha = (2/pi) int_0^(pi/2) cos^(alpha+1) by quadrature (wallis)."""
    paper = np.sqrt(np.pi) * (alpha**2 - 1) * gamma((alpha - 1) / 2) / (alpha * 2**alpha * gamma(alpha / 2))
    quadrature = 2.0 ** (1 - alpha) / dps.c_alpha_wallis(alpha)
    assert dps.tau0(alpha) == pytest.approx(paper, rel=1e-13)
    assert dps.tau0(alpha) == pytest.approx(quadrature, rel=1e-12)
    if alpha == 1.5:
        assert dps.tau0(alpha) == pytest.approx(5 * gamma(0.25) ** 2 / (24 * np.sqrt(np.pi)), rel=1e-14)


def test_tau0_tends_to_two_as_alpha_to_one():
    """tau0 -> 2 as alpha -> 1+ (SCENES.md checks), like 2 - O(alpha - 1); finite down to alpha - 1 = 1e-12."""
    gaps = [2.0 - dps.tau0(1.0 + h) for h in (1e-2, 1e-4, 1e-6, 1e-12)]
    assert gaps[0] < 0.02 and abs(gaps[3]) < 1e-10
    assert gaps[1] / gaps[0] == pytest.approx(1e-2, rel=0.02)     # linear in alpha - 1


@pytest.mark.parametrize("alpha", ALPHAS)
@pytest.mark.parametrize("q", [np.pi / 5, 4 * np.pi / 5, np.pi])
def test_plane_wave_is_an_exact_dps_solution(alpha, q):
    """(ansatz3) solves (dfnls) with Omega from (ds): residual at round-off, on N = 10 and N = 2 (q = pi)."""
    N = 2 if q == np.pi else 10
    R = 0.7
    n = np.arange(N)
    A = dps.plane_wave(n, 0.3, R, q, 0.2, alpha)
    lhs = 1j * dps.plane_wave_frequency(R, q, alpha) * A           # dA/dtau of the plane wave
    res = np.max(np.abs(dps.rhs(A, alpha) - lhs)) / np.max(np.abs(lhs))
    assert res < 1e-14
    # the relation (freq): omega_tw = 1 + eps^(alpha-1) Omega with a = 2 eps R, R = 1, and its inverse
    a = 0.37
    Om1 = dps.plane_wave_frequency(1, q, alpha)
    assert dps.omega_tw(a, q, alpha) == pytest.approx(1 + (a / 2) ** (alpha - 1) * Om1, rel=1e-14)
    assert dps.amplitude_from_omega(dps.omega_tw(a, q, alpha), q, alpha) == pytest.approx(a, rel=1e-9)


@pytest.mark.parametrize("alpha", ALPHAS)
def test_dps_integrator_keeps_the_plane_wave(alpha):
    """integrate_dps on a plane wave, N = 10, q = 4 pi/5, to Omega tau = 20: max error < 1e-8."""
    q, N = 4 * np.pi / 5, 10
    n = np.arange(N)
    Om = dps.plane_wave_frequency(1.0, q, alpha)
    tau = np.linspace(0.0, 20.0 / Om, 5)
    s = integrate_dps(dps.plane_wave(n, 0.0, 1.0, q, 0.0, alpha), tau, alpha=alpha)
    ref = dps.plane_wave(n[None, :], tau[:, None], 1.0, q, 0.0, alpha)
    assert np.max(np.abs(s.A - ref)) < 1e-7
    assert s.max_l2_drift < 1e-8


# ------------------------------------------------------------------ homoclinics of (dpsstn) for every alpha

@pytest.fixture(scope="module")
def sized():
    """The site-centred homoclinic of each alpha on the ring N chosen from its decay (16 decades)."""
    return {alpha: homoclinic_continuation.solve_sized("site", alpha, decades=16) for alpha in ALPHAS}


@pytest.mark.parametrize("alpha", ALPHAS)
def test_homoclinic_residual_and_amplitude(sized, alpha):
    """Unit-amplitude profile at round-off; the mu = 1 solution, 10^log10_scale times it, solves (dpsstn)
    with residual <= 1e-15 max|a| (no underflow down to alpha = 1.01, where max|a| ~ 1e-60)."""
    sol, N = sized[alpha]
    assert sol.converged and sol.residual < 5e-15
    a = sol.a
    assert np.max(np.abs(a)) == pytest.approx(10.0**sol.log10_scale, rel=1e-12)
    assert np.max(np.abs(homoclinic.residual(a, alpha))) < 5e-15 * np.max(np.abs(a))
    s2, sd = homoclinic.energy_balance(a, alpha)       # sum a^2 = sum |da|^(alpha+1) (section 2.2)
    assert s2 == pytest.approx(sd, rel=1e-12)
    # symmetric up to the conditioning of the nearly translation-invariant broad core (5e-10 at alpha = 1.01)
    assert homoclinic.symmetry_error(sol.profile, "site", int(np.argmax(np.abs(sol.profile)))) < 2e-9
    # the sites' log10 |a_n| (tails in log variables) reach 16 decades below the centre inside the ring
    L = homoclinic_tails.log10_abs_scaled(sol)
    assert np.max(L) == pytest.approx(sol.log10_scale, abs=1e-12)
    assert homoclinic_tails.decay_sites(L, 16) < N // 2


def test_homoclinic_width_and_amplitude_scaling_with_alpha(sized):
    """As alpha -> 1+: the profile's mu, nu -> 4+ like 4 + 0.78 (alpha - 1) (the band edge of the
    linearised staggered problem), the core widens like (alpha - 1)^(-1/2) (8-decade half-width
    14 sites at alpha = 1.1, 43 at 1.01: ratio sqrt(10)), and the mu = 1 amplitude is
    nu^(-1/(alpha-1)) ~ 10^(-0.6/(alpha-1)) (10^-60.3 at alpha = 1.01). The width decreases with alpha."""
    w8 = {al: homoclinic_tails.decay_sites(homoclinic_tails.log10_abs_scaled(sized[al][0]), 8) for al in ALPHAS}
    nu = {al: sized[al][0].nu for al in ALPHAS}
    assert [w8[al] for al in ALPHAS] == sorted(w8.values(), reverse=True)
    assert w8[3.0] <= 4 and w8[1.5] == 6 and w8[1.1] == 14
    assert w8[1.01] / w8[1.1] == pytest.approx(np.sqrt(10), rel=0.05)
    assert (nu[1.01] - 4) / (nu[1.1] - 4) == pytest.approx(0.1, rel=0.05)
    assert (nu[1.01] - 4) / 0.01 == pytest.approx(0.78, rel=0.02)
    assert sized[1.01][0].log10_scale == pytest.approx(-60.290, abs=1e-3)
    assert sized[1.01][1] == 128 and sized[1.5][1] == 22       # the ring N chosen from the decay


def test_paper_start_fails_far_from_three_halves_and_solve_kind_recovers():
    """The paper's direct Powell solve from a_{N/2} = -0.1 on N = 50 falls to a = 0 at alpha = 3 and
    finds a non-localised solution at alpha = 1.01; solve_kind continues in alpha instead."""
    assert np.max(np.abs(homoclinic.solve(homoclinic.initial_guess(50, "site", 3.0), 3.0).a)) == 0.0
    bad = homoclinic.solve(homoclinic.initial_guess(50, "site", 1.01), 1.01)
    assert not homoclinic.localised(bad.a)
    for alpha in (3.0, 1.01):
        sol = homoclinic_continuation.solve_kind(50, "site", alpha)
        assert sol.method == "continued" and sol.converged
        assert sol.residual < 5e-15 * np.max(np.abs(sol.a))
    assert homoclinic_continuation.solve_kind(50, "site", 1.5).method == "direct"   # the paper's case is unchanged


def test_underflowing_homoclinic_fails_with_a_clear_message():
    """alpha = 1.001: the mu = 1 amplitude 10^-602 is not a double; the message names it."""
    with pytest.raises(ValueError, match=r"alpha=1.001.*10\^-602.*underflows"):
        homoclinic_continuation.solve_kind(50, "bond", 1.001)
    sol = homoclinic_continuation.continued("bond", 1.001, 50)          # the profile itself is fine
    assert sol.converged and sol.underflow and sol.log10_scale == pytest.approx(-602.36, abs=0.01)


# ------------------------------------------------------------------ lattice energy for every alpha

@pytest.mark.parametrize("alpha", ALPHAS)
def test_lattice_energy_drift_every_alpha(alpha):
    """Travelling wave a = 0.1, q = pi/4, N = 16, t = 50, default srkn6c step: relative drift <= 1e-8
    (measured 2.0e-9 at alpha = 1.01, 5e-10 at 1.1, 1e-11 at 1.5, 1e-13 at 2, 3e-15 at 3)."""
    d = initial.travelling_wave(16, np.pi / 4, alpha, a=0.1)
    s = integrate_lattice(d.x0, d.v0, np.linspace(0.0, 50.0, 6), alpha=alpha, method="srkn6c")
    assert s.energy_drift < 1e-8
    assert np.all(np.isfinite(s.x))


# ------------------------------------------------------------------ amplitudes from 1e-8 to omega_tw = 1.5

def _E_tw(a, T=100.0, N=20, q=np.pi / 5, alpha=1.5):
    d = initial.travelling_wave(N, q, alpha, a=a)
    t = np.linspace(0.0, T, 101)
    s = integrate_lattice(d.x0, d.v0, t, alpha=alpha, method="srkn6c")
    A = integrate_dps(d.A0, d.eps ** (alpha - 1) * t, alpha=alpha).A
    return compare.relative_error(s.x, compare.approximate_displacement(A, t, d.eps), a), s


def test_tiny_amplitude_error_follows_dps_homogeneity():
    """a = 1e-8 (forces ~1e-12): E(t) = |x_app - x|_inf / a stays meaningful. The ansatz error is
    relative O(a^(alpha-1)), so E(t)/a^(alpha-1) has a limit as a -> 0 at fixed t: 0.130 at a = 1e-8 and
    1e-6 (equal to 1 %), 0.153 at a = 1e-2 (where tau = eps^(1/2) t reaches 7 and the DpS phase error
    adds). Energy drift ~1e-14."""
    E8, s8 = _E_tw(1e-8)
    E6, _ = _E_tw(1e-6)
    E2, _ = _E_tw(1e-2)
    assert np.all(np.isfinite(E8)) and 0 < E8.max() < 2e-5
    assert E8.max() / 1e-4 == pytest.approx(E6.max() / 1e-3, rel=0.01)
    assert E8.max() / 1e-4 == pytest.approx(E2.max() / 1e-1, rel=0.25)
    assert s8.energy_drift < 1e-12
    assert np.max(np.abs(lattice.bond_forces(s8.x, 1.5))) < 1e-11


def test_strongly_nonlinear_wave_drift():
    """omega_tw = 1.5 (a = 52.95, compressions up to ~71): default srkn6c, N = 50, t = 100: drift < 1e-9
    (measured 1.7e-10, 13570 steps)."""
    d = initial.travelling_wave(50, np.pi / 5, 1.5, omega_tw=1.5)
    assert d.info["a"] == pytest.approx(52.9, abs=0.05)
    s = integrate_lattice(d.x0, d.v0, np.linspace(0.0, 100.0, 11), alpha=1.5, method="srkn6c")
    assert s.energy_drift < 1e-9
    assert s.max_compression > 60


# ------------------------------------------------------------------ N = 2

def _oscillator_period(A, c, alpha):
    """Period of a'' + a + c a|a|^(alpha-1) = 0 at amplitude A (substitution a = A sin th)."""
    def g(th):
        s, co = np.sin(th), np.cos(th)
        ratio = -np.expm1((alpha + 1) * np.log(s)) / co**2 if co > 1e-6 and s > 0 else \
            (1.0 if s == 0 else (alpha + 1) / 2)
        return 1.0 / np.sqrt(1.0 + 2.0 * c * A ** (alpha - 1) * ratio / (alpha + 1))
    return 4.0 * quad(g, 0.0, np.pi / 2, epsabs=0.0, epsrel=1e-13, limit=200)[0]


@pytest.mark.parametrize("alpha", [1.5, 3.0])
def test_two_bead_ring_is_the_binary_oscillation(alpha):
    """N = 2 periodic: x = (a, -a) is (inteq) (both bonds join the same two beads); after one period of
    the (inteq) quadrature (theorem1.binary_period) the state returns to within 1e-9 a0."""
    a0 = 0.8
    T = theorem1.binary_period(a0, alpha)
    assert T == pytest.approx(_oscillator_period(a0, 2.0**alpha, alpha), rel=1e-12)
    s = integrate_lattice([a0, -a0], [0.0, 0.0], [0.0, T / 2, T], alpha=alpha, method="srkn6c")
    assert np.max(np.abs(s.x[-1] - [a0, -a0])) < 1e-9 * a0 and np.max(np.abs(s.v[-1])) < 1e-9 * a0
    assert np.max(np.abs(s.x[1] + [a0, -a0])) < 1e-9 * a0        # half a period: (-a0, a0)
    assert s.energy_drift < 2e-9


@pytest.mark.parametrize("alpha", [1.5, 2.0])
def test_two_bead_free_chain_period_and_energy(alpha):
    """N = 2, free ends: r = x1 - x0 obeys r'' + r = 2 max(-r, 0)^alpha, the 1-dof Hamiltonian
    r'^2/2 + r^2/2 + 2 max(-r,0)^(alpha+1)/(alpha+1); its period is pi (r > 0, harmonic) plus half the
    period of r'' + r + 2 r|r|^(alpha-1) = 0 at the amplitude A of equal energy. The state returns."""
    w = 1.3                                         # r(0) = 0, r'(0) = -w: contact starts at once
    A = brentq(
        lambda A: A**2 / 2 + 2 * A ** (alpha + 1) / (alpha + 1) - w**2 / 2, 0.0, w)
    T = np.pi + _oscillator_period(A, 2.0, alpha) / 2
    x0, v0 = np.array([0.2, 0.2]), np.array([0.5 + w / 2, 0.5 - w / 2])   # centre of mass moves too
    s = integrate_lattice(x0, v0, [0.0, T, 2 * T], alpha=alpha, bc="free", method="srkn6c")
    r, rdot = s.x[:, 1] - s.x[:, 0], s.v[:, 1] - s.v[:, 0]
    assert np.max(np.abs(r[1:])) < 1e-9 and np.max(np.abs(rdot[1:] + w)) < 1e-9
    S = 0.4 * np.cos([0.0, T, 2 * T]) + 1.0 * np.sin([0.0, T, 2 * T])   # s = x0 + x1 is harmonic
    assert np.max(np.abs(s.x.sum(axis=1) - S)) < 1e-12
    assert s.max_compression == pytest.approx(A, rel=1e-5)       # sampled at step ends
    assert s.energy_drift < 5e-9


def test_two_site_dps_free_and_periodic():
    """DpS with N = 2. Free ends: S = A0 + A1 is constant and D = A1 - A0 = D0 exp(i |D0|^(alpha-1) tau/tau0).
    Periodic: the q = pi plane wave. Both to 1e-8."""
    alpha = 1.5
    A0 = np.array([0.3 + 0.1j, -0.5 + 0.2j])
    tau = np.linspace(0.0, 20.0, 5)
    s = integrate_dps(A0, tau, alpha=alpha, bc="free")
    D0 = A0[1] - A0[0]
    D = D0 * np.exp(1j * abs(D0) ** (alpha - 1) * tau / dps.tau0(alpha))
    assert np.max(np.abs(s.A[:, 1] - s.A[:, 0] - D)) < 1e-8
    assert np.max(np.abs(s.A.sum(axis=1) - A0.sum())) < 1e-12
    n = np.arange(2)
    p = integrate_dps(dps.plane_wave(n, 0.0, 1.0, np.pi, 0.0, alpha), tau, alpha=alpha)
    assert np.max(np.abs(p.A - dps.plane_wave(n[None], tau[:, None], 1.0, np.pi, 0.0, alpha))) < 1e-8


def test_config_accepts_N2_and_names_bad_N_and_q():
    """N = 2 with q = pi on a ring validates; N = 1 and q N/(2 pi) = 0.4 give one line each naming key and value."""
    from cradle.pipeline import config as cc

    def cfg(N, q):
        return {"scenes": {"two": {"N": N, "bc": "periodic", "t_end": 10.0, "store": {"every": 1.0},
                                   "initial": {"kind": "travelling", "q": q, "omega_tw": 1.1}}}}

    ok = cc.validate(cfg(2, "pi"))
    assert ok["scenes"]["two"]["N"] == 2
    assert cc.scene(ok, "two").initial.wavenumber == pytest.approx(np.pi)
    with pytest.raises(cc.ConfigError) as e1:
        cc.validate(cfg(1, "pi"))
    assert "config error: scenes.two.N = 1: must be >= 2" in str(e1.value)
    with pytest.raises(cc.ConfigError) as e2:
        cc.validate(cfg(5, "pi/5"))
    assert "scenes.two.initial.q = 'pi/5'" in str(e2.value) and "q N/(2 pi) = 0.5" in str(e2.value)


@pytest.mark.parametrize("alpha, guess, log10_amp", [(1.01, "site", -60.290), (3.0, "site", -0.4246)])
def test_homoclinic_stage_far_from_three_halves(alpha, guess, log10_amp):
    """stages.homoclinic_solution (config entry, N = 50) now gives the alpha = 1.01 and alpha = 3
    site-centred solutions (by continuation) instead of failing or returning a = 0."""
    from cradle.scenes import stages
    from cradle.scenes.spec import HomoclinicEntry

    ds = stages.homoclinic_solution(HomoclinicEntry(alpha=alpha, N=50, bc="periodic", guess=guess), "x")
    assert ds.attrs["method"] == "continued" and ds.attrs["converged"] == 1
    assert ds.attrs["log10_max_abs_a"] == pytest.approx(log10_amp, abs=1e-3)
    assert ds.attrs["residual"] < 5e-15 * ds.attrs["max_abs_a"]
    assert np.all(np.isfinite(ds["log10_abs_a"].values))


def test_dps_breather_near_alpha_one_needs_astronomically_small_amplitudes():
    """alpha = 1.01: the DpS small parameter is a^(alpha-1), so the breather approximation holds only
    for a ~ 1e-150 (a^(alpha-1) = 0.03): E(t = 20) = 0.01 there, > 1 at a = 1e-2 (a^(alpha-1) = 0.95).
    The lattice at a = 1e-150 (forces ~1e-152) runs in double precision with drift ~1e-10."""
    profile = homoclinic_continuation.continued("bond", 1.01, 128).profile     # N = 128 from solve_sized
    t = np.linspace(0.0, 20.0, 11)
    E = {}
    for amp in (1e-2, 1e-150):
        d = initial.breather(profile, 1.01, amplitude=amp)
        s = integrate_lattice(d.x0, d.v0, t, alpha=1.01, method="srkn6c")
        A = integrate_dps(d.A0, t, alpha=1.01).A
        E[amp] = compare.relative_error(s.x, compare.approximate_displacement(A, t, 1.0), amp)[-1]
        assert s.energy_drift < 1e-7
    assert E[1e-150] < 0.02 and E[1e-2] > 0.5
