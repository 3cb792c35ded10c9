"""The DpS right-hand side family: (dfnls), (dpsdamped) and (dpsimperfect), one loop over the sites.

State y = real view of A (Re A_0, Im A_0, Re A_1, ...), extended for (dpsdamped) by the two amounts the
damping removes, Q_l2 and Q_S. Every member is

    dA_n/dtau = kappa (W_n - W_{n-1}) / (2 i tau0 m_n) - (gamma~/2) A_n + i (delta_n + (3/2) beta~_n |A_n|^2) A_n,

W_n = k_n g(|A_{n+1} - A_n|; delta~_n) (A_{n+1} - A_n)/|A_{n+1} - A_n| the coupling of bond n (W_{N-1} = 0 with
free ends), each factor the DpS counterpart of a lattice term (:mod:`cradle.integrators.terms`): Hertz's
contact (g(r; 0) = r^alpha, the p-Laplacian of (dfnls)), precompression or gaps (delta~_n, the tabulated
g of :mod:`cradle.models.dps_sites`), inhomogeneity (k_n, m_n, the detuning delta_n), the on-site quartic or
pendulum (beta~_n), the contact damping (kappa) and the on-site damping (gamma~). :class:`DpsSystem` holds one
unit per factor, the absent ones doing no arithmetic; :func:`dps_rhs` is the loop, compiled per combination.

What is monitored (:class:`Conserved`, :class:`Balanced`, :class:`Weighted`): the l2 norm and S = sum |A_{n+1} -
A_n|^(alpha+1) of (dfnls) (H = -S/((alpha+1) tau0)); with damping their balance laws l2 + Q_l2 and S + Q_S,
Q_l2' = gamma~ sum |A_n|^2 + (Im kappa / tau0) S, Q_S' = (alpha+1) [(Im kappa / (2 tau0)) sum |W_n - W_{n-1}|^2 +
(gamma~/2) S] (:mod:`cradle.models.dps_damped`); with sites the weighted l2 = sum m_n |A_n|^2 and the H of
(dpsimperfect).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, NamedTuple

import numba
import numpy as np
from numba import njit

from cradle.integrators import _cache, _kernels_dps_sites as KS
from cradle.integrators._dop853 import monitor, rhs
from cradle.integrators._generic import absent, generic, implements
from cradle.integrators.terms import (
    contact_damping as CD,
    hertz,
    inhomogeneity as IH,
    onsite_damping as OD,
    onsite_harmonic,
    onsite_quartic,
    precompression as PC,
)
from cradle.integrators.terms.slots import (
    dps_coupling,
    dps_decay,
    dps_factor,
    dps_kappa,
    dps_l2_loss,
    dps_rotate,
    dps_S_loss,
    dps_weight,
)

if TYPE_CHECKING:
    from collections.abc import Callable

    from cradle.integrators._types import Floats

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating


class Conserved(NamedTuple):
    """(dfnls): stats = [l2_0, S0, max |l2-l2_0|/l2_0, max |S-S0|/S0]."""


class Balanced(NamedTuple):
    """(dpsdamped), y extended by Q_l2, Q_S: stats as :class:`Conserved` with l2 + Q_l2 and S + Q_S."""


class Weighted(NamedTuple):
    """(dpsimperfect): stats = [l2_0, H0, max |l2-l2_0|/l2_0, max |H-H0|/|H0|] with the weighted l2 and its H,
    from the coefficients packed in ``par`` (:func:`cradle.integrators._kernels_dps_sites.pack`)."""

    par: np.ndarray


class DpsSystem(NamedTuple):
    """One member of the family (module docstring): the coupling of the bonds (``coupling``), the sites
    (``sites``: masses, stiffnesses, detuning), the on-site quartic (``onsite``), the damping
    (``contact_damping``, ``onsite_damping``) and what is monitored (``invariants``)."""

    alpha: float
    periodic: bool
    inv2tau0: float
    coupling: NamedTuple
    sites: NamedTuple
    onsite: NamedTuple
    contact_damping: NamedTuple
    onsite_damping: NamedTuple
    invariants: NamedTuple


def dfnls(alpha: float, periodic: bool, inv2tau0: float) -> DpsSystem:
    """(dfnls)."""
    return DpsSystem(float(alpha), bool(periodic), float(inv2tau0), hertz.PLaplacian(), IH.Homogeneous(),
                     onsite_harmonic.Harmonic(), CD.NoContactDamping(), OD.NoOnsiteDamping(), Conserved())


def damped(alpha: float, periodic: bool, inv2tau0: float, gamma: float, kappa: complex) -> DpsSystem:
    """(dpsdamped) with on-site rate gamma~ and contact factor kappa (:func:`cradle.models.dps_damped.contact_factor`;
    1 without contact damping)."""
    cd: NamedTuple = CD.NoContactDamping() if kappa == 1.0 else CD.SlowContactDamping(float(kappa.real),
                                                                                       float(kappa.imag))
    od: NamedTuple = OD.SlowOnsiteDamping(0.5 * float(gamma)) if gamma != 0.0 else OD.NoOnsiteDamping()
    return DpsSystem(float(alpha), bool(periodic), float(inv2tau0), hertz.PLaplacian(), IH.Homogeneous(),
                     onsite_harmonic.Harmonic(), cd, od, Balanced())


# Any: a cradle.models DpsSites; a kernel module's cradle imports (annotations' too) are the kernel cache's key
def imperfect(alpha: float, periodic: bool, sites: Any, par: np.ndarray) -> DpsSystem:
    """(dpsimperfect) of a :class:`cradle.models.dps_sites.DpsSites` and its packed ``par``
    (:func:`cradle.integrators._kernels_dps_sites.pack`)."""
    coupling: NamedTuple = PC.tabulated(par) if sites.compressed else hertz.PLaplacian()
    onsite: NamedTuple = (onsite_harmonic.Harmonic() if np.all(sites.beta == 0.0)
                          else onsite_quartic.SlowQuartic(np.ascontiguousarray(sites.beta)))
    return DpsSystem(float(alpha), bool(periodic), float(par[0]), coupling, IH.slow_sites(sites), onsite,
                     CD.NoContactDamping(), OD.NoOnsiteDamping(), Weighted(par))


@generic
def sites_of(invariants: NamedTuple, y: Floats) -> int:
    """The number of sites N of the state y."""


@generic
def bond_sum(invariants: NamedTuple, S: float, r: float, s: float) -> float:
    """S + |A_{n+1} - A_n|^(alpha+1) where the balance laws need S (r = |A_{n+1} - A_n|, s = W_n / r)."""


@generic
def site_sums(invariants: NamedTuple, l2: float, L2: float, ar: float, ai: float, wr: float,
              wi: float) -> tuple[float, float]:
    """(l2 + |A_n|^2, L2 + |W_n - W_{n-1}|^2) where the balance laws need them."""


@generic
def close(invariants: NamedTuple, system: NamedTuple, dy: Floats, N: int, S: float, l2: float, L2: float) -> None:
    """The entries after the sites: the rates of Q_l2 and Q_S of (dpsdamped)."""


@njit(cache=True)
def dps_rhs(system: DpsSystem, y: Floats, dy: Floats) -> None:
    """dA_n/dtau of ``system`` (module docstring) on the real view y."""
    inv = system.invariants
    N = sites_of(inv, y)
    alpha = system.alpha
    gr_last = 0.0
    gi_last = 0.0
    S = 0.0
    if system.periodic:
        dr = y[0] - y[2 * N - 2]
        di = y[1] - y[2 * N - 1]
        r = math.hypot(dr, di)
        s = dps_weight(system.sites, N - 1, dps_coupling(system.coupling, r, N - 1, alpha))
        gr_last = dr * s
        gi_last = di * s
        S = bond_sum(inv, S, r, s)
    gpr = gr_last
    gpi = gi_last
    l2 = 0.0
    L2 = 0.0
    for n in range(N):
        if n < N - 1:
            dr = y[2 * n + 2] - y[2 * n]
            di = y[2 * n + 3] - y[2 * n + 1]
            r = math.hypot(dr, di)
            s = dps_weight(system.sites, n, dps_coupling(system.coupling, r, n, alpha))
            gr = dr * s
            gi = di * s
            S = bond_sum(inv, S, r, s)
        else:
            gr = gr_last
            gi = gi_last
        wr = gr - gpr
        wi = gi - gpi
        ar = y[2 * n]
        ai = y[2 * n + 1]
        ur, ui = dps_kappa(system.contact_damping, wr, wi)
        c = dps_factor(system.sites, n, system.inv2tau0)
        # -i (ur + i ui) c = (ui - i ur) c
        a, b = dps_decay(system.onsite_damping, ui * c, -ur * c, ar, ai)
        dy[2 * n], dy[2 * n + 1] = dps_rotate(system.onsite, system.sites, n, a, b, ar, ai)
        l2, L2 = site_sums(inv, l2, L2, ar, ai, wr, wi)
        gpr = gr
        gpi = gi
    close(inv, system, dy, N, S, l2, L2)


def scipy_fun(system: DpsSystem, y0: Floats) -> Callable[[float, Floats], Floats]:
    """f(tau, y) = dA_n/dtau of ``system`` on the real view y, for scipy's solvers.

    The compiled :func:`dps_rhs` for the types of (system, y0) is looked up once and called directly: numba's
    dispatcher would type the NamedTuple ``system`` field by field on every call, which at a few hundred sites
    costs as much as the right-hand side itself."""
    dy0 = np.empty_like(y0)
    dps_rhs(system, y0, dy0)   # compiles or loads the overload
    cres = dps_rhs.overloads[(numba.typeof(system), numba.typeof(y0), numba.typeof(dy0))]
    entry = cres.entry_point   # type: ignore[attr-defined]  # (numba's stubs leave it out)

    def fun(tau: float, y: Floats) -> Floats:
        if y.dtype != np.float64 or not y.flags.c_contiguous:   # the overload's layout, checked here, not by numba
            y = np.ascontiguousarray(y, dtype=np.float64)
        dy = np.empty_like(y)
        entry(system, y, dy)
        return dy

    return fun


@implements(sites_of, Conserved)
@implements(sites_of, Weighted)
@njit(cache=True)
def _sites(invariants: Conserved | Weighted, y: Floats) -> int:
    return y.shape[0] // 2


@implements(sites_of, Balanced)
@njit(cache=True)
def _sites_balanced(invariants: Balanced, y: Floats) -> int:
    return (y.shape[0] - 2) // 2


@implements(bond_sum, Balanced)
@njit(cache=True)
def _bond_sum(invariants: Balanced, S: float, r: float, s: float) -> float:
    return S + r * r * s


@implements(site_sums, Balanced)
@njit(cache=True)
def _site_sums(invariants: Balanced, l2: float, L2: float, ar: float, ai: float, wr: float,
               wi: float) -> tuple[float, float]:
    return l2 + (ar * ar + ai * ai), L2 + (wr * wr + wi * wi)


@implements(close, Balanced)
@njit(cache=True)
def _close(invariants: Balanced, system: DpsSystem, dy: Floats, N: int, S: float, l2: float, L2: float) -> None:
    inv2tau0 = system.inv2tau0
    od = system.onsite_damping
    cd = system.contact_damping
    dy[2 * N] = dps_l2_loss(od, l2, S, inv2tau0) + dps_l2_loss(cd, l2, S, inv2tau0)
    dy[2 * N + 1] = (system.alpha + 1.0) * (dps_S_loss(cd, L2, S, inv2tau0) + dps_S_loss(od, L2, S, inv2tau0))


@implements(rhs, DpsSystem)
@njit(cache=True)
def _rhs(system: DpsSystem, y: Floats, dy: Floats) -> None:
    dps_rhs(system, y, dy)


@njit(cache=True)
def dps_invariants(y: Floats, alpha: float, periodic: bool) -> tuple[float, float, float, float]:
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
        S += r * r * hertz.g_over_r(r, alpha)
    return l2, S, pr, pi


@generic
def watch(invariants: NamedTuple, system: NamedTuple, y: Floats, stats: Floats) -> None:
    """Update the drifts in ``stats`` (the layout of the invariants' class) after an accepted step."""


@implements(monitor, DpsSystem)
@njit(cache=True)
def _monitor(system: DpsSystem, y: Floats, stats: Floats) -> None:
    watch(system.invariants, system, y, stats)


@njit(cache=True)
def _drifts(stats: Floats, l2: float, S: float) -> None:
    """stats[2:4] = the largest relative changes of l2 and S from stats[0:2]."""
    s0 = stats[0] if stats[0] != 0.0 else 1.0
    s1 = stats[1] if stats[1] != 0.0 else 1.0
    stats[2] = max(stats[2], abs(l2 - stats[0]) / s0)
    stats[3] = max(stats[3], abs(S - stats[1]) / s1)


@implements(watch, Conserved)
@njit(cache=True)
def _watch_conserved(invariants: Conserved, system: DpsSystem, y: Floats, stats: Floats) -> None:
    l2, S, _pr, _pi = dps_invariants(y, system.alpha, system.periodic)
    _drifts(stats, l2, S)


@implements(watch, Balanced)
@njit(cache=True)
def _watch_balanced(invariants: Balanced, system: DpsSystem, y: Floats, stats: Floats) -> None:
    n = y.shape[0] - 2
    l2, S, _pr, _pi = dps_invariants(y[:n], system.alpha, system.periodic)
    _drifts(stats, l2 + y[n], S + y[n + 1])


@implements(watch, Weighted)
@njit(cache=True)
def _watch_weighted(invariants: Weighted, system: DpsSystem, y: Floats, stats: Floats) -> None:
    l2, H, _pr, _pi = KS.dps_sites_invariants(y, system.alpha, invariants.par, system.periodic)
    s0 = stats[0] if stats[0] != 0.0 else 1.0
    s1 = abs(stats[1]) if stats[1] != 0.0 else 1.0
    stats[2] = max(stats[2], abs(l2 - stats[0]) / s0)
    stats[3] = max(stats[3], abs(H - stats[1]) / s1)


for _invariants in (Conserved, Weighted):   # no balance laws: nothing to add up
    absent(bond_sum, _invariants, "S")
    absent(site_sums, _invariants, "l2", "L2")
    absent(close, _invariants)
