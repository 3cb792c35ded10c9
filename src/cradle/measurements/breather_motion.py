"""A localised state in motion on a ring: where it is, how fast it goes, how much it leaves behind.

Both models are measured by one weight per site w_n(t) >= 0 whose sum is conserved: the lattice's energy density
(:func:`energy_density`, the split of (ham) that gives each bead half of its two bonds), and for (dfnls) the norm
density |A_n|^2 (the lattice's energy is 2 eps^2 sum |A_n|^2 to leading order through (ansatz), so the two
weights agree there up to that factor). Then

* the position (:func:`track`): the centroid of w over the ``core`` sites either side of its peak, the peak
  followed from sample to sample (searched within :data:`REACH` sites of the last position; a sample whose
  largest weight lies farther is refused) and unwrapped on the ring, so that a state that travels round keeps
  counting;
* the velocity (:func:`velocity`): the least-squares slope of the position against time;
* the radiation (:func:`radiation`): the fraction of sum w outside the ``window`` sites either side of the
  position: what the state has left behind (and, at t = 0, its own tail).
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.models import lattice

#: sites either side of the last position in which the peak is looked for at the next sample (a sampling that
#: moves the state farther between samples is refused)
REACH = 2


def energy_density(x: ArrayLike, v: ArrayLike, alpha: float) -> NDArray[np.float64]:
    """e_n = v_n^2/2 + x_n^2/2 + (V0(x_{n+1} - x_n) + V0(x_n - x_{n-1}))/2 on the ring (last axis n): sum_n e_n
    is the Hamiltonian (ham)."""
    x = np.asarray(x, dtype=float)
    bonds = lattice.V0(lattice.bond_elongations(x), alpha)
    return 0.5 * np.asarray(v, dtype=float) ** 2 + 0.5 * x**2 + 0.5 * (bonds + np.roll(bonds, 1, axis=-1))


def track(w: ArrayLike, core: int) -> NDArray[np.float64]:
    """The position (sites, unwrapped) at each row of ``w`` (samples x sites): the centroid of w over the 2 core + 1
    sites around its peak, the peak looked for within :data:`REACH` sites of the previous position."""
    w = np.asarray(w, dtype=float)
    M = w.shape[-1]
    offsets = np.arange(-core, core + 1)
    near = np.arange(-REACH, REACH + 1)
    out = np.empty(w.shape[0])
    prev = None
    for j, row in enumerate(w):
        if prev is None:
            peak = int(np.argmax(row))
        else:
            cand = (int(round(prev)) + near) % M
            peak = int(cand[np.argmax(row[cand])])
            top = int(np.argmax(row))
            if row[top] > row[peak] and abs((top - peak + M // 2) % M - M // 2) > REACH:
                raise ValueError(f"the peak left the {REACH} sites around the last position between samples {j - 1} "
                                 f"and {j}: sample more often")
        idx = (peak + offsets) % M
        p = peak + float(np.sum(offsets * row[idx]) / np.sum(row[idx]))
        if prev is not None:
            p = prev + ((p - prev + M / 2) % M - M / 2)
        out[j] = p
        prev = p
    return out


def velocity(t: ArrayLike, position: ArrayLike) -> float:
    """The least-squares slope of the position against t (sites per unit time)."""
    return float(np.polyfit(np.asarray(t, dtype=float), np.asarray(position, dtype=float), 1)[0])


def radiation(w: ArrayLike, position: ArrayLike, window: int) -> NDArray[np.float64]:
    """At each row: sum of w outside the 2 window + 1 sites around round(position), over sum w."""
    w = np.asarray(w, dtype=float)
    M = w.shape[-1]
    offsets = np.arange(-window, window + 1)
    idx = (np.rint(np.asarray(position)).astype(int)[:, None] + offsets[None, :]) % M
    inside = np.take_along_axis(w, idx, axis=-1).sum(axis=-1)
    return np.asarray(1.0 - inside / w.sum(axis=-1), dtype=np.float64)
