"""Kuwabara-Kono viscoelastic contact damping: a bond in contact pushes with k_n max(c^alpha + eta c^(alpha-1) c', 0).

Parameters: :class:`cradle.models.damping.Damping` ``contact`` = eta. Force: on a bond with overlap c > 0 and
rate c', k_n [(delta_n)_+^alpha - max(c^alpha + eta c^(alpha-1) c', 0)] (clipped: a contact never pulls).
Dissipation: P = sum k_n (max(c^alpha + eta c^(alpha-1) c', 0) - c^alpha) c' (eta k_n c^(alpha-1) c'^2 unclipped,
-k_n c^alpha c' clipped). DpS counterpart: the complex factor kappa(eta, alpha) = 1 + i eta/alpha + ... on the
p-Laplacian of (dpsdamped) (:func:`cradle.models.dps_damped.contact_factor`; the site law of
:class:`cradle.integrators.systems.dps.DpsDamped`).

:func:`damped_bond` is the same force on the paper's touching bond (k = 1, delta = 0), the bond law of the
damped (nc) kernel :func:`cradle.integrators._kernels.lattice_damped_rhs`.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, NamedTuple

from numba import njit

from cradle.integrators import _cache
from cradle.integrators._generic import absent, implements
from cradle.integrators.terms.slots import damp_bond, dps_kappa, dps_l2_loss, dps_S_loss, rest, stiff

if TYPE_CHECKING:
    from cradle.integrators._types import Floats

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating


class NoContactDamping(NamedTuple):
    """eta = 0: no arithmetic."""


class ContactDamping(NamedTuple):
    """eta > 0."""

    eta: float


@njit(cache=True)
def damped_bond(c: float, rate: float, alpha: float, eta: float, mode: int) -> tuple[float, float]:
    """(force magnitude max(c^alpha + eta c^(alpha-1) c', 0), elastic part c^alpha) of a compressed touching bond
    c > 0 of (ncdamped), c' = ``rate`` (Hertz modes only: mode 0 is the c sqrt(c) fast path)."""
    if mode == 0:
        s = math.sqrt(c)
        el = c * s
    else:
        s = c ** (alpha - 1.0)
        el = c * s
    return max(el + eta * s * rate, 0.0), el


@implements(damp_bond, NoContactDamping)
@njit(cache=True)
def _none(damping: NoContactDamping, sites: NamedTuple, contact: NamedTuple, n: int, m: int, diff: float, el: float,
          sa: float, y: Floats, J: Floats, N: int, P: float) -> tuple[float, float]:
    return stiff(sites, n, diff), P


@implements(damp_bond, ContactDamping)
@njit(cache=True)
def _damp(damping: ContactDamping, sites: NamedTuple, contact: NamedTuple, n: int, m: int, diff: float, el: float,
          sa: float, y: Floats, J: Floats, N: int, P: float) -> tuple[float, float]:
    eta = damping.eta
    rate = J[n] * y[N + n] - J[m] * y[N + m]   # c' = -(u'_{n+1} - u'_n)
    push = el + eta * sa * rate
    if push < 0.0:   # the contact would pull: no force
        return stiff(sites, n, rest(contact, n)), P - stiff(sites, n, el) * rate
    return stiff(sites, n, diff - eta * sa * rate), P + stiff(sites, n, eta) * sa * rate * rate


class SlowContactDamping(NamedTuple):
    """The DpS counterpart: kappa = kr + i ki (:func:`cradle.models.dps_damped.contact_factor`)."""

    kr: float
    ki: float


@implements(dps_kappa, SlowContactDamping)
@njit(cache=True)
def _dps_kappa(damping: SlowContactDamping, wr: float, wi: float) -> tuple[float, float]:
    # kappa w = (kr wr - ki wi) + i (kr wi + ki wr)
    return damping.kr * wr - damping.ki * wi, damping.kr * wi + damping.ki * wr


@implements(dps_l2_loss, SlowContactDamping)
@njit(cache=True)
def _l2_loss(damping: SlowContactDamping, l2: float, S: float, inv2tau0: float) -> float:
    return 2.0 * damping.ki * inv2tau0 * S   # (Im kappa / tau0) S


@implements(dps_S_loss, SlowContactDamping)
@njit(cache=True)
def _S_loss(damping: SlowContactDamping, L2: float, S: float, inv2tau0: float) -> float:
    return damping.ki * inv2tau0 * L2        # (Im kappa / (2 tau0)) sum |W_n - W_{n-1}|^2


absent(dps_kappa, NoContactDamping, "wr", "wi")
absent(dps_l2_loss, NoContactDamping, "0.0")
absent(dps_S_loss, NoContactDamping, "0.0")
