"""Slow motion at impacts: which stored states of a run a movie shows, chosen from its impact times.

A desk toy's contact lasts about 1e-4 of a swing (the Hertz contact time t_c,
:func:`cradle.models.desk_toy.collision_time_nc`): a movie whose frames are evenly spaced in time never shows
one. The run is stored instead on a uniform grid t_j = t_0 + j h with h a fraction of t_c, and the movie shows
a subset of its states:

* inside an impact window (:func:`impact_windows`: from ``margin`` before a contact starts to ``margin`` after
  it ends; windows that overlap are one), every stored state: the frame spacing is h;
* outside, the frame spacing grows geometrically with the distance to the nearest window, by the factor
  ``ramp`` per frame, h, h ramp, h ramp^2, ..., until it reaches ``sparse``; between the ramps of two windows
  the frames are evenly spaced, at most ``sparse`` apart (:func:`frame_indices`).

Played at a fixed frame rate, the movie slows down smoothly into each impact and speeds up out of it (the speed
of frame k, in seconds of the run per second of movie, is (t_k - t_(k-1)) times the frame rate:
:func:`cradle.figures.desk_toy_movie.playback_speed`).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from collections.abc import Iterable

    from numpy.typing import ArrayLike, NDArray


def _runs(flags: NDArray[np.bool_]) -> list[tuple[int, int]]:
    """(first, last) index of every run of True in ``flags``."""
    padded = np.concatenate([[False], flags, [False]]).astype(np.int8)
    edges = np.flatnonzero(np.diff(padded))
    return [(int(a), int(b) - 1) for a, b in zip(edges[::2], edges[1::2], strict=True)]


def impact_windows(t: ArrayLike, touching: ArrayLike, margin: float,
                   instants: Iterable[float] = ()) -> NDArray[np.float64]:
    """The impact windows (k, 2) of a run stored at the times ``t``, in time order, disjoint: each run of
    stored states with ``touching`` True (a bond compressed) and each of the ``instants`` (a hard sphere's
    collision, which lasts no time) widened by ``margin`` on both sides and clipped to [t_0, t_end]; windows
    that overlap are merged."""
    t = np.asarray(t, dtype=float)
    touching = np.asarray(touching, dtype=bool)
    if touching.shape != t.shape:
        raise ValueError(f"touching has shape {touching.shape}, t {t.shape}: one flag per stored time")
    if not margin >= 0:
        raise ValueError(f"margin = {margin!r}: must be >= 0 (a time)")
    spans = [(t[a], t[b]) for a, b in _runs(touching)] + [(float(s), float(s)) for s in instants]
    merged: list[list[float]] = []
    for a, b in sorted(spans):
        lo, hi = max(a - margin, t[0]), min(b + margin, t[-1])
        if merged and lo <= merged[-1][1]:
            merged[-1][1] = max(merged[-1][1], hi)
        else:
            merged.append([lo, hi])
    return np.array(merged, dtype=float).reshape(-1, 2)


def ramp_offsets(h: float, sparse: float, ramp: float) -> NDArray[np.float64]:
    """Distances from a window's edge of the frames of its ramp: d_j = h (ramp^j - 1) / (ramp - 1), j = 1, 2, ...,
    while the spacing h ramp^(j-1) that leads to d_j is below ``sparse``."""
    if not ramp > 1:
        raise ValueError(f"ramp = {ramp!r}: must be > 1 (the growth of the frame spacing per frame)")
    if not sparse >= h > 0:
        raise ValueError(f"sparse = {sparse!r}, h = {h!r}: need sparse >= h > 0")
    steps = max(0, math.ceil(math.log(sparse / h) / math.log(ramp)))
    return np.asarray(h * (ramp ** np.arange(1, steps + 1, dtype=float) - 1.0) / (ramp - 1.0), dtype=np.float64)


def frame_indices(t: ArrayLike, windows: ArrayLike, sparse: float, ramp: float) -> NDArray[np.int64]:
    """Indices into the uniform grid ``t`` of the frames (module docstring): every stored state inside each of the
    ``windows`` (:func:`impact_windows`), a ramp of spacings h ramp^j on each side, and between the ramps evenly
    spaced frames at most ``sparse`` apart; the first and last stored states always. Each frame is a stored
    state: times are rounded to the grid, never interpolated."""
    t = np.asarray(t, dtype=float)
    if t.ndim != 1 or t.size < 2:
        raise ValueError("t must hold at least two stored times")
    h = (t[-1] - t[0]) / (t.size - 1)
    if not np.allclose(np.diff(t), h, rtol=1e-6, atol=0.0):
        raise ValueError("t must be a uniform grid (the frames are its stored states)")
    w = np.asarray(windows, dtype=float).reshape(-1, 2)
    offsets = ramp_offsets(h, max(sparse, h), ramp)
    reach = offsets[-1] if offsets.size else 0.0
    def index(times: NDArray[np.float64]) -> NDArray[np.int64]:
        return np.rint((times[(times >= t[0]) & (times <= t[-1])] - t[0]) / h).astype(np.int64)

    picks = [np.array([0, t.size - 1])]
    # the regions between windows farther than a ramp's reach from any: evenly spaced frames
    free_lo = [t[0]] + list(w[:, 1] + reach)
    free_hi = list(w[:, 0] - reach) + [t[-1]]
    for a, b in w:
        lo, hi = index(np.array([max(a, t[0]), min(b, t[-1])]))
        picks += [np.arange(lo, hi + 1), index(a - offsets), index(b + offsets)]
    for a, b in zip(free_lo, free_hi, strict=True):
        if b > a:
            picks.append(index(np.linspace(a, b, math.ceil((b - a) / sparse) + 1)))
    return np.unique(np.clip(np.concatenate(picks), 0, t.size - 1))
