"""The harmonic on-site potential W(x) = x^2/2 of the paper's (nc).

Parameters: :class:`cradle.models.onsite.OnSite` with ``potential: harmonic`` (or a quartic with beta = 0, a
pendulum with scale = 0). Force: W'(x) = x. Energy: x^2/2. DpS counterpart: none beyond the carrier e^{it}
of (ansatz) itself (the frequency 1 of every bead).
"""
from __future__ import annotations

from typing import NamedTuple

from numba import njit

from cradle.integrators import _cache
from cradle.integrators._generic import implements
from cradle.integrators.terms.slots import dps_rotate, dps_rotate_detuned, onsite_energy, onsite_force, position

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating


class Harmonic(NamedTuple):
    """W = x^2/2."""


@implements(position, Harmonic)
@njit(cache=True)
def _position(onsite: Harmonic, n: int, x: float) -> tuple[float, float]:
    return x, 1.0


@implements(onsite_force, Harmonic)
@njit(cache=True)
def _force(onsite: Harmonic, x: float, u: float) -> float:
    return x


@implements(onsite_energy, Harmonic)
@njit(cache=True)
def _energy(onsite: Harmonic, n: int, x: float) -> float:
    return 0.5 * x * x


@implements(dps_rotate, Harmonic)
@njit(cache=True)
def _dps_rotate(onsite: Harmonic, sites: NamedTuple, n: int, a: float, b: float, ar: float,
                ai: float) -> tuple[float, float]:
    return dps_rotate_detuned(sites, n, a, b, ar, ai)
