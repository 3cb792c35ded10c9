"""The lattice (nc)/(meca) and the damped lattice (ncdamped) as systems of the compiled DOP853.

State y = [x, v] for (nc)/(meca) and y = [x, v, s D] for (ncdamped) (D the dissipated energy, s its scale in
the state); the right-hand sides and energies are those of :mod:`cradle.integrators._kernels`.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np
from numba import njit

from cradle.integrators import _cache, _kernels as K
from cradle.integrators._dop853 import monitor, rhs
from cradle.integrators._generic import implements

if TYPE_CHECKING:
    from cradle.integrators._types import Floats

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating


class Lattice(NamedTuple):
    """(nc)/(meca) on y = [x, v]; ``mode`` the contact law (:func:`cradle.integrators._kernels.mode_flag`),
    ``f``, ``F`` work arrays of length N. Monitored: stats = [H0, max |H-H0|/|H0|, max compression, H]."""

    alpha: float
    mode: int
    periodic: bool
    f: np.ndarray
    F: np.ndarray


class DampedLattice(NamedTuple):
    """(ncdamped) on y = [x, v, s D] with on-site damping gamma and contact damping eta (Hertz laws only).
    Monitored: stats = [H0, max |H+D-H0|/|H0|, max compression, H, s]: H + D is conserved by (ncdamped), its
    drift is the integrator's error."""

    alpha: float
    mode: int
    periodic: bool
    gamma: float
    eta: float
    dscale: float
    f: np.ndarray
    F: np.ndarray


def lattice(N: int, alpha: float, mode: int, periodic: bool) -> Lattice:
    return Lattice(float(alpha), int(mode), bool(periodic), np.empty(N), np.empty(N))


def damped_lattice(N: int, alpha: float, mode: int, periodic: bool, gamma: float, eta: float,
                   dscale: float) -> DampedLattice:
    return DampedLattice(float(alpha), int(mode), bool(periodic), float(gamma), float(eta), float(dscale),
                         np.empty(N), np.empty(N))


@implements(rhs, Lattice)
@njit(cache=True)
def _rhs(system: Lattice, y: Floats, dy: Floats) -> None:
    K.lattice_rhs(y, dy, system.f, system.F, system.alpha, system.mode, system.periodic)


@implements(rhs, DampedLattice)
@njit(cache=True)
def _damped_rhs(system: DampedLattice, y: Floats, dy: Floats) -> None:
    K.lattice_damped_rhs(y, dy, system.f, system.F, system.alpha, system.mode, system.gamma, system.eta,
                         system.dscale, system.periodic)


@implements(monitor, Lattice)
@njit(cache=True)
def _monitor(system: Lattice, y: Floats, stats: Floats) -> None:
    n = y.shape[0] // 2
    H, cm = K.lattice_energy(y[:n], y[n:], system.alpha, system.mode, system.periodic)
    sc = abs(stats[0]) if stats[0] != 0.0 else 1.0
    stats[1] = max(stats[1], abs(H - stats[0]) / sc)
    stats[2] = max(stats[2], cm)
    stats[3] = H


@implements(monitor, DampedLattice)
@njit(cache=True)
def _damped_monitor(system: DampedLattice, y: Floats, stats: Floats) -> None:
    n = (y.shape[0] - 1) // 2
    H, cm = K.lattice_energy(y[:n], y[n:2 * n], system.alpha, system.mode, system.periodic)
    sc = abs(stats[0]) if stats[0] != 0.0 else 1.0
    stats[1] = max(stats[1], abs(H + y[2 * n] / stats[4] - stats[0]) / sc)
    stats[2] = max(stats[2], cm)
    stats[3] = H
