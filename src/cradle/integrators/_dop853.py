"""DOP853 (Dormand-Prince 8(5,3)) with error control, compiled with numba.

Same tableau (taken from ``scipy.integrate._ivp.dop853_coefficients``),
error norm and step-size controller (safety 0.9, factors in [0.2, 10],
exponent -1/8) as ``scipy.integrate.DOP853`` (Hairer, Norsett & Wanner,
Solving ODEs I, sec. II.5), but the whole loop runs in numba: the steps are
shortened so that they end exactly on the output times (no dense output),
and the invariants are monitored after every accepted step. Used by
``method="dop853_numba"`` of :func:`cradle.integrators.integrate_lattice`
(kind 0, (nc)/(meca), y = [x, v]; kind 2, (ncdamped) with its dissipated
energy, y = [x, v, s D]; kind 4, the imperfect cradle (ncimperfect), y = [x, v], or with the same
damping y = [x, v, s D]) and :func:`cradle.integrators.integrate_dps`
(kind 1, (dfnls), y = real view of A; kind 3, the damped (dpsdamped), y = real view of A and the two
dissipated amounts; kind 5, (dpsimperfect) of cradle.models.dps_sites, y = real view of A). ``par`` is
a float64 array of the kind's parameters: kind 1 reads 1/(2 tau0) = par[0]; kind 2 gamma = par[0],
eta = par[1] and the scale s = par[2] of D in the state; kind 3 the ``par`` of
:func:`cradle.integrators._kernels.dps_damped_rhs`; kind 4 the ``par`` of
:func:`cradle.integrators._lattice_terms.pack` (site coefficients and damping); kind 5 that of
:func:`cradle.integrators._kernels_dps_sites.pack`; kind 0 none.
Kind 2 with ``events`` (the default of a damped lattice run) is stepped by
:func:`cradle.integrators._dop853_onset.run_events` instead: the same steps, except that they end at
the contact events.
"""
from __future__ import annotations

import math
import time
from types import ModuleType

import numpy as np
from numba import njit

from cradle.integrators import _cache, _kernels as K, _kernels_dps_sites as KS, _lattice_terms as LT

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating


def _scipy_dop853_tableau() -> ModuleType:
    """scipy's DOP853 tableau (scipy/integrate/_ivp/dop853_coefficients.py, numpy only), loaded
    from its file: importing it as scipy.integrate._ivp... would import all of scipy.integrate
    (0.5 s per process start)."""
    import importlib.util
    from pathlib import Path

    scipy = importlib.util.find_spec("scipy")
    assert scipy is not None and scipy.origin is not None, "scipy is a dependency"
    scipy_dir = Path(scipy.origin).parent
    spec = importlib.util.spec_from_file_location(
        "_cradle_dop853_coefficients", scipy_dir / "integrate" / "_ivp" / "dop853_coefficients.py")
    assert spec is not None and spec.loader is not None, "a .py file has a source loader"
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


_c = _scipy_dop853_tableau()

_NS = _c.N_STAGES  # 12
A = np.ascontiguousarray(_c.A[:_NS, :_NS], dtype=float)
B = np.ascontiguousarray(_c.B, dtype=float)
C = np.ascontiguousarray(_c.C[:_NS], dtype=float)
E3 = np.ascontiguousarray(_c.E3, dtype=float)
E5 = np.ascontiguousarray(_c.E5, dtype=float)

LATTICE, DPS, LATTICE_DAMPED, DPS_DAMPED = 0, 1, 2, 3
LATTICE_TERMS = 4
DPS_SITES = 5   # (dpsimperfect), y = real view of A, par of _kernels_dps_sites.pack


@njit(cache=True)
def _work_size(kind, n):
    """Length of the force work arrays f, F: the number of beads for the lattice kinds."""
    if kind == 0:
        return n // 2
    if kind == 2:
        return (n - 1) // 2
    if kind == 4:   # y = [x, v] or [x, v, s D]
        return n // 2
    return 1


@njit(cache=True)
def _rhs(kind, y, dy, f, F, alpha, mode, par, periodic):
    if kind == 0:
        K.lattice_rhs(y, dy, f, F, alpha, mode, periodic)
    elif kind == 2:
        K.lattice_damped_rhs(y, dy, f, F, alpha, mode, par[0], par[1], par[2], periodic)
    elif kind == 3:
        K.dps_damped_rhs(y, dy, alpha, par, periodic)
    elif kind == 4:
        LT.terms_rhs(y, dy, f, F, alpha, mode, par, periodic)
    elif kind == 5:
        KS.dps_sites_rhs(y, dy, alpha, par, periodic)
    else:
        K.dps_rhs(y, dy, alpha, par[0], periodic)


@njit(cache=True)
def _monitor(kind, y, alpha, mode, par, periodic, stats):
    """Update the invariant drifts in ``stats`` after an accepted step.

    kind 0: stats = [H0, max |H-H0|/|H0|, max compression, H]
    kind 1: stats = [l2_0, S0, max |l2-l2_0|/l2_0, max |S-S0|/S0] (H = -S/((alpha+1) tau0))
    kind 2: stats = [H0, max |H+D-H0|/|H0|, max compression, H, s] (y[-1] = s D): the stored plus
    dissipated energy H + D is conserved by (ncdamped), its drift is the integrator's error
    kind 4: the same as kind 2 (D = 0 on y = [x, v] without damping) with the generalised (ham) of
    (ncimperfect) (:func:`._lattice_terms.terms_energy`, its site coefficients in ``par``)
    kind 3: the same as kind 1 with l2 + Q_l2 and S + Q_S (the balance laws: Q the dissipated amounts, y's
    two last entries)
    kind 5: stats = [l2_0, H0, max |l2-l2_0|/l2_0, max |H-H0|/|H0|] with the weighted l2 = sum m_n |A_n|^2 and the H
    of (dpsimperfect)
    """
    if kind == 0:
        n = y.shape[0] // 2
        H, cm = K.lattice_energy(y[:n], y[n:], alpha, mode, periodic)
        sc = abs(stats[0]) if stats[0] != 0.0 else 1.0
        stats[1] = max(stats[1], abs(H - stats[0]) / sc)
        stats[2] = max(stats[2], cm)
        stats[3] = H
    elif kind == 2:
        n = (y.shape[0] - 1) // 2
        H, cm = K.lattice_energy(y[:n], y[n:2 * n], alpha, mode, periodic)
        sc = abs(stats[0]) if stats[0] != 0.0 else 1.0
        stats[1] = max(stats[1], abs(H + y[2 * n] / stats[4] - stats[0]) / sc)
        stats[2] = max(stats[2], cm)
        stats[3] = H
    elif kind == 4:
        n = y.shape[0] // 2
        H, cm = LT.terms_energy(y[:n], y[n:2 * n], alpha, mode, par, periodic)
        sc = abs(stats[0]) if stats[0] != 0.0 else 1.0
        D = y[2 * n] / stats[4] if y.shape[0] > 2 * n else 0.0
        stats[1] = max(stats[1], abs(H + D - stats[0]) / sc)
        stats[2] = max(stats[2], cm)
        stats[3] = H
    elif kind == 5:
        l2, H, _pr, _pi = KS.dps_sites_invariants(y, alpha, par, periodic)
        s0 = stats[0] if stats[0] != 0.0 else 1.0
        s1 = abs(stats[1]) if stats[1] != 0.0 else 1.0
        stats[2] = max(stats[2], abs(l2 - stats[0]) / s0)
        stats[3] = max(stats[3], abs(H - stats[1]) / s1)
    elif kind == 3:
        n = y.shape[0] - 2
        l2, S, _pr, _pi = K.dps_invariants(y[:n], alpha, periodic)
        s0 = stats[0] if stats[0] != 0.0 else 1.0
        s1 = stats[1] if stats[1] != 0.0 else 1.0
        stats[2] = max(stats[2], abs(l2 + y[n] - stats[0]) / s0)
        stats[3] = max(stats[3], abs(S + y[n + 1] - stats[1]) / s1)
    else:
        l2, S, _pr, _pi = K.dps_invariants(y, alpha, periodic)
        s0 = stats[0] if stats[0] != 0.0 else 1.0
        s1 = stats[1] if stats[1] != 0.0 else 1.0
        stats[2] = max(stats[2], abs(l2 - stats[0]) / s0)
        stats[3] = max(stats[3], abs(S - stats[1]) / s1)


@njit(cache=True)
def dop853_run(kind, y, fy, tgrid, k, state, max_steps, rtol, atol, A, B, C, E3, E5,
               alpha, mode, par, periodic, Y, shift, stats, counts):
    """Advance with DOP853 until tgrid[-1] or ``max_steps`` accepted steps; resumable.

    ``y`` (state) and ``fy`` (= f(y), FSAL) are updated in place; ``state`` =
    [t, h]; interval k ends at tgrid[k+1], where the state is stored in row
    k + 1 - shift of Y (skipped if negative). ``counts`` += [accepted steps,
    rhs evaluations, rejected steps]. Returns (k, status), status -1 if the
    step size underflowed.
    """
    n = y.shape[0]
    nf = _work_size(kind, n)
    f = np.empty(nf)
    F = np.empty(nf)
    Ks = np.empty((13, n))
    ys = np.empty(n)
    ynew = np.empty(n)
    err5 = np.empty(n)
    err3 = np.empty(n)
    nint = tgrid.shape[0] - 1
    t = state[0]
    h = state[1]
    taken = 0
    nfev = 0
    nrej = 0
    status = 0
    while k < nint and taken < max_steps:
        t_target = tgrid[k + 1]
        rejected = False
        while True:
            min_step = 10.0 * max(abs(t), 1e-300) * 2.220446049250313e-16
            if h < min_step:
                status = -1
                break
            h_try = h
            clipped = t + h >= t_target
            if clipped:
                h_try = t_target - t
            for i in range(n):
                Ks[0, i] = fy[i]
            # stage loops ordered j-outer / i-inner so that they vectorise
            for s in range(1, _NS):
                for i in range(n):
                    ys[i] = y[i]
                for j in range(s):
                    cj = h_try * A[s, j]
                    if cj != 0.0:
                        for i in range(n):
                            ys[i] += cj * Ks[j, i]
                _rhs(kind, ys, Ks[s], f, F, alpha, mode, par, periodic)
            for i in range(n):
                ynew[i] = y[i]
                err5[i] = 0.0
                err3[i] = 0.0
            for j in range(_NS + 1):
                if j < _NS and B[j] != 0.0:
                    cj = h_try * B[j]
                    for i in range(n):
                        ynew[i] += cj * Ks[j, i]
                if j == _NS:
                    _rhs(kind, ynew, Ks[_NS], f, F, alpha, mode, par, periodic)
                c5 = E5[j]
                c3 = E3[j]
                for i in range(n):
                    err5[i] += c5 * Ks[j, i]
                    err3[i] += c3 * Ks[j, i]
            nfev += _NS
            e5 = 0.0
            e3 = 0.0
            for i in range(n):
                sc = atol + max(abs(y[i]), abs(ynew[i])) * rtol
                e5 += (err5[i] / sc) ** 2
                e3 += (err3[i] / sc) ** 2
            if e5 == 0.0 and e3 == 0.0:
                err = 0.0
            else:
                err = h_try * e5 / math.sqrt((e5 + 0.01 * e3) * n)
            if err < 1.0:
                if err == 0.0:
                    fac = 10.0
                else:
                    fac = min(10.0, 0.9 * err ** (-1.0 / 8.0))
                if rejected:
                    fac = min(1.0, fac)
                h_new = h_try * fac
                if clipped:  # a short step to hit t_target says little about the natural step
                    h_new = max(h_new, h)
                h = h_new
                break
            h = h_try * max(0.2, 0.9 * err ** (-1.0 / 8.0))
            rejected = True
            nrej += 1
        if status != 0:
            break
        for i in range(n):
            y[i] = ynew[i]
            fy[i] = Ks[_NS, i]
        t = t_target if clipped else t + h_try
        taken += 1
        _monitor(kind, y, alpha, mode, par, periodic, stats)
        if clipped:
            row = k + 1 - shift
            if row >= 0:
                for i in range(n):
                    Y[row, i] = y[i]
            k += 1
    state[0] = t
    state[1] = h
    counts[0] += taken
    counts[1] += nfev
    counts[2] += nrej
    return k, status


def initial_step(fun, y0, f0, t_bound, rtol, atol, order=7):
    """Initial step of scipy's ``select_initial_step`` (Hairer et al., sec. II.4)."""
    scale = atol + np.abs(y0) * rtol
    rms = lambda z: float(np.sqrt(np.mean(z * z)))  # noqa: E731
    d0, d1 = rms(y0 / scale), rms(f0 / scale)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, t_bound)
    f1 = fun(y0 + h0 * f0)
    d2 = rms((f1 - f0) / scale) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / (order + 1))
    return min(100 * h0, h1, t_bound)


def run_dop853(kind, y0, t_out, rtol, atol, alpha, mode, par, periodic, stats, progress, state=None,
               counts=None, t_bound=None, events=None, event_times=None):
    """Python driver of :func:`dop853_run`: returns (Y (T, n), n_steps, n_rhs_evals).

    ``stats`` must hold the initial invariants (see :func:`_monitor`) and is
    updated in place. ``progress(t, t_final)`` is called about once per second.

    Continuing a run: ``state`` = [t, h] (float64, updated in place) is where the previous call
    stopped (``y0`` its last row, t <= t_out[0]) and the step it would take next (h = 0 on the
    first call: the initial step is chosen as below); ``counts``
    (int64 [steps, rhs evaluations, -]) accumulates over the calls. Steps end on every output
    time, so a run cut into consecutive calls this way takes exactly the steps of one call: the
    rows are bitwise equal (one more rhs evaluation per call, for f(y0)). Without ``state`` the
    run starts at t = 0 with scipy's initial step for [0, ``t_bound``] (default t_out[-1]: the
    first of several calls passes the last time of the whole run).

    ``events`` (kind 2 only; int64, 4 entries, incremented): the steps end at the contact events
    (:mod:`cradle.integrators._dop853_onset`); it counts [events located, switches left unlocated,
    re-steps, re-steps failing the error test], and ``event_times`` (float64) receives the times of the
    first located events. A run with events starts at t = 0 (no ``state``).
    """
    n = y0.size
    T = t_out.size
    par = np.ascontiguousarray(par, dtype=np.float64).reshape(-1)   # one compiled signature for every kind
    Y = np.empty((T, n))
    t_start = 0.0 if state is None else float(state[0])
    if t_out[0] == t_start:
        tgrid, shift = t_out, 0
        Y[0] = y0
    else:
        tgrid, shift = np.concatenate(([t_start], t_out)), 1
    y = y0.copy()
    fy = np.empty(n)
    nf = _work_size(kind, n)
    f, F = np.empty(nf), np.empty(nf)

    def fun(z):
        dz = np.empty_like(z)
        _rhs(kind, z, dz, f, F, alpha, mode, par, periodic)
        return dz

    fy[:] = fun(y)
    if counts is None:
        counts = np.array([0, 0, 0], dtype=np.int64)
    n0, f0 = int(counts[0]), int(counts[1])
    counts[1] += 1
    t_final = float(tgrid[-1])
    nint = tgrid.size - 1
    if nint == 0:
        return Y, 0, 1
    if state is None:
        state = np.zeros(2)
    if state[1] == 0.0:
        state[1] = initial_step(fun, y, fy, t_final if t_bound is None else float(t_bound), rtol, atol)
        counts[1] += 1
    budget = np.iinfo(np.int64).max if progress is None else max(1, int(2e6 / n))
    if events is not None:
        from cradle.integrators import _dop853_onset

        side = _dop853_onset.states(y, bool(periodic), float(par[1]))
        state = np.array([state[0], state[1], float(_dop853_onset.PLAIN)])
        if event_times is None:
            event_times = np.empty(0)
    k = 0
    while k < nint:
        t0 = time.perf_counter()
        n_before = counts[0]
        if events is not None:
            k, status = _dop853_onset.run_events(y, fy, tgrid, k, state, budget, float(rtol), float(atol), A, B, C, E3,
                                                 E5, float(alpha), int(mode), par, bool(periodic), Y, shift, stats,
                                                 counts, side, events, event_times)
        else:
            k, status = dop853_run(kind, y, fy, tgrid, k, state, budget, float(rtol), float(atol), A, B, C, E3, E5,
                                   float(alpha), int(mode), par, bool(periodic), Y, shift, stats, counts)
        if status != 0:
            raise RuntimeError(f"dop853_numba: step size underflow at t={state[0]!r}")
        if progress is not None:
            elapsed = time.perf_counter() - t0
            taken = int(counts[0] - n_before)
            if elapsed > 0 and taken > 0:
                budget = max(1, int(taken / elapsed))
            progress(float(state[0]) if k < nint else t_final, t_final)
    return Y, int(counts[0]) - n0, int(counts[1]) - f0
