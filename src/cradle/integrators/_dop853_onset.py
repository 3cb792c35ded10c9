"""Contact events of the damped lattice (ncdamped) in DOP853 (kind 2): steps end where a bond's force switches.

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

An event costs the crossing step it replaces and its re-steps (12 force evaluations each). A bond that
switches twice inside one step (a contact shorter than the step) is not seen; a switch that cannot be
located (Newton leaving the step) keeps the crossing step, counted in ``ev[1]``.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from cradle.integrators import _cache, _kernels as K

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating

_NS = 12                # DOP853's stages (the 13th is the FSAL evaluation at the step's end)
PLAIN, SQRT_START, SQRT_END = 0, 1, 2
OPEN, CLIPPED, PUSHING = 0, 1, 2
#: an event within EDGE h of a step's start or end is left at that end
EDGE = 1e-9
#: bonds whose switching times lie within GROUP h of the earliest switch with it
GROUP = 1e-7
#: most re-steps spent locating one event
MAX_NEWTON = 4


@njit(cache=True)
def _speed(sub, c, h):
    """dt/du at u = c h of a step of length h in u: t = t0 + u^2 (SQRT_START), t = t0 + h^2 - (h - u)^2
    (SQRT_END), u itself (PLAIN)."""
    if sub == SQRT_START:
        return 2.0 * c * h
    if sub == SQRT_END:
        return 2.0 * h * (1.0 - c)
    return 1.0


@njit(cache=True)
def _trial(y, fy, h, sub, Ks, ys, ynew, fnew, err5, err3, f, F, alpha, mode, par, periodic, rtol, atol,
           A, B, C, E3, E5):
    """One DOP853 step of length h in the step variable from (y, fy = f(y)): ynew, fnew = f(ynew), and
    returns the error norm (accept if < 1). PLAIN does the operations of
    :func:`cradle.integrators._dop853.dop853_run` in the same order."""
    n = y.shape[0]
    w = _speed(sub, 0.0, h)
    for i in range(n):
        Ks[0, i] = w * fy[i]    # w = 1 exactly on a plain step
    for s in range(1, _NS):
        for i in range(n):
            ys[i] = y[i]
        for j in range(s):
            cj = h * A[s, j]
            if cj != 0.0:
                for i in range(n):
                    ys[i] += cj * Ks[j, i]
        K.lattice_damped_rhs(ys, Ks[s], f, F, alpha, mode, par[0], par[1], par[2], periodic)
        if sub != PLAIN:
            w = _speed(sub, C[s], h)
            for i in range(n):
                Ks[s, i] *= w
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
            K.lattice_damped_rhs(ynew, Ks[_NS], f, F, alpha, mode, par[0], par[1], par[2], periodic)
            for i in range(n):
                fnew[i] = Ks[_NS, i]
            if sub != PLAIN:
                w = _speed(sub, 1.0, h)
                for i in range(n):
                    Ks[_NS, i] *= w
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


@njit(cache=True)
def _state(y, N, b, eta):
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
def states(y, periodic, eta):
    """Every bond's contact state (:func:`_state`) in y = [x, v, s D]: the ``side`` a run starts with."""
    N = (y.shape[0] - 1) // 2
    nb = N if periodic else N - 1
    out = np.empty(nb, dtype=np.int8)
    for b in range(nb):
        out[b] = _state(y, N, b, eta)
    return out


@njit(cache=True)
def _transition(a, z, eta):
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
def _switch(y, dy, N, b, eta, qtype):
    """(s, ds/dt) of bond b's switching function: q = c + eta c' (qtype) or c, from the state y and its
    derivative dy = f(y)."""
    m = b + 1 if b + 1 < N else 0
    c = y[b] - y[m]
    cd = y[N + b] - y[N + m]
    if qtype:
        return c + eta * cd, cd + eta * (dy[N + b] - dy[N + m])
    return c, cd


@njit(cache=True)
def _hermite_root(s0, d0, s1, d1):
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


@njit(cache=True)
def run_events(y, fy, tgrid, k, state, max_steps, rtol, atol, A, B, C, E3, E5, alpha, mode, par, periodic, Y,
               shift, stats, counts, side, ev, tev):
    """Advance (ncdamped), y = [x, v, s D], with DOP853 until tgrid[-1] or ``max_steps`` accepted steps,
    steps ending at the contact events (module docstring); resumable like
    :func:`cradle.integrators._dop853.dop853_run`, with ``state`` = [t, h, PLAIN or SQRT_START (the next
    step starts at an onset)] and ``side`` (int8, one per bond) the bonds' activities, both updated in
    place. ``ev`` += [events located, switches left unlocated, re-steps, re-steps failing the error test
    (a shorter step is tried)]; the times of the first located events are written to ``tev`` (as many as
    it holds). Returns (k, status)."""
    n = y.shape[0]
    N = (n - 1) // 2
    nb = N if periodic else N - 1
    eta = par[1]
    f = np.empty(N)
    F = np.empty(N)
    Ks = np.empty((13, n))
    ys = np.empty(n)
    ynew = np.empty(n)
    fnew = np.empty(n)
    ytr = np.empty(n)
    ftr = np.empty(n)
    err5 = np.empty(n)
    err3 = np.empty(n)
    theta = np.full(nb, 2.0)
    target = np.empty(nb, dtype=np.int8)
    zend = np.empty(nb, dtype=np.int8)      # the bonds' states at the trial's end
    cand = np.empty(nb, dtype=np.int64)     # the bonds whose state changed in it
    ncand = 0
    qtype = np.zeros(nb, dtype=np.bool_)
    loc_tol = rtol ** (2.0 / 3.0)   # the event time's tolerance, per unit step (module docstring)
    nint = tgrid.shape[0] - 1
    t = state[0]
    h = state[1]
    pend = int(state[2])
    taken = 0
    nfev = 0
    nrej = 0
    status = 0
    while k < nint and taken < max_steps:
        t_target = tgrid[k + 1]
        rejected = False
        onset_end = False       # the accepted step ends at an onset: the next one starts in u
        group_from = -1.0       # >= 0: bonds with theta <= group_from switch at the step's end
        while True:
            min_step = 10.0 * max(abs(t), 1e-300) * 2.220446049250313e-16
            if h < min_step:
                status = -1
                break
            h_try = h
            clipped = t + h >= t_target
            if clipped:
                h_try = t_target - t
            h_step = h_try      # the accepted step's length in t
            restepped = False   # the accepted step is a re-step ending at an event
            sub = pend
            hu = h_try if sub == PLAIN else math.sqrt(h_try)     # the step's length in its variable
            err = _trial(y, fy, hu, sub, Ks, ys, ynew, fnew, err5, err3, f, F, alpha, mode, par, periodic,
                         rtol, atol, A, B, C, E3, E5)
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
            w0 = _speed(sub, 0.0, hu) * hu     # dt/dtheta at the step's ends, theta = u / hu
            w1 = _speed(sub, 1.0, hu) * hu
            # the switches inside the accepted step: first guesses from the cubic Hermite of s
            th_min = 2.0
            b_min = -1
            ncand = 0
            for b in range(nb):
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
                theta[b] = _hermite_root(s0, d0 * w0, s1, d1 * w1)
                if EDGE <= theta[b] < th_min:   # below EDGE: switched at the step's start
                    th_min = theta[b]
                    b_min = b
            if b_min < 0:
                break
            a = side[b_min]
            qt = qtype[b_min]
            onset = a == OPEN
            if th_min > 1.0 - EDGE:
                group_from = th_min + GROUP
                onset_end = onset
                if ev[0] < tev.shape[0]:
                    tev[ev[0]] = t + h_try
                ev[0] += 1
                break
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
                err_ev = _trial(y, fy, u, sub, Ks, ys, ynew, fnew, err5, err3, f, F, alpha, mode, par, periodic,
                                rtol, atol, A, B, C, E3, E5)
                nfev += _NS
                ev[2] += 1
                s, ds = _switch(ynew, fnew, N, b_min, eta, qt)
                ok = ds != 0.0
                if not ok:
                    break
                delta = -s / ds
                if abs(delta) <= loc_tol * h_try:
                    break
                if not (EDGE * h_try < h_ev + delta < h_try):
                    ok = False
                    break
                h_ev += delta
            if ok and err_ev < 1.0:
                h_step = h_ev
                restepped = True
                clipped = False
                group_from = th_min + GROUP
                onset_end = onset
                if ev[0] < tev.shape[0]:
                    tev[ev[0]] = t + h_ev
                ev[0] += 1
            elif ok:            # the step to the event failed the error test: a shorter step
                ev[3] += 1
                fac = max(0.2, 0.9 * err_ev ** (-1.0 / 8.0))
                h = h_ev * fac if sub == PLAIN else h_ev * fac * fac
                rejected = True
                nrej += 1
                continue
            else:               # not located: the crossing step as it was
                for i in range(n):
                    ynew[i] = ytr[i]
                    fnew[i] = ftr[i]
                ev[1] += 1
            break
        if status != 0:
            break
        for i in range(n):
            y[i] = ynew[i]
            fy[i] = fnew[i]
        t = t_target if clipped else t + h_step
        if restepped:           # the states at the re-step's end
            for b in range(nb):
                zend[b] = _state(y, N, b, eta)
        for b in range(nb):
            side[b] = zend[b]
        for j in range(ncand):
            b = cand[j]
            if theta[b] <= group_from:
                side[b] = target[b]     # switched at the event, whatever the sign at the end rounds to
        pend = SQRT_START if onset_end else PLAIN
        taken += 1
        # the invariants, as _dop853._monitor does for kind 2
        H, cm = K.lattice_energy(y[:N], y[N:2 * N], alpha, mode, periodic)
        sc = abs(stats[0]) if stats[0] != 0.0 else 1.0
        stats[1] = max(stats[1], abs(H + y[2 * N] / stats[4] - stats[0]) / sc)
        stats[2] = max(stats[2], cm)
        stats[3] = H
        if clipped:
            row = k + 1 - shift
            if row >= 0:
                for i in range(n):
                    Y[row, i] = y[i]
            k += 1
    state[0] = t
    state[1] = h
    state[2] = pend
    counts[0] += taken
    counts[1] += nfev
    counts[2] += nrej
    return k, status
