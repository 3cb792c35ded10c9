"""Numba kernels of the imperfect cradle (ncimperfect) of :mod:`cradle.models.lattice_terms`: its right-hand
side, and with the damping of (ncdamped) and the dissipated energy (kind 4 of :mod:`cradle.integrators._dop853`), and
its generalised energy (ham).

The site coefficients travel in one float64 array ``par`` (:func:`pack`): a header of ``HEAD`` entries
[gamma, eta, s (the scale of D in the state), on-site code (0 harmonic, 1 quartic, 2 pendulum), beta, 0, 0, 0],
then seven blocks of N entries: m_n, omega_n^2, k_n, delta_n, (delta_n)_+^alpha, s_n (pendulum), 1/m_n.

Precision near rest of a precompressed bond: k (delta^alpha - (delta - d)^alpha), a difference of two nearly
equal numbers for |d| << delta, is evaluated as d (delta^2 + delta c + c^2) / (delta^(3/2) + c^(3/2)) for
alpha = 3/2 (c = delta - d) and as -delta^alpha expm1(alpha log1p(-d/delta)) otherwise, to full relative precision
however small d (the linear dispersion is measured at d ~ 1e-4 delta_0).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from cradle.integrators import _cache

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating

#: length of the header of ``par``; the seven blocks of N site coefficients follow
HEAD = 8
HARMONIC, QUARTIC, PENDULUM = 0, 1, 2


def pack(mass, omega, stiffness, delta, s, alpha, code, beta, gamma, eta, dscale):
    """The ``par`` of :func:`terms_rhs` and :func:`terms_energy` (float64, HEAD + 7 N entries)."""
    mass = np.asarray(mass, dtype=float)
    delta = np.asarray(delta, dtype=float)
    head = np.array([gamma, eta, dscale, float(code), beta, 0.0, 0.0, 0.0])
    return np.ascontiguousarray(np.concatenate((head, mass, np.asarray(omega, dtype=float) ** 2,
                                                np.asarray(stiffness, dtype=float), delta,
                                                np.maximum(delta, 0.0) ** alpha, np.asarray(s, dtype=float),
                                                1.0 / mass)))


@njit(cache=True, inline="always")
def _pow(c, alpha, mode):
    """(c^alpha, c^(alpha-1)) of a compression c > 0 (mode 0: the alpha = 3/2 fast path)."""
    if mode == 0:
        r = math.sqrt(c)
        return c * r, r
    r = c ** (alpha - 1.0)
    return c * r, r


@njit(cache=True)
def terms_rhs(y, dy, f, F, alpha, mode, par, periodic):
    """First-order form of (ncimperfect), y = [x, v], or with the damping of (ncdamped), y = [x, v, s D]:
    dy = [v, -omega_n^2 W'(x_n) - gamma v_n + J_n (g_n - g_{n-1}) / m_n, s P], g_n = k_n ((delta_n)_+^alpha -
    max(c^alpha + eta c^(alpha-1) c', 0)) on a bond with overlap c = delta_n - (u_{n+1} - u_n) > 0, else
    k_n (delta_n)_+^alpha; P the dissipated power (:mod:`cradle.models.lattice_terms`). ``f``, ``F``: work
    arrays of length N (F holds the horizontal positions u). Hertz modes 0 and 1 only. Without damping
    (gamma = eta = 0, y of length 2N) and with every coefficient 1 it computes the floats of
    :func:`cradle.integrators._kernels.lattice_rhs` (x 1, + 0: exact), so a run is bitwise that of kind 0."""
    N = f.shape[0]
    gamma = par[0]
    eta = par[1]
    dscale = par[2]
    code = int(par[3])
    beta = par[4]
    o = HEAD
    P = 0.0
    # horizontal positions u in F, and the pendulum's J = du/dx in dy[N:2N] (overwritten last)
    if code == 2:
        for n in range(N):
            sx = par[o + 5 * N + n] * y[n]
            F[n] = math.sin(sx) / par[o + 5 * N + n]
            dy[N + n] = math.cos(sx)
    else:
        for n in range(N):
            F[n] = y[n]
            dy[N + n] = 1.0
    nb = N if periodic else N - 1
    for n in range(nb):
        m = n + 1 if n + 1 < N else 0
        kn = par[o + 2 * N + n]
        dn = par[o + 3 * N + n]
        dpa = par[o + 4 * N + n]
        d = F[m] - F[n]
        c = dn - d
        if c > 0.0:
            el, sa = _pow(c, alpha, mode)
            if dn > 0.0 and mode == 0:
                # delta^(3/2) - c^(3/2) = (delta^3 - c^3)/(delta^(3/2) + c^(3/2)), delta - c = d: no cancellation
                diff = d * (dn * dn + dn * c + c * c) / (dpa + el)
            elif dn > 0.0:
                diff = -dpa * math.expm1(alpha * math.log1p(-d / dn))   # dpa - el, without cancellation
            else:
                diff = -el
            if eta != 0.0:
                rate = dy[N + n] * y[N + n] - dy[N + m] * y[N + m]   # c' = -(u'_{n+1} - u'_n)
                push = el + eta * sa * rate
                if push < 0.0:   # the contact would pull: no force
                    f[n] = kn * dpa
                    P -= kn * el * rate
                else:
                    f[n] = kn * (diff - eta * sa * rate)
                    P += kn * eta * sa * rate * rate
            else:
                f[n] = kn * diff
        else:
            f[n] = kn * dpa
    if not periodic:
        f[N - 1] = 0.0
    for n in range(N):
        net = f[n] - f[n - 1] if n > 0 else f[0] - f[N - 1]
        x = y[n]
        v = y[N + n]
        w2 = par[o + N + n]
        if code == 0:
            on = w2 * x
        elif code == 1:
            on = w2 * (x + beta * x * x * x)
        else:
            on = w2 * F[n]
        dy[n] = v
        dy[N + n] = dy[N + n] * net * par[o + 6 * N + n] - on - gamma * v
        P += gamma * par[o + n] * v * v
    if y.shape[0] > 2 * N:
        dy[2 * N] = dscale * P


@njit(cache=True)
def terms_energy(x, v, alpha, mode, par, periodic):
    """The generalised (ham) of (ncimperfect) at one state, and the largest bond overlap c = delta_n - d."""
    N = x.shape[0]
    code = int(par[3])
    beta = par[4]
    o = HEAD
    u = np.empty(N)
    e = 0.0
    for n in range(N):
        xn = x[n]
        mw2 = par[o + n] * par[o + N + n]
        if code == 2:
            sn = par[o + 5 * N + n]
            u[n] = math.sin(sn * xn) / sn
            h = math.sin(0.5 * sn * xn) / sn
            W = 2.0 * h * h
        elif code == 1:
            u[n] = xn
            W = 0.5 * xn * xn + 0.25 * beta * xn ** 4
        else:
            u[n] = xn
            W = 0.5 * xn * xn
        e += 0.5 * par[o + n] * v[n] * v[n] + mw2 * W
    cmax = 0.0
    a1 = alpha + 1.0
    nb = N if periodic else N - 1
    for n in range(nb):
        m = n + 1 if n + 1 < N else 0
        kn = par[o + 2 * N + n]
        dn = par[o + 3 * N + n]
        d = u[m] - u[n]
        c = dn - d
        if dn > 0.0:
            dpa = par[o + 4 * N + n]
            if c > 0.0:
                # delta^(alpha+1)/(alpha+1) ((1 - r)^(alpha+1) - 1 + (alpha+1) r), r = d/delta
                r = d / dn
                phi = dpa * dn / a1 * (math.expm1(a1 * math.log1p(-r)) + a1 * r)
            else:
                phi = dpa * (d - dn / a1)
        else:
            phi = c ** a1 / a1 if c > 0.0 else 0.0
        e += kn * phi
        cmax = max(cmax, c)
    return e, cmax
