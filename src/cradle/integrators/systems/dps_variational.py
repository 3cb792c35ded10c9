"""(dfnls) on a ring with m columns of its variational equations: the system of the travelling breathers' shooting.

State y: the real view of A (Re A_0, Im A_0, Re A_1, ..., as every DpS system of :mod:`.dps`), then the real view
of the perturbations V (N x m complex, row by row: V_{0,0}, V_{0,1}, ..., V_{1,0}, ...). The orbit's right-hand
side is that of (dfnls) (:func:`cradle.integrators.systems.dps.dps_rhs`, the same machine code as every DpS run);
the columns obey the variational equation

    dV_n/dtau = (G_n - G_{n-1}) / (2 i tau0),   G_n = Dg(s_n) (V_{n+1} - V_n),   s_n = A_{n+1} - A_n,

with Dg(s) w = |s|^(alpha-1) w + (alpha-1) |s|^(alpha-3) s Re(conj(s) w) (g(z) = z |z|^(alpha-1) is not
holomorphic; 0 at s = 0, alpha > 1): :func:`cradle.models.dps_travelling.linearised_rhs`, which the tests compare
with. What is monitored: the orbit's norm and S (:class:`cradle.integrators.systems.dps.Conserved`).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, NamedTuple

from numba import njit

from cradle.integrators import _cache
from cradle.integrators._dop853 import monitor, rhs
from cradle.integrators._generic import implements
from cradle.integrators.systems import dps as SD
from cradle.integrators.terms import hertz

if TYPE_CHECKING:
    from cradle.integrators._types import Floats

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating


class DpsVariational(NamedTuple):
    """(dfnls) on a ring (``base``, :func:`cradle.integrators.systems.dps.dfnls` with periodic ends) and ``m``
    columns of its variational equations (module docstring)."""

    base: SD.DpsSystem
    m: int


@njit(cache=True)
def variational_rhs(system: DpsVariational, y: Floats, dy: Floats) -> None:
    """dy = f(y) of ``system``: the orbit by (dfnls), the columns by its variational equation (module docstring).

    Each bond's G_n is added to its left site's rate and taken from its right one's, so that every bond is
    visited once."""
    N = (y.shape[0] // 2) // (1 + system.m)
    m = system.m
    alpha = system.base.alpha
    c = system.base.inv2tau0
    SD.dps_rhs(system.base, y[:2 * N], dy[:2 * N])
    V = 2 * N
    for k in range(V, y.shape[0]):
        dy[k] = 0.0
    for n in range(N):
        n1 = n + 1 if n + 1 < N else 0
        sr = y[2 * n1] - y[2 * n]
        si = y[2 * n1 + 1] - y[2 * n + 1]
        r2 = sr * sr + si * si
        w1 = hertz.g_over_r(math.sqrt(r2), alpha)
        w2 = (alpha - 1.0) * w1 / r2 if r2 > 0.0 else 0.0
        a = V + 2 * m * n
        b = V + 2 * m * n1
        for j in range(m):
            dr = y[b + 2 * j] - y[a + 2 * j]
            di = y[b + 2 * j + 1] - y[a + 2 * j + 1]
            p = w2 * (sr * dr + si * di)
            gr = w1 * dr + p * sr
            gi = w1 * di + p * si
            # -i (gr + i gi) / (2 tau0) = (gi - i gr) c: + to site n, - to site n + 1
            dy[a + 2 * j] += gi * c
            dy[a + 2 * j + 1] -= gr * c
            dy[b + 2 * j] -= gi * c
            dy[b + 2 * j + 1] += gr * c


@implements(rhs, DpsVariational)
@njit(cache=True)
def _rhs(system: DpsVariational, y: Floats, dy: Floats) -> None:
    variational_rhs(system, y, dy)   # a call: inlined into the stages, its body raised NumbaIRAssumptionWarning


def dfnls_variational(alpha: float, inv2tau0: float, m: int) -> DpsVariational:
    """(dfnls) on a ring with m variational columns."""
    return DpsVariational(SD.dfnls(alpha, True, inv2tau0), int(m))


@implements(monitor, DpsVariational)
@njit(cache=True)
def _monitor(system: DpsVariational, y: Floats, stats: Floats) -> None:
    N = (y.shape[0] // 2) // (1 + system.m)
    SD.watch(system.base.invariants, system.base, y[:2 * N], stats)
