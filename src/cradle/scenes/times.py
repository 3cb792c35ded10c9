"""The times a scene stores: 0, the grid k*every on [0, t_end], t_end and the snapshots, told apart to
:data:`cradle.specs.values.TIME_TOL`."""
from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from cradle.specs.values import TIME_TOL


def grid_size(snapshots: Sequence[float] | None, every: float | None, t_end: float) -> int:
    """An upper bound on the number of times :func:`store_times` gives for these ``snapshots`` and ``every``."""
    n = len(snapshots or ()) + 2
    if every:
        k = t_end / every * (1.0 + 1e-12) + TIME_TOL
        n += int(math.floor(min(k, 1e18))) + 1   # t_end / every may overflow to inf
    return n


def store_times(snapshots: Sequence[float] | None, every: float | None, t_end: float) -> list[float]:
    """The sorted times a scene stores: 0, the grid k*every on [0, t_end], t_end and the snapshots.

    Times are rounded to 1e-9; times closer than 1e-9 (e.g. a snapshot on the
    grid) are one time. 0 and t_end are always included.
    """
    t_end = float(t_end)
    parts = [np.array([0.0, t_end]), np.asarray([float(s) for s in snapshots or ()], dtype=float)]
    if every:
        every = float(every)
        n = int(math.floor(t_end / every * (1.0 + 1e-12) + TIME_TOL))
        grid = np.arange(n + 1) * every
        parts.append(grid[grid <= t_end + TIME_TOL])
    t = np.sort(np.concatenate(parts))
    keep = np.ones(t.size, dtype=bool)
    keep[1:] = np.diff(t) > TIME_TOL  # a time within TIME_TOL of the previous one is the same time
    t = np.round(t[keep], 9)
    t[0] = 0.0
    if abs(t[-1] - t_end) <= TIME_TOL:
        t[-1] = round(t_end, 9)
    return t.tolist()
