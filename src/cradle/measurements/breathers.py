"""Measurements on breathers from stored trajectories (section 4.3, figures plot18, loc1, fini).

Pure numpy on arrays: the peak compression of every bond per breather
period (the outcome of two interacting breathers, loc1, is
:mod:`cradle.measurements.interactions`), a breather's frequency from zero crossings and the number of
periods after which exact and approximate solutions drift half a period
apart (plot18, fini), the amplitude radiated away from a breather's core
(plot18, large amplitude).
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray


def peak_compression(t: ArrayLike, force: ArrayLike, period: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Window starts and the peak compression max |f_n| of every bond in each breather period.

    ``t`` (T,) increasing stored times, ``force`` (T, N); windows are
    [t_0 + k period, t_0 + (k+1) period), k = 0..K-1, only complete windows
    (a window holding no stored time gives a row of NaN). Returns
    (starts (K,), P (K, N)).
    """
    t = np.asarray(t, dtype=float)
    f = np.abs(np.asarray(force, dtype=float))
    if f.ndim != 2 or f.shape[0] != t.size:
        raise ValueError(f"force must have shape (len(t), N), got {f.shape} with len(t) = {t.size}")
    if not period > 0:
        raise ValueError(f"period must be > 0, got {period!r}")
    span = t[-1] - t[0]
    K = int(np.floor(span / period + 1e-9))
    starts = t[0] + period * np.arange(K)
    P = np.full((K, f.shape[1]), np.nan)
    k = np.floor((t - t[0]) / period + 1e-9).astype(int)
    if K and np.all(k[1:] >= k[:-1]):
        # increasing times: each window's rows are one contiguous block, reduced at once
        first = np.searchsorted(k, np.arange(K + 1))
        full = first[1:] > first[:-1]
        if full.any():
            P[full] = np.maximum.reduceat(f[:first[-1]], first[:-1][full], axis=0)
        return starts, P
    for i in range(K):
        rows = f[k == i]
        if rows.size:
            P[i] = rows.max(axis=0)
    return starts, P


def frequency_from_crossings(t: ArrayLike, x: ArrayLike) -> float:
    """Angular frequency of an oscillating signal x(t) from its upward zero crossings
    (linear interpolation between samples, then a least-squares line through
    crossing time against crossing number). NaN with fewer than 3 crossings."""
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    i = np.flatnonzero((x[:-1] < 0) & (x[1:] >= 0))
    if i.size < 3:
        return float("nan")
    tc = t[i] - x[i] * (t[i + 1] - t[i]) / (x[i + 1] - x[i])
    slope = np.polyfit(np.arange(tc.size), tc, 1)[0]
    return float(2.0 * np.pi / slope)


def half_period_shift(t: ArrayLike, x_exact: ArrayLike, x_approx: ArrayLike,
                      omega_sw: float) -> dict[str, float]:
    """Frequencies of exact and approximate signals (zero crossings) and the number of
    breather periods after which they drift half a period apart, pi / |omega_ex - omega_app|
    in units of 2 pi / omega_sw."""
    w_ex = frequency_from_crossings(t, x_exact)
    w_ap = frequency_from_crossings(t, x_approx)
    dw = abs(w_ex - w_ap)
    periods = (np.pi / dw) / (2.0 * np.pi / omega_sw) if dw > 0 else float("inf")
    return {"omega_exact": w_ex, "omega_approx": w_ap, "half_shift_periods": float(periods)}


def dispersive_amplitude(x: ArrayLike, core: float, halfwidth: float = 6, periodic: bool = True) -> float:
    """max |x_n| over the sites farther than ``halfwidth`` from ``core`` (a site or a bond midpoint):
    the amplitude of what the breather radiated (plot18, bottom right)."""
    x = np.asarray(x, dtype=float)
    n = np.arange(x.size)
    d = np.abs(n - core)
    if periodic:
        d = np.minimum(d, x.size - d)
    far = d > halfwidth
    return float(np.max(np.abs(x[far]))) if far.any() else 0.0
