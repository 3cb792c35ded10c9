"""The impulse of one bond force along a cubic model of its elongation: numba kernels.

For the contact-onset correction of the splittings (:mod:`cradle.integrators._onset`),
the contribution of one bond k to a step of length h of (nc) in the
variation-of-constants formula,

    I = int_0^h (sin(h - tau), cos(h - tau)) f(d~(tau)) dtau,

along the cubic Hermite model d~ of its elongation built from the elongations
and their rates at both ends of the step. Computed "exactly": the cubic is
cut at its extrema into monotone pieces and each of these at its root
(safeguarded Newton), and every piece where the force is nonzero is
integrated by 8-point Gauss-Legendre after the map tau = root +- L u^2,
under which (tau - root)^alpha dtau is u^(2 alpha + 1) times a smooth
function; the error is far below the truncation error of the splittings,
across one onset and for a contact that begins and ends within one step
(tests/test_integrators.py).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from numba import njit

from cradle.integrators import _cache
from cradle.integrators._kernels import _bond

if TYPE_CHECKING:
    from cradle.integrators._types import Floats

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating

# 8-point Gauss-Legendre on [0, 1]
_GX, _GW = np.polynomial.legendre.leggauss(8)
GL_U = np.ascontiguousarray(0.5 * (_GX + 1.0))
GL_W = np.ascontiguousarray(0.5 * _GW)


@njit(cache=True)
def cubic(c0: float, c1: float, c2: float, c3: float, s: float) -> float:
    """c0 + c1 s + c2 s^2 + c3 s^3 (Horner)."""
    return c0 + s * (c1 + s * (c2 + s * c3))


_SIN = np.array([1.0 / math.factorial(2 * k + 1) * (-1) ** k for k in range(8)])   # x^1 .. x^15
_COS = np.array([1.0 / math.factorial(2 * k) * (-1) ** k for k in range(9)])       # x^0 .. x^16


@njit(cache=True)
def _sincos(x: float) -> tuple[float, float]:
    """(sin x, cos x): Taylor polynomials of degree 15/16 for |x| <= 1 (error < 3e-15), libm beyond."""
    if abs(x) > 1.0:
        return math.sin(x), math.cos(x)
    z = x * x
    sv = _SIN[7]
    for i in range(6, -1, -1):
        sv = sv * z + _SIN[i]
    cv = _COS[8]
    for i in range(7, -1, -1):
        cv = cv * z + _COS[i]
    return x * sv, cv


@njit(cache=True)
def _root(c0: float, c1: float, c2: float, c3: float, lo: float, hi: float, plo: float) -> float:
    """Root of the cubic in [lo, hi] where it is monotone with a sign change (plo = p(lo))."""
    phi = cubic(c0, c1, c2, c3, hi)
    s = lo - plo * (hi - lo) / (phi - plo) if phi != plo else 0.5 * (lo + hi)
    for _ in range(60):
        ps = cubic(c0, c1, c2, c3, s)
        if ps == 0.0:
            return s
        if (ps < 0.0) == (plo < 0.0):
            lo = s
            plo = ps
        else:
            hi = s
        dp = c1 + s * (2.0 * c2 + 3.0 * s * c3)
        sn = s - ps / dp if dp != 0.0 else 0.5 * (lo + hi)
        if not (lo < sn < hi):
            sn = 0.5 * (lo + hi)
        if abs(sn - s) <= 4e-16:
            return sn
        s = sn
    return s


@njit(cache=True)
def _piece(c0: float, c1: float, c2: float, c3: float, p: float, q: float, side: int, h: float, alpha: float,
           mode: int) -> tuple[float, float]:
    """int over s in [p, q] of (sin(h(1-s)), cos(h(1-s))) f(d~(s)) ds by 8-point Gauss-Legendre.

    ``side`` = -1 if d~(p) = 0, +1 if d~(q) = 0, 0 if neither: near a root
    the force behaves like |s - root|^alpha, and the map s = root +- L u^2
    makes the integrand u^(2 alpha + 1) times a smooth function (a
    polynomial times a smooth factor for alpha = 3/2).
    """
    L = q - p
    ix = 0.0
    iv = 0.0
    if L <= 0.0:
        return ix, iv
    if (mode == 0 or mode == 1) and cubic(c0, c1, c2, c3, p + 0.5 * L) >= 0.0:
        return ix, iv  # Hertz: no contact on this piece
    for jj in range(GL_U.shape[0]):
        u = GL_U[jj]
        if side < 0:
            s = p + L * u * u
            wgt = GL_W[jj] * 2.0 * u
        elif side > 0:
            s = q - L * u * u
            wgt = GL_W[jj] * 2.0 * u
        else:
            s = p + L * u
            wgt = GL_W[jj]
        fv = _bond(cubic(c0, c1, c2, c3, s), alpha, mode)[0]
        if fv != 0.0:
            sa, ca = _sincos(h * (1.0 - s))
            ix += wgt * fv * sa
            iv += wgt * fv * ca
    return L * ix, L * iv


@njit(cache=True)
def hermite(d0: float, w0: float, d1: float, w1: float, h: float) -> tuple[float, float, float, float]:
    """Coefficients in s = tau/h of the cubic with values d0, d1 and slopes w0, w1 at tau = 0, h."""
    c2 = -3.0 * d0 + 3.0 * d1 - 2.0 * h * w0 - h * w1
    c3 = 2.0 * d0 - 2.0 * d1 + h * w0 + h * w1
    return d0, h * w0, c2, c3


@njit(cache=True)
def extrema(c1: float, c2: float, c3: float) -> tuple[float, float]:
    """The extrema of the cubic in (0, 1), sorted; 2.0 where there is none."""
    qa = 3.0 * c3
    qb = 2.0 * c2
    e1 = 2.0
    e2 = 2.0
    if qa != 0.0:
        disc = qb * qb - 4.0 * qa * c1
        if disc > 0.0:
            sq = math.sqrt(disc)
            qq = -0.5 * (qb + sq if qb >= 0.0 else qb - sq)
            e1 = qq / qa
            e2 = c1 / qq if qq != 0.0 else 2.0
    elif qb != 0.0:
        e1 = -c1 / qb
    if e1 > e2:
        e1, e2 = e2, e1
    if not 0.0 < e1 < 1.0:
        e1 = e2
        e2 = 2.0
    if not 0.0 < e1 < 1.0:
        e1 = 2.0
    if not 0.0 < e2 < 1.0 or e2 == e1:
        e2 = 2.0
    return e1, e2


@njit(cache=True)
def _count_roots(c0: float, c1: float, c2: float, c3: float, e1: float, e2: float) -> int:
    """Number of sign changes of the cubic over its monotone pieces of [0, 1] (= roots in (0, 1))."""
    nroots = 0
    plo = c0
    for i in range(3):
        hi = e1 if i == 0 else (e2 if i == 1 else 1.0)
        if hi > 1.0:
            continue
        phi = cubic(c0, c1, c2, c3, hi)
        if (plo < 0.0) != (phi < 0.0) and plo != 0.0 and phi != 0.0:
            nroots += 1
        plo = phi
    return nroots


@njit(cache=True)
def integrate_pieces(c0: float, c1: float, c2: float, c3: float, e1: float, e2: float, h: float, alpha: float,
                     mode: int) -> tuple[float, float]:
    """int_0^1 (sin(h(1-s)), cos(h(1-s))) f(d~(s)) ds over the monotone pieces, split at the roots."""
    ix = 0.0
    iv = 0.0
    lo = 0.0
    plo = c0
    for i in range(3):
        hi = e1 if i == 0 else (e2 if i == 1 else 1.0)
        if hi > 1.0:
            continue
        phi = cubic(c0, c1, c2, c3, hi)
        if (plo < 0.0) != (phi < 0.0) and plo != 0.0 and phi != 0.0:
            r = _root(c0, c1, c2, c3, lo, hi, plo)
            px, pv = _piece(c0, c1, c2, c3, lo, r, 1, h, alpha, mode)
            ix += px
            iv += pv
            px, pv = _piece(c0, c1, c2, c3, r, hi, -1, h, alpha, mode)
        else:
            px, pv = _piece(c0, c1, c2, c3, lo, hi, 0, h, alpha, mode)
        ix += px
        iv += pv
        lo = hi
        plo = phi
    return ix, iv


@njit(cache=True)
def exact_impulse(d0: float, w0: float, d1: float, w1: float, h: float, alpha: float, mode: int, out: Floats) -> int:
    """I = int_0^h (sin(h - tau), cos(h - tau)) f(d~(tau)) dtau along the cubic Hermite d~.

    d~(0) = d0, d~'(0) = w0, d~(h) = d1, d~'(h) = w1; f is the bond force of
    ``mode`` (see :mod:`._kernels`). In s = tau/h the cubic is split at its
    extrema in (0, 1) into monotone pieces, and each of these at its root,
    if any; every sub-piece is integrated by :func:`_piece`. Writes
    (I_x, I_v) into ``out[0:2]`` and returns the number of roots of d~ in (0, h).
    """
    c0, c1, c2, c3 = hermite(d0, w0, d1, w1, h)
    e1, e2 = extrema(c1, c2, c3)
    ix, iv = integrate_pieces(c0, c1, c2, c3, e1, e2, h, alpha, mode)
    out[0] = h * ix
    out[1] = h * iv
    return _count_roots(c0, c1, c2, c3, e1, e2)
