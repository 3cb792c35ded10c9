"""The one splitting loop of (nc)/(meca): symplectic BAB splittings of (ham), with or without a step correction.

Splitting H = H_A + H_B of (ham): H_A = sum (v^2 + x^2)/2 integrated exactly (rotation by the angle a_i h),
H_B = contact potential integrated by kicks v += b_i h F(x). The rotation is applied as x += x (cos - 1) +
v sin with cos - 1 = -2 sin^2(a_i h / 2): the rounded cos(a_i h) ~ 1 would scale x^2 + v^2 by the same
1 + O(1e-16) at every stage, a systematic energy drift over the many rotations of a long run; written this
way the rounding is unbiased. One step: kick b_0, rotate a_0, kick b_1, ..., rotate a_{m-1}, kick b_m; the
force of the last kick (end-of-step x) is reused by the next step's first kick (FSAL).

What a step does besides is its ``correction``, a ``typing.NamedTuple`` dispatched at compile time
(:mod:`cradle.integrators._generic`): :class:`NoCorrection` (the plain splitting: nothing else is compiled
in) or the contact-onset correction of "srkn6c", "srkn4c"
(:class:`cradle.integrators._onset.OnsetCorrection`), which keeps the stage forces and replaces the
quadrature of the bonds at a contact onset after every step.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
from numba import njit

from cradle.integrators import _cache
from cradle.integrators._generic import absent, generic, implements
from cradle.integrators._kernels import forces, forces_only, kick_rotate, last_kick

if TYPE_CHECKING:
    from cradle.integrators._types import Floats, Ints

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating


class NoCorrection(NamedTuple):
    """The plain splitting: ``f`` the bond forces' work array (length N)."""

    f: np.ndarray


@generic
def start_interval(correction: NamedTuple, h: float, bh: Floats) -> None:
    """Prepare the steps of length h of an output interval (``bh`` = b_i h)."""


@generic
def start_step(correction: NamedTuple) -> Floats:
    """The array receiving the bond forces at the step's end."""


@generic
def stage_forces(correction: NamedTuple, fend: Floats, i: int) -> Floats:
    """The array receiving the bond forces of kick i (0 < i < m)."""


@generic
def correct(correction: NamedTuple, x: Floats, v: Floats, F: Floats, fend: Floats, h: float, e: float, pot: float,
            cmax: float, alpha: float, mode: int, periodic: bool,
            counts: Ints) -> tuple[float, float, float]:
    """After the closing kick: the corrected (sum (x^2 + v^2), contact energy, largest compression)."""


@implements(start_step, NoCorrection)
@njit(cache=True)
def _start_step(correction: NoCorrection) -> Floats:
    return correction.f


@njit(cache=True)
def split_run(correction: NamedTuple, x: Floats, v: Floats, F: Floats, tgrid: Floats, dt: float, k: int, j: int,
              max_steps: int, a: Floats, b: Floats, alpha: float, mode: int, periodic: bool, X: Floats, V: Floats,
              E: Floats, shift: int, stats: Floats, counts: Ints) -> tuple[int, int]:
    """Advance (nc)/(meca) with a symplectic BAB splitting (module docstring); resumable.

    ``F`` must hold F(x) on entry and holds it on exit (FSAL). The interval [tgrid[k], tgrid[k+1]] is
    covered by n_k = ceil(len/dt) equal steps. Starting at interval ``k`` after ``j`` of its steps, at most
    ``max_steps`` steps are taken; when interval k completes, the state is stored in row ``k + 1 - shift``
    of X, V, E (skipped if negative). ``stats`` = [H0, max relative |H - H0|, max compression (at step ends),
    last H] and ``counts`` = [n_steps, n_force_evals, then the correction's own counters] are updated in
    place. Energy is evaluated after every step. Returns the new ``(k, j)``.
    """
    N = x.shape[0]
    m: int = a.shape[0]
    nint = tgrid.shape[0] - 1
    cs = np.empty(m)
    sn = np.empty(m)
    bh = np.empty(m + 1)
    H0 = stats[0]
    scale = abs(H0) if H0 != 0.0 else 1.0
    drift = stats[1]
    cmax_all = stats[2]
    H = stats[3]
    pot = 0.0
    taken = 0
    nfev = 0
    while k < nint and taken < max_steps:
        length = tgrid[k + 1] - tgrid[k]
        nk = max(1, int(math.ceil(length / dt * (1.0 - 1e-12))))
        h = length / nk
        for i in range(m):
            cs[i] = -2.0 * math.sin(0.5 * a[i] * h) ** 2  # cos(a_i h) - 1, to full relative precision
            sn[i] = math.sin(a[i] * h)
        for i in range(m + 1):
            bh[i] = b[i] * h
        start_interval(correction, h, bh)
        while j < nk and taken < max_steps:
            fend = start_step(correction)
            for i in range(m):
                bi = bh[i]
                ci = cs[i]
                si = sn[i]
                kick_rotate(x, v, F, bi, ci, si)
                if i < m - 1:
                    forces_only(x, stage_forces(correction, fend, i + 1), F, alpha, mode, periodic)
                else:  # end-of-step positions: contact energy and compression too
                    pot, cm = forces(x, fend, F, alpha, mode, periodic)
                    if cm > cmax_all:
                        cmax_all = cm
            bi = bh[m]
            e = last_kick(x, v, F, bi)
            e, pot, cmax_all = correct(correction, x, v, F, fend, h, e, pot, cmax_all, alpha, mode, periodic,
                                       counts)
            H = 0.5 * e + pot
            dr = abs(H - H0) / scale
            if dr > drift:
                drift = dr
            j += 1
            taken += 1
            nfev += m
        if j >= nk:
            row = k + 1 - shift
            if row >= 0:
                for n in range(N):
                    X[row, n] = x[n]
                    V[row, n] = v[n]
                E[row] = H
            k += 1
            j = 0
    stats[1] = drift
    stats[2] = cmax_all
    stats[3] = H
    counts[0] += taken
    counts[1] += nfev
    return k, j


absent(start_interval, NoCorrection)
absent(stage_forces, NoCorrection, "fend")
absent(correct, NoCorrection, "e", "pot", "cmax")
