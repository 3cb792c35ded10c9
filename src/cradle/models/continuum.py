"""The continuum limit alpha -> 1+: the DpS breathers of (dpsstn) and the solitary waves of (sw) become Gaussians.

Write alpha = 1 + eps. The nonlinearity of both equations expands as

    g(s) = s |s|^eps = s (1 + eps ln|s| + eps^2 ln^2|s| / 2 + ...)                              (:func:`g_series`)

**DpS (log-NLS).** A breather of (dpsstn) above the phonon band is staggered: a_n = (-1)^n b_n with b_n > 0, and
-nu a_n = g(a_{n+1} - a_n) - g(a_n - a_{n-1}) becomes, exactly (g is odd),

    nu b_n = g(b_n + b_{n+1}) + g(b_n + b_{n-1})                                               (stag)

(the profile held at unit amplitude, max b = 1, and nu the mu of (dpsst) it solves:
:class:`cradle.models.homoclinic_continuation.ScaledHomoclinic`). For a slowly varying b (b_n = b(x), x = n),
b(x +- 1) = b +- b' + b''/2 + ..., and 2 g(2b) = 4 b (1 + eps ln(2b) + O(eps^2)), so

    nu b = 4 b + 4 eps b ln(2b) + b'' + O(eps^2 b)   (b'' = O(eps b), b'''' and eps b'^2/b = O(eps^2 b)).

With nu = 4 + eps m and X = sqrt(eps) x, the terms of order eps give the stationary logarithmic NLS equation

    b_XX + 4 b ln(2b) - m b = 0,                                                               (lognls)

whose localised solutions are the Gaussians b = B exp(-(X - X0)^2), m = 4 ln(2B) - 2 (substitute: the X^2 terms
cancel for the exponent 1 only). So, to leading order in eps and with no free parameter,

    b_n / max b = exp(-eps (n - n_c)^2),     nu = 4 + eps (4 ln 2 - 2) + O(eps^2)   (B = 1)

(:func:`dps_gaussian`, :func:`nu_limit`), n_c = the central site of a site-centred breather, the middle of the
central bond of a bond-centred one: both parities tend to the same Gaussian. The neglected terms are O(eps^2 b)
against the O(eps b) of (lognls), so the distance of the computed profile to the Gaussian is O(eps). This is the
continuum limit of James & Starosvetsky ("Breather solutions of the discrete p-Schroedinger equation", in
Localized Excitations in Nonlinear Complex Systems, Springer 2014, doi 10.1007/978-3-319-02057-0_4: "In the limit of
weak nonlinearity (alpha -> 1+), we introduce a continuum limit connecting the stationary DpS and logarithmic
nonlinear Schroedinger equations. In this limit, breathers correspond asymptotically to Gaussian homoclinic
solutions"); the scaling and the constants above are derived here.

**Hertz chain without on-site potential (log-KdV).** The travelling wave R(xi), xi = n - c t, of the strains of
x_n'' = f(x_{n-1} - x_n) - f(x_n - x_{n+1}), f(r) = r_+^alpha, solves (sw): c^2 R'' = f(R(xi+1)) - 2 f(R) +
f(R(xi-1)) (:mod:`cradle.models.solitary`). The long-wave expansion of the second difference, d^2 + d^4/12 + ...,
and f(R) = R + eps R ln R + O(eps^2) give, with c^2 = 1 + eps s and Y = sqrt(eps) xi, at order eps^2,

    s R = R ln R + R_YY / 12                                 (twice integrated; the travelling log-KdV wave)

whose localised solutions are R = A exp(-3 (Y - Y0)^2), s = ln A - 1/2. So

    R / max R = exp(-3 eps xi^2),     c^2 = 1 + eps (ln A - 1/2) + O(eps^2),   A = max R

(:func:`kdv_gaussian`, :func:`kdv_speed_squared`): at c = 1 the amplitude tends to e^(1/2) for every eps. This is the
log-KdV limit of James & Pelinovsky, "Gaussian solitary waves and compactons in Fermi-Pasta-Ulam lattices with
Hertzian potentials", Proc. R. Soc. A 470 (2014) 20130462 (arXiv 1307.3837), derived here in the units of (sw).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

if TYPE_CHECKING:
    from cradle.models.solitary import SolitaryWave

#: m of (lognls) for the unit-amplitude Gaussian (B = 1): nu = 4 + eps LOG_NLS_M + O(eps^2)
LOG_NLS_M = 4.0 * math.log(2.0) - 2.0
#: the Gaussian exponent of the log-KdV wave in xi sqrt(eps): R ~ exp(-KDV_KAPPA eps xi^2)
KDV_KAPPA = 3.0


def g_series(s: ArrayLike, eps: float, order: int = 1) -> NDArray[np.float64]:
    """The expansion of g(s) = s |s|^eps in eps up to ``order``: s sum_k (eps ln|s|)^k / k! (0 at s = 0)."""
    s = np.asarray(s, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        L = np.where(s != 0.0, eps * np.log(np.abs(s)), 0.0)
    total = np.zeros_like(s)
    term = np.ones_like(s)
    for k in range(order + 1):
        if k:
            term = term * L / k
        total = total + term
    return s * total


def dps_gaussian(n: ArrayLike, centre: float, eps: float) -> NDArray[np.float64]:
    """The log-NLS Gaussian exp(-eps (n - centre)^2) that the envelope b_n / max b tends to (module docstring)."""
    n = np.asarray(n, dtype=float)
    return np.exp(-eps * (n - centre) ** 2)


def nu_limit(eps: float) -> float:
    """nu = 4 + eps (4 ln 2 - 2): the mu of (dpsst) solved by the unit-amplitude breather, to first order in eps."""
    return 4.0 + eps * LOG_NLS_M


def kdv_gaussian(xi: ArrayLike, eps: float) -> NDArray[np.float64]:
    """The log-KdV Gaussian exp(-3 eps xi^2) that the strain R / max R of (sw) tends to (module docstring)."""
    xi = np.asarray(xi, dtype=float)
    return np.exp(-KDV_KAPPA * eps * xi**2)


def kdv_speed_squared(eps: float, amplitude: float) -> float:
    """c^2 = 1 + eps (ln A - 1/2) of the log-KdV wave of amplitude A = max R, to first order in eps."""
    return 1.0 + eps * (math.log(amplitude) - 0.5)


def half_width(eps: float, decades: float, kappa: float = 1.0) -> int:
    """Sites from the centre at which the Gaussian exp(-kappa eps x^2) is ``decades`` decades down."""
    return int(math.ceil(math.sqrt(decades * math.log(10.0) / (kappa * eps))))


# ----------------------------------------------------------------- the DpS breathers near alpha = 1


@dataclass(frozen=True)
class DpsLimit:
    """A unit-amplitude breather of (dpsst) at alpha = 1 + eps on a ring of N sites and its envelope.

    ``profile`` solves -nu a_n = g(a_{n+1} - a_n) - g(a_n - a_{n-1}) (max |a| = 1); ``envelope`` b_n =
    (-1)^(n - pin) sign(a_pin) a_n (positive for a staggered breather, (stag)); ``centre`` n_c: the pinned site
    (site) or pin + 1/2 (bond)."""

    eps: float
    kind: str
    n: NDArray[np.float64]
    profile: NDArray[np.float64]
    envelope: NDArray[np.float64]
    centre: float
    nu: float
    residual: float
    converged: bool

    @property
    def gaussian(self) -> NDArray[np.float64]:
        """The log-NLS Gaussian at the same centre, scaled to the envelope's maximum on the lattice (1 at the central
        site; exp(-eps/4) at the two central sites of a bond-centred one is scaled to 1)."""
        G = dps_gaussian(self.n, self.centre, self.eps)
        return G / float(np.max(G))


def dps_breather(eps: float, kind: str, decades: float = 16.0, margin: int = 4) -> DpsLimit:
    """The site- or bond-centred breather of (dpsst) at alpha = 1 + eps, unit amplitude, on a ring wide enough for
    the Gaussian to fall by ``decades`` decades on each side (plus ``margin`` sites), solved from the log-NLS Gaussian
    itself by :func:`cradle.models.homoclinic_continuation.solve_scaled` (Powell's hybrid method, then Newton)."""
    from cradle.models.homoclinic_continuation import solve_scaled

    if kind not in ("site", "bond"):
        raise ValueError(f"kind = {kind!r}: must be site or bond")
    half = half_width(eps, decades) + margin
    N = 2 * half
    n = np.arange(N, dtype=float)
    pin = half
    centre = pin + (0.5 if kind == "bond" else 0.0)
    guess = (-1.0) ** (n - pin) * dps_gaussian(n, centre, eps)
    sol = solve_scaled(guess, 1.0 + eps)
    a = sol.profile
    env = (-1.0) ** (n - pin) * np.sign(a[pin]) * a
    return DpsLimit(eps=eps, kind=kind, n=n, profile=a, envelope=env, centre=centre, nu=float(sol.nu),
                    residual=float(sol.residual), converged=bool(sol.converged))


# ----------------------------------------------------------------- the Hertz chain's solitary waves near alpha = 1


def hertz_wave(eps: float, decades: float = 16.0, points: int = 8, tol: float = 1e-15,
               max_iterations: int = 100000) -> SolitaryWave:
    """The solitary wave of (sw) with f(r) = r_+^(1 + eps) at c = 1, on a periodic box wide enough for the log-KdV
    Gaussian to fall by ``decades`` decades on each side (plus 4 sites), ``points`` points per site
    (:func:`cradle.models.solitary.solve`, from the log-KdV Gaussian)."""
    from cradle.models import solitary

    length = 2.0 * (half_width(eps, decades, KDV_KAPPA) + 4)
    return solitary.solve(1.0, length, points, tol, max_iterations, alpha=1.0 + eps)
