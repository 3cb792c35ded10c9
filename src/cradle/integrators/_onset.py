"""Contact-onset correction of the splittings ("srkn6c", "srkn4c"): what it adds to a step of the splitting loop.

Why the splittings lose their order on (nc)
-------------------------------------------
With the harmonic part rotated exactly, one splitting step of length h is,
*exactly* (kicks and rotations are linear once the kick forces are known),

    y(h) = R(h) y(0) + sum_i R((1 - c_i) h) (0, b_i h F(x_i)),            (S)

x_i the positions at the kick nodes c_i h (c_0 = 0, c_i = a_0 + ... +
a_{i-1}, c_m = 1), while the exact flow is the variation-of-constants formula

    y(h) = R(h) y(0) + int_0^h R(h - tau) (0, F(x(tau))) dtau,            (V)

R(theta)(x, v) = (x cos theta + v sin theta, v cos theta - x sin theta).
(S) is a quadrature of (V) whose stage errors cancel through the order
conditions, which assume a smooth force. Along a trajectory the Hertz bond
force is (tau - tau*)_+^alpha near a contact onset tau*: the step across
the onset makes an O(h^(alpha+1)) error, and so do the few steps next to it
(the p-th derivative of the force grows like |tau - tau*|^(alpha - p)). The
global error is O(h^(alpha+1)) = O(h^2.5) whatever the nominal order.

The correction
--------------
The sum (S) is linear in the bond forces: bond k adds +g_k to bead k and
-g_k to bead k+1, g_k = sum_i R((1 - c_i) h) (0, b_i h f_k(x_i)). After
every step, for each bond k that is "at onset" - its elongation d_k changes
sign during the step, or |d_k| < near * h * (|d_k'(0)| + |d_k'(h)|) at a
step end (near = 4/27: the largest excursion of a cubic Hermite beyond its
chord), and (Hertz) it is in contact at some point of the step - the
contribution g_k is replaced by the integral of (V) for that bond alone,

    I_k = int_0^h (sin(h - tau), cos(h - tau)) f(d~_k(tau)) dtau,

along the cubic Hermite model d~_k of d_k(tau) built from the elongations
and their rates at both ends of the step: (x, v) of bead k += I_k - g_k,
bead k+1 -= I_k - g_k. The integral is computed "exactly", by Gauss-Legendre
on the monotone pieces of the cubic cut at its roots
(:mod:`cradle.integrators._onset_impulse`). The neighbouring
bonds keep their quadrature; the forces at the step end (FSAL) and the
energy are updated locally.

What remains is the error of the model (the trajectory is C^{3, alpha-1},
so d~ - d = O(h^3.5) for alpha = 3/2, times f' = O(h^(1/2)) near onset,
times h): the local error of a crossing step is O(h^5) against O(h^2.5)
uncorrected (two-bead chain, tests/test_integrators.py); the observed
global order is 5 on a 16-bead travelling wave and 3.2-3.8 on the paper's
scenes at t = 100, against 2.3-2.7 (benchmarks/onset_correction.py). Bonds
near onset but not crossing matter as much as crossing ones: with
``near`` = 0 (crossings only) the order on the paper's scenes stays ~2.6.
The step is no
longer exactly symplectic: on the steps away from onsets it is the
symplectic splitting, on onset steps a local O(h^2.5) modification of it,
and the energy drift - measured after every step as for every method - is
smaller than the plain splitting's at the same step and stays bounded over
long runs (tests/test_integrators.py).

``variant`` 2 ("replace", the default) subtracts the quadrature actually
taken (stored stage forces); variant 1 ("difference") subtracts the same
quadrature evaluated on the model. Both, with or without a refinement of
the model's end values (``n_iter``), were measured in
benchmarks/onset_correction.py; 2 with no refinement is as accurate and the
cheapest.

In the code: :class:`OnsetCorrection` is the ``correction`` argument of the one splitting loop
(:func:`cradle.integrators._splitting.split_run`); its implementations of the loop's operations keep the
stage forces (``stage_forces``, ``start_step``), set the quadrature weights per output interval
(``start_interval``) and apply the screen and the replacement after every step (``correct``).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
from numba import njit

from cradle.integrators import _cache
from cradle.integrators._generic import implements
from cradle.integrators._kernels import _bond
from cradle.integrators._onset_impulse import cubic, extrema, hermite, integrate_pieces
from cradle.integrators._splitting import correct, stage_forces, start_interval, start_step

if TYPE_CHECKING:
    from cradle.integrators._types import Floats, Ints

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating

#: Default ``near`` of the onset screen: a cubic Hermite on [0, h] stays within
#: (4/27) h (|d'(0)| + |d'(h)|) of its chord's range.
NEAR_DEFAULT = 4.0 / 27.0


@njit(cache=True)
def _set_bond(bb: int, x: Floats, v: Floats, fend: Floats, d1: Floats, w1: Floats, alpha: float, mode: int,
              N: int) -> float:
    """Recompute the end-of-step elongation, rate and force of bond bb; return the change of d*f."""
    nxt = bb + 1 if bb + 1 < N else 0
    old = d1[bb] * fend[bb]
    d = x[nxt] - x[bb]
    d1[bb] = d
    w1[bb] = v[nxt] - v[bb]
    fv = _bond(d, alpha, mode)[0]
    fend[bb] = fv
    return d * fv - old


@njit(cache=True)
def _apply(k: int, dx: float, dv: float, x: Floats, v: Floats, F: Floats, fend: Floats, d1: Floats, w1: Floats,
           alpha: float, mode: int, periodic: bool, N: int) -> tuple[float, float]:
    """Add (dx, dv) to bead k and subtract it from bead k+1; update the end forces locally.

    Returns (change of sum(x^2 + v^2), change of sum_bonds d f).
    """
    k1 = k + 1 if k + 1 < N else 0
    de = -(x[k] * x[k] + v[k] * v[k] + x[k1] * x[k1] + v[k1] * v[k1])
    x[k] += dx
    v[k] += dv
    x[k1] -= dx
    v[k1] -= dv
    de += x[k] * x[k] + v[k] * v[k] + x[k1] * x[k1] + v[k1] * v[k1]
    km = k - 1 if k > 0 else N - 1
    kp = k1
    dpot = _set_bond(k, x, v, fend, d1, w1, alpha, mode, N)
    if periodic or k > 0:
        dpot += _set_bond(km, x, v, fend, d1, w1, alpha, mode, N)
    if periodic or kp < N - 1:
        if kp != km:
            dpot += _set_bond(kp, x, v, fend, d1, w1, alpha, mode, N)
    # net forces F_n = f_n - f_{n-1} of beads k-1 .. k+2 (f_{N-1} = 0 with free ends)
    n = km
    for _ in range(4):
        F[n] = fend[n] - fend[n - 1 if n > 0 else N - 1]
        n = n + 1 if n + 1 < N else 0
    return de, dpot


class OnsetCorrection(NamedTuple):
    """The state of the onset correction of a splitting run (the ``correction`` of
    :func:`cradle.integrators._splitting.split_run`).

    ``fs`` (m+1, N): the bond forces of every kick of the current step, row ``ctl[0]`` holding those at the
    step's start (FSAL); ``d``, ``w`` (2, N): bond elongations and rates at the step's start (row ``ctl[2]``)
    and end; ``flag``, ``idx``, ``gq``: work arrays; ``cnode`` (m+1) the kick nodes, ``qs``, ``qc`` the
    weights of the step's quadrature of each bond (set per output interval), ``margin`` = [near h];
    ``variant``: 0 none (plain splitting), 1 "difference", 2 "replace" (module docstring); ``n_iter``
    refinements of the end values of the Hermite model; ``near`` the screen's margin. The counters it adds
    to ``counts[2:5]``: corrected crossings, steps with a correction, bonds flagged by the screen.
    """

    fs: np.ndarray
    d: np.ndarray
    w: np.ndarray
    flag: np.ndarray
    idx: np.ndarray
    gq: np.ndarray
    cnode: np.ndarray
    qs: np.ndarray
    qc: np.ndarray
    ctl: np.ndarray
    margin: np.ndarray
    variant: int
    n_iter: int
    near: float


def onset_correction(x: Floats, v: Floats, a: Floats, variant: int, n_iter: int, near: float) -> OnsetCorrection:
    """The correction's state for a run from (x, v) with the splitting's rotation coefficients ``a``; its row m
    of ``fs`` is where the caller puts the forces at x."""
    N = x.size
    m = a.size
    cnode = np.concatenate(([0.0], np.cumsum(a)))
    cnode[-1] = 1.0
    d = np.empty((2, N))
    w = np.empty((2, N))
    d[0] = np.roll(x, -1) - x
    w[0] = np.roll(v, -1) - v
    return OnsetCorrection(np.zeros((m + 1, N)), d, w, np.zeros(N, dtype=np.uint8), np.empty(N, dtype=np.int64),
                           np.empty((N, 2)), cnode, np.empty(m + 1), np.empty(m + 1),
                           np.array([m, m, 0], dtype=np.int64), np.zeros(1), int(variant), int(n_iter), float(near))


@implements(start_interval, OnsetCorrection)
@njit(cache=True)
def _start_interval(correction: OnsetCorrection, h: float, bh: Floats) -> None:
    cnode = correction.cnode
    for i in range(bh.shape[0]):
        correction.qs[i] = bh[i] * math.sin((1.0 - cnode[i]) * h)
        correction.qc[i] = bh[i] * math.cos((1.0 - cnode[i]) * h)
    correction.margin[0] = correction.near * h


@implements(start_step, OnsetCorrection)
@njit(cache=True)
def _start_step(correction: OnsetCorrection) -> Floats:
    m = correction.fs.shape[0] - 1
    rowf = 0 if correction.ctl[0] == m else m
    correction.ctl[1] = rowf
    return correction.fs[rowf]


@implements(stage_forces, OnsetCorrection)
@njit(cache=True)
def _stage_forces(correction: OnsetCorrection, fend: Floats, i: int) -> Floats:
    return correction.fs[i]


@implements(correct, OnsetCorrection)
@njit(cache=True)
def _correct(correction: OnsetCorrection, x: Floats, v: Floats, F: Floats, fend: Floats, h: float, e: float, pot: float,
             cmax: float, alpha: float, mode: int, periodic: bool, counts: Ints) -> tuple[float, float, float]:
    """The screen and the correction of one step (module docstring)."""
    cmax_all = cmax
    N = x.shape[0]
    fs = correction.fs
    m = fs.shape[0] - 1
    nb = N if periodic else N - 1
    row0 = correction.ctl[0]
    rowf = correction.ctl[1]
    cur = correction.ctl[2]
    da = correction.d[cur]
    wa = correction.w[cur]
    db = correction.d[1 - cur]
    wb = correction.w[1 - cur]
    flag = correction.flag
    idx = correction.idx
    gq = correction.gq
    qs = correction.qs
    qc = correction.qc
    cnode = correction.cnode
    variant = correction.variant
    margin_h = correction.margin[0]
    hertz = mode == 0 or mode == 1
    # end-of-step elongations and rates, and the crossing screen (vectorised)
    for n in range(N - 1):
        db[n] = x[n + 1] - x[n]
        wb[n] = v[n + 1] - v[n]
    db[N - 1] = x[0] - x[N - 1]
    wb[N - 1] = v[0] - v[N - 1]
    nflag = 0
    if variant != 0:
        for n in range(N):
            p0 = da[n]
            p1 = db[n]
            mg = margin_h * (abs(wa[n]) + abs(wb[n]))
            flag[n] = ((p0 < 0.0) != (p1 < 0.0)) | (abs(p0) < mg) | (abs(p1) < mg)
        for n in range(nb):
            if flag[n]:
                idx[nflag] = n
                nflag += 1
    counts[4] += nflag
    if nflag > 0:
        # keep the flagged bonds whose model crosses zero (or, Hertz, whose stages saw both
        # states), with the quadrature actually taken (variant 2) or its value on the model
        # (variant 1), before any correction moves a bead
        ncross = 0
        for ii in range(nflag):
            kb = idx[ii]
            c0, c1, c2, c3 = hermite(da[kb], wa[kb], db[kb], wb[kb], h)
            e1, e2 = extrema(c1, c2, c3)
            if hertz:
                # only bonds in contact somewhere in the step (model or stages) are replaced
                contact = c0 < 0.0 or db[kb] < 0.0
                if not contact and e1 <= 1.0:
                    contact = cubic(c0, c1, c2, c3, e1) < 0.0
                if not contact and e2 <= 1.0:
                    contact = cubic(c0, c1, c2, c3, e2) < 0.0
                if not contact:
                    for i in range(m + 1):
                        if fs[row0 if i == 0 else (rowf if i == m else i), kb] != 0.0:
                            contact = True
                            break
                if not contact:
                    continue
            gx = 0.0
            gv = 0.0
            if variant == 2:
                for i in range(m + 1):
                    fv = fs[row0 if i == 0 else (rowf if i == m else i), kb]
                    gx += qs[i] * fv
                    gv += qc[i] * fv
            else:
                for i in range(m + 1):
                    fv = _bond(cubic(c0, c1, c2, c3, cnode[i]), alpha, mode)[0]
                    gx += qs[i] * fv
                    gv += qc[i] * fv
            idx[ncross] = kb
            gq[ncross, 0] = gx
            gq[ncross, 1] = gv
            ncross += 1
        dpot_sum = 0.0
        for ii in range(ncross):
            kb = idx[ii]
            gx = gq[ii, 0]
            gv = gq[ii, 1]
            ax = 0.0
            av = 0.0
            for _it in range(correction.n_iter + 1):
                c0, c1, c2, c3 = hermite(da[kb], wa[kb], db[kb], wb[kb], h)
                e1, e2 = extrema(c1, c2, c3)
                ix, iv = integrate_pieces(c0, c1, c2, c3, e1, e2, h, alpha, mode)
                nx = h * ix - gx
                nv = h * iv - gv
                de, dp = _apply(kb, nx - ax, nv - av, x, v, F, fend, db, wb, alpha, mode, periodic, N)
                e += de
                dpot_sum += dp
                ax = nx
                av = nv
            if hertz and -db[kb] > cmax_all:
                cmax_all = -db[kb]
        pot += dpot_sum * (1.0 / (alpha + 1.0))
        counts[2] += ncross
        if ncross > 0:
            counts[3] += 1
    correction.ctl[2] = 1 - cur
    correction.ctl[0] = rowf
    return e, pot, cmax_all
