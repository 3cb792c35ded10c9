"""The imperfect cradle (ncimperfect) of :mod:`cradle.models.lattice_terms` as a system of the compiled DOP853:
its right-hand side and generalised energy (ham), composed of the term units of :mod:`cradle.integrators.terms`.

    m_n ( x_n'' + omega_n^2 W'(x_n) ) = J_n [ k_n F_n(u_{n+1} - u_n) - k_{n-1} F_{n-1}(u_n - u_{n-1}) ]
                                        (- gamma m_n v_n and the Kuwabara-Kono term with damping)

on y = [x, v], or y = [x, v, s D] with damping (D the dissipated energy, s its scale in the state). The system
holds one unit per slot (:class:`Imperfect`); :func:`cradle.integrators.lattice_adaptive.imperfect_system` picks
them from the declared terms, a term at its default being the slot's absent unit. Hertz contacts only (``mode`` 0
or 1).
"""
from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np
from numba import njit

from cradle.integrators import _cache
from cradle.integrators._dop853 import monitor, rhs
from cradle.integrators._generic import absent, generic, implements
from cradle.integrators.terms import (
    hertz,
)
from cradle.integrators.terms.slots import (
    damp_bond,
    damp_site,
    elastic,
    mass_omega2,
    mass_times,
    onsite_energy,
    onsite_force,
    onsite_scale,
    overlap,
    per_mass,
    position,
    potential,
    rest,
    stiff,
)

if TYPE_CHECKING:
    from cradle.integrators._types import Floats

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating


class NoDissipation(NamedTuple):
    """y = [x, v]: no damping, no D."""


class Dissipation(NamedTuple):
    """y = [x, v, s D]: the dissipated energy D integrated with the run, s = ``dscale``."""

    dscale: float


class Imperfect(NamedTuple):
    """(ncimperfect): its units (contact law, sites, on-site potential, on-site and contact damping, D) and
    work arrays of N: ``f`` bond forces, ``U`` horizontal positions, ``J`` their derivatives du/dx, ``Ue``
    the positions of the energy. Monitored: stats = [H0, max |H+D-H0|/|H0|, max overlap, H, s]."""

    alpha: float
    mode: int
    periodic: bool
    contact: NamedTuple
    sites: NamedTuple
    onsite: NamedTuple
    onsite_damping: NamedTuple
    contact_damping: NamedTuple
    dissipation: NamedTuple
    f: np.ndarray
    U: np.ndarray
    J: np.ndarray
    Ue: np.ndarray


@generic
def store_power(dissipation: NamedTuple, dy: Floats, N: int, P: float) -> None:
    """dy[2N] = s P with damping (nothing without)."""


@generic
def dissipated(dissipation: NamedTuple, y: Floats, N: int, stats: Floats) -> float:
    """D at the state y (0 without damping)."""


@implements(store_power, Dissipation)
@njit(cache=True)
def _store(dissipation: Dissipation, dy: Floats, N: int, P: float) -> None:
    dy[2 * N] = dissipation.dscale * P


@implements(dissipated, Dissipation)
@njit(cache=True)
def _dissipated(dissipation: Dissipation, y: Floats, N: int, stats: Floats) -> float:
    return y[2 * N] / stats[4]


@njit(cache=True)
def imperfect_rhs(system: Imperfect, y: Floats, dy: Floats) -> None:
    """dy = f(y) of (ncimperfect) (module docstring)."""
    f = system.f
    U = system.U
    J = system.J
    N = f.shape[0]
    alpha = system.alpha
    mode = system.mode
    for n in range(N):
        U[n], J[n] = position(system.onsite, n, y[n])
    P = 0.0
    nb = N if system.periodic else N - 1
    for n in range(nb):
        m = n + 1 if n + 1 < N else 0
        d = U[m] - U[n]
        c = overlap(system.contact, n, d)
        if c > 0.0:
            el, sa = hertz.hertz(c, alpha, mode)
            diff = elastic(system.contact, n, d, c, el, alpha, mode)
            f[n], P = damp_bond(system.contact_damping, system.sites, system.contact, n, m, diff, el, sa, y, J, N, P)
        else:
            f[n] = stiff(system.sites, n, rest(system.contact, n))
    if not system.periodic:
        f[N - 1] = 0.0
    for n in range(N):
        net = f[n] - f[n - 1] if n > 0 else f[0] - f[N - 1]
        x = y[n]
        v = y[N + n]
        on = onsite_scale(system.sites, n, onsite_force(system.onsite, x, U[n]))
        dy[n] = v
        dy[N + n], P = damp_site(system.onsite_damping, system.sites, n, per_mass(system.sites, n, J[n] * net) - on, v,
                                 P)
    store_power(system.dissipation, dy, N, P)


@njit(cache=True)
def imperfect_energy(system: Imperfect, x: Floats, v: Floats) -> tuple[float, float]:
    """The generalised (ham) of (ncimperfect) at one state, and the largest bond overlap c = delta_n - d."""
    N = x.shape[0]
    u = system.Ue
    e = 0.0
    for n in range(N):
        xn = x[n]
        u[n] = position(system.onsite, n, xn)[0]
        W = onsite_energy(system.onsite, n, xn)
        e += mass_times(system.sites, n, 0.5) * v[n] * v[n] + mass_omega2(system.sites, n, W)
    cmax = 0.0
    a1 = system.alpha + 1.0
    nb = N if system.periodic else N - 1
    for n in range(nb):
        m = n + 1 if n + 1 < N else 0
        d = u[m] - u[n]
        c = overlap(system.contact, n, d)
        e += stiff(system.sites, n, potential(system.contact, n, d, c, a1))
        cmax = max(cmax, c)
    return e, cmax


@implements(rhs, Imperfect)
@njit(cache=True)
def _rhs(system: Imperfect, y: Floats, dy: Floats) -> None:
    imperfect_rhs(system, y, dy)


@implements(monitor, Imperfect)
@njit(cache=True)
def _monitor(system: Imperfect, y: Floats, stats: Floats) -> None:
    n = y.shape[0] // 2
    H, cm = imperfect_energy(system, y[:n], y[n:2 * n])
    sc = abs(stats[0]) if stats[0] != 0.0 else 1.0
    D = dissipated(system.dissipation, y, n, stats)
    stats[1] = max(stats[1], abs(H + D - stats[0]) / sc)
    stats[2] = max(stats[2], cm)
    stats[3] = H


absent(store_power, NoDissipation)
absent(dissipated, NoDissipation, "0.0")
