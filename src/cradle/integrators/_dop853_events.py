"""Contact events of the damped lattice (ncdamped) in DOP853: steps end where a bond's force switches.

Why DOP853 loses its order on (ncdamped)
----------------------------------------
The bond force of (ncdamped), g = max(c^alpha + eta c^(alpha-1) c', 0) H(c) (c the compression, q =
c + eta c'), and the dissipated power P (whose integral D is a component of the state) are smooth
except where a bond changes state, OPEN (c <= 0), CLIPPED (c > 0, q <= 0: no force) or PUSHING:

* onset, OPEN -> PUSHING (c crossing 0 upwards; q = eta c' > 0 there): after it g rises like
  (t - t_on)^(1/2) (eta > 0) or (t - t_on)^(3/2) (eta = 0);
* Hertz release, PUSHING -> OPEN (eta = 0 only): g falls like (t_off - t)^(3/2);
* clip and unclip, PUSHING <-> CLIPPED (q crossing 0; with eta > 0 every release is a clip first, c' < 0
  at c = 0 making q < c): g = c^(alpha-1) q has a kink;
* release of a clipped bond, CLIPPED -> OPEN: g = 0 on both sides, but P holds the elastic part
  -c^alpha c' of the clipped bond (the energy (ham) counts its potential while no force acts), which
  falls like (t_off - t)^(3/2): x and v are smooth there, D is not.

A Runge-Kutta step across such a point has an error O(h^(beta+1)) (beta = 1/2, 3/2 or 1) whatever its
order; so has its embedded error estimate, with a ratio to the true error that depends on where the
point falls in the step. Observed: the error falls like rtol^0.6-0.9 (docs/damped-orders.md).

The treatment
-------------
``side`` holds every bond's state at the current step's start. After an accepted step, the bonds whose
state at the step's end differs (an O(N) check; a step without one is DOP853's step, bitwise):

1. locate: each such bond's first switch (:func:`_transition`: s = q for a clip or unclip, else s = c)
   from the cubic Hermite of s through the step's end values and rates (from the states and their
   FSAL derivatives: no force evaluation); the earliest, theta* of the step, is the event, and every
   bond switching within ``GROUP`` of it (the mirror bonds of a symmetric packet) switches with it;
2. refine: re-step from the step's start to the event and correct its time by Newton on the bond's s
   at the re-step's end (s and s' from its state and FSAL derivative), until the correction is below
   rtol^(2/3) h (at most ``MAX_NEWTON`` re-steps): an onset's force rises like (t - t_on)^(1/2) at
   worst, so an onset misplaced by delta changes the step's impulse by a relative (delta/h)^(3/2),
   held to rtol. The re-step lies on the smooth side of the event, so its end values carry a smooth
   step's error, which the crossing step's own interpolants (Hermite or DOP853's 7th-order dense
   output, 3 more stages) do not: they give the first guess only, and the free Hermite is used;
3. the step that ends at the event replaces the crossing step (a re-step failing the error test is
   a rejected step: a shorter one is tried); the switching bonds take their new state;
4. square-root time at the singular end of a step: the solution is a smooth function of
   u = (t - t_on)^(1/2) after an onset (g and P are powers of c ~ c'(t_on)(t - t_on)) and of
   w = (t_off - t)^(1/2) before a release, so the step that starts at an onset is taken in u
   (t = t_on + u^2, dy/du = 2 u f(y), one step of length h^(1/2); its events are located as above,
   in u), and the re-step that ends at a release in w (t = t_off - w^2). A clip is only a kink:
   plain steps on both sides. After the step in u the controller grades the steps away from the onset.

In the code: :class:`ContactEvents` is the ``events`` argument of the one DOP853 loop
(:func:`cradle.integrators._dop853.dop853_run`); its implementations of the loop's operations choose each
step's variable (``start_step``, ``time_variable``), locate and refine the events after an accepted trial
(``locate``) and set the bonds' states at the step's end (``commit``).

An event costs the crossing step it replaces and its re-steps (12 force evaluations each). A bond that
switches twice inside one step (a contact shorter than the step) is not seen; a switch that cannot be
located (Newton leaving the step) keeps the crossing step, counted in ``ev[1]``.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
from numba import njit

from cradle.integrators import _cache

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating

from cradle.integrators._dop853 import (  # noqa: E402
    _NS,
    PLAIN,
    SQRT_END,
    SQRT_START,
    SubstitutedTime,
    commit,
    end_buffer,
    locate,
    speed,
    start_step,
    time_variable,
    trial,
)
from cradle.integrators._generic import implements  # noqa: E402

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from cradle.integrators._types import Floats, Ints

OPEN, CLIPPED, PUSHING = 0, 1, 2
#: an event within EDGE h of a step's start or end is left at that end
EDGE = 1e-9
#: bonds whose switching times lie within GROUP h of the earliest switch with it
GROUP = 1e-7
#: most re-steps spent locating one event
MAX_NEWTON = 4


@njit(cache=True)
def _state(y: Floats, N: int, b: int, eta: float) -> int:
    """Bond b's (beads b, b+1 mod N) contact state in y: OPEN (c <= 0), CLIPPED (c > 0, c + eta c' <= 0:
    no force) or PUSHING."""
    m = b + 1 if b + 1 < N else 0
    c = y[b] - y[m]
    if c <= 0.0:
        return OPEN
    if eta == 0.0 or c + eta * (y[N + b] - y[N + m]) > 0.0:
        return PUSHING
    return CLIPPED


@njit(cache=True)
def states(y: Floats, periodic: bool, eta: float) -> NDArray[np.int8]:
    """Every bond's contact state (:func:`_state`) in y = [x, v, s D]: the ``side`` a run starts with."""
    N = (y.shape[0] - 1) // 2
    nb = N if periodic else N - 1
    out = np.empty(nb, dtype=np.int8)
    for b in range(nb):
        out[b] = _state(y, N, b, eta)
    return out


@njit(cache=True)
def _transition(a: int, z: int, eta: float) -> tuple[bool, int]:
    """(q-type, next state) of the first switch of a bond going from state a to state z within a step:
    q-type when q = c + eta c' crosses 0 (a clip or unclip), else c crosses 0 (onset or release)."""
    if a == PUSHING:
        if eta > 0.0:
            return True, CLIPPED    # with eta > 0 a release is a clip first (q < c when c' < 0)
        return False, OPEN
    if a == CLIPPED:
        if z == PUSHING:
            return True, PUSHING
        return False, OPEN
    return False, PUSHING           # an onset pushes: q = eta c' > 0 at c = 0


@njit(cache=True)
def _switch(y: Floats, dy: Floats, N: int, b: int, eta: float, qtype: bool) -> tuple[float, float]:
    """(s, ds/dt) of bond b's switching function: q = c + eta c' (qtype) or c, from the state y and its
    derivative dy = f(y)."""
    m = b + 1 if b + 1 < N else 0
    c = y[b] - y[m]
    cd = y[N + b] - y[N + m]
    if qtype:
        return c + eta * cd, cd + eta * (dy[N + b] - dy[N + m])
    return c, cd


@njit(cache=True)
def _hermite_root(s0: float, d0: float, s1: float, d1: float) -> float:
    """theta in [0, 1] where the cubic Hermite with values s0, s1 and slopes d0, d1 (per unit theta)
    changes sign (s0 > 0 != s1 > 0), by bisection."""
    lo, hi = 0.0, 1.0
    pos0 = s0 > 0.0
    for _ in range(60):
        th = 0.5 * (lo + hi)
        t2 = th * th
        t3 = t2 * th
        v = (2 * t3 - 3 * t2 + 1) * s0 + (t3 - 2 * t2 + th) * d0 + (-2 * t3 + 3 * t2) * s1 + (t3 - t2) * d1
        if (v > 0.0) == pos0:
            lo = th
        else:
            hi = th
        if hi - lo <= 1e-16:
            break
    return 0.5 * (lo + hi)


class ContactEvents(NamedTuple):
    """The contact events of a run of (ncdamped), y = [x, v, s D] (module docstring): the bonds' states at the
    current step's start (``side``), the work arrays of the location, ``ctl`` = [variable of the next step
    (PLAIN or SQRT_START: it starts at an onset), the accepted step ends at an onset, bonds with theta <= this
    switch at its end, number of candidates], and the counters ``ev`` += [events located, switches left
    unlocated, re-steps, re-steps failing the error test (a shorter step is tried)]; the times of the first
    located events are written to ``tev`` (as many as it holds)."""

    eta: float
    N: int
    nb: int
    loc_tol: float
    side: np.ndarray
    theta: np.ndarray
    target: np.ndarray
    zend: np.ndarray
    cand: np.ndarray
    qtype: np.ndarray
    ctl: np.ndarray
    fnew: np.ndarray
    ytr: np.ndarray
    ftr: np.ndarray
    ev: np.ndarray
    tev: np.ndarray


def contact_events(y0: Floats, periodic: bool, eta: float, rtol: float, ev: Ints, tev: Floats | None) -> ContactEvents:
    """The events of a run from y0 = [x, v, s D] (``ev``: int64, 4 counters; ``tev``: float64 or None)."""
    n = y0.size
    N = (n - 1) // 2
    nb = N if periodic else N - 1
    return ContactEvents(float(eta), N, nb, float(rtol) ** (2.0 / 3.0), states(y0, bool(periodic), float(eta)),
                         np.full(nb, 2.0), np.empty(nb, dtype=np.int8), np.empty(nb, dtype=np.int8),
                         np.empty(nb, dtype=np.int64), np.zeros(nb, dtype=np.bool_),
                         np.array([float(PLAIN), 0.0, -1.0, 0.0]), np.empty(n), np.empty(n), np.empty(n), ev,
                         np.empty(0) if tev is None else tev)


@implements(end_buffer, ContactEvents)
@njit(cache=True)
def _buffer(events: ContactEvents, Ks: Floats) -> Floats:
    return events.fnew


@implements(start_step, ContactEvents)
@njit(cache=True)
def _start(events: ContactEvents) -> int:
    events.ctl[1] = 0.0     # the accepted step ends at an onset: the next one starts in u
    events.ctl[2] = -1.0    # >= 0: bonds with theta <= this switch at the step's end
    return int(events.ctl[0])


@implements(time_variable, ContactEvents)
@njit(cache=True)
def _time(events: ContactEvents, sub: int) -> NamedTuple:
    return SubstitutedTime(sub)


@implements(locate, ContactEvents)
@njit(cache=True)
def _locate(events: ContactEvents, system: NamedTuple, y: Floats, fy: Floats, ynew: Floats, fnew: Floats, t: float,
            h: float, h_try: float, hu: float, sub: int, clipped: bool, Ks: Floats, ys: Floats, err5: Floats,
            err3: Floats, rtol: float, atol: float, A: Floats, B: Floats, C: Floats, E3: Floats,
            E5: Floats) -> tuple[bool, float, float, bool, bool, int, int]:
    n = y.shape[0]
    N = events.N
    eta = events.eta
    side = events.side
    theta = events.theta
    target = events.target
    zend = events.zend
    cand = events.cand
    qtype = events.qtype
    ev = events.ev
    tev = events.tev
    ytr = events.ytr
    ftr = events.ftr
    h_step = h_try      # the accepted step's length in t
    restepped = False   # the accepted step is a re-step ending at an event
    nfev = 0
    w0 = speed(sub, 0.0, hu) * hu     # dt/dtheta at the step's ends, theta = u / hu
    w1 = speed(sub, 1.0, hu) * hu
    # the switches inside the accepted step: first guesses from the cubic Hermite of s
    th_min = 2.0
    b_min = -1
    ncand = 0
    for b in range(events.nb):
        z = _state(ynew, N, b, eta)
        zend[b] = z
        if z == side[b]:
            continue
        cand[ncand] = b
        ncand += 1
        theta[b] = 2.0
        qt, target[b] = _transition(side[b], z, eta)
        qtype[b] = qt
        s0, d0 = _switch(y, fy, N, b, eta, qt)
        s1, d1 = _switch(ynew, fnew, N, b, eta, qt)
        if (s0 > 0.0) == (s1 > 0.0):
            continue    # switched at the step's start (its side was set there)
        if s0 == 0.0 and d0 >= 0.0:
            # leaves zero at the step's start: a bond of touching balls at rest pushed by a neighbour's onset
            # (c grows like a power of t - t_on from there): switched at the start, not inside the step, where
            # the Hermite puts a root of that flat start
            theta[b] = 0.0
            continue
        theta[b] = _hermite_root(s0, d0 * w0, s1, d1 * w1)
        if EDGE <= theta[b] < th_min:   # below EDGE: switched at the step's start
            th_min = theta[b]
            b_min = b
    events.ctl[3] = ncand
    if b_min < 0:
        return False, h, h_step, clipped, restepped, nfev, 0
    a = side[b_min]
    qt = qtype[b_min]
    onset = a == OPEN
    if th_min > 1.0 - EDGE:
        events.ctl[2] = th_min + GROUP
        events.ctl[1] = 1.0 if onset else 0.0
        if ev[0] < tev.shape[0]:
            tev[ev[0]] = t + h_try
        ev[0] += 1
        return False, h, h_step, clipped, restepped, nfev, 0
    # refine the event time by Newton on re-steps from the step's start
    for i in range(n):
        ytr[i] = ynew[i]
        ftr[i] = fnew[i]
    if sub == PLAIN and not qt and not onset:   # a release: c^alpha at its end
        sub = SQRT_END
    h_ev = th_min * h_try if sub != SQRT_START else (th_min * hu) ** 2
    ok = False
    err_ev = 2.0
    for _ in range(MAX_NEWTON):
        u = h_ev if sub == PLAIN else math.sqrt(h_ev)
        err_ev = trial(system, SubstitutedTime(sub), y, fy, u, Ks, ys, ynew, fnew, err5, err3, rtol, atol,
                       A, B, C, E3, E5)
        nfev += _NS
        ev[2] += 1
        s, ds = _switch(ynew, fnew, N, b_min, eta, qt)
        ok = ds != 0.0
        if not ok:
            break
        delta = -s / ds
        if abs(delta) <= events.loc_tol * h_try:
            break
        if not (EDGE * h_try < h_ev + delta < h_try):
            ok = False
            break
        h_ev += delta
    if ok and err_ev < 1.0:
        h_step = h_ev
        restepped = True
        clipped = False
        events.ctl[2] = th_min + GROUP
        events.ctl[1] = 1.0 if onset else 0.0
        if ev[0] < tev.shape[0]:
            tev[ev[0]] = t + h_ev
        ev[0] += 1
    elif ok:            # the step to the event failed the error test: a shorter step
        ev[3] += 1
        fac = max(0.2, 0.9 * err_ev ** (-1.0 / 8.0))
        h = h_ev * fac if sub == PLAIN else h_ev * fac * fac
        return True, h, h_step, clipped, restepped, nfev, 1
    else:               # not located: the crossing step as it was
        for i in range(n):
            ynew[i] = ytr[i]
            fnew[i] = ftr[i]
        ev[1] += 1
    return False, h, h_step, clipped, restepped, nfev, 0


@implements(commit, ContactEvents)
@njit(cache=True)
def _commit(events: ContactEvents, y: Floats, restepped: bool) -> None:
    side = events.side
    zend = events.zend
    if restepped:           # the states at the re-step's end
        for b in range(events.nb):
            zend[b] = _state(y, events.N, b, events.eta)
    for b in range(events.nb):
        side[b] = zend[b]
    group_from = events.ctl[2]
    for j in range(int(events.ctl[3])):
        b = events.cand[j]
        if events.theta[b] <= group_from:
            side[b] = events.target[b]     # switched at the event, whatever the sign at the end rounds to
    events.ctl[0] = SQRT_START if events.ctl[1] != 0.0 else PLAIN
