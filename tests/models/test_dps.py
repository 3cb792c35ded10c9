"""DpS equation (dfnls): tau0 (tau0)/(wallis)/(thec), dispersion relations (ds)/(freq), invariants."""
import numpy as np
import pytest
from scipy.special import gamma

from cradle.models import dps


@pytest.mark.parametrize("alpha", [1.01, 1.1, 1.5, 2.0, 2.5, 3.0])
def test_closed_form_c_alpha_equals_wallis_integral(alpha):
    # (thec) against the quadrature of (wallis)
    assert dps.c_alpha(alpha) == pytest.approx(dps.c_alpha_wallis(alpha), rel=1e-12)


@pytest.mark.parametrize("alpha", [1.1, 1.5, 2.0, 3.0])
def test_tau0_matches_its_gamma_form(alpha):
    # (tau0): tau0 = sqrt(pi)(alpha^2-1) Gamma((alpha-1)/2) / (alpha 2^alpha Gamma(alpha/2))
    expected = np.sqrt(np.pi) * (alpha**2 - 1) * gamma((alpha - 1) / 2) / (alpha * 2**alpha * gamma(alpha / 2))
    assert dps.tau0(alpha) == pytest.approx(expected, rel=1e-13)


def test_tau0_hertz_closed_form():
    assert dps.tau0(1.5) == pytest.approx(5 * gamma(0.25) ** 2 / (24 * np.sqrt(np.pi)), rel=1e-14)
    assert round(dps.tau0(1.5), 3) == 1.545


def test_tau0_tends_to_two_as_alpha_to_one():
    values = [dps.tau0(1 + h) for h in (1e-2, 1e-4, 1e-6, 1e-9)]
    errors = [abs(v - 2.0) for v in values]
    assert errors == sorted(errors, reverse=True)
    assert errors[-1] < 1e-8
    assert c_alpha_one_limit() == pytest.approx(0.5, abs=1e-9)


def c_alpha_one_limit():
    # c_alpha -> (2/pi) int cos^2 = 1/2 as alpha -> 1+
    return dps.c_alpha(1 + 1e-10)


@pytest.mark.parametrize("omega, a", [(1.01, 2.118e-2), (1.1, 2.118), (1.5, 52.95)])
def test_freq_amplitudes_of_section_4_1(omega, a):
    got = dps.amplitude_from_omega(omega, np.pi / 5, 1.5)
    assert got == pytest.approx(a, rel=5e-4)
    assert dps.omega_tw(got, np.pi / 5, 1.5) == pytest.approx(omega, rel=1e-14)


def test_eps_of_fft106():
    # section 4.2: q = 4 pi/5, omega_tw = 1.1 gives eps = a/2 ~ 3.8e-3
    assert dps.amplitude_from_omega(1.1, 4 * np.pi / 5, 1.5) / 2 == pytest.approx(3.8e-3, abs=0.05e-3)


@pytest.mark.parametrize("alpha", [1.5, 2.0, 3.0])
@pytest.mark.parametrize("q", [np.pi / 5, np.pi / 2, 4 * np.pi / 5, np.pi])
def test_plane_wave_solves_dps(alpha, q):
    # (ansatz3) with Omega from (ds) is an exact solution: dA/dtau = i Omega A
    N = 20
    n = np.arange(N)
    A = dps.plane_wave(n, 0.3, R=0.7, q=q, phi=0.4, alpha=alpha)
    Om = dps.plane_wave_frequency(0.7, q, alpha)
    assert np.max(np.abs(dps.rhs(A, alpha) - 1j * Om * A)) < 1e-14 * max(1.0, Om)


def test_invariants_are_invariant_under_gauge_and_translation():
    rng = np.random.default_rng(1)
    A = rng.normal(size=12) + 1j * rng.normal(size=12)
    H = dps.hamiltonian(A, 1.5)
    assert dps.hamiltonian(A * np.exp(0.7j) + 0.3 - 0.2j, 1.5) == pytest.approx(H, rel=1e-13)
    # d/dtau l2 = 0 and d/dtau P = 0 along the vector field, pointwise
    F = dps.rhs(A, 1.5)
    assert abs(2 * np.real(np.vdot(A, F))) < 1e-14
    assert abs(np.sum(F)) < 1e-14
    # H is conserved: grad_H . F = 0 (directional derivative by finite differences)
    h = 1e-6
    dH = (dps.hamiltonian(A + h * F, 1.5) - dps.hamiltonian(A - h * F, 1.5)) / (2 * h)
    assert abs(dH) < 1e-9


def test_free_end_rhs_conserves_l2_and_P():
    rng = np.random.default_rng(2)
    A = rng.normal(size=9) + 1j * rng.normal(size=9)
    F = dps.rhs(A, 1.5, bc="free")
    assert abs(2 * np.real(np.vdot(A, F))) < 1e-14
    assert abs(np.sum(F)) < 1e-14


def test_bad_alpha_and_omega_raise_with_the_value():
    with pytest.raises(ValueError, match="alpha = 1.0"):
        dps.tau0(1.0)
    with pytest.raises(ValueError, match="omega_tw=0.99"):
        dps.amplitude_from_omega(0.99, np.pi / 5, 1.5)
