"""(dpsimperfect) of cradle.models.dps_sites: the averaged bond force g(r; delta~) and its potential against closed
forms and an independent projection of the Hertz force, the Hamiltonian structure of the right-hand side, and the
coefficients built from a lattice's sites."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from cradle.models import dps_sites as S
from cradle.models.dps import p_laplacian, rhs as dps_rhs, tau0
from cradle.specs.values import ConfigError


@pytest.mark.parametrize("alpha", [1.1, 1.5, 2.0, 3.0])
def test_quadrature_against_the_closed_forms(alpha):
    # rho = 0: the p-Laplacian, g = r^alpha and P = r^(alpha+1)/(alpha+1) (the (nonl) Wallis integral)
    G, P = S.profile_quadrature(0.0, alpha)
    assert G == pytest.approx(1.0, rel=1e-12)
    assert P == pytest.approx(1.0 / (alpha + 1.0), rel=1e-12)
    # rho -> 2-: the quadrature meets the 2F1 closed form of full contact (continuous: the kink is (2-rho)^(alpha+1/2))
    for a, b in zip(S.profile_quadrature(2.0 - 1e-12, alpha), S.profile_quadrature(2.0, alpha), strict=True):
        assert a == pytest.approx(b, rel=1e-11)
    # rho -> -2+: contact only at the extreme of the swing, g ~ (rho + 2)^(alpha+1/2) -> 0
    assert abs(S.profile_quadrature(-2.0 + 1e-10, alpha)[0]) < 1e-12


@pytest.mark.parametrize("alpha", [1.1, 1.5])
def test_tables_against_the_quadrature(alpha):
    """The accuracy stated in docs/imperfect-dps.md: the Chebyshev tables and the 2F1 series reproduce the
    quadrature to 1e-12 (relative to max(1, value)) over rho in [-2, 6]."""
    rho = np.concatenate([np.random.default_rng(3).uniform(-2.0, 6.0, 60), [-1.9999, 1.9999, 2.0, 3.9999, 4.0]])
    ref = np.array([S.profile_quadrature(float(x), alpha) for x in rho])
    g, P = S.coupling(np.ones_like(rho), rho, alpha)
    assert np.max(np.abs(g - ref[:, 0]) / np.maximum(1.0, ref[:, 0])) < 1e-12
    assert np.max(np.abs(P - ref[:, 1]) / np.maximum(1.0, ref[:, 1])) < 1e-12


def test_g_is_the_first_fourier_coefficient_of_the_precompressed_hertz_force():
    """Phi(z) = tau0 (1/2pi) int F~(z e^{it} + c.c.) e^{-it} dt, F~(d) = -(delta~ - d)_+^alpha + delta~_+^alpha, for
    complex z of every phase and delta~ from a gap to a strong precompression (quadrature between the kinks)."""
    alpha = 1.5
    rng = np.random.default_rng(7)
    for delta in (-1.3, -0.2, 0.4, 1.7, 3.5, 9.0):
        z = complex(rng.normal(), rng.normal())
        r, th = abs(z), math.atan2(z.imag, z.real)

        def F(d, delta=delta):
            return -max(delta - d, 0.0) ** alpha + max(delta, 0.0) ** alpha

        # d = 2 r cos(t + th) crosses delta~ at t = +-s* - th
        pts = [] if abs(delta) >= 2 * r else [(math.acos(delta / (2 * r)) - th) % (2 * math.pi),
                                              (-math.acos(delta / (2 * r)) - th) % (2 * math.pi)]
        re = quad(lambda t, th=th, r=r: F(2 * r * math.cos(t + th)) * math.cos(t), 0, 2 * math.pi, points=pts or None,
                  epsabs=1e-13, epsrel=1e-12, limit=400)[0]
        im = quad(lambda t, th=th, r=r: -F(2 * r * math.cos(t + th)) * math.sin(t), 0, 2 * math.pi, points=pts or None,
                  epsabs=1e-13, epsrel=1e-12, limit=400)[0]
        phi = tau0(alpha) * complex(re, im) / (2 * math.pi)
        g, _ = S.coupling(r, delta, alpha)
        assert abs(phi - g * z / r) < 1e-11 * max(1.0, abs(phi)), delta


def test_g_tends_to_the_linear_coupling_for_large_precompression():
    """delta~ >> r: g = tau0 kappa~ r (1 + a1 (2r/delta~)^2 + ...), kappa~ = alpha delta~^(alpha-1),
    a1 = (1-alpha)(2-alpha)/8 (the first term of the 2F1 series)."""
    alpha = 1.5
    delta = 2.0
    a1 = (1.0 - alpha) * (2.0 - alpha) / 8.0
    for r in (1e-1, 1e-2, 1e-3):
        g, P = S.coupling(r, delta, alpha)
        lin = tau0(alpha) * S.linear_coupling(delta, alpha) * r
        assert (g / lin - 1.0) / (2 * r / delta) ** 2 == pytest.approx(a1, rel=0.05)
        assert P / (lin * r / 2.0) == pytest.approx(1.0, abs=(2 * r / delta) ** 2)   # P = tau0 kappa~ r^2 / 2


def test_potential_derivative_is_g():
    """dP/dr = g on every branch (the Hamiltonian and the right-hand side agree): 4th-order differences."""
    alpha = 1.5
    h = 1e-4
    for delta in (-1.0, 0.7, 2.5, 6.0):
        r = np.array([0.3, 0.6, 0.9, 1.3, 2.0])
        P = [S.coupling(r + k * h, delta, alpha)[1] for k in (-2, -1, 1, 2)]
        dP = (P[0] - 8 * P[1] + 8 * P[2] - P[3]) / (12 * h)
        g, _ = S.coupling(r, delta, alpha)
        assert np.max(np.abs(dP - g)) < 1e-9


def _random_sites(N, rng, delta0=0.02, eps=0.01, beta=0.5):
    return S.dps_sites(rng.uniform(0.8, 1.25, N), 1.0 + 0.03 * rng.normal(size=N), rng.uniform(0.6, 1.4, N),
                       alpha=1.5, eps=eps, beta=beta, delta0=delta0)


@pytest.mark.parametrize("bc", ["periodic", "free"])
def test_rhs_is_hamiltonian(bc):
    """m_n dA_n/dtau = -i dH/d conj(A_n) (so sum m |A|^2 and H are conserved): central differences of H."""
    rng = np.random.default_rng(11)
    N = 7
    sites = _random_sites(N, rng)
    A = rng.normal(size=N) + 1j * rng.normal(size=N)
    h = 1e-6
    grad = np.empty(N, dtype=complex)
    for n in range(N):
        e = np.zeros(N)
        e[n] = h
        dx = (S.hamiltonian(A + e, 1.5, sites, bc) - S.hamiltonian(A - e, 1.5, sites, bc)) / (2 * h)
        dy = (S.hamiltonian(A + 1j * e, 1.5, sites, bc) - S.hamiltonian(A - 1j * e, 1.5, sites, bc)) / (2 * h)
        grad[n] = 0.5 * (dx + 1j * dy)
    lhs = sites.mass * S.rhs(A, 1.5, sites, bc)
    assert np.max(np.abs(lhs + 1j * grad)) < 1e-7 * np.max(np.abs(lhs))
    # the weighted l2 norm: d/dtau sum m |A|^2 = 2 Re sum m conj(A) A' = 0 exactly
    assert abs(np.sum(sites.mass * np.conj(A) * S.rhs(A, 1.5, sites, bc)).real) < 1e-12 * np.sum(np.abs(lhs * A))


def test_homogeneous_coefficients_are_dfnls():
    rng = np.random.default_rng(2)
    A = rng.normal(size=9) + 1j * rng.normal(size=9)
    for bc in ("periodic", "free"):
        assert np.max(np.abs(S.rhs(A, 1.5, S.homogeneous(9), bc) - dps_rhs(A, 1.5, bc))) < 1e-14
        assert np.max(np.abs(p_laplacian(A, 1.5, bc))) > 1.0


def test_isolated_detuned_site_turns_at_its_detuning():
    sites = S.dps_sites([1.3], [1.02], [1.0], alpha=1.5, eps=0.01, beta=0.4)
    A = np.array([0.7 - 0.2j])
    # one bead of a ring of one: its bond joins it to itself, D = 0
    rot = sites.detuning[0] + 1.5 * sites.beta[0] * abs(A[0]) ** 2
    assert S.rhs(A, 1.5, sites)[0] == pytest.approx(1j * rot * A[0], rel=1e-15)


def test_coefficients_from_the_lattice_sites():
    alpha, eps = 1.5, 0.04
    om = np.array([1.0, 1.01, 0.98])
    k = np.array([1.0, 2.0, 0.5])
    s = S.dps_sites([1.0, 2.0, 0.5], om, k, alpha=alpha, eps=eps, beta=0.3, delta0=0.002)
    np.testing.assert_allclose(s.detuning, (om - 1.0) / eps**0.5, rtol=1e-15)
    np.testing.assert_allclose(s.inv_mass, [1.0, 0.5, 2.0], rtol=1e-15)
    np.testing.assert_allclose(s.beta, 0.3 * om**2 * eps**1.5, rtol=1e-15)
    # delta_n = delta0 k_n^(-1/alpha): the static force k_n delta_n^alpha = delta0^alpha of every bond
    np.testing.assert_allclose(k * (s.delta * eps) ** alpha, 0.002**alpha, rtol=1e-13)
    p = S.dps_sites([1.0] * 3, om, [1.0] * 3, alpha=alpha, eps=eps, pendulum_scale=1e-3)
    np.testing.assert_allclose(p.beta, -om**2 * (1e-3 * om**2) ** 2 / 6.0 * eps**1.5, rtol=1e-14)


@pytest.mark.parametrize(("kwargs", "key"), [
    ({"sites_mass": [1.0, -1.0]}, "sites_mass"), ({"sites_omega": [1.0, 0.0]}, "sites_omega"),
    ({"sites_stiffness": [1.0]}, "sites_stiffness"), ({"eps": 0.0}, "eps"), ({"alpha": 1.0}, "alpha"),
    ({"beta": 0.1, "pendulum_scale": 0.1}, "beta"), ({"delta0": math.nan}, "delta0")])
def test_bad_input_is_one_line(kwargs, key):
    args = {"sites_mass": [1.0, 1.0], "sites_omega": [1.0, 1.0], "sites_stiffness": [1.0, 1.0], "alpha": 1.5,
            "eps": 0.01}
    args.update(kwargs)
    with pytest.raises(ConfigError) as err:
        S.dps_sites(args.pop("sites_mass"), args.pop("sites_omega"), args.pop("sites_stiffness"), **args)
    assert str(err.value).startswith(key) and "\n" not in str(err.value)


def test_sites_of_the_wrong_count_are_one_line():
    with pytest.raises(ConfigError, match=r"^DpsSites.weight: 2 values for 3 sites"):
        S.DpsSites(np.zeros(3), np.ones(3), np.ones(2), 0.0, 0.0)
    s = S.DpsSites(np.zeros(3), 1.0, np.ones(3), 0.5, 0.0)   # scalars broadcast
    assert s.beta.tolist() == [0.5, 0.5, 0.5] and not s.compressed
