"""Inhomogeneity: bead masses m_n, on-site frequencies omega_n and contact stiffnesses k_n.

Parameters: :class:`cradle.models.inhomogeneity.Inhomogeneity`, drawn into :class:`cradle.models.inhomogeneity.Sites`
(:func:`build`). Force: the bond forces weighted by k_n, the net force on bead n divided by m_n, the on-site
force scaled by omega_n^2. Energy: m_n v_n^2/2 + m_n omega_n^2 W(x_n) + k_n Phi_n. DpS counterpart: the
detuning delta_n = (omega_n - 1) eps^(1-alpha), the factor 1/m_n on the coupling and the weight k_n of bond n
(:func:`cradle.models.dps_sites.dps_sites`; the site law and bond of :class:`cradle.integrators.systems.dps.DpsSites`).
"""
from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np
from numba import njit

from cradle.integrators import _cache
from cradle.integrators._generic import absent, implements
from cradle.integrators.terms.slots import (
    dps_detuning,
    dps_factor,
    dps_rotate_detuned,
    dps_weight,
    mass_omega2,
    mass_times,
    onsite_scale,
    per_mass,
    stiff,
)

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating


class Homogeneous(NamedTuple):
    """Every coefficient 1 (the paper's cradle): no arithmetic."""


class Inhomogeneous(NamedTuple):
    """The site coefficients: m_n, 1/m_n, omega_n^2, k_n (arrays of N)."""

    mass: np.ndarray
    inv_mass: np.ndarray
    omega2: np.ndarray
    stiffness: np.ndarray


# Any: a cradle.models Sites; a kernel module's cradle imports (annotations' too) are the kernel cache's key
def build(sites: Any) -> Inhomogeneous:
    """The unit of a :class:`cradle.models.inhomogeneity.Sites`."""
    mass = np.ascontiguousarray(sites.mass, dtype=float)
    return Inhomogeneous(mass, 1.0 / mass, np.asarray(sites.omega, dtype=float) ** 2,
                         np.ascontiguousarray(sites.stiffness, dtype=float))


@implements(stiff, Inhomogeneous)
@njit(cache=True)
def _stiff(sites: Inhomogeneous, n: int, X: float) -> float:
    return sites.stiffness[n] * X


@implements(per_mass, Inhomogeneous)
@njit(cache=True)
def _per_mass(sites: Inhomogeneous, n: int, X: float) -> float:
    return X * sites.inv_mass[n]


@implements(onsite_scale, Inhomogeneous)
@njit(cache=True)
def _onsite_scale(sites: Inhomogeneous, n: int, X: float) -> float:
    return sites.omega2[n] * X


@implements(mass_times, Inhomogeneous)
@njit(cache=True)
def _mass_times(sites: Inhomogeneous, n: int, X: float) -> float:
    return X * sites.mass[n]


@implements(mass_omega2, Inhomogeneous)
@njit(cache=True)
def _mass_omega2(sites: Inhomogeneous, n: int, X: float) -> float:
    return (sites.mass[n] * sites.omega2[n]) * X


class SlowSites(NamedTuple):
    """The DpS counterpart (:class:`cradle.models.dps_sites.DpsSites`): 1/m_n, k_n of bond n, detuning delta_n."""

    inv_mass: np.ndarray
    weight: np.ndarray
    detuning: np.ndarray


# Any: a cradle.models DpsSites; a kernel module's cradle imports (annotations' too) are the kernel cache's key
def slow_sites(sites: Any) -> SlowSites | Homogeneous:
    """The unit of a :class:`cradle.models.dps_sites.DpsSites` (:class:`Homogeneous` if every coefficient is 1 and
    no site is detuned)."""
    if np.all(sites.inv_mass == 1.0) and np.all(sites.weight == 1.0) and np.all(sites.detuning == 0.0):
        return Homogeneous()
    return SlowSites(np.ascontiguousarray(sites.inv_mass), np.ascontiguousarray(sites.weight),
                     np.ascontiguousarray(sites.detuning))


@implements(dps_weight, SlowSites)
@njit(cache=True)
def _dps_weight(sites: SlowSites, n: int, s: float) -> float:
    return sites.weight[n] * s


@implements(dps_factor, SlowSites)
@njit(cache=True)
def _dps_factor(sites: SlowSites, n: int, inv2tau0: float) -> float:
    return sites.inv_mass[n] * inv2tau0


@implements(dps_detuning, SlowSites)
@njit(cache=True)
def _dps_detuning(sites: SlowSites, n: int, X: float) -> float:
    return sites.detuning[n] + X


@implements(dps_rotate_detuned, SlowSites)
@njit(cache=True)
def _dps_rotate(sites: SlowSites, n: int, a: float, b: float, ar: float, ai: float) -> tuple[float, float]:
    rot = sites.detuning[n]
    # i rot (ar + i ai) = -rot ai + i rot ar
    return a - rot * ai, b + rot * ar


for _operation in (stiff, per_mass, onsite_scale, mass_times, mass_omega2, dps_detuning):
    absent(_operation, Homogeneous, "X")
absent(dps_weight, Homogeneous, "s")
absent(dps_factor, Homogeneous, "inv2tau0")
absent(dps_rotate_detuned, Homogeneous, "a", "b")
