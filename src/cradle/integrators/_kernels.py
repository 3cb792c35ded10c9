"""Numba kernels of the lattice (nc)/(meca) and of the damped (ncdamped): contact forces, right-hand sides, energy.

Every kernel is ``@njit(cache=True)`` and is called with one fixed set of
argument types (float64 arrays, float alpha, int64 flags), so each compiles
once and is then loaded from the on-disk cache.

Contact-law flag ``mode`` (see :func:`mode_flag`):

* 0 - Hertz V0 (vhertz), alpha == 1.5 : f = -c sqrt(c), c = max(-d, 0)
* 1 - Hertz V0 (vhertz), any alpha     : f = -c**alpha
* 2 - smooth U of (meca), alpha == 1.5 : f = d sqrt(|d|)
* 3 - smooth U of (meca), any alpha    : f = d |d|**(alpha-1)

with d = x_{n+1} - x_n the elongation of bond n. In all four cases the bond
potential is V(d) = d f(d) / (alpha + 1) (V0(d) = c^(alpha+1)/(alpha+1) with
d f = c^(alpha+1); U(d) = |d|^(alpha+1)/(alpha+1) with d f = |d|^(alpha+1)),
so the potential energy of (ham) comes for free with every force evaluation.
The "compression" monitored for the stiffness is c = max(-d, 0) for Hertz and
|d| for the smooth law (whose stiffness U'' = alpha |d|^(alpha-1) is even).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from numba import njit

from cradle.integrators import _cache
from cradle.integrators.terms.contact_damping import damped_bond

if TYPE_CHECKING:
    from cradle.integrators._types import Floats

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating

HERTZ_15, HERTZ, SMOOTH_15, SMOOTH = 0, 1, 2, 3


def mode_flag(potential: str, alpha: float) -> int:
    """Integer contact-law flag used by the kernels (fast path when alpha == 1.5)."""
    fast = alpha == 1.5
    if potential == "hertz":
        return HERTZ_15 if fast else HERTZ
    return SMOOTH_15 if fast else SMOOTH


@njit(cache=True)
def _bond(d: float, alpha: float, mode: int) -> tuple[float, float]:
    """(f, c): bond force f = V'(d) and the compression c monitored for stiffness."""
    if mode == 0:
        c = max(-d, 0.0)
        return -c * math.sqrt(c), c
    elif mode == 1:
        c = max(-d, 0.0)
        return -(c**alpha), c
    elif mode == 2:
        c = abs(d)
        return d * math.sqrt(c), c
    else:
        c = abs(d)
        return d * c ** (alpha - 1.0), c


@njit(cache=True)
def forces(x: Floats, f: Floats, F: Floats, alpha: float, mode: int, periodic: bool) -> tuple[float, float]:
    """Contact forces of (nc)/(meca) at positions x.

    Fills ``f[n]`` (force on bond n, 0 on the missing bond N-1 with free ends)
    and ``F[n] = f[n] - f[n-1]`` (net contact force on bead n). Returns
    ``(pot, cmax)``: the contact part sum_n V(x_{n+1}-x_n) of (ham) and the
    largest bond compression.
    """
    N = x.shape[0]
    pot = 0.0
    cmax = 0.0
    for n in range(N - 1):
        d = x[n + 1] - x[n]
        fn, c = _bond(d, alpha, mode)
        f[n] = fn
        pot += d * fn
        cmax = max(cmax, c)
    if periodic:
        d = x[0] - x[N - 1]
        fn, c = _bond(d, alpha, mode)
        f[N - 1] = fn
        pot += d * fn
        cmax = max(cmax, c)
    else:
        f[N - 1] = 0.0
    F[0] = f[0] - f[N - 1]
    for n in range(1, N):
        F[n] = f[n] - f[n - 1]
    return pot / (alpha + 1.0), cmax


@njit(cache=True)
def forces_only(x: Floats, f: Floats, F: Floats, alpha: float, mode: int, periodic: bool) -> None:
    """Same as :func:`forces` without the energy/compression reductions.

    Without the two reductions the loops vectorise (about 3x faster); used for
    the inner stages of a splitting step.
    """
    N = x.shape[0]
    for n in range(N - 1):
        f[n] = _bond(x[n + 1] - x[n], alpha, mode)[0]
    if periodic:
        f[N - 1] = _bond(x[0] - x[N - 1], alpha, mode)[0]
    else:
        f[N - 1] = 0.0
    F[0] = f[0] - f[N - 1]
    for n in range(1, N):
        F[n] = f[n] - f[n - 1]


@njit(cache=True)
def lattice_energy(x: Floats, v: Floats, alpha: float, mode: int, periodic: bool) -> tuple[float, float]:
    """Hamiltonian (ham) of one state, and its largest bond compression."""
    N = x.shape[0]
    f = np.empty(N)
    F = np.empty(N)
    pot, cmax = forces(x, f, F, alpha, mode, periodic)
    e = 0.0
    for n in range(N):
        e += v[n] * v[n] + x[n] * x[n]
    return 0.5 * e + pot, cmax


@njit(cache=True, inline="always")
def kick_rotate(x: Floats, v: Floats, F: Floats, b: float, c: float, s: float) -> None:
    """One stage of an RKN splitting: kick v += b F, then the exact harmonic flow of the on-site
    part over the stage, (x, v) rotated with c = cos(a h) - 1, s = sin(a h) (inlined: hot loop)."""
    for n in range(x.shape[0]):
        vn = v[n] + b * F[n]
        xn = x[n]
        x[n] = xn + (xn * c + vn * s)
        v[n] = vn + (vn * c - xn * s)


@njit(cache=True, inline="always")
def last_kick(x: Floats, v: Floats, F: Floats, b: float) -> float:
    """The closing kick v += b F of a step; returns sum(v^2 + x^2), twice the harmonic energy."""
    e = 0.0
    for n in range(x.shape[0]):
        vn = v[n] + b * F[n]
        v[n] = vn
        e += vn * vn + x[n] * x[n]
    return e


@njit(cache=True)
def lattice_rhs(y: Floats, dy: Floats, f: Floats, F: Floats, alpha: float, mode: int, periodic: bool) -> None:
    """First-order form of (nc)/(meca), y = [x, v]: dy = [v, -x + F(x)]."""
    N = f.shape[0]
    x = y[:N]
    forces(x, f, F, alpha, mode, periodic)
    for n in range(N):
        dy[n] = y[N + n]
        dy[N + n] = F[n] - y[n]


@njit(cache=True)
def lattice_damped_rhs(y: Floats, dy: Floats, f: Floats, F: Floats, alpha: float, mode: int, gamma: float, eta: float,
                       dscale: float, periodic: bool) -> None:
    """First-order form of (ncdamped) with its dissipated energy, y = [x, v, s D] (length 2N + 1):
    dy = [v, -x - gamma v + g_n - g_{n-1}, s P], g_n = -max(c^alpha + eta c^(alpha-1) c', 0) on a
    compressed bond (c = -(x_{n+1} - x_n) > 0, c' = -(v_{n+1} - v_n)), P the dissipated power of
    :mod:`cradle.models.damping` (Hertz modes 0 and 1 only), s = ``dscale`` the scale of D in the
    state (the error control's weight of D). ``f``, ``F``: work arrays of length N."""
    N = f.shape[0]
    P = 0.0
    nb = N if periodic else N - 1
    for n in range(nb):
        m = n + 1 if n + 1 < N else 0
        c = y[n] - y[m]
        if c > 0.0:
            rate = y[N + n] - y[N + m]
            g, el = damped_bond(c, rate, alpha, eta, mode)
            f[n] = -g
            P += (g - el) * rate
        else:
            f[n] = 0.0
    if not periodic:
        f[N - 1] = 0.0
    F[0] = f[0] - f[N - 1]
    for n in range(1, N):
        F[n] = f[n] - f[n - 1]
    for n in range(N):
        vn = y[N + n]
        dy[n] = vn
        dy[N + n] = F[n] - y[n] - gamma * vn
        P += gamma * vn * vn
    dy[2 * N] = dscale * P


@njit(cache=True)
def lattice_jac(y: Floats, J: Floats, alpha: float, mode: int, periodic: bool) -> None:
    """Dense Jacobian of :func:`lattice_rhs` (for the implicit scipy methods).

    With k_n = dV'/dd on bond n (Hertz: alpha c^(alpha-1); smooth:
    alpha |d|^(alpha-1)), dF_n/dx_{n+1} = k_n, dF_n/dx_{n-1} = k_{n-1},
    dF_n/dx_n = -k_n - k_{n-1}.
    """
    N = y.shape[0] // 2
    J[:, :] = 0.0
    nb = N if periodic else N - 1
    for n in range(N):
        J[n, N + n] = 1.0
        J[N + n, n] = -1.0
    for n in range(nb):
        m = n + 1 if n + 1 < N else 0
        d = y[m] - y[n]
        if mode == 0 or mode == 1:
            c = max(-d, 0.0)
        else:
            c = abs(d)
        kn = alpha * c ** (alpha - 1.0) if c > 0.0 else 0.0
        # bond n: F_n += f_n, F_m -= f_n, df_n/dx_m = kn, df_n/dx_n = -kn
        J[N + n, m] += kn
        J[N + n, n] -= kn
        J[N + m, m] -= kn
        J[N + m, n] += kn
