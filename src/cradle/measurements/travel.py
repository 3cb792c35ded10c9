"""Where a localised DpS solution is on its ring, and how far it went: the verdicts of the mobility runs.

The position is the peak of |A_n|^2 refined by the parabola through the largest site and its two neighbours,
unwrapped on the ring (a breather that travels round the ring keeps counting); the displacement is
max_tau |x(tau) - x(0)|, and a run "travels" when it exceeds a threshold (in sites), else it is "pinned".
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray


def peak_position(A: ArrayLike) -> NDArray[np.float64]:
    """The position (sites) of the largest |A_n|^2 in each row of ``A`` (T x N), parabola-refined, unwrapped."""
    m = np.abs(np.asarray(A)) ** 2
    N = m.shape[-1]
    i = np.argmax(m, axis=-1)
    left, mid, right = (np.take_along_axis(m, ((i + k) % N)[:, None], -1)[:, 0] for k in (-1, 0, 1))
    den = left - 2.0 * mid + right
    off = np.where(den != 0, 0.5 * (left - right) / np.where(den != 0, den, 1.0), 0.0)
    x = (i + off).astype(np.float64)
    return np.unwrap(x * 2.0 * np.pi / N) * N / (2.0 * np.pi)


def displacement(A: ArrayLike) -> float:
    """max over the rows of |x - x_0|, x the :func:`peak_position`."""
    x = peak_position(A)
    return float(np.max(np.abs(x - x[0])))
