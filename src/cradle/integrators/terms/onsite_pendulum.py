"""The pendulum: bead n hangs on a string of length l_n, x its arc length, u = sin(s_n x)/s_n its horizontal position.

Parameters: :class:`cradle.models.onsite.OnSite` with ``potential: pendulum`` and ``scale`` = X / l_0; s_n = scale
omega_n^2 (:func:`cradle.models.lattice_terms.pendulum_scales`). Force: W'(x) = sin(s_n x)/s_n = u, and the
contacts act on u (times J = du/dx = cos(s_n x) on bead n). Energy: W(x) = (1 - cos(s_n x))/s_n^2, written
2 sin^2(s_n x / 2)/s_n^2 (no cancellation). DpS counterpart: the quartic of :mod:`.onsite_quartic` with beta_n =
-s_n^2/6 at this order (:func:`cradle.models.dps_sites.dps_sites`).
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from cradle.integrators import _cache
from cradle.integrators._generic import implements
from cradle.integrators.terms.slots import onsite_energy, onsite_force, position

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating


class Pendulum(NamedTuple):
    """s_n of every bead."""

    s: np.ndarray


@implements(position, Pendulum)
@njit(cache=True)
def _position(onsite: Pendulum, n: int, x: float) -> tuple[float, float]:
    sn = onsite.s[n]
    sx = sn * x
    return math.sin(sx) / sn, math.cos(sx)


@implements(onsite_force, Pendulum)
@njit(cache=True)
def _force(onsite: Pendulum, x: float, u: float) -> float:
    return u


@implements(onsite_energy, Pendulum)
@njit(cache=True)
def _energy(onsite: Pendulum, n: int, x: float) -> float:
    sn = onsite.s[n]
    h = math.sin(0.5 * sn * x) / sn
    return 2.0 * h * h
