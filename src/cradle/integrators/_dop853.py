"""DOP853 (Dormand-Prince 8(5,3)) with error control, compiled with numba: the one DOP853 loop.

Same tableau (taken from ``scipy.integrate._ivp.dop853_coefficients``),
error norm and step-size controller (safety 0.9, factors in [0.2, 10],
exponent -1/8) as ``scipy.integrate.DOP853`` (Hairer, Norsett & Wanner,
Solving ODEs I, sec. II.5), but the whole loop runs in numba: the steps are
shortened so that they end exactly on the output times (no dense output),
and the invariants are monitored after every accepted step. Used by
``method="dop853_numba"`` of :func:`cradle.integrators.integrate_lattice` and
:func:`cradle.integrators.integrate_dps`.

What is integrated is a *system*: a ``typing.NamedTuple`` of :mod:`cradle.integrators.systems` (the
lattice (nc)/(meca), the damped (ncdamped), the imperfect (ncimperfect) with its terms, the DpS (dfnls) and
its damped and site-dependent forms), whose right-hand side :func:`rhs` and invariants :func:`monitor` are
generic operations (:mod:`cradle.integrators._generic`): :func:`dop853_run` is compiled once per system
type, with that system's right-hand side in its stages. The contact events of (ncdamped)
(:mod:`cradle.integrators._dop853_events`: steps ending where a bond's force switches) are another
argument of the same loop, ``events``: :class:`NoEvents` (the plain DOP853 step, nothing else compiled in)
or :class:`cradle.integrators._dop853_events.ContactEvents`.
"""
from __future__ import annotations

import math
import time
from types import ModuleType
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
from numba import njit

from cradle.integrators import _cache
from cradle.integrators._generic import absent, generic, implements

if TYPE_CHECKING:
    from collections.abc import Callable

    from cradle.integrators._types import Floats, Ints

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


@generic
def rhs(system: NamedTuple, y: Floats, dy: Floats) -> None:
    """dy = f(y), the right-hand side of ``system`` at the state y."""


@generic
def monitor(system: NamedTuple, y: Floats, stats: Floats) -> None:
    """Update the invariants' drifts in ``stats`` after an accepted step (the system's own layout)."""


class PlainTime(NamedTuple):
    """The step variable of a plain DOP853 step: t itself (no weight on the stages)."""

    sub: int


class SubstitutedTime(NamedTuple):
    """The step variable of a step of :mod:`._dop853_events`: t (PLAIN), or u with t = t0 + u^2 (SQRT_START) or
    t = t0 + h^2 - (h - u)^2 (SQRT_END); the stages carry the weight dt/du."""

    sub: int


class NoEvents(NamedTuple):
    """No event location: every step is DOP853's step."""

    n: int


PLAIN, SQRT_START, SQRT_END = 0, 1, 2


@njit(cache=True)
def speed(sub: int, c: float, h: float) -> float:
    """dt/du at u = c h of a step of length h in u: t = t0 + u^2 (SQRT_START), t = t0 + h^2 - (h - u)^2
    (SQRT_END), u itself (PLAIN)."""
    if sub == SQRT_START:
        return 2.0 * c * h
    if sub == SQRT_END:
        return 2.0 * h * (1.0 - c)
    return 1.0


@generic
def first_stage(tv: NamedTuple, Ks: Floats, fy: Floats, h: float) -> None:
    """Ks[0] = the first stage (fy, weighted by the step variable's dt/du)."""


@implements(first_stage, PlainTime)
@njit(cache=True)
def _first_plain(tv: PlainTime, Ks: Floats, fy: Floats, h: float) -> None:
    for i in range(fy.shape[0]):
        Ks[0, i] = fy[i]


@implements(first_stage, SubstitutedTime)
@njit(cache=True)
def _first_substituted(tv: SubstitutedTime, Ks: Floats, fy: Floats, h: float) -> None:
    w = speed(tv.sub, 0.0, h)
    for i in range(fy.shape[0]):
        Ks[0, i] = w * fy[i]    # w = 1 exactly on a plain step


@generic
def weigh_stage(tv: NamedTuple, Ks: Floats, s: int, c: float, h: float) -> None:
    """Weigh stage s (evaluated at u = c h) by dt/du."""


@implements(weigh_stage, SubstitutedTime)
@njit(cache=True)
def _weigh_substituted(tv: SubstitutedTime, Ks: Floats, s: int, c: float, h: float) -> None:
    if tv.sub != PLAIN:
        w = speed(tv.sub, c, h)
        for i in range(Ks.shape[1]):
            Ks[s, i] *= w


@generic
def end_rates(tv: NamedTuple, Ks: Floats, fnew: Floats, h: float) -> None:
    """fnew = f(ynew) (before the end stage is weighed) and weigh the end stage."""


@implements(end_rates, SubstitutedTime)
@njit(cache=True)
def _end_substituted(tv: SubstitutedTime, Ks: Floats, fnew: Floats, h: float) -> None:
    for i in range(fnew.shape[0]):
        fnew[i] = Ks[_NS, i]
    _weigh_substituted(tv, Ks, _NS, 1.0, h)


@njit(cache=True)
def trial(system: NamedTuple, tv: NamedTuple, y: Floats, fy: Floats, h: float, Ks: Floats, ys: Floats, ynew: Floats,
          fnew: Floats, err5: Floats, err3: Floats, rtol: float, atol: float, A: Floats, B: Floats, C: Floats,
          E3: Floats, E5: Floats) -> float:
    """One DOP853 step of length h in the step variable ``tv`` from (y, fy = f(y)): ynew, fnew = f(ynew);
    returns the error norm (accept if < 1)."""
    n = y.shape[0]
    first_stage(tv, Ks, fy, h)
    # stage loops ordered j-outer / i-inner so that they vectorise
    for s in range(1, _NS):
        for i in range(n):
            ys[i] = y[i]
        for j in range(s):
            cj = h * A[s, j]
            if cj != 0.0:
                for i in range(n):
                    ys[i] += cj * Ks[j, i]
        rhs(system, ys, Ks[s])
        weigh_stage(tv, Ks, s, C[s], h)
    for i in range(n):
        ynew[i] = y[i]
        err5[i] = 0.0
        err3[i] = 0.0
    for j in range(_NS + 1):
        if j < _NS and B[j] != 0.0:
            cj = h * B[j]
            for i in range(n):
                ynew[i] += cj * Ks[j, i]
        if j == _NS:
            rhs(system, ynew, Ks[_NS])
            end_rates(tv, Ks, fnew, h)
        c5 = E5[j]
        c3 = E3[j]
        for i in range(n):
            err5[i] += c5 * Ks[j, i]
            err3[i] += c3 * Ks[j, i]
    e5 = 0.0
    e3 = 0.0
    for i in range(n):
        sc = atol + max(abs(y[i]), abs(ynew[i])) * rtol
        e5 += (err5[i] / sc) ** 2
        e3 += (err3[i] / sc) ** 2
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return h * e5 / math.sqrt((e5 + 0.01 * e3) * n)


# --- what the event location adds to a step (NoEvents: nothing) ------------------------------------------------


@generic
def end_buffer(events: NamedTuple, Ks: Floats) -> Floats:
    """The array receiving f(ynew) of a trial: the row Ks[_NS] itself for plain steps (no copy)."""


@implements(end_buffer, NoEvents)
@njit(cache=True)
def _buffer_plain(events: NoEvents, Ks: Floats) -> Floats:
    return Ks[_NS]


@generic
def start_step(events: NamedTuple) -> int:
    """The variable (PLAIN, SQRT_START) of the next step, which starts now."""


@implements(start_step, NoEvents)
@njit(cache=True)
def _start_plain(events: NoEvents) -> int:
    return PLAIN


@generic
def time_variable(events: NamedTuple, sub: int) -> NamedTuple:
    """The step variable of a trial in ``sub``."""


@implements(time_variable, NoEvents)
@njit(cache=True)
def _time_plain(events: NoEvents, sub: int) -> NamedTuple:
    return PlainTime(PLAIN)


@generic
def locate(events: NamedTuple, system: NamedTuple, y: Floats, fy: Floats, ynew: Floats, fnew: Floats, t: float,
           h: float, h_try: float, hu: float, sub: int, clipped: bool, Ks: Floats, ys: Floats, err5: Floats,
           err3: Floats, rtol: float, atol: float, A: Floats, B: Floats, C: Floats, E3: Floats,
           E5: Floats) -> tuple[bool, float, float, bool, bool, int, int]:
    """After an accepted trial: (retry, h, h_step, clipped, restepped, extra rhs evaluations, extra rejections);
    ``retry``: the step is rejected and a shorter one is tried with the new h."""


@implements(locate, NoEvents)
@njit(cache=True)
def _locate_plain(events: NoEvents, system: NamedTuple, y: Floats, fy: Floats, ynew: Floats, fnew: Floats, t: float,
                  h: float, h_try: float, hu: float, sub: int, clipped: bool, Ks: Floats, ys: Floats, err5: Floats,
                  err3: Floats, rtol: float, atol: float, A: Floats, B: Floats, C: Floats, E3: Floats,
                  E5: Floats) -> tuple[bool, float, float, bool, bool, int, int]:
    return False, h, h_try, clipped, False, 0, 0


@generic
def commit(events: NamedTuple, y: Floats, restepped: bool) -> None:
    """The accepted step's end: the bonds' states and the next step's variable."""


@njit(cache=True)
def dop853_run(system: NamedTuple, events: NamedTuple, y: Floats, fy: Floats, tgrid: Floats, k: int, state: Floats,
               max_steps: int, rtol: float, atol: float, A: Floats, B: Floats, C: Floats, E3: Floats, E5: Floats,
               Y: Floats, shift: int, stats: Floats, counts: Ints) -> tuple[int, int]:
    """Advance ``system`` with DOP853 until tgrid[-1] or ``max_steps`` accepted steps; resumable.

    ``y`` (state) and ``fy`` (= f(y), FSAL) are updated in place; ``state`` = [t, h]; interval k ends at
    tgrid[k+1], where the state is stored in row k + 1 - shift of Y (skipped if negative). ``events``:
    :class:`NoEvents`, or the contact events of (ncdamped) (:mod:`._dop853_events`, their counters in it).
    ``counts`` += [accepted steps, rhs evaluations, rejected steps]. Returns (k, status), status -1 if the
    step size underflowed.
    """
    n = y.shape[0]
    Ks = np.empty((13, n))
    ys = np.empty(n)
    ynew = np.empty(n)
    fnew = end_buffer(events, Ks)
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
        sub0 = start_step(events)
        while True:
            min_step = 10.0 * max(abs(t), 1e-300) * 2.220446049250313e-16
            if h < min_step:
                status = -1
                break
            h_try = h
            clipped = t + h >= t_target
            if clipped:
                h_try = t_target - t
            sub = sub0
            hu = h_try if sub == PLAIN else math.sqrt(h_try)     # the step's length in its variable
            err = trial(system, time_variable(events, sub), y, fy, hu, Ks, ys, ynew, fnew, err5, err3, rtol, atol,
                        A, B, C, E3, E5)
            nfev += _NS
            if err >= 1.0:
                fac = max(0.2, 0.9 * err ** (-1.0 / 8.0))
                h = h_try * fac if sub == PLAIN else h_try * fac * fac
                rejected = True
                nrej += 1
                continue
            if sub == PLAIN:    # h kept after a step in u: it says little about the step in t
                fac = 10.0 if err == 0.0 else min(10.0, 0.9 * err ** (-1.0 / 8.0))
                if rejected:
                    fac = min(1.0, fac)
                h_new = h_try * fac
                if clipped:  # a short step to hit t_target says little about the natural step
                    h_new = max(h_new, h)
                h = h_new
            retry, h, h_step, clipped, restepped, more, again = locate(
                events, system, y, fy, ynew, fnew, t, h, h_try, hu, sub, clipped, Ks, ys, err5, err3, rtol, atol,
                A, B, C, E3, E5)
            nfev += more
            if retry:
                rejected = True
                nrej += again
                continue
            break
        if status != 0:
            break
        for i in range(n):
            y[i] = ynew[i]
            fy[i] = fnew[i]
        t = t_target if clipped else t + h_step
        commit(events, y, restepped)
        taken += 1
        monitor(system, y, stats)
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


def initial_step(fun: Callable[[Floats], Floats], y0: Floats, f0: Floats, t_bound: float, rtol: float, atol: float,
                 order: int = 7) -> float:
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


def run_dop853(system: NamedTuple, y0: Floats, t_out: Floats, rtol: float, atol: float, stats: Floats,
               progress: Callable[[float, float], None] | None, state: Floats | None = None,
               counts: Ints | None = None, t_bound: float | None = None,
               events: NamedTuple | None = None) -> tuple[Floats, int, int]:
    """Python driver of :func:`dop853_run` on ``system``: returns (Y (T, n), n_steps, n_rhs_evals).

    ``stats`` must hold the initial invariants (the system's :func:`monitor` layout) and is
    updated in place. ``progress(t, t_final)`` is called about once per second.

    Continuing a run: ``state`` = [t, h] (float64, updated in place) is where the previous call
    stopped (``y0`` its last row, t <= t_out[0]) and the step it would take next (h = 0 on the
    first call: the initial step is chosen as below); ``counts``
    (int64 [steps, rhs evaluations, -]) accumulates over the calls. Steps end on every output
    time, so a run cut into consecutive calls this way takes exactly the steps of one call: the
    rows are bitwise equal (one more rhs evaluation per call, for f(y0)). Without ``state`` the
    run starts at t = 0 with scipy's initial step for [0, ``t_bound``] (default t_out[-1]: the
    first of several calls passes the last time of the whole run).

    ``events``: None, or the contact events of (ncdamped) built for y0
    (:func:`cradle.integrators._dop853_events.contact_events`); a run with events starts at t = 0.
    """
    n = y0.size
    T = t_out.size
    Y = np.empty((T, n))
    t_start = 0.0 if state is None else float(state[0])
    if t_out[0] == t_start:
        tgrid, shift = t_out, 0
        Y[0] = y0
    else:
        tgrid, shift = np.concatenate(([t_start], t_out)), 1
    y = y0.copy()
    fy = np.empty(n)

    def fun(z: Floats) -> Floats:
        dz = np.empty_like(z)
        rhs(system, z, dz)
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
    if events is None:
        events = NoEvents(n)
    k = 0
    while k < nint:
        t0 = time.perf_counter()
        n_before = counts[0]
        k, status = dop853_run(system, events, y, fy, tgrid, k, state, budget, float(rtol), float(atol), A, B, C, E3,
                               E5, Y, shift, stats, counts)
        if status != 0:
            raise RuntimeError(f"dop853_numba: step size underflow at t={state[0]!r}")
        if progress is not None:
            elapsed = time.perf_counter() - t0
            taken = int(counts[0] - n_before)
            if elapsed > 0 and taken > 0:
                budget = max(1, int(taken / elapsed))
            progress(float(state[0]) if k < nint else t_final, t_final)
    return Y, int(counts[0]) - n0, int(counts[1]) - f0


absent(weigh_stage, PlainTime)
absent(end_rates, PlainTime)   # fnew is the row Ks[_NS] itself (end_buffer)
absent(commit, NoEvents)
