"""(nc) on a ring with m columns of its variational equations: the system of the lattice travelling breathers'
shooting (:mod:`cradle.integrators.lattice_travelling`).

State y = [x, v, X, W]: the orbit (x, v) (N each), then the perturbations of positions X and of velocities W
(N x m each, row by row: X_{0,0}, X_{0,1}, ..., X_{1,0}, ...). The orbit's right-hand side is that of (nc)
(:func:`cradle.integrators._kernels.lattice_rhs`, the same machine code as every lattice run); the columns obey the
variational equation

    X' = W,   W' = -X + K_n (X_{n+1} - X_n) - K_{n-1} (X_n - X_{n-1}),   K_n = alpha (x_n - x_{n+1})_+^(alpha-1),

the Jacobian's lower-left block of :func:`cradle.integrators._kernels.lattice_jac` applied bond by bond (each bond
visited once, K_n = 0 on an open bond). What is monitored: the orbit's energy (ham), as
:class:`cradle.integrators.systems.lattice.Lattice` does (stats = [H0, max |H-H0|/|H0|, max compression, H]).
"""
from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np
from numba import njit

from cradle.integrators import _cache, _kernels as K
from cradle.integrators._dop853 import monitor, rhs
from cradle.integrators._generic import implements
from cradle.integrators.terms.hertz import hertz

if TYPE_CHECKING:
    from cradle.integrators._types import Floats

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating


class LatticeVariational(NamedTuple):
    """(nc) with Hertz contacts on a ring (``alpha``, ``mode`` of :func:`cradle.integrators._kernels.mode_flag`,
    work arrays ``f``, ``F`` of length N) and ``m`` columns of its variational equations (module docstring)."""

    alpha: float
    mode: int
    m: int
    f: np.ndarray
    F: np.ndarray


def lattice_variational(N: int, alpha: float, m: int) -> LatticeVariational:
    """(nc) with Hertz contacts on a ring of N beads with m variational columns."""
    return LatticeVariational(float(alpha), K.mode_flag("hertz", alpha), int(m), np.empty(N), np.empty(N))


@njit(cache=True)
def variational_rhs(system: LatticeVariational, y: Floats, dy: Floats) -> None:
    """dy = f(y) of ``system``: the orbit by (nc), the columns by its variational equation (module docstring)."""
    N = system.f.shape[0]
    m = system.m
    K.lattice_rhs(y[:2 * N], dy[:2 * N], system.f, system.F, system.alpha, system.mode, True)
    X = 2 * N
    W = 2 * N + N * m
    for k in range(N * m):
        dy[X + k] = y[W + k]
        dy[W + k] = -y[X + k]
    for n in range(N):
        n1 = n + 1 if n + 1 < N else 0
        c = y[n] - y[n1]
        if c <= 0.0:
            continue
        kn = system.alpha * hertz(c, system.alpha, system.mode)[1]   # V0'' = alpha c^(alpha-1)
        a = n * m
        b = n1 * m
        for j in range(m):
            g = kn * (y[X + b + j] - y[X + a + j])
            dy[W + a + j] += g
            dy[W + b + j] -= g


@implements(rhs, LatticeVariational)
@njit(cache=True)
def _rhs(system: LatticeVariational, y: Floats, dy: Floats) -> None:
    variational_rhs(system, y, dy)   # a call, as systems.dps_variational does (inlining raised IR warnings)


@implements(monitor, LatticeVariational)
@njit(cache=True)
def _monitor(system: LatticeVariational, y: Floats, stats: Floats) -> None:
    N = system.f.shape[0]
    H, cm = K.lattice_energy(y[:N], y[N:2 * N], system.alpha, system.mode, True)
    sc = abs(stats[0]) if stats[0] != 0.0 else 1.0
    stats[1] = max(stats[1], abs(H - stats[0]) / sc)
    stats[2] = max(stats[2], cm)
    stats[3] = H
