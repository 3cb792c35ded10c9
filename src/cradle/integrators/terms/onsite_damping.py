"""Linear on-site damping: a force -gamma m_n v_n on every bead of (ncdamped).

Parameters: :class:`cradle.models.damping.Damping` ``onsite`` = gamma. Force: -gamma v_n per unit mass.
Dissipation: P = gamma sum m_n v_n^2. DpS counterpart: the decay -(gamma~/2) A_n of (dpsdamped), gamma~ = gamma
eps^(1-alpha) (:func:`cradle.models.dps_damped.slow_damping`; the site law of
:class:`cradle.integrators.systems.dps.DpsDamped`).
"""
from __future__ import annotations

from typing import NamedTuple

from numba import njit

from cradle.integrators import _cache
from cradle.integrators._generic import absent, implements
from cradle.integrators.terms.slots import damp_site, dps_decay, dps_l2_loss, dps_S_loss, mass_times

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating


class NoOnsiteDamping(NamedTuple):
    """gamma = 0: no arithmetic."""


class OnsiteDamping(NamedTuple):
    """gamma > 0."""

    gamma: float


@implements(damp_site, OnsiteDamping)
@njit(cache=True)
def _damp(damping: OnsiteDamping, sites: NamedTuple, n: int, acc: float, v: float, P: float) -> tuple[float, float]:
    return acc - damping.gamma * v, P + mass_times(sites, n, damping.gamma) * v * v


class SlowOnsiteDamping(NamedTuple):
    """The DpS counterpart: gamma~/2."""

    half_gamma: float


@implements(dps_decay, SlowOnsiteDamping)
@njit(cache=True)
def _dps_decay(damping: SlowOnsiteDamping, a: float, b: float, ar: float, ai: float) -> tuple[float, float]:
    return a - damping.half_gamma * ar, b - damping.half_gamma * ai


@implements(dps_l2_loss, SlowOnsiteDamping)
@njit(cache=True)
def _l2_loss(damping: SlowOnsiteDamping, l2: float, S: float, inv2tau0: float) -> float:
    return 2.0 * damping.half_gamma * l2     # gamma~ sum |A_n|^2


@implements(dps_S_loss, SlowOnsiteDamping)
@njit(cache=True)
def _S_loss(damping: SlowOnsiteDamping, L2: float, S: float, inv2tau0: float) -> float:
    return damping.half_gamma * S            # (gamma~/2) S


absent(damp_site, NoOnsiteDamping, "acc", "P")
absent(dps_decay, NoOnsiteDamping, "a", "b")
absent(dps_l2_loss, NoOnsiteDamping, "0.0")
absent(dps_S_loss, NoOnsiteDamping, "0.0")
