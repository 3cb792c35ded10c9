"""Hertz's contact (vhertz) between touching beads: the contact law of (nc) in the imperfect cradle.

Parameters: the exponent alpha (and the fast path ``mode`` 0 for alpha = 3/2,
:func:`cradle.integrators._kernels.mode_flag`).
Force: F(d) = -c^alpha on a bond with overlap c = -d > 0, 0 apart. Energy: Phi(d) = c^(alpha+1)/(alpha+1).
DpS counterpart: averaged over the fast phase, the p-Laplacian coupling g(z) = z |z|^(alpha-1) of (dfnls)
(:class:`PLaplacian`, :func:`g_over_r`).

The paper's (nc) itself is integrated by the tuned kernels of :mod:`cradle.integrators._kernels` (which keep their
own arithmetic: energy from d f); this unit is the contact law of (ncimperfect) without precompression.
"""
from __future__ import annotations

import math
from typing import NamedTuple

from numba import njit

from cradle.integrators import _cache
from cradle.integrators._generic import implements
from cradle.integrators.terms.slots import dps_coupling, elastic, overlap, potential, rest

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating


class Touching(NamedTuple):
    """The beads touch at rest (no precompression, no gap)."""


@njit(cache=True, inline="always")
def hertz(c: float, alpha: float, mode: int) -> tuple[float, float]:
    """(c^alpha, c^(alpha-1)) of an overlap c > 0 (mode 0: the alpha = 3/2 fast path)."""
    if mode == 0:
        r = math.sqrt(c)
        return c * r, r
    r = c ** (alpha - 1.0)
    return c * r, r


@njit(cache=True)
def g_over_r(r: float, alpha: float) -> float:
    """g(r)/r = r^(alpha-1) for r >= 0 (sqrt fast path for alpha = 3/2; 0 at r = 0): the DpS counterpart."""
    if r <= 0.0:
        return 0.0
    if alpha == 1.5:
        return math.sqrt(r)
    return r ** (alpha - 1.0)


@implements(overlap, Touching)
@njit(cache=True)
def _overlap(contact: Touching, n: int, d: float) -> float:
    return 0.0 - d   # not -d: the overlap of a bond at rest is +0, as with a zero delta_n


@implements(elastic, Touching)
@njit(cache=True)
def _elastic(contact: Touching, n: int, d: float, c: float, el: float, alpha: float, mode: int) -> float:
    return -el


@implements(rest, Touching)
@njit(cache=True)
def _rest(contact: Touching, n: int) -> float:
    return 0.0


@implements(potential, Touching)
@njit(cache=True)
def _potential(contact: Touching, n: int, d: float, c: float, a1: float) -> float:
    return c ** a1 / a1 if c > 0.0 else 0.0


class PLaplacian(NamedTuple):
    """The DpS counterpart of the touching Hertz contact: W_n = g(A_{n+1} - A_n), the p-Laplacian of (dfnls)."""


@implements(dps_coupling, PLaplacian)
@njit(cache=True)
def _dps_coupling(coupling: PLaplacian, r: float, n: int, alpha: float) -> float:
    return g_over_r(r, alpha)
