"""The quartic on-site potential W(x) = x^2/2 + beta x^4/4 (hard for beta > 0, soft for beta < 0).

Parameters: :class:`cradle.models.onsite.OnSite` with ``potential: quartic`` and ``beta``. Force: W'(x) = x +
beta x^3. Energy: W(x). DpS counterpart: the rotation (3/2) beta~_n |A_n|^2 A_n of (dpsimperfect), beta~_n =
omega_n^2 beta eps^(3-alpha) (:func:`cradle.models.dps_sites.dps_sites`; the site law of
:class:`cradle.integrators.systems.dps.DpsSites`): the first harmonic of beta x^3 along x = 2 eps |A| cos t.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from cradle.integrators import _cache
from cradle.integrators._generic import implements
from cradle.integrators.terms.slots import dps_detuning, dps_rotate, onsite_energy, onsite_force, position

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating


class Quartic(NamedTuple):
    """W = x^2/2 + beta x^4/4."""

    beta: float


@implements(position, Quartic)
@njit(cache=True)
def _position(onsite: Quartic, n: int, x: float) -> tuple[float, float]:
    return x, 1.0


@implements(onsite_force, Quartic)
@njit(cache=True)
def _force(onsite: Quartic, x: float, u: float) -> float:
    return x + onsite.beta * x * x * x


@implements(onsite_energy, Quartic)
@njit(cache=True)
def _energy(onsite: Quartic, n: int, x: float) -> float:
    return 0.5 * x * x + 0.25 * onsite.beta * x ** 4


class SlowQuartic(NamedTuple):
    """The DpS counterpart: beta~_n of every site (:class:`cradle.models.dps_sites.DpsSites` ``beta``; a pendulum's
    beta_n = -s_n^2/6)."""

    beta: np.ndarray


@implements(dps_rotate, SlowQuartic)
@njit(cache=True)
def _dps_rotate(onsite: SlowQuartic, sites: NamedTuple, n: int, a: float, b: float, ar: float,
                ai: float) -> tuple[float, float]:
    rot = dps_detuning(sites, n, 1.5 * onsite.beta[n] * (ar * ar + ai * ai))
    # i rot (ar + i ai) = -rot ai + i rot ar
    return a - rot * ai, b + rot * ar
