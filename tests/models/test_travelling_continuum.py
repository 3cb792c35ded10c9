"""The time-dependent continuum equations near alpha = 1 (cradle.models.travelling_continuum): what a boost does.

From mathematics: g's real derivatives against difference quotients; the boosted log-NLS Gaussian solves (lognlst)
(Galilean invariance: the residual is rounding); the static compactons solve the forms (At)-(Ct) at k = 0, and the
boosted one leaves in (Bt) exactly the closed-form defect 2 i k (1 - |phi|^eps) phi' + k^2 ((1 + eps) phi^(1 + eps)
- phi); the boosted Gaussian sampled on the lattice satisfies the TB condition (tb) with the theta of (theta); at c =
0 the travelling profiles are the static ones and the complex distance is the static comparison's max-norm one.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from cradle.measurements.continuum import complex_distance, sup_distance
from cradle.models import compacton as K, travelling_continuum as T
from cradle.models.continuum import dps_gaussian

#: terms of the equations are of size 4 max|U| = 8: rounding leaves a few ulps of that, relative to max|U|
ROUNDING = 1e-12


def _g(z, eps):
    return z * np.abs(z) ** eps


def test_derivatives_of_g_against_difference_quotients():
    rng = np.random.default_rng(0)
    z = rng.normal(size=20) + 1j * rng.normal(size=20)
    h = rng.normal(size=20) + 1j * rng.normal(size=20)
    eps, d = 0.3, 1e-4
    first = (_g(z + d * h, eps) - _g(z - d * h, eps)) / (2 * d)
    second = (_g(z + d * h, eps) - 2 * _g(z, eps) + _g(z - d * h, eps)) / d**2
    # central quotients: errors d^2 |g'''| / 6 and d^2 |g''''| / 12, far below 1e-6 at |z| ~ 1, plus the
    # rounding of the second quotient, ~ 1e-16 / d^2 = 1e-8
    assert np.max(np.abs(first - T.dg(z, h, eps))) < 1e-6
    assert np.max(np.abs(second - T.d2g(z, h, eps))) < 1e-6
    # real z, h: g''(z) h^2 = eps (1 + eps) |z|^(eps - 1) h^2, and the limits at z = 0 are 0 (alpha > 1)
    x = np.array([0.5, 2.0])
    assert np.allclose(T.d2g(x, np.ones(2), eps).real, eps * (1 + eps) * x ** (eps - 1), rtol=1e-14, atol=0)
    assert T.dg(np.zeros(1), np.ones(1), eps)[0] == 0 and T.d2g(np.zeros(1), np.ones(1), eps)[0] == 0


@pytest.mark.parametrize("eps", [0.2, 0.01])
@pytest.mark.parametrize("K_", [0.0, 0.5, 1.0])
def test_the_boosted_gaussian_solves_the_log_nls(eps, K_):
    # Galilean invariance: any boost of the Gaussian is a solution
    assert T.boost_residual("log-NLS", eps, K_ * math.sqrt(eps)) < ROUNDING


@pytest.mark.parametrize("form", K.FORMS)
def test_the_static_compactons_solve_their_forms(form):
    for eps in (0.2, 0.02):
        assert T.boost_residual(form, eps, 0.0) < ROUNDING


def test_the_boosted_compacton_leaves_the_closed_form_galilean_defect_in_form_b():
    eps, k, tau0 = 0.1, 0.3, 1.7
    kap = K.dps_kappa(eps, "B")
    x = np.linspace(-0.49 * math.pi / kap, 0.49 * math.pi / kap, 801)
    phi, d1, d2 = T.compacton_profile(x, eps, kap, 2.0)
    nu = K.dps_nu(eps, "B")
    R = T.residual("B", phi, d1, d2, x, k, -(nu - k * k) / (2 * tau0), eps, tau0)
    defect = (2j * k * (1 - phi**eps) * d1 + k * k * ((1 + eps) * phi ** (1 + eps) - phi)) * np.exp(1j * k * x)
    assert np.max(np.abs(R - defect)) < ROUNDING * np.max(phi)
    assert np.max(np.abs(R)) > 1e3 * ROUNDING            # not a solution: the form is not Galilean-invariant


def test_the_boosted_gaussian_satisfies_the_tb_condition_with_its_theta():
    eps, kappa, beta, tau0 = 0.05, 0.2, 0.8, 1.9
    c = kappa / tau0
    T_ = 1.0 / c
    nu = T.nu_gaussian(eps, beta)
    Omega = (kappa**2 - nu) / (2 * tau0)
    n = np.arange(-60, 61, dtype=float)

    def A(tau):   # the staggered lattice field of (boost)
        return (-1.0) ** n * beta * np.exp(-eps * (n - c * tau) ** 2) * np.exp(1j * (kappa * n - Omega * tau))

    theta = T.boost_theta(c, tau0, nu)
    tau = 0.37
    lhs = A(tau + T_)[1:]
    rhs = np.exp(1j * theta) * A(tau)[:-1]                # A_n(tau + T) = e^{i theta} A_{n-1}(tau)
    assert np.max(np.abs(lhs - rhs)) < 1e-12
    assert -math.pi < theta <= math.pi


def test_at_c_0_the_travelling_profiles_are_the_static_ones():
    eps, tau0 = 0.1, 1.9
    n = np.arange(40, dtype=float)
    assert np.array_equal(T.travelling_profile("gaussian", n, 20.0, eps, 0.0, tau0).real, dps_gaussian(n, 20.0, eps))
    assert np.allclose(T.travelling_profile("gaussian carrier", n, 20.5, eps, 0.0, tau0), dps_gaussian(n, 20.5, eps)
                       / np.max(dps_gaussian(n, 20.5, eps)), rtol=1e-15, atol=0)
    for form in K.FORMS:
        C = K.dps_compacton(n, 20.0, eps, form)
        for model in (form, form + " carrier"):
            assert np.allclose(T.travelling_profile(model, n, 20.0, eps, 0.0, tau0), C / C.max(), rtol=1e-15,
                               atol=1e-300)
    # moving: the carrier Gaussian is exp(-a (n - centre)^2) with the lattice's phase gradient
    c = 0.05
    kl = math.asin(tau0 * c)
    G = np.exp(-T.carrier_width(eps, kl) * (n - 20.0) ** 2) * np.exp(1j * kl * (n - 20.0))
    # exp of an exponent up to a (n - centre)^2 ~ 40, computed two ways: relative rounding ~ 40 ulps
    assert np.allclose(T.travelling_profile("gaussian carrier", n, 20.0, eps, c, tau0), G, rtol=1e-13, atol=1e-300)
    with pytest.raises(ValueError, match="must be one of"):
        T.travelling_profile("carrier", n, 20.0, eps, c, tau0)
    # for real positive profiles the complex distance is the static comparison's
    b = dps_gaussian(n, 19.7, 0.09)
    G = dps_gaussian(n, 20.0, eps)
    assert complex_distance(-3.0 * b, G) == pytest.approx(sup_distance(b, G), rel=1e-14)


def test_the_carrier_width_narrows_by_kappa_squared_over_4():
    eps = 0.01
    for kap in (0.1, 0.03):
        rel = T.carrier_width(eps, kap) / eps - 1.0
        # (1 + cos k) / (2 cos k) = 1 + k^2/4 + 5 k^4/48 + ...
        assert rel == pytest.approx(kap**2 / 4, rel=kap**2)
    assert T.carrier_kappa(0.05, 2.0) == pytest.approx(math.asin(0.1), rel=1e-15)
