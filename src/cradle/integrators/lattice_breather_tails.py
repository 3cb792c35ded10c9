"""Tails of the exact breathers of (nc) far below machine precision, in log variables.

Beyond the core of a breather, |x_{n+1}| << |x_n| << |x_{n-1}| (the right tail; the left one is its mirror
image), so (nc) at bead n reduces to a linear oscillator driven by its inner neighbour,

    x_n'' + x_n = (x_{n-1} - x_n)_+^alpha - (x_n - x_{n+1})_+^alpha  ~  (x_{n-1})_+^alpha,

with relative errors O(|x_n / x_{n-1}|) and O(|x_n|^(alpha-1)), both far below 1e-16 there. Its T-periodic
solution is the Fourier multiplier y_k = f_k / (1 - k^2 omega_b^2) (never resonant: omega_b > 1). Writing
x_n(t) = e^{L_n} s_n(t) with max|s_n| = 1, the recursion

    s_n ~ L[(s_{n-1})_+^alpha],   L_n = alpha L_{n-1} + ln max|L[(s_{n-1})_+^alpha]|

runs in (shape, log-amplitude) variables where nothing underflows: the double-exponential decay
ln|x_n| ~ -C alpha^n, i.e. ln(-ln|x_n / max x|) with slope ln(alpha) against n, as the DpS tail of (dpsstn).
It starts from the last bead the shooting resolves (|x_n| >= start_rel max|x|), sampled over one period.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from cradle.integrators._types import Floats
    from cradle.integrators.lattice_breathers import Breather


def trajectory(b: Breather, M: int = 1024, rtol: float = 1e-13) -> Floats:
    """x_n(t) at t = k T / M, k = 0..M-1, of the breather ``b`` (shape (M, N)), by DOP853 with dense output."""
    from scipy.integrate import solve_ivp

    from cradle.integrators.lattice_breathers import _rhs_factory

    N = b.x0.size
    y0 = np.concatenate([b.x0, np.zeros(N), [0.0]])
    t = b.T * np.arange(M) / M
    atol = np.full(y0.size, rtol * b.amplitude)
    sol = solve_ivp(_rhs_factory(N, 0, b.alpha, b.bc == "periodic"), (0.0, b.T), y0, method="DOP853", rtol=rtol,
                    atol=atol, t_eval=t)
    return sol.y[:N].T


def log10_tail(b: Breather, centre: float, length: int, start_rel: float = 1e-7, M: int = 1024,
               rtol: float = 1e-13) -> tuple[NDArray[np.int_], Floats, int]:
    """log10 max_t |x_n(t)| on the right of ``centre`` for j = 1..length beads beyond it: from the trajectory
    while |x_n| >= start_rel max|x|, then by the recursion of the module docstring. Returns
    (j, log10 amplitude, index of the first recursed bead)."""
    X = trajectory(b, M, rtol)
    N = b.x0.size
    amp = float(np.max(np.abs(X)))
    c0 = int(np.floor(centre)) + 1                     # first bead right of the centre (a bond centre: c + 1)
    js = np.arange(1, length + 1)
    out = np.full(length, np.nan)
    k = np.fft.rfftfreq(M, 1.0 / M)                      # harmonics k = 0..M/2 of omega_b
    mult = 1.0 / (1.0 - (k * b.omega) ** 2)
    s, L, first = None, None, length
    for i, j in enumerate(js):
        n = (c0 + j - 1) % N if b.bc == "periodic" else c0 + j - 1
        resolved = (b.bc == "periodic" or n < N) and s is None
        if resolved:
            m = float(np.max(np.abs(X[:, n])))
            if m >= start_rel * amp:
                out[i] = np.log10(m)
                s_prev, L_prev = X[:, n] / m, np.log(m)
                continue
            s, L, first = s_prev, L_prev, i
        assert s is not None, "the recursion starts inside the chain: its end bead is below start_rel max|x|"
        f = np.maximum(s, 0.0) ** b.alpha
        y = np.fft.irfft(np.fft.rfft(f) * mult, M)
        m = float(np.max(np.abs(y)))
        s, L = y / m, b.alpha * L + np.log(m)  # type: ignore[operator]  # L set with s
        out[i] = L / np.log(10.0)
    return js, out, first


def double_exponential_slope(log10_amp: Floats, log10_max: float, first: int) -> float:
    """Slope of ln(-ln(|x_j| / max|x|)) against j over the recursed beads (DpS: ln alpha)."""
    r = (np.asarray(log10_amp[first:]) - log10_max) * np.log(10.0)
    j = np.arange(first, len(log10_amp)) + 1
    ok = np.isfinite(r) & (r < 0)
    if ok.sum() < 2:
        return float("nan")
    return float(np.polyfit(j[ok], np.log(-r[ok]), 1)[0])
