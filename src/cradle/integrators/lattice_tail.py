"""The signed tail of a travelling breather of (nc) on a ring, and where it vanishes along a family (issue 37, item 2:
the parameters where the tail nearly vanishes).

Far from its core the beads of a TB (tbnc) are free oscillators of frequency 1 (the Hertz coupling of an amplitude a
is of order a^(alpha-1)), so there xi_n = (x_n - i v_n) / 2 turns as e^{it}, and x_n(t + T) = x_{n-1}(t) makes the
far field a plane wave of wavenumber T: xi_n(t) = B e^{-iT(n - n0 - N/2)} e^{i(t - t1)}, B its value at the
antipode of the bead n0 at the time t1.

The sign. (nc) is reversible: R, x_n(t) -> -x_{2 n0 - n}(-t) (the chain reflected about bead n0, x -> -x, time
reversed), maps a TB of period T onto a TB of period T moving the same way; and it keeps the carrier's phase
xi -> e^{i phi} xi almost exactly (DpS's phase symmetry). A TB is therefore symmetric, at one time t1 a period,
under R combined with a phase: eta_n = xi_n / xi_{n0} = conj(eta_{2 n0 - n}) (the envelope centred on the bead n0).
At that time B / xi_{n0} is real: R maps the far arc onto itself about the antipode, where the plane wave is
-e^{i phi} conj(B), and the centre, where xi_{n0} = -e^{i phi} conj(xi_{n0}). Its sign is the tail's sign relative
to the core's, and a change of sign along a family is a zero of the tail (or a pole: a ring resonance, the tail
large on both sides).

The signed tail ``sigma = Re(B / xi_{n0}) |xi_{n0}| / max |xi_n|`` at t1: +-|B| / max|xi| where the phase is exact,
comparable to :func:`cradle.models.dps_travelling.tail_amplitude` (the far quarter's max over the peak at the stored
time). What is not real in B / xi_{n0} is returned as ``phase_defect`` (measured: a few % of |sigma|; the core's
xi_n is taken with its own carrier frequency, xi_n = (x_n - i v_n / omega) / 2, so that its phase is the carrier's).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from cradle.integrators import lattice_travelling as LT

if TYPE_CHECKING:
    from collections.abc import Callable

    from cradle.integrators._types import Floats

#: samples per unit time of the period's scan for the symmetric time (a carrier period is 2 pi)
SAMPLES_PER_UNIT = 20
#: DOP853 relative tolerance of the scan (the minimum is then refined at LT.RTOL)
SCAN_RTOL = 1e-12


@dataclass(frozen=True)
class SignedTail:
    """The tail of a TB at its symmetric time t1 (module docstring): ``sigma`` the signed far field over the peak,
    ``phase_defect`` Im(B / xi_{n0}) |xi_{n0}| / max|xi| (what is not real), ``symmetry_defect`` the weighted
    distance of eta_n to conj(eta_{2 n0 - n}) at t1, ``plane_wave_defect`` max |xi_n - plane wave| / |B| over the far
    sites, ``omega`` the core's carrier frequency, ``t1`` and ``n0``."""

    sigma: float
    phase_defect: float
    symmetry_defect: float
    plane_wave_defect: float
    omega: float
    t1: float
    n0: int


def symmetry_defect(x: Floats, v: Floats, n0: int, omega: float) -> float:
    """sqrt(sum_n w_n^2 |eta_n - conj(eta_{2 n0 - n})|^2), eta_n = xi_n / xi_{n0}, xi_n = (x_n - i v_n / omega) / 2,
    w_n = |xi_n| / max |xi|: zero when the state is R-symmetric about bead n0 up to a phase."""
    N = x.size
    xi = 0.5 * (x - 1j * v / omega)
    eta = xi / xi[n0]
    mirror = (2 * n0 - np.arange(N)) % N
    w = np.abs(xi) / float(np.max(np.abs(xi)))
    return float(np.sqrt(np.sum(np.abs((eta - np.conj(eta[mirror])) * w) ** 2)))


def carrier_frequency(X: Floats, V: Floats) -> float:
    """omega = rms(v) / rms(x) at the largest bead of each sample: the core's carrier frequency (for x = a cos(omega
    t), v = -a omega sin(omega t) over whole carrier periods)."""
    p = np.argmax(np.hypot(X, V), axis=1)
    k = np.arange(p.size)
    return float(np.sqrt(np.sum(V[k, p] ** 2) / np.sum(X[k, p] ** 2)))


def symmetric_time(z: Floats, T: float, alpha: float) -> tuple[float, int, Floats, float, float]:
    """(t1, n0, z(t1), symmetry defect, omega): the time in [0, T] and bead where the TB is R-symmetric up to a phase
    (:func:`symmetry_defect` least over a scan of SAMPLES_PER_UNIT per unit time and the beads next to the largest,
    then refined by Brent's method), its state there and the core's carrier frequency."""
    from scipy.optimize import minimize_scalar

    z = np.asarray(z, float)
    N = z.size // 2
    ts = np.linspace(0.0, T, int(SAMPLES_PER_UNIT * T) + 1)
    X, V = LT.orbit(z, ts, alpha, SCAN_RTOL)
    omega = carrier_frequency(X, V)
    best = (math.inf, 0, 0)
    for k in range(ts.size):
        p = int(np.argmax(np.hypot(X[k], V[k])))
        for n0 in ((p - 1) % N, p, (p + 1) % N):
            d = symmetry_defect(X[k], V[k], n0, omega)
            if d < best[0]:
                best = (d, k, n0)
    _, k, n0 = best
    k = min(max(k, 1), ts.size - 2)
    # the defect between the neighbouring samples, from the sample before (the core's defect needs no more than
    # the scan's tolerance; the state at t1 itself is integrated from z at LT.RTOL below)
    start = np.concatenate([X[k - 1], V[k - 1]])

    def defect2(t: float) -> float:
        X1, V1 = LT.orbit(start, np.array([0.0, t - ts[k - 1]]), alpha, SCAN_RTOL)
        return symmetry_defect(X1[-1], V1[-1], n0, omega) ** 2

    t1 = float(minimize_scalar(defect2, bounds=(ts[k - 1], ts[k + 1]), method="bounded",
                               options={"xatol": 1e-9}).x)
    X1, V1 = LT.orbit(z, np.array([0.0, t1]), alpha)
    return t1, n0, np.concatenate([X1[-1], V1[-1]]), symmetry_defect(X1[-1], V1[-1], n0, omega), omega


def signed_tail(z: Floats, T: float, alpha: float) -> SignedTail:
    """The signed tail of the TB (z, T) (module docstring): the plane wave B e^{-iT(d - N/2)} fitted (mean of
    xi_n e^{iT(d - N/2)}) over the far quarter, ring distance d = n - n0 (mod N) within N/8 of N/2, at the symmetric
    time t1."""
    N = np.asarray(z).size // 2
    t1, n0, z1, sym, omega = symmetric_time(z, T, alpha)
    x, v = z1[:N], z1[N:]
    xi = 0.5 * (x - 1j * v)
    d = (np.arange(N) - n0) % N
    far = np.abs(d - N / 2) <= N / 8
    wave = np.exp(-1j * T * (d[far] - N / 2))
    B = complex(np.mean(xi[far] / wave))
    pw = float(np.max(np.abs(xi[far] - B * wave)) / abs(B))
    core = 0.5 * (x[n0] - 1j * v[n0] / omega)
    ratio = B / core * abs(core) / float(np.max(np.abs(xi)))
    return SignedTail(float(ratio.real), float(ratio.imag), sym, pw, omega, t1, n0)


def locate_zero(a: LT.LatticeTB, b: LT.LatticeTB, sa: float, sb: float, tol: float, max_iter: int = 6,
                log: Callable[[str], object] | None = None
                ) -> tuple[LT.LatticeTB, SignedTail, list[tuple[float, float]]]:
    """(TB, its signed tail, the (c, sigma) of every iterate): the zero of the signed tail between the members ``a``
    and ``b`` of a family (signed tails ``sa``, ``sb`` of opposite signs) by regula falsi (the Illinois variant): the
    member at the interpolated c, predicted by interpolating z between the bracket's ends, solved by
    :func:`LT.newton` to ``tol``; it replaces the end of its sign. Stops after ``max_iter`` iterates, at an iterate
    whose |sigma| is at most ``tol`` (the residual's bound: a smaller tail is not resolved, the floor), or when Newton
    fails; returns the iterate of least |sigma|."""
    if sa * sb >= 0:
        raise ValueError(f"locate_zero: the signed tails {sa:.3g} and {sb:.3g} do not bracket a zero")
    trace: list[tuple[float, float]] = []
    best: tuple[LT.LatticeTB, SignedTail] | None = None
    side = 0
    for _ in range(max_iter):
        c = a.c - sa * (b.c - a.c) / (sb - sa)
        w = (c - a.c) / (b.c - a.c)
        m = LT.newton((1.0 - w) * a.z + w * b.z, 1.0 / c, a.alpha, reference=a.z if w < 0.5 else b.z, tol=tol)
        if not m.converged:
            break
        s = signed_tail(m.z, m.T, m.alpha)
        trace.append((m.c, s.sigma))
        if log:
            log(f"lattice tail zero: c = {m.c:.12g}, sigma = {s.sigma:.3g}, residual {m.residual:.2g}")
        if best is None or abs(s.sigma) < abs(best[1].sigma):
            best = (m, s)
        if abs(s.sigma) <= tol:
            break
        # Illinois: the end kept twice in a row has its value halved, so that both ends move
        if s.sigma * sa > 0:
            a, sa = m, s.sigma
            sb = 0.5 * sb if side == -1 else sb
            side = -1
        else:
            b, sb = m, s.sigma
            sa = 0.5 * sa if side == 1 else sa
            side = 1
    if best is None:
        raise RuntimeError(f"lattice tail zero: Newton failed at the first iterate between c = {a.c:.10g} and "
                           f"{b.c:.10g}")
    return best[0], best[1], trace
