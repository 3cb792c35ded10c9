"""The adaptive drivers on (nc)/(meca): scipy's solvers stepped manually, and DOP853 in numba.

scipy's "dop853", "rk45", "lsoda", "radau" get the numba right-hand side
(:func:`cradle.integrators._kernels.lattice_rhs`; "radau" and "lsoda" also the
analytic Jacobian) and dense output at the output times; "dop853_numba" runs
entirely in numba (:mod:`cradle.integrators._dop853`) with steps ending
exactly on the output times. The energy (ham) is evaluated after every
accepted step. The damped lattice (ncdamped) is integrated by "dop853_numba" only
(:func:`run_dop853_damped`), with its dissipated energy as a component of the state; so is the imperfect
cradle (ncimperfect) of :mod:`cradle.models.lattice_terms` (:func:`run_dop853_terms`).
"""
from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from cradle.integrators import _dop853, _dop853_events, _kernels as K
from cradle.integrators._scipy_steps import stepped
from cradle.integrators.systems import imperfect as SI, lattice as SL
from cradle.integrators.terms import (
    contact_damping as CD,
    hertz,
    inhomogeneity as IH,
    onsite_damping as OD,
    onsite_harmonic,
    onsite_none,
    onsite_pendulum,
    onsite_quartic,
    precompression as PC,
)
from cradle.models import lattice_terms as LTm

if TYPE_CHECKING:
    from collections.abc import Callable

    from cradle.integrators._types import DampedRun, Floats, Ints, LatticeRun
    from cradle.models.damping import Damping
    from cradle.models.inhomogeneity import Sites
    from cradle.models.lattice_terms import Terms

#: scipy.integrate.solve_ivp classes, the baselines (looked up when used: scipy.integrate costs 0.5 s to import)
SCIPY_METHODS = {"dop853": "DOP853", "rk45": "RK45", "lsoda": "LSODA", "radau": "Radau"}
ADAPTIVE_METHODS = tuple(SCIPY_METHODS) + ("dop853_numba",)


def run_scipy(x0: Floats, v0: Floats, t_out: Floats, method: str, rtol: float, atol: float, alpha: float, mode: int,
              periodic: bool, progress: Callable[[float, float], None] | None) -> LatticeRun:
    """(X, V, E, drift, steps, function evaluations, max compression) of scipy's ``method`` from t = 0."""
    N = x0.size
    T = t_out.size
    y0 = np.concatenate((x0, v0))
    f = np.empty(N)
    F = np.empty(N)

    def fun(t: float, y: Floats) -> Floats:
        dy = np.empty_like(y)
        K.lattice_rhs(y, dy, f, F, alpha, mode, periodic)
        return dy

    extra = {}
    if method in ("radau", "lsoda"):
        def jac(t: float, y: Floats) -> Floats:
            J = np.empty((2 * N, 2 * N))
            K.lattice_jac(y, J, alpha, mode, periodic)
            return J
        extra["jac"] = jac

    X = np.empty((T, N))
    V = np.empty((T, N))
    E = np.empty(T)
    H0, c0 = K.lattice_energy(x0, v0, alpha, mode, periodic)
    scale = abs(H0) if H0 != 0.0 else 1.0
    monitored = [0.0, c0]   # the largest relative energy drift and compression over every accepted step

    def store(i: int, y: Floats) -> None:
        X[i], V[i] = y[:N], y[N:]
        E[i] = K.lattice_energy(X[i], V[i], alpha, mode, periodic)[0]

    def on_step(y: Floats, t: float) -> None:
        H, cm = K.lattice_energy(y[:N], y[N:], alpha, mode, periodic)
        monitored[0] = max(monitored[0], abs(H - H0) / scale)
        monitored[1] = max(monitored[1], cm)

    n_steps, nfev = stepped(SCIPY_METHODS[method], fun, y0, t_out, rtol, atol, store, on_step, progress, method,
                            clock="t", **extra)
    drift, cmax = monitored
    return X, V, E, drift, n_steps, int(nfev), float(cmax)


def run_dop853_numba(x0: Floats, v0: Floats, t_out: Floats, rtol: float, atol: float, alpha: float, mode: int,
                     periodic: bool, progress: Callable[[float, float], None] | None) -> LatticeRun:
    """(X, V, E, drift, steps, function evaluations, max compression) of DOP853 in numba from t = 0."""
    N = x0.size
    H0, c0 = K.lattice_energy(x0, v0, alpha, mode, periodic)
    stats = np.array([H0, 0.0, c0, H0])
    Y, n_steps, nfev = _dop853.run_dop853(SL.lattice(N, alpha, mode, periodic), np.concatenate((x0, v0)), t_out, rtol,
                                          atol, stats, progress)
    X = np.ascontiguousarray(Y[:, :N])
    V = np.ascontiguousarray(Y[:, N:])
    E = np.array([K.lattice_energy(X[i], V[i], alpha, mode, periodic)[0] for i in range(len(t_out))])
    return X, V, E, float(stats[1]), n_steps, nfev, float(stats[2])


def run_dop853_damped(x0: Floats, v0: Floats, t_out: Floats, rtol: float, atol: float, alpha: float, mode: int,
                      periodic: bool, damping: Damping, progress: Callable[[float, float], None] | None,
                      onset: bool = True, events: Ints | None = None, event_times: Floats | None = None) -> DampedRun:
    """(X, V, E, D, drift, steps, function evaluations, max compression) of DOP853 in numba on (ncdamped)
    from t = 0: y = [x, v, s D], D(0) = 0 the dissipated energy (dD/dt = P, :mod:`cradle.models.damping`);
    drift = max over every step of |H + D - H(0)| / |H(0)|.

    The scale s = atol / (rtol |H(0)|) makes the error control hold D to rtol |H(0)| (absolute) like the
    stored energy, not to atol: at a contact onset the contact damping's power rises like sqrt(t - t_on),
    whose quadrature over a step has a relative error independent of the step, so D held to atol while
    it is still below atol would shrink the step to underflow.

    ``onset`` (default): the steps end at the contact onsets, releases and clips
    (:mod:`cradle.integrators._dop853_events`); False: plain DOP853 across them. ``events`` (int64, 4
    entries, with ``onset``) is incremented by [events located, switches left unlocated, re-steps, re-steps
    failing the error test]; ``event_times`` (float64, with ``onset``) receives the times of the first
    located events.
    """
    N = x0.size
    H0, c0 = K.lattice_energy(x0, v0, alpha, mode, periodic)
    dscale = atol / (rtol * abs(H0)) if H0 != 0.0 else 1.0
    stats = np.array([H0, 0.0, c0, H0, dscale])
    system = SL.damped_lattice(N, alpha, mode, periodic, damping.onsite, damping.contact, dscale)
    y0 = np.concatenate((x0, v0, [0.0]))
    located = None
    if onset:
        located = _dop853_events.contact_events(y0, periodic, damping.contact, rtol,
                                                np.zeros(4, dtype=np.int64) if events is None else events, event_times)
    Y, n_steps, nfev = _dop853.run_dop853(system, y0, t_out, rtol, atol, stats, progress, events=located)
    X = np.ascontiguousarray(Y[:, :N])
    V = np.ascontiguousarray(Y[:, N:2 * N])
    D = Y[:, 2 * N] / dscale
    E = np.array([K.lattice_energy(X[i], V[i], alpha, mode, periodic)[0] for i in range(len(t_out))])
    return X, V, E, D, float(stats[1]), n_steps, nfev, float(stats[2])


def run_dop853_terms(x0: Floats, v0: Floats, t_out: Floats, rtol: float, atol: float, alpha: float, mode: int,
                     periodic: bool, terms: Terms, sites: Sites, damping: Damping | None,
                     progress: Callable[[float, float], None] | None) -> DampedRun:
    """(X, V, E, D, drift, steps, function evaluations, max overlap) of DOP853 in numba on the imperfect cradle
    (ncimperfect) (:mod:`cradle.integrators.systems.imperfect`, its terms the units of
    :mod:`cradle.integrators.terms`), with ``damping`` (or None) from t = 0: y = [x, v, s D] (y = [x, v] and D = 0
    without damping), E the generalised (ham), D the dissipated energy, drift = max over every step of
    |H + D - H(0)| / |H(0)|; no contact-event location. For the pendulum x is the arc variable."""
    N = x0.size
    system = imperfect_system(alpha, mode, periodic, terms, sites)
    H0, c0 = SI.imperfect_energy(system, x0, v0)
    dscale = atol / (rtol * abs(H0)) if H0 != 0.0 else 1.0
    if damping is not None:
        system = imperfect_system(alpha, mode, periodic, terms, sites, damping, dscale)
    stats = np.array([H0, 0.0, c0, H0, dscale])
    y0 = np.concatenate((x0, v0, [0.0]) if damping is not None else (x0, v0))
    Y, n_steps, nfev = _dop853.run_dop853(system, y0, t_out, rtol, atol, stats, progress)
    X = np.ascontiguousarray(Y[:, :N])
    V = np.ascontiguousarray(Y[:, N:2 * N])
    D = Y[:, 2 * N] / dscale if damping is not None else np.zeros(len(t_out))
    E = np.array([SI.imperfect_energy(system, X[i], V[i])[0] for i in range(len(t_out))])
    return X, V, E, D, float(stats[1]), n_steps, nfev, float(stats[2])


def run_dop853_hertz_chain(x0: Floats, v0: Floats, t_out: Floats, rtol: float, atol: float, alpha: float,
                           periodic: bool, progress: Callable[[float, float], None] | None = None) -> LatticeRun:
    """(X, V, E, drift, steps, function evaluations, max compression) of DOP853 in numba on the Hertz chain
    without on-site potential, x_n'' = V0'(x_{n+1} - x_n) - V0'(x_n - x_{n-1}) with V0 of (vhertz): the system of
    (ncimperfect) with touching homogeneous beads and the on-site slot's absent unit
    (:class:`cradle.integrators.terms.onsite_none.NoOnsite`), no damping; E its energy (kinetic plus Hertz)."""
    N = x0.size
    system = SI.Imperfect(float(alpha), int(K.mode_flag("hertz", alpha)), bool(periodic), hertz.Touching(),
                          IH.Homogeneous(), onsite_none.NoOnsite(), OD.NoOnsiteDamping(), CD.NoContactDamping(),
                          SI.NoDissipation(), np.empty(N), np.empty(N), np.empty(N), np.empty(N))
    H0, c0 = SI.imperfect_energy(system, x0, v0)
    stats = np.array([H0, 0.0, c0, H0, 1.0])
    Y, n_steps, nfev = _dop853.run_dop853(system, np.concatenate((x0, v0)), t_out, rtol, atol, stats, progress)
    X = np.ascontiguousarray(Y[:, :N])
    V = np.ascontiguousarray(Y[:, N:])
    E = np.array([SI.imperfect_energy(system, X[i], V[i])[0] for i in range(len(t_out))])
    return X, V, E, float(stats[1]), n_steps, nfev, float(stats[2])


def imperfect_system(alpha: float, mode: int, periodic: bool, terms: Terms, sites: Sites,
                     damping: Damping | None = None, dscale: float | None = None) -> SI.Imperfect:
    """The system of the declared ``terms`` (:class:`cradle.models.lattice_terms.Terms`) on ``sites``
    (:class:`cradle.models.inhomogeneity.Sites`) with ``damping`` (:class:`cradle.models.damping.Damping`, or
    None: y = [x, v]); ``dscale`` the scale of D in the state (with damping)."""
    N = sites.mass.size
    contact: NamedTuple = hertz.Touching()
    if terms.precompression.active:
        contact = PC.build(LTm.static_overlaps(terms.precompression.delta0, sites.stiffness, alpha), alpha)
    site_unit: NamedTuple = IH.build(sites) if terms.inhomogeneity.active else IH.Homogeneous()
    onsite: NamedTuple = onsite_harmonic.Harmonic()
    if terms.onsite.active and terms.onsite.potential == "quartic":
        onsite = onsite_quartic.Quartic(float(terms.onsite.beta))
    elif terms.onsite.active and terms.onsite.potential == "pendulum":
        onsite = onsite_pendulum.Pendulum(np.ascontiguousarray(LTm.pendulum_scales(terms, sites), dtype=float))
    gamma = 0.0 if damping is None else damping.onsite
    eta = 0.0 if damping is None else damping.contact
    od: NamedTuple = OD.OnsiteDamping(float(gamma)) if gamma != 0.0 else OD.NoOnsiteDamping()
    cd: NamedTuple = CD.ContactDamping(float(eta)) if eta != 0.0 else CD.NoContactDamping()
    dis: NamedTuple = SI.NoDissipation()
    if damping is not None:
        dis = SI.Dissipation(1.0 if dscale is None else float(dscale))
    return SI.Imperfect(float(alpha), int(mode), bool(periodic), contact, site_unit, onsite, od, cd, dis, np.empty(N),
                        np.empty(N), np.empty(N), np.empty(N))
