"""Numba kernels for the time integration of (nc)/(meca) and (dfnls).

Every kernel is ``@njit(cache=True)`` and is called with one fixed set of
argument types (float64 arrays, float alpha, int64 flags), so each compiles
once and is then loaded from the on-disk cache.

Contact-law flag ``mode`` (see :func:`mode_flag`):

* 0 - Hertz V0 (vhertz), alpha == 1.5 : f = -c sqrt(c), c = max(-d, 0)
* 1 - Hertz V0 (vhertz), any alpha     : f = -c**alpha
* 2 - smooth U of (meca), alpha == 1.5 : f = d sqrt(|d|)
* 3 - smooth U of (meca), any alpha    : f = d |d|**(alpha-1)

with d = x_{n+1} - x_n the elongation of bond n. In all four cases the bond
potential is V(d) = d f(d) / (alpha + 1) (V0(d) = c^(alpha+1)/(alpha+1) with
d f = c^(alpha+1); U(d) = |d|^(alpha+1)/(alpha+1) with d f = |d|^(alpha+1)),
so the potential energy of (ham) comes for free with every force evaluation.
The "compression" monitored for the stiffness is c = max(-d, 0) for Hertz and
|d| for the smooth law (whose stiffness U'' = alpha |d|^(alpha-1) is even).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from cradle.integrators import _cache

_cache.activate()   # before the first @njit: numba picks the cache folder when decorating

HERTZ_15, HERTZ, SMOOTH_15, SMOOTH = 0, 1, 2, 3


def mode_flag(potential: str, alpha: float) -> int:
    """Integer contact-law flag used by the kernels (fast path when alpha == 1.5)."""
    fast = alpha == 1.5
    if potential == "hertz":
        return HERTZ_15 if fast else HERTZ
    return SMOOTH_15 if fast else SMOOTH


@njit(cache=True)
def _bond(d, alpha, mode):
    """(f, c): bond force f = V'(d) and the compression c monitored for stiffness."""
    if mode == 0:
        c = max(-d, 0.0)
        return -c * math.sqrt(c), c
    elif mode == 1:
        c = max(-d, 0.0)
        return -(c**alpha), c
    elif mode == 2:
        c = abs(d)
        return d * math.sqrt(c), c
    else:
        c = abs(d)
        return d * c ** (alpha - 1.0), c


@njit(cache=True)
def forces(x, f, F, alpha, mode, periodic):
    """Contact forces of (nc)/(meca) at positions x.

    Fills ``f[n]`` (force on bond n, 0 on the missing bond N-1 with free ends)
    and ``F[n] = f[n] - f[n-1]`` (net contact force on bead n). Returns
    ``(pot, cmax)``: the contact part sum_n V(x_{n+1}-x_n) of (ham) and the
    largest bond compression.
    """
    N = x.shape[0]
    pot = 0.0
    cmax = 0.0
    for n in range(N - 1):
        d = x[n + 1] - x[n]
        fn, c = _bond(d, alpha, mode)
        f[n] = fn
        pot += d * fn
        cmax = max(cmax, c)
    if periodic:
        d = x[0] - x[N - 1]
        fn, c = _bond(d, alpha, mode)
        f[N - 1] = fn
        pot += d * fn
        cmax = max(cmax, c)
    else:
        f[N - 1] = 0.0
    F[0] = f[0] - f[N - 1]
    for n in range(1, N):
        F[n] = f[n] - f[n - 1]
    return pot / (alpha + 1.0), cmax


@njit(cache=True)
def forces_only(x, f, F, alpha, mode, periodic):
    """Same as :func:`forces` without the energy/compression reductions.

    Without the two reductions the loops vectorise (about 3x faster); used for
    the inner stages of a splitting step.
    """
    N = x.shape[0]
    for n in range(N - 1):
        f[n] = _bond(x[n + 1] - x[n], alpha, mode)[0]
    if periodic:
        f[N - 1] = _bond(x[0] - x[N - 1], alpha, mode)[0]
    else:
        f[N - 1] = 0.0
    F[0] = f[0] - f[N - 1]
    for n in range(1, N):
        F[n] = f[n] - f[n - 1]


@njit(cache=True)
def lattice_energy(x, v, alpha, mode, periodic):
    """Hamiltonian (ham) of one state, and its largest bond compression."""
    N = x.shape[0]
    f = np.empty(N)
    F = np.empty(N)
    pot, cmax = forces(x, f, F, alpha, mode, periodic)
    e = 0.0
    for n in range(N):
        e += v[n] * v[n] + x[n] * x[n]
    return 0.5 * e + pot, cmax


@njit(cache=True, inline="always")
def kick_rotate(x, v, F, b, c, s):
    """One stage of an RKN splitting: kick v += b F, then the exact harmonic flow of the on-site
    part over the stage, (x, v) rotated with c = cos(a h) - 1, s = sin(a h) (inlined: hot loop)."""
    for n in range(x.shape[0]):
        vn = v[n] + b * F[n]
        xn = x[n]
        x[n] = xn + (xn * c + vn * s)
        v[n] = vn + (vn * c - xn * s)


@njit(cache=True, inline="always")
def last_kick(x, v, F, b):
    """The closing kick v += b F of a step; returns sum(v^2 + x^2), twice the harmonic energy."""
    e = 0.0
    for n in range(x.shape[0]):
        vn = v[n] + b * F[n]
        v[n] = vn
        e += vn * vn + x[n] * x[n]
    return e


@njit(cache=True)
def split_run(x, v, f, F, tgrid, dt, k, j, max_steps, a, b, alpha, mode, periodic,
              X, V, E, shift, stats, counts):
    """Advance (nc)/(meca) with a symplectic BAB splitting; resumable.

    Splitting H = H_A + H_B of (ham): H_A = sum (v^2 + x^2)/2 integrated
    exactly (rotation by the angle a_i h), H_B = contact potential integrated
    by kicks v += b_i h F(x). The rotation is applied as x += x (cos - 1) +
    v sin with cos - 1 = -2 sin^2(a_i h / 2): the rounded cos(a_i h) ~ 1 would
    scale x^2 + v^2 by the same 1 + O(1e-16) at every stage, a systematic
    energy drift of ~1e-9 over the 10^7 rotations of a long run; written this
    way the rounding is unbiased. One step: kick b_0, rotate a_0, kick b_1, ...,
    rotate a_{m-1}, kick b_m; the force of the last kick (end-of-step x) is
    reused by the next step's first kick (FSAL), so ``F`` must hold F(x) on
    entry and holds it on exit.

    The interval [tgrid[k], tgrid[k+1]] is covered by n_k = ceil(len/dt)
    equal steps. Starting at interval ``k`` after ``j`` of its steps, at most
    ``max_steps`` steps are taken; when interval k completes, the state is
    stored in row ``k + 1 - shift`` of X, V, E (skipped if negative).
    ``stats`` = [H0, max relative |H - H0|, max compression (at step ends), last H] and
    ``counts`` = [n_steps, n_force_evals] are updated in place. Energy is
    evaluated after every step. Returns the new ``(k, j)``.
    """
    N = x.shape[0]
    m = a.shape[0]
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
        while j < nk and taken < max_steps:
            for i in range(m):
                bi = bh[i]
                ci = cs[i]
                si = sn[i]
                kick_rotate(x, v, F, bi, ci, si)
                if i < m - 1:
                    forces_only(x, f, F, alpha, mode, periodic)
                else:  # end-of-step positions: contact energy and compression too
                    pot, cm = forces(x, f, F, alpha, mode, periodic)
                    if cm > cmax_all:
                        cmax_all = cm
            bi = bh[m]
            e = last_kick(x, v, F, bi)
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


@njit(cache=True)
def lattice_rhs(y, dy, f, F, alpha, mode, periodic):
    """First-order form of (nc)/(meca), y = [x, v]: dy = [v, -x + F(x)]."""
    N = f.shape[0]
    x = y[:N]
    forces(x, f, F, alpha, mode, periodic)
    for n in range(N):
        dy[n] = y[N + n]
        dy[N + n] = F[n] - y[n]


@njit(cache=True)
def _damped_bond(c, rate, alpha, eta, mode):
    """(force magnitude max(c^alpha + eta c^(alpha-1) c', 0), elastic part c^alpha) of a compressed bond
    c > 0 of (ncdamped), c' = ``rate`` (Hertz modes only: mode 0 is the c sqrt(c) fast path)."""
    if mode == 0:
        s = math.sqrt(c)
        el = c * s
    else:
        s = c ** (alpha - 1.0)
        el = c * s
    return max(el + eta * s * rate, 0.0), el


@njit(cache=True)
def lattice_damped_rhs(y, dy, f, F, alpha, mode, gamma, eta, dscale, periodic):
    """First-order form of (ncdamped) with its dissipated energy, y = [x, v, s D] (length 2N + 1):
    dy = [v, -x - gamma v + g_n - g_{n-1}, s P], g_n = -max(c^alpha + eta c^(alpha-1) c', 0) on a
    compressed bond (c = -(x_{n+1} - x_n) > 0, c' = -(v_{n+1} - v_n)), P the dissipated power of
    :mod:`cradle.models.damping` (Hertz modes 0 and 1 only), s = ``dscale`` the scale of D in the
    state (the error control's weight of D). ``f``, ``F``: work arrays of length N."""
    N = f.shape[0]
    P = 0.0
    nb = N if periodic else N - 1
    for n in range(nb):
        m = n + 1 if n + 1 < N else 0
        c = y[n] - y[m]
        if c > 0.0:
            rate = y[N + n] - y[N + m]
            g, el = _damped_bond(c, rate, alpha, eta, mode)
            f[n] = -g
            P += (g - el) * rate
        else:
            f[n] = 0.0
    if not periodic:
        f[N - 1] = 0.0
    F[0] = f[0] - f[N - 1]
    for n in range(1, N):
        F[n] = f[n] - f[n - 1]
    for n in range(N):
        vn = y[N + n]
        dy[n] = vn
        dy[N + n] = F[n] - y[n] - gamma * vn
        P += gamma * vn * vn
    dy[2 * N] = dscale * P


@njit(cache=True)
def lattice_jac(y, J, alpha, mode, periodic):
    """Dense Jacobian of :func:`lattice_rhs` (for the implicit scipy methods).

    With k_n = dV'/dd on bond n (Hertz: alpha c^(alpha-1); smooth:
    alpha |d|^(alpha-1)), dF_n/dx_{n+1} = k_n, dF_n/dx_{n-1} = k_{n-1},
    dF_n/dx_n = -k_n - k_{n-1}.
    """
    N = y.shape[0] // 2
    J[:, :] = 0.0
    nb = N if periodic else N - 1
    for n in range(N):
        J[n, N + n] = 1.0
        J[N + n, n] = -1.0
    for n in range(nb):
        m = n + 1 if n + 1 < N else 0
        d = y[m] - y[n]
        if mode == 0 or mode == 1:
            c = max(-d, 0.0)
        else:
            c = abs(d)
        kn = alpha * c ** (alpha - 1.0) if c > 0.0 else 0.0
        # bond n: F_n += f_n, F_m -= f_n, df_n/dx_m = kn, df_n/dx_n = -kn
        J[N + n, m] += kn
        J[N + n, n] -= kn
        J[N + m, m] -= kn
        J[N + m, n] += kn


@njit(cache=True)
def _pow_am1(r, alpha):
    """r^(alpha-1) for r >= 0 (sqrt fast path for alpha = 3/2; 0 at r = 0)."""
    if r <= 0.0:
        return 0.0
    if alpha == 1.5:
        return math.sqrt(r)
    return r ** (alpha - 1.0)


@njit(cache=True)
def dps_rhs(y, dy, alpha, inv2tau0, periodic):
    """(dfnls) on the real view y = (Re A_0, Im A_0, Re A_1, ...).

    dA_n/dtau = (G_n - G_{n-1}) / (2 i tau0), G_n = g(A_{n+1} - A_n),
    g(z) = z |z|^(alpha-1); G_{N-1} = 0 with free ends.
    """
    N = y.shape[0] // 2
    gr_last = 0.0
    gi_last = 0.0
    if periodic:
        dr = y[0] - y[2 * N - 2]
        di = y[1] - y[2 * N - 1]
        r = math.hypot(dr, di)
        s = _pow_am1(r, alpha)
        gr_last = dr * s
        gi_last = di * s
    gpr = gr_last
    gpi = gi_last
    for n in range(N):
        if n < N - 1:
            dr = y[2 * n + 2] - y[2 * n]
            di = y[2 * n + 3] - y[2 * n + 1]
            r = math.hypot(dr, di)
            s = _pow_am1(r, alpha)
            gr = dr * s
            gi = di * s
        else:
            gr = gr_last
            gi = gi_last
        wr = gr - gpr
        wi = gi - gpi
        # -i (wr + i wi) / (2 tau0) = (wi - i wr) / (2 tau0)
        dy[2 * n] = wi * inv2tau0
        dy[2 * n + 1] = -wr * inv2tau0
        gpr = gr
        gpi = gi


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


@njit(cache=True)
def dps_damped_rhs(y, dy, alpha, par, periodic):
    """(dpsdamped) on y = (Re A_0, Im A_0, ..., Re A_{N-1}, Im A_{N-1}, Q_l2, Q_S), par = [1/(2 tau0), gamma~,
    Re kappa, Im kappa] (:mod:`cradle.models.dps_damped`).

    dA_n/dtau = kappa (G_n - G_{n-1}) / (2 i tau0) - (gamma~/2) A_n; the two last entries integrate what the
    damping removes from sum |A_n|^2 and from S = sum |A_{n+1} - A_n|^(alpha+1) = -(alpha+1) tau0 H (the
    balance laws of (dpsdamped)): Q_l2' = gamma~ sum |A_n|^2 + (Im kappa / tau0) S and
    Q_S' = (alpha+1) [(Im kappa / (2 tau0)) sum |G_n - G_{n-1}|^2 + (gamma~/2) S].
    """
    N = (y.shape[0] - 2) // 2
    inv2tau0 = par[0]
    half_gamma = 0.5 * par[1]
    kr = par[2]
    ki = par[3]
    gr_last = 0.0
    gi_last = 0.0
    S = 0.0
    if periodic:
        dr = y[0] - y[2 * N - 2]
        di = y[1] - y[2 * N - 1]
        r = math.hypot(dr, di)
        s = _pow_am1(r, alpha)
        gr_last = dr * s
        gi_last = di * s
        S += r * r * s
    gpr = gr_last
    gpi = gi_last
    l2 = 0.0
    L2 = 0.0
    for n in range(N):
        if n < N - 1:
            dr = y[2 * n + 2] - y[2 * n]
            di = y[2 * n + 3] - y[2 * n + 1]
            r = math.hypot(dr, di)
            s = _pow_am1(r, alpha)
            gr = dr * s
            gi = di * s
            S += r * r * s
        else:
            gr = gr_last
            gi = gi_last
        wr = gr - gpr
        wi = gi - gpi
        # kappa w = (kr wr - ki wi) + i (kr wi + ki wr); -i (a + i b) / (2 tau0) = (b - i a) / (2 tau0)
        ar = y[2 * n]
        ai = y[2 * n + 1]
        dy[2 * n] = (kr * wi + ki * wr) * inv2tau0 - half_gamma * ar
        dy[2 * n + 1] = -(kr * wr - ki * wi) * inv2tau0 - half_gamma * ai
        l2 += ar * ar + ai * ai
        L2 += wr * wr + wi * wi
        gpr = gr
        gpi = gi
    dy[2 * N] = 2.0 * half_gamma * l2 + 2.0 * ki * inv2tau0 * S
    dy[2 * N + 1] = (alpha + 1.0) * (ki * inv2tau0 * L2 + half_gamma * S)
