"""The compression pulse of an impact on a chain, measured on a stored run (t, v): when it reaches each bead,
how fast it travels, how wide it is.

A pulse running along a chain of touching beads gives each bead in turn a velocity bump. For bead n:

* its arrival time t_n and peak velocity v_n (:func:`peaks`): the largest stored v_n(t), refined by the parabola
  through it and its two neighbours (exact for a peak sampled finely enough to be quadratic there);
* the pulse's speed between beads n-1 and n+1 (:func:`local_speeds`): 2 / (t_{n+1} - t_{n-1}) sites per unit
  time, and over a stretch of beads the slope of n against t_n (:func:`fitted_speed`);
* its width (:func:`widths`): the full width at half maximum of v_n(t) in time, times the local speed, in sites.
  For a travelling wave x_n(t) = X(n - c t) this is the full width at half maximum of the velocity profile
  v(xi) of :mod:`cradle.models.solitary`, so the two compare directly.

Units are those of the run (sites, and its time and velocity); the caller converts to SI.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray


def peaks(t: ArrayLike, v: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(t_n, v_n): the time and value of each bead's largest velocity (``v`` of shape (time, bead)), refined by the
    parabola through the stored maximum and its neighbours (a maximum at the first or last stored time is kept
    as stored)."""
    t = np.asarray(t, dtype=float)
    v = np.asarray(v, dtype=float)
    i = np.argmax(v, axis=0)
    cols = np.arange(v.shape[1])
    tn, vn = t[i].copy(), v[i, cols].copy()
    inner = (i > 0) & (i < t.size - 1)
    j, k = i[inner], cols[inner]
    y0, y1, y2 = v[j - 1, k], v[j, k], v[j + 1, k]
    h = t[j + 1] - t[j]   # a uniform stretch of stored times around the peak
    den = y0 - 2.0 * y1 + y2
    s = np.where(den < 0.0, 0.5 * (y0 - y2) / np.where(den < 0.0, den, -1.0), 0.0)
    tn[inner] = t[j] + s * h
    vn[inner] = y1 - 0.25 * (y0 - y2) * s
    return tn, vn


def local_speeds(tn: ArrayLike) -> NDArray[np.float64]:
    """2 / (t_{n+1} - t_{n-1}) (sites per unit time) at each inner bead n, NaN at the two ends."""
    tn = np.asarray(tn, dtype=float)
    out = np.full(tn.size, np.nan)
    out[1:-1] = 2.0 / (tn[2:] - tn[:-2])
    return out


def fitted_speed(tn: ArrayLike, beads: ArrayLike) -> float:
    """The least-squares slope of the bead index against t_n over ``beads`` (indices): sites per unit time."""
    b = np.asarray(beads, dtype=int)
    return float(np.polyfit(np.asarray(tn, dtype=float)[b], b.astype(float), 1)[0])


def widths(t: ArrayLike, v: ArrayLike, speeds: ArrayLike) -> NDArray[np.float64]:
    """Each bead's full width at half maximum of v_n(t) (crossings by linear interpolation) times its speed
    (``speeds``, sites per unit time): the pulse's width in sites; NaN where the speed is NaN or v_n(t) does
    not fall below half its peak on both sides within the stored times."""
    t = np.asarray(t, dtype=float)
    v = np.asarray(v, dtype=float)
    sp = np.asarray(speeds, dtype=float)
    out = np.full(v.shape[1], np.nan)
    for n in range(v.shape[1]):
        y = v[:, n]
        i = int(np.argmax(y))
        half = 0.5 * y[i]
        below_l = np.flatnonzero(y[:i] < half)
        below_r = np.flatnonzero(y[i:] < half)
        if not (below_l.size and below_r.size and np.isfinite(sp[n])):
            continue
        a = int(below_l[-1])
        b = i + int(below_r[0])
        left = t[a] + (half - y[a]) * (t[a + 1] - t[a]) / (y[a + 1] - y[a])
        right = t[b - 1] + (half - y[b - 1]) * (t[b] - t[b - 1]) / (y[b] - y[b - 1])
        out[n] = (right - left) * sp[n]
    return out
