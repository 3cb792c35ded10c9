"""models.compacton: the compactons solve their degenerate equations, vanish beyond pi/(2 kappa), and tend to the
Gaussians of the alpha -> 1+ limit at distance O(alpha - 1) with the first-order constants of models.continuum.

The equations are applied by finite differences of the profile itself (central, Richardson-extrapolated: error
O(h^4)), not through the closed-form derivatives the module's constants come from."""
from __future__ import annotations

import math

import numpy as np
import pytest

from cradle.models import compacton as K, continuum as C

H = 2e-3


def _rich(d, f, x):
    """Richardson's extrapolation of a central difference from the steps H and H/2: error O(H^4)."""
    return (4.0 * d(f, x, H / 2) - d(f, x, H)) / 3.0


def _d1(f, x):
    return _rich(lambda f, x, h: (f(x + h) - f(x - h)) / (2 * h), f, x)


def _d2(f, x):
    return _rich(lambda f, x, h: (f(x + h) - 2 * f(x) + f(x - h)) / h**2, f, x)


@pytest.mark.parametrize("eps", [0.3, 0.1, 0.02])
@pytest.mark.parametrize("form", K.FORMS)
def test_the_dps_compacton_solves_its_degenerate_equation(form, eps):
    u = lambda x: 2.0 * K.dps_compacton(x, 0.0, eps, form)      # noqa: E731  (u = 2b, max b = 1)
    g = lambda s: s ** (1.0 + eps)                                # noqa: E731
    nu = K.dps_nu(eps, form)
    x = np.linspace(-0.97, 0.97, 41) * K.dps_half_width(eps, form)
    U = u(x)
    if form == "A":
        disp = _d2(lambda y: g(u(y)), x)
    elif form == "B":
        disp = (1 + eps) * U**eps * _d2(u, x)
    else:
        disp = (1 + eps) * U**eps * _d2(u, x) + 0.5 * (1 + eps) * eps * U ** (eps - 1) * _d1(u, x) ** 2
    res = nu * U - 4.0 * g(U) - disp
    # the extrapolated differences leave O(h^4) times a sixth derivative (each derivative brings a factor
    # (2/eps) kappa <= 2 and the profile is at most 2) and rounding ~1e-16 / h^2: both far below 1e-8
    assert float(np.max(np.abs(res))) < 1e-8 * nu * 2.0


@pytest.mark.parametrize("eps", [0.3, 0.05])
@pytest.mark.parametrize("c", [1.0, 1.1])
def test_the_hertz_compacton_solves_the_twice_integrated_wave_equation(eps, c):
    amp = math.exp(K.hertz_log_amplitude(eps, c))
    R = lambda x: amp * K.hertz_compacton(x, eps)                 # noqa: E731
    v = lambda x: R(x) ** (1.0 + eps)                             # noqa: E731
    x = np.linspace(-0.97, 0.97, 41) * 0.5 * math.pi / K.hertz_kappa(eps)
    res = c**2 * R(x) - v(x) - _d2(v, x) / 12.0
    assert float(np.max(np.abs(res))) < 1e-8 * amp


@pytest.mark.parametrize("form", K.FORMS)
def test_the_support_is_pi_over_two_kappa(form):
    eps = 0.1
    hw = K.dps_half_width(eps, form)
    assert hw == pytest.approx(0.5 * math.pi / K.dps_kappa(eps, form), rel=1e-15)
    inside = np.linspace(-hw, hw, 201)[1:-1]
    assert np.all(K.dps_compacton(inside, 0.0, eps, form) > 0)
    outside = np.concatenate([np.linspace(1 + 1e-12, 3, 50), -np.linspace(1 + 1e-12, 3, 50)]) * hw
    assert np.all(K.dps_compacton(outside, 0.0, eps, form) == 0)
    # the shape is cos^(2/eps): its value at half the support is cos(pi/4)^(2/eps) = 2^(-1/eps)
    assert K.dps_compacton(np.array([hw / 2]), 0.0, eps, form)[0] == pytest.approx(2.0 ** (-1.0 / eps), rel=1e-12)
    # v = u^r (r = 1 + eps for A) vanishes with its first two derivatives at the edge: a classical solution
    y = hw - np.array([1e-2, 1e-3])
    v = K.dps_compacton(y, 0.0, eps, form) ** (1 + eps)
    assert v[1] / v[0] < 1e-2 ** 2


def test_the_compactons_tend_to_the_gaussians_with_the_first_order_constants():
    def dist(eps, form):
        n = np.linspace(-8, 8, 801) / math.sqrt(eps)
        return float(np.max(np.abs(K.dps_compacton(n, 0.0, eps, form) - C.dps_gaussian(n, 0.0, eps))))

    for form in K.FORMS:
        e1, e2 = 1e-3, 1e-4
        assert math.log(dist(e1, form) / dist(e2, form)) / math.log(e1 / e2) == pytest.approx(1.0, abs=0.02)
        # nu = 4 + eps (4 ln 2 - 2) + O(eps^2)
        q = [(K.dps_nu(e, form) - 4.0) / e for e in (e1, e2)]
        assert abs(q[1] - C.LOG_NLS_M) < abs(q[0] - C.LOG_NLS_M) / 5 and abs(q[1] - C.LOG_NLS_M) < 1e-3
    xi = np.linspace(-8, 8, 801) / math.sqrt(3e-4)
    assert float(np.max(np.abs(K.hertz_compacton(xi, 3e-4) - C.kdv_gaussian(xi, 3e-4)))) < 1e-3
    # ln max R -> 1/2 at c = 1 (the log-KdV amplitude e^(1/2))
    assert abs(K.hertz_log_amplitude(1e-4) - 0.5) < 1e-4


def test_an_unknown_form_is_refused():
    with pytest.raises(ValueError, match="form = 'D'"):
        K.dps_kappa(0.1, "D")
