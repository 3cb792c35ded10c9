"""Numba kernels of (dpsimperfect), the DpS equation with site-dependent coefficients (cradle.models.dps_sites).

State y = real view of A (Re A_0, Im A_0, Re A_1, ...). Everything about the chain is in one float64
array ``par`` (:func:`pack`): a header, then the per-site and per-bond coefficients, then the Chebyshev
and 2F1 coefficients of the averaged bond force g(r; delta~) and its potential P (models.dps_sites.contact_tables).
The right-hand side is :class:`cradle.integrators.systems.dps.DpsSites` of the DpS family.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
from numba import njit

from cradle.integrators import _cache

if TYPE_CHECKING:
    from cradle.integrators._types import Floats

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating

#: header of ``par``: [1/(2 tau0), N, Chebyshev length 1, Chebyshev length 2, series length, compressed, PSI_MAX, tau0]
HEADER = 8


# Any: a cradle.models DpsSites; a kernel module's cradle imports (annotations' too) are the kernel cache's key
def pack(sites: Any, tables: dict[str, np.ndarray] | None, tau0: float, psi_max: float) -> np.ndarray:
    """``par`` of (dpsimperfect) from a :class:`cradle.models.dps_sites.DpsSites` and its contact tables (None when no
    bond is compressed)."""
    N = sites.N
    if tables is None:
        tab = [np.zeros(1), np.zeros(1), np.zeros(1), np.zeros(1), np.zeros(1), np.zeros(1)]
    else:
        tab = [tables[k] for k in ("G1", "G2", "Ga", "P1", "P2", "Ph")]
    head = [0.5 / tau0, N, tab[0].size, tab[1].size, tab[2].size, 0.0 if tables is None else 1.0, psi_max, tau0]
    return np.ascontiguousarray(np.concatenate(
        [np.array(head, dtype=float), sites.detuning, sites.inv_mass, sites.weight, sites.beta, sites.delta,
         *[np.asarray(t, dtype=float) for t in tab]]))


@njit(cache=True)
def _clenshaw(c: Floats, o: int, n: int, t: float) -> float:
    """sum_k c[o + k] T_k(t), k < n."""
    b1 = 0.0
    b2 = 0.0
    for k in range(n - 1, 0, -1):
        b0 = 2.0 * t * b1 - b2 + c[o + k]
        b2 = b1
        b1 = b0
    return t * b1 - b2 + c[o]


@njit(cache=True)
def _horner(c: Floats, o: int, n: int, y: float) -> float:
    s = 0.0
    for k in range(n - 1, -1, -1):
        s = s * y + c[o + k]
    return s


@njit(cache=True)
def _offsets(par: Floats) -> tuple[int, int, int, int, int, int, int, int, int, int, int, int, int, int, int]:
    """Offsets in ``par`` of the coefficient blocks: (N, detuning, inv_mass, weight, beta, delta, G1, G2, Ga, P1, P2,
    Ph, n1, n2, ns)."""
    N = int(par[1])
    n1 = int(par[2])
    n2 = int(par[3])
    ns = int(par[4])
    o = HEADER
    od, om, ow, ob, oe = o, o + N, o + 2 * N, o + 3 * N, o + 4 * N
    og1 = o + 5 * N
    og2 = og1 + n1
    oga = og2 + n2
    op1 = oga + ns
    op2 = op1 + n1
    oph = op2 + n2
    return N, od, om, ow, ob, oe, og1, og2, oga, op1, op2, oph, n1, n2, ns


@njit(cache=True)
def _table(rho: float, psi_max: float) -> tuple[int, float]:
    """Where rho = delta~/r falls: (0, -) no contact (rho <= -2); (1, t) the Chebyshev table in phi (rho < 2);
    (2, t) the one in psi (rho < 4); (3, y) the 2F1 series in y = 4/rho^2."""
    if rho <= -2.0:
        return 0, 0.0
    if rho < 2.0:
        return 1, 2.0 * math.acos(0.5 * rho) / math.pi - 1.0
    if rho < 4.0:
        return 2, 2.0 * math.acosh(0.5 * rho) / psi_max - 1.0
    return 3, 4.0 / (rho * rho)


@njit(cache=True)
def _g_over_r(r: float, d: float, alpha: float, par: Floats, og1: int, og2: int, oga: int, n1: int, n2: int,
              ns: int) -> float:
    """g(r; d) / r (so that Phi(z) = z g/r), r >= 0."""
    if d == 0.0:
        if r <= 0.0:
            return 0.0
        if alpha == 1.5:
            return math.sqrt(r)
        return r ** (alpha - 1.0)
    if r <= 0.0:
        if d > 0.0:
            return par[7] * alpha * d ** (alpha - 1.0)
        return 0.0
    where, t = _table(d / r, par[6])
    if where == 0:
        return 0.0
    if where == 1:
        return r ** (alpha - 1.0) * _clenshaw(par, og1, n1, t)
    if where == 2:
        return r ** (alpha - 1.0) * _clenshaw(par, og2, n2, t)
    return par[7] * alpha * d ** (alpha - 1.0) * _horner(par, oga, ns, t)


@njit(cache=True)
def _potential(r: float, d: float, alpha: float, par: Floats, op1: int, op2: int, oph: int, n1: int, n2: int,
               ns: int) -> float:
    """P(r; d) = int_0^r g(s; d) ds."""
    if d == 0.0:
        return r ** (alpha + 1.0) / (alpha + 1.0)
    if r <= 0.0:
        return 0.0
    where, t = _table(d / r, par[6])
    if where == 0:
        return 0.0
    if where == 1:
        return (r ** (alpha + 1.0) * _clenshaw(par, op1, n1, t)
                - par[7] * max(d, 0.0) ** (alpha + 1.0) / (2.0 * (alpha + 1.0)))
    if where == 2:
        return r ** (alpha + 1.0) * _clenshaw(par, op2, n2, t)
    return 2.0 * par[7] * r * r * d ** (alpha - 1.0) * _horner(par, oph, ns, t) / (alpha + 1.0)


@njit(cache=True)
def dps_sites_invariants(y: Floats, alpha: float, par: Floats, periodic: bool) -> tuple[float, float, float, float]:
    """(sum m_n |A_n|^2, H, Re P, Im P) of (dpsimperfect), P = sum m_n A_n."""
    N, od, om, ow, ob, oe, og1, og2, oga, op1, op2, oph, n1, n2, ns = _offsets(par)
    l2 = 0.0
    H = 0.0
    pr = 0.0
    pi = 0.0
    for n in range(N):
        m = 1.0 / par[om + n]
        a2 = y[2 * n] ** 2 + y[2 * n + 1] ** 2
        l2 += m * a2
        H -= m * (par[od + n] * a2 + 0.75 * par[ob + n] * a2 * a2)
        pr += m * y[2 * n]
        pi += m * y[2 * n + 1]
    nb = N if periodic else N - 1
    bonds = 0.0
    for n in range(nb):
        k = n + 1 if n + 1 < N else 0
        r = math.hypot(y[2 * k] - y[2 * n], y[2 * k + 1] - y[2 * n + 1])
        bonds += par[ow + n] * _potential(r, par[oe + n], alpha, par, op1, op2, oph, n1, n2, ns)
    H -= bonds * 2.0 * par[0]
    return l2, H, pr, pi
