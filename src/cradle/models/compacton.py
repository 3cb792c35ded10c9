"""Compactons of the degenerate continuum equations near p = alpha + 1 = 2 (issue 37, item 5): the DpS breathers and
the Hertz chain's solitary waves against profiles of compact support.

Write alpha = 1 + eps and g(s) = s |s|^eps. The log-NLS and log-KdV limits of :mod:`cradle.models.continuum` expand
the nonlinearity in eps; keeping it whole and expanding only the differences in the slow variable gives equations
whose dispersion degenerates where the profile vanishes, and whose localised solutions have compact support.

**DpS.** The staggered stationary equation (stag) of :mod:`cradle.models.continuum`, nu b_n = g(b_n + b_{n+1}) +
g(b_n + b_{n-1}), with u = 2b slowly varying (b_n + b_{n+-1} = u +- u'/2 + u''/4 + ...) is, to second order in the
derivatives,

    nu u = 4 g(u) + g'(u) u'' + g''(u) u'^2 / 2.                                               (C)

The u'^2 term is O(eps^2 u) on the scale x ~ eps^(-1/2), as is the u'''' term left out, so two shorter equations are
as consistent:

    nu u = 4 g(u) + (g(u))''                                                                   (A)
    nu u = 4 g(u) + g'(u) u''.                                                                 (B)

Each becomes v'' + 4 k v = k nu v^q, v = u^r, with q = 1/(1 + eps) (A), 1 - eps (B), (2 - eps)/(2 + eps) (C),
r = 1 + eps, 1, 1 + eps/2 and k = 1, 1/(1 + eps), r/(1 + eps) (the sublinear power q < 1 is what allows compact
support). Its zero-energy solution is v = V cos^(2/(1-q))(kappa x) on |kappa x| <= pi/2 and 0 outside (v, v' and v''
continuous at the edge: a classical solution), so that in each form

    b / max b = cos^(2/eps)(kappa (n - n_c)),  |n - n_c| <= pi / (2 kappa),   0 beyond,        (compacton)
    kappa = eps / (1 + eps) (A),  eps / sqrt(1 + eps) (B),  eps sqrt(2 / ((2 + eps)(1 + eps))) (C),
    nu = 2^(1+eps) (2 + eps)/(1 + eps) (A),  2^(1+eps) (2 - eps) (B),  2^(3+eps) / (2 + eps) (C)   (max b = 1).

Each tends to the log-NLS Gaussian exp(-eps (n - n_c)^2) (cos^(2/eps)(eps y) = exp(-eps y^2 + O(eps^2 y^4))) with
nu = 4 + eps (4 ln 2 - 2) + O(eps^2), the constants of :mod:`cradle.models.continuum`. These three equations and
their solutions are derived here. James (Phil. Trans. R. Soc. A 376 (2018) 20170138, abstract) derives from DpS, for
p slightly above 2, the log-NLS equation and "fully nonlinear degenerate NLS equations with compacton solutions";
the body of that paper was not available to us, so whether (A)-(C) are his equations is not known.

**Hertz chain without on-site potential.** (sw), c^2 R'' = f(R(xi+1)) - 2 f(R) + f(R(xi-1)), f(R) = R^(1+eps),
with the second difference d^2 + d^4/12 and integrated twice, is c^2 R = v + v''/12 with v = f(R): v'' + 12 v =
12 c^2 v^(1/(1+eps)), the same form (q = 1/(1 + eps), a Hoelder-continuous power of v), whose compacton is

    R / max R = cos^(2/eps)(kappa xi),  kappa = sqrt(3) eps / (1 + eps),   (max R)^eps = c^2 2 (1 + eps)/(2 + eps),

tending to the log-KdV Gaussian exp(-3 eps xi^2) and, at c = 1, to ln max R -> 1/2. James & Pelinovsky (Proc. R.
Soc. A 470 (2014) 20130462, arXiv 1307.3837, abstract) derive "a generalized KdV equation with Hoelder-continuous
fractional power nonlinearity" admitting compactons and check "the pointwise convergence of compactons towards the
limiting Gaussian profile"; the equation here is derived in the units of (sw).
"""
from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

#: the three degenerate forms of the staggered stationary DpS (module docstring)
FORMS = ("A", "B", "C")


def dps_kappa(eps: float, form: str) -> float:
    """kappa of the DpS compacton of ``form`` (A, B or C; module docstring) at alpha = 1 + eps."""
    if form == "A":
        return eps / (1.0 + eps)
    if form == "B":
        return eps / math.sqrt(1.0 + eps)
    if form == "C":
        return eps * math.sqrt(2.0 / ((2.0 + eps) * (1.0 + eps)))
    raise ValueError(f"form = {form!r}: must be one of {', '.join(FORMS)}")


def dps_nu(eps: float, form: str) -> float:
    """nu of the unit-amplitude (max b = 1) DpS compacton of ``form``: the mu of (dpsst) it approximates."""
    if form == "A":
        return 2.0 ** (1.0 + eps) * (2.0 + eps) / (1.0 + eps)
    if form == "B":
        return 2.0 ** (1.0 + eps) * (2.0 - eps)
    if form == "C":
        return 2.0 ** (3.0 + eps) / (2.0 + eps)
    raise ValueError(f"form = {form!r}: must be one of {', '.join(FORMS)}")


def profile(y: ArrayLike, eps: float, kappa: float) -> NDArray[np.float64]:
    """cos^(2/eps)(kappa y) on |kappa y| <= pi/2, 0 beyond: the compacton of unit maximum centred at y = 0."""
    z = kappa * np.asarray(y, dtype=float)
    inside = np.abs(z) < 0.5 * math.pi
    c = np.where(inside, np.cos(np.where(inside, z, 0.0)), 0.0)
    with np.errstate(under="ignore"):
        return np.where(inside, np.abs(c) ** (2.0 / eps), 0.0)


def dps_compacton(n: ArrayLike, centre: float, eps: float, form: str) -> NDArray[np.float64]:
    """b_n / max b of the DpS compacton of ``form`` centred at ``centre`` (a site or the middle of a bond)."""
    return profile(np.asarray(n, dtype=float) - centre, eps, dps_kappa(eps, form))


def dps_half_width(eps: float, form: str) -> float:
    """Half the support of the DpS compacton, pi / (2 kappa) sites."""
    return 0.5 * math.pi / dps_kappa(eps, form)


def hertz_kappa(eps: float) -> float:
    """kappa = sqrt(3) eps / (1 + eps) of the compacton of the Hertz chain's travelling waves."""
    return math.sqrt(3.0) * eps / (1.0 + eps)


def hertz_compacton(xi: ArrayLike, eps: float) -> NDArray[np.float64]:
    """R / max R of the Hertz chain's compacton centred at xi = 0."""
    return profile(xi, eps, hertz_kappa(eps))


def hertz_log_amplitude(eps: float, c: float = 1.0) -> float:
    """ln max R of the Hertz chain's compacton of speed c: (ln c^2 + ln(2 (1 + eps)/(2 + eps))) / eps."""
    return (2.0 * math.log(c) + math.log(2.0 * (1.0 + eps) / (2.0 + eps))) / eps
