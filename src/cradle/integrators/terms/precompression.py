"""Precompression: a static overlap delta_n > 0 of every contact (or a gap, delta_n < 0).

Parameters: :class:`cradle.models.precompression.Precompression` (delta_0), with delta_n = delta_0
k_n^(-1/alpha) (:func:`cradle.models.lattice_terms.static_overlaps`). Force: Hertz's law on the total overlap,
F_n(d) = -(delta_n - d)_+^alpha + (delta_n)_+^alpha (F_n(0) = 0). Energy: Phi_n(d) =
((delta_n - d)_+^(alpha+1) - (delta_n)_+^(alpha+1))/(alpha+1) + (delta_n)_+^alpha d. DpS counterpart: the
averaged force g(r; delta~_n), delta~_n = delta_n / eps, tabulated in :mod:`cradle.models.dps_sites` and
evaluated by :func:`cradle.integrators._kernels_dps_sites._g_over_r` (the bond of
:class:`cradle.integrators.systems.dps.DpsSites`).

Near rest a precompressed bond's force is a difference of nearly equal numbers; it is evaluated without
cancellation: d (delta^2 + delta c + c^2) / (delta^(3/2) + c^(3/2)) for alpha = 3/2 (c = delta - d), and
-delta^alpha expm1(alpha log1p(-d/delta)) otherwise (the linear dispersion is measured at d << delta_0).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
from numba import njit

from cradle.integrators import _cache
from cradle.integrators._generic import implements
from cradle.integrators._kernels_dps_sites import _g_over_r
from cradle.integrators.terms.slots import dps_coupling, elastic, overlap, potential, rest

if TYPE_CHECKING:
    from cradle.integrators._types import Floats

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating


class Precompressed(NamedTuple):
    """delta_n of every bond and (delta_n)_+^alpha."""

    delta: np.ndarray
    dpa: np.ndarray


def build(delta: Floats, alpha: float) -> Precompressed:
    delta = np.ascontiguousarray(delta, dtype=float)
    return Precompressed(delta, np.maximum(delta, 0.0) ** alpha)


@implements(overlap, Precompressed)
@njit(cache=True)
def _overlap(contact: Precompressed, n: int, d: float) -> float:
    return contact.delta[n] - d


@implements(elastic, Precompressed)
@njit(cache=True)
def _elastic(contact: Precompressed, n: int, d: float, c: float, el: float, alpha: float, mode: int) -> float:
    dn = contact.delta[n]
    if dn > 0.0 and mode == 0:
        # delta^(3/2) - c^(3/2) = (delta^3 - c^3)/(delta^(3/2) + c^(3/2)), delta - c = d: no cancellation
        return d * (dn * dn + dn * c + c * c) / (contact.dpa[n] + el)
    if dn > 0.0:
        return -contact.dpa[n] * math.expm1(alpha * math.log1p(-d / dn))   # dpa - el, without cancellation
    return -el


@implements(rest, Precompressed)
@njit(cache=True)
def _rest(contact: Precompressed, n: int) -> float:
    return contact.dpa[n]


@implements(potential, Precompressed)
@njit(cache=True)
def _potential(contact: Precompressed, n: int, d: float, c: float, a1: float) -> float:
    dn = contact.delta[n]
    if dn > 0.0:
        dpa = contact.dpa[n]
        if c > 0.0:
            # delta^(alpha+1)/(alpha+1) ((1 - r)^(alpha+1) - 1 + (alpha+1) r), r = d/delta
            r = d / dn
            return dpa * dn / a1 * (math.expm1(a1 * math.log1p(-r)) + a1 * r)
        return dpa * (d - dn / a1)
    return c ** a1 / a1 if c > 0.0 else 0.0


class Tabulated(NamedTuple):
    """The DpS counterpart: g(r; delta~_n)/r from the tables of :mod:`cradle.models.dps_sites` packed in ``par``
    (:func:`cradle.integrators._kernels_dps_sites.pack`) at the offsets of its blocks."""

    par: np.ndarray
    oe: int
    og1: int
    og2: int
    oga: int
    n1: int
    n2: int
    ns: int


def tabulated(par: Floats) -> Tabulated:
    """The :class:`Tabulated` of a packed ``par``."""
    from cradle.integrators._kernels_dps_sites import _offsets

    _N, _od, _om, _ow, _ob, oe, og1, og2, oga, _op1, _op2, _oph, n1, n2, ns = _offsets(par)
    return Tabulated(par, oe, og1, og2, oga, n1, n2, ns)


@implements(dps_coupling, Tabulated)
@njit(cache=True)
def _dps_coupling(coupling: Tabulated, r: float, n: int, alpha: float) -> float:
    par = coupling.par
    return _g_over_r(r, par[coupling.oe + n], alpha, par, coupling.og1, coupling.og2, coupling.oga, coupling.n1,
                     coupling.n2, coupling.ns)
