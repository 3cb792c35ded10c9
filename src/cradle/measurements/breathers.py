"""Measurements on breathers from stored trajectories (section 4.3, figures plot18, loc1, fini).

Pure numpy on arrays: the peak compression of every bond per breather
period, the number of breathers it shows, the merging time of two breathers
(loc1), a breather's frequency from zero crossings and the number of
periods after which exact and approximate solutions drift half a period
apart (plot18, fini), the amplitude radiated away from a breather's core
(plot18, large amplitude).
"""
from __future__ import annotations

import numpy as np

# merging_time: a breather is a run of consecutive bonds whose peak compression over one breather
# period reaches MERGE_REL times the largest of that period; the merged state must last at least
# MERGE_MIN_PERIODS periods before the end of the data to count (see merging_time).
MERGE_REL = 0.5
MERGE_MIN_PERIODS = 50.0


def peak_compression(t, force, period):
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
    for i in range(K):
        rows = f[k == i]
        if rows.size:
            P[i] = rows.max(axis=0)
    return starts, P


def count_humps(profile, rel=MERGE_REL, periodic=True) -> int:
    """Number of humps of a non-negative profile: maximal runs of consecutive sites
    (cyclically if ``periodic``) whose value is >= rel * max. 0 for an all-zero or NaN profile."""
    p = np.asarray(profile, dtype=float)
    top = np.nanmax(p) if np.any(np.isfinite(p)) else np.nan
    if not np.isfinite(top) or top <= 0:
        return 0
    above = p >= rel * top
    if above.all():
        return 1
    starts = above & ~np.roll(above, 1)          # a run begins where the previous site is below
    if not periodic:
        starts[0] = above[0]
    return int(np.count_nonzero(starts))


def merging_time(ds, period=None, *, rel=MERGE_REL, min_periods=MERGE_MIN_PERIODS, periodic=True) -> float:
    """Merging time of two breathers, in breather periods, from stored forces.

    ``ds`` is anything indexable by "t" (T,) and "force" (T, N) (an xarray
    Dataset of results/sim/<scene>/{exact,dps}.nc or a dict of arrays);
    ``period`` defaults to 2 pi / ds.attrs["omega_sw"]. Pure numpy on the
    arrays.

    Criterion. The time axis is cut into breather periods; in each, the
    localisation profile is the peak compression max_t |f_n| of every bond
    (:func:`peak_compression`). A breather is a maximal run of consecutive
    bonds whose peak compression is at least ``rel`` times the period's
    largest (:func:`count_humps`). The breathers have merged at the start of
    the first period from which every later period shows a single such run;
    that single-breather state must last at least ``min_periods`` periods
    before the end of the data (otherwise a last transient overlap, e.g. two
    travelling breathers crossing at the end, would count). Returns the
    merging time in periods (t_merge - t_0) / period, 0.0 if the data hold a
    single breather throughout, NaN if the breathers have not merged for good.
    """
    t = np.asarray(ds["t"], dtype=float)
    force = np.asarray(ds["force"], dtype=float)
    if period is None:
        period = 2.0 * np.pi / float(ds.attrs["omega_sw"])
    starts, P = peak_compression(t, force, period)
    return merging_time_of_peaks(starts, P, t[0], period, rel=rel, min_periods=min_periods, periodic=periodic)


def merging_time_of_peaks(starts, P, t0, period, *, rel=MERGE_REL, min_periods=MERGE_MIN_PERIODS,
                          periodic=True) -> float:
    """:func:`merging_time` from the peak compression ``P`` (K, N) of the periods starting at ``starts``
    (:func:`peak_compression`; the streamed scene job accumulates them block by block)."""
    if len(starts) == 0:
        return float("nan")
    counts = np.array([count_humps(p, rel, periodic) for p in P])
    single = counts == 1
    if not single[-1]:
        return float("nan")
    not_single = np.flatnonzero(~single)
    first = int(not_single[-1]) + 1 if not_single.size else 0
    if len(starts) - first < min_periods:
        return float("nan")
    return float((starts[first] - t0) / period)


def frequency_from_crossings(t, x) -> float:
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


def half_period_shift(t, x_exact, x_approx, omega_sw) -> dict:
    """Frequencies of exact and approximate signals (zero crossings) and the number of
    breather periods after which they drift half a period apart, pi / |omega_ex - omega_app|
    in units of 2 pi / omega_sw."""
    w_ex = frequency_from_crossings(t, x_exact)
    w_ap = frequency_from_crossings(t, x_approx)
    dw = abs(w_ex - w_ap)
    periods = (np.pi / dw) / (2.0 * np.pi / omega_sw) if dw > 0 else float("inf")
    return {"omega_exact": w_ex, "omega_approx": w_ap, "half_shift_periods": float(periods)}


def dispersive_amplitude(x, core, halfwidth=6, periodic=True) -> float:
    """max |x_n| over the sites farther than ``halfwidth`` from ``core`` (a site or a bond midpoint):
    the amplitude of what the breather radiated (plot18, bottom right)."""
    x = np.asarray(x, dtype=float)
    n = np.arange(x.size)
    d = np.abs(n - core)
    if periodic:
        d = np.minimum(d, x.size - d)
    far = d > halfwidth
    return float(np.max(np.abs(x[far]))) if far.any() else 0.0
