"""Checks of the arrays the lattice and DpS drivers take (initial states, output times; clear ValueErrors).

Their scalar arguments are checked against the shared declarations (``cradle.specs.checked``)."""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, DTypeLike


def check_times(t: ArrayLike, name: str) -> np.ndarray:
    """Output times: 1-D, non-empty, finite, >= 0 and strictly increasing."""
    t = np.asarray(t, dtype=float)
    if t.ndim == 0:
        t = t.reshape(1)
    if t.ndim != 1 or t.size == 0:
        raise ValueError(f"{name} must be a non-empty 1-D array of times, got shape {t.shape}")
    if not np.all(np.isfinite(t)):
        bad = float(t[~np.isfinite(t)][0])
        raise ValueError(f"{name} must be finite, got {name} containing {bad!r}")
    if t[0] < 0.0:
        raise ValueError(f"{name} must be >= 0 (integration starts at 0), got {name}[0]={float(t[0])!r}")
    if t.size > 1:
        dif = np.diff(t)
        if np.any(dif <= 0.0):
            i = int(np.argmax(dif <= 0.0))
            raise ValueError(
                f"{name} must be strictly increasing, "
                f"got {name}[{i}]={float(t[i])!r} >= {name}[{i + 1}]={float(t[i + 1])!r}"
            )
    return t


def check_state(arr: ArrayLike, name: str, dtype: DTypeLike = float) -> np.ndarray:
    """A finite 1-D state vector with N >= 2 entries."""
    arr = np.array(arr, dtype=dtype, copy=True)
    if arr.ndim != 1:
        raise ValueError(f"{name} must be 1-D (one value per bead), got shape {arr.shape}")
    if arr.size < 2:
        raise ValueError(f"N must be >= 2, got {name} with N={arr.size}")
    if not np.all(np.isfinite(arr)):
        i = int(np.argmax(~np.isfinite(arr)))
        raise ValueError(f"{name} must be finite, got {name}[{i}]={arr[i].item()!r}")
    return arr

