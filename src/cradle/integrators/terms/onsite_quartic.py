"""The quartic on-site potential W(x) = x^2/2 + beta x^4/4 (hard for beta > 0, soft for beta < 0).

Parameters: :class:`cradle.models.onsite.OnSite` with ``potential: quartic`` and ``beta``. Force: W'(x) = x +
beta x^3. Energy: W(x). DpS counterpart: the rotation (3/2) beta~_n |A_n|^2 A_n of (dpsimperfect), beta~_n =
omega_n^2 beta eps^(3-alpha) (:func:`cradle.models.dps_sites.dps_sites`; the site law of
:class:`cradle.integrators.systems.dps.DpsSites`): the first harmonic of beta x^3 along x = 2 eps |A| cos t.
"""
from __future__ import annotations

from typing import NamedTuple

from numba import njit

from cradle.integrators import _cache
from cradle.integrators._generic import implements
from cradle.integrators.terms.slots import onsite_energy, onsite_force, position

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating


class Quartic(NamedTuple):
    """W = x^2/2 + beta x^4/4."""

    beta: float


@implements(position, Quartic)
@njit(cache=True)
def _position(onsite, n, x):
    return x, 1.0


@implements(onsite_force, Quartic)
@njit(cache=True)
def _force(onsite, x, u):
    return x + onsite.beta * x * x * x


@implements(onsite_energy, Quartic)
@njit(cache=True)
def _energy(onsite, n, x):
    return 0.5 * x * x + 0.25 * onsite.beta * x ** 4
