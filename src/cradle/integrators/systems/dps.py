"""The DpS right-hand side family: (dfnls), (dpsdamped) and (dpsimperfect), one loop over the sites.

State y = real view of A (Re A_0, Im A_0, Re A_1, ...), extended for (dpsdamped) by the two amounts the
damping removes, Q_l2 and Q_S. Every member is

    dA_n/dtau = site_n( W_n - W_{n-1} ),   W_n the bond coupling of bond n (W_{N-1} = 0 with free ends),

with the bond coupling and the site law of its system (the DpS counterparts of the lattice terms):

* :class:`Dps`, (dfnls): W_n = g(A_{n+1} - A_n), g(z) = z |z|^(alpha-1) (Hertz's contact averaged), and the
  site law (W_n - W_{n-1}) / (2 i tau0);
* :class:`DpsDamped`, (dpsdamped): the same W, the site law kappa (W_n - W_{n-1}) / (2 i tau0) - (gamma~/2) A_n
  (contact damping: the complex factor kappa; on-site damping: the decay gamma~), and the balance laws
  Q_l2' = gamma~ sum |A_n|^2 + (Im kappa / tau0) S, Q_S' = (alpha+1) [(Im kappa / (2 tau0)) sum |W_n - W_{n-1}|^2
  + (gamma~/2) S] of :mod:`cradle.models.dps_damped`, S = sum |A_{n+1} - A_n|^(alpha+1);
* :class:`DpsSites`, (dpsimperfect): W_n = k_n Phi_n(A_{n+1} - A_n) (stiffness; precompression or gaps through
  the averaged force g(r; delta~_n) of :mod:`cradle.models.dps_sites`), and the site law
  (1/m_n) (W_n - W_{n-1}) / (2 i tau0) + i (delta_n + (3/2) beta~_n |A_n|^2) A_n (masses; detuning; the on-site
  quartic or pendulum).

:func:`dps_rhs` is the loop; the generic operations :func:`bond`, :func:`site` and :func:`close` are each
system's. Also the invariants monitored after every step.
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from cradle.integrators import _cache, _kernels_dps_sites as KS
from cradle.integrators._dop853 import monitor, rhs
from cradle.integrators._generic import generic, implements

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating


class Dps(NamedTuple):
    """(dfnls). Monitored: stats = [l2_0, S0, max |l2-l2_0|/l2_0, max |S-S0|/S0] (H = -S/((alpha+1) tau0))."""

    alpha: float
    periodic: bool
    inv2tau0: float


class DpsDamped(NamedTuple):
    """(dpsdamped): gamma~, kappa = kr + i ki (:func:`cradle.models.dps_damped.contact_factor`). Monitored: as
    :class:`Dps` with l2 + Q_l2 and S + Q_S (the balance laws)."""

    alpha: float
    periodic: bool
    inv2tau0: float
    half_gamma: float
    kr: float
    ki: float


class DpsSites(NamedTuple):
    """(dpsimperfect): the coefficients in ``par`` (:func:`cradle.integrators._kernels_dps_sites.pack`) and
    their offsets. Monitored: stats = [l2_0, H0, max |l2-l2_0|/l2_0, max |H-H0|/|H0|], l2 = sum m_n |A_n|^2."""

    alpha: float
    periodic: bool
    inv2tau0: float
    par: np.ndarray
    N: int
    od: int
    om: int
    ow: int
    ob: int
    oe: int
    og1: int
    og2: int
    oga: int
    n1: int
    n2: int
    ns: int


def dps_sites_system(alpha: float, periodic: bool, par: np.ndarray) -> DpsSites:
    """The :class:`DpsSites` of ``par``."""
    N, od, om, ow, ob, oe, og1, og2, oga, _op1, _op2, _oph, n1, n2, ns = KS._offsets(par)
    return DpsSites(float(alpha), bool(periodic), float(par[0]), par, N, od, om, ow, ob, oe, og1, og2, oga, n1, n2,
                    ns)


@njit(cache=True)
def _pow_am1(r, alpha):
    """r^(alpha-1) for r >= 0 (sqrt fast path for alpha = 3/2; 0 at r = 0)."""
    if r <= 0.0:
        return 0.0
    if alpha == 1.5:
        return math.sqrt(r)
    return r ** (alpha - 1.0)


@generic
def sites(system, y):
    """The number of sites N of the state y."""


@generic
def bond(system, dr, di, n, S):
    """(Re W_n, Im W_n, S) of bond n with A_{n+1} - A_n = dr + i di; S the running sum of the balance laws."""


@generic
def site(system, y, dy, n, wr, wi, l2, L2):
    """dA_n/dtau into dy[2n], dy[2n+1] from W_n - W_{n-1} = wr + i wi; returns the running sums (l2, L2)."""


@generic
def close(system, dy, N, S, l2, L2):
    """The entries after the sites (the balance laws' rates of (dpsdamped))."""


@njit(cache=True)
def dps_rhs(system, y, dy):
    """dA_n/dtau of ``system`` (module docstring) on the real view y."""
    N = sites(system, y)
    gr_last = 0.0
    gi_last = 0.0
    S = 0.0
    if system.periodic:
        dr = y[0] - y[2 * N - 2]
        di = y[1] - y[2 * N - 1]
        gr_last, gi_last, S = bond(system, dr, di, N - 1, S)
    gpr = gr_last
    gpi = gi_last
    l2 = 0.0
    L2 = 0.0
    for n in range(N):
        if n < N - 1:
            dr = y[2 * n + 2] - y[2 * n]
            di = y[2 * n + 3] - y[2 * n + 1]
            gr, gi, S = bond(system, dr, di, n, S)
        else:
            gr = gr_last
            gi = gi_last
        l2, L2 = site(system, y, dy, n, gr - gpr, gi - gpi, l2, L2)
        gpr = gr
        gpi = gi
    close(system, dy, N, S, l2, L2)


# --- (dfnls) -------------------------------------------------------------------------------------------------


@implements(sites, Dps)
@njit(cache=True)
def _sites(system, y):
    return y.shape[0] // 2


@implements(bond, Dps)
@njit(cache=True)
def _bond(system, dr, di, n, S):
    s = _pow_am1(math.hypot(dr, di), system.alpha)
    return dr * s, di * s, S


@implements(site, Dps)
@njit(cache=True)
def _site(system, y, dy, n, wr, wi, l2, L2):
    # -i (wr + i wi) / (2 tau0) = (wi - i wr) / (2 tau0)
    dy[2 * n] = wi * system.inv2tau0
    dy[2 * n + 1] = -wr * system.inv2tau0
    return l2, L2


@implements(close, Dps)
@njit(cache=True)
def _close(system, dy, N, S, l2, L2):
    pass


# --- (dpsdamped) ---------------------------------------------------------------------------------------------


@implements(sites, DpsDamped)
@njit(cache=True)
def _damped_sites(system, y):
    return (y.shape[0] - 2) // 2


@implements(bond, DpsDamped)
@njit(cache=True)
def _damped_bond(system, dr, di, n, S):
    r = math.hypot(dr, di)
    s = _pow_am1(r, system.alpha)
    return dr * s, di * s, S + r * r * s


@implements(site, DpsDamped)
@njit(cache=True)
def _damped_site(system, y, dy, n, wr, wi, l2, L2):
    # kappa w = (kr wr - ki wi) + i (kr wi + ki wr); -i (a + i b) / (2 tau0) = (b - i a) / (2 tau0)
    kr = system.kr
    ki = system.ki
    ar = y[2 * n]
    ai = y[2 * n + 1]
    dy[2 * n] = (kr * wi + ki * wr) * system.inv2tau0 - system.half_gamma * ar
    dy[2 * n + 1] = -(kr * wr - ki * wi) * system.inv2tau0 - system.half_gamma * ai
    return l2 + (ar * ar + ai * ai), L2 + (wr * wr + wi * wi)


@implements(close, DpsDamped)
@njit(cache=True)
def _damped_close(system, dy, N, S, l2, L2):
    dy[2 * N] = 2.0 * system.half_gamma * l2 + 2.0 * system.ki * system.inv2tau0 * S
    dy[2 * N + 1] = (system.alpha + 1.0) * (system.ki * system.inv2tau0 * L2 + system.half_gamma * S)


# --- (dpsimperfect) ------------------------------------------------------------------------------------------


@implements(sites, DpsSites)
@njit(cache=True)
def _sites_sites(system, y):
    return system.N


@implements(bond, DpsSites)
@njit(cache=True)
def _sites_bond(system, dr, di, n, S):
    par = system.par
    s = par[system.ow + n] * KS._g_over_r(math.hypot(dr, di), par[system.oe + n], system.alpha, par, system.og1,
                                          system.og2, system.oga, system.n1, system.n2, system.ns)
    return dr * s, di * s, S


@implements(site, DpsSites)
@njit(cache=True)
def _sites_site(system, y, dy, n, wr, wi, l2, L2):
    par = system.par
    c = par[system.om + n] * system.inv2tau0
    ar = y[2 * n]
    ai = y[2 * n + 1]
    rot = par[system.od + n] + 1.5 * par[system.ob + n] * (ar * ar + ai * ai)
    # -i (a + i b) c = (b - i a) c ; i rot (ar + i ai) = -rot ai + i rot ar
    dy[2 * n] = wi * c - rot * ai
    dy[2 * n + 1] = -wr * c + rot * ar
    return l2, L2


@implements(close, DpsSites)
@njit(cache=True)
def _sites_close(system, dy, N, S, l2, L2):
    pass


# --- the right-hand side and invariants of each system for the DOP853 loop ----------------------------------


@implements(rhs, Dps)
@njit(cache=True)
def _rhs(system, y, dy):
    dps_rhs(system, y, dy)


@implements(rhs, DpsDamped)
@njit(cache=True)
def _damped_rhs(system, y, dy):
    dps_rhs(system, y, dy)


@implements(rhs, DpsSites)
@njit(cache=True)
def _sites_rhs(system, y, dy):
    dps_rhs(system, y, dy)


@njit(cache=True)
def dps_invariants(y, alpha, periodic):
    """(l2, S, Re P, Im P): sum |A_n|^2, sum |A_{n+1}-A_n|^(alpha+1), P = sum A_n.

    The DpS Hamiltonian is H = -S / ((alpha + 1) tau0).
    """
    N = y.shape[0] // 2
    l2 = 0.0
    S = 0.0
    pr = 0.0
    pi = 0.0
    nb = N if periodic else N - 1
    for n in range(N):
        l2 += y[2 * n] ** 2 + y[2 * n + 1] ** 2
        pr += y[2 * n]
        pi += y[2 * n + 1]
    for n in range(nb):
        m = n + 1 if n + 1 < N else 0
        r = math.hypot(y[2 * m] - y[2 * n], y[2 * m + 1] - y[2 * n + 1])
        S += r * r * _pow_am1(r, alpha)
    return l2, S, pr, pi


@implements(monitor, Dps)
@njit(cache=True)
def _monitor(system, y, stats):
    l2, S, _pr, _pi = dps_invariants(y, system.alpha, system.periodic)
    s0 = stats[0] if stats[0] != 0.0 else 1.0
    s1 = stats[1] if stats[1] != 0.0 else 1.0
    stats[2] = max(stats[2], abs(l2 - stats[0]) / s0)
    stats[3] = max(stats[3], abs(S - stats[1]) / s1)


@implements(monitor, DpsDamped)
@njit(cache=True)
def _damped_monitor(system, y, stats):
    n = y.shape[0] - 2
    l2, S, _pr, _pi = dps_invariants(y[:n], system.alpha, system.periodic)
    s0 = stats[0] if stats[0] != 0.0 else 1.0
    s1 = stats[1] if stats[1] != 0.0 else 1.0
    stats[2] = max(stats[2], abs(l2 + y[n] - stats[0]) / s0)
    stats[3] = max(stats[3], abs(S + y[n + 1] - stats[1]) / s1)


@implements(monitor, DpsSites)
@njit(cache=True)
def _sites_monitor(system, y, stats):
    l2, H, _pr, _pi = KS.dps_sites_invariants(y, system.alpha, system.par, system.periodic)
    s0 = stats[0] if stats[0] != 0.0 else 1.0
    s1 = abs(stats[1]) if stats[1] != 0.0 else 1.0
    stats[2] = max(stats[2], abs(l2 - stats[0]) / s0)
    stats[3] = max(stats[3], abs(H - stats[1]) / s1)
