"""Measurements of the desk-toy experiments on stored runs (t, x, v) of either model: the lattice (nc) or the
hard-sphere cradle (:mod:`cradle.models.hard_spheres`), in (nc)'s variables, the lifted balls at the left end
released at rest at t = 0 (:mod:`cradle.models.desk_toy`).

* Each bead's energy (:func:`bead_energies`): (v_n^2 + x_n^2)/2 plus half the Hertz energy V0 of (vhertz) of
  each of its bonds (free ends), so that the beads' energies sum to (ham). Hard spheres have no bond energy
  (their gaps are >= 0, where V0 = 0).
* One out, one out (:func:`out_fractions`, :func:`pattern_hold`). In the ideal cradle the released balls hit
  the line at t = pi/2, the same number of balls leave the far end and are at their largest swing at t = pi,
  come back at 3 pi/2, and the balls at the release end are out at t = 2 pi: at t = k pi (k = 1, 2, ...) the
  ``lifted`` outermost balls of the right end (k odd) or of the left end (k even) carry all the energy. The
  measured fraction f_k is their share of the energy at the stored time nearest k pi; the pattern holds while
  f_k >= a threshold, and breaks at the first k pi where it does not. The result depends on the threshold: it
  is an argument, and the benchmark reports two.
* The break-up of the line (:func:`cascade_end`, :func:`line_state`): Hutzler, Delaney, Weaire & MacLeod (Am. J.
  Phys. 72 (2004) 1508) observe that the first impact breaks the line: the balls that should stay at rest
  leave with small velocities and small gaps open between them. The first cascade ends at the first stored
  time after the first compression at which no bond is compressed; the velocities there, and the gaps at a
  later time (the first largest swing, t = pi), are what the benchmark reports. Between contacts a gap is
  harmonic (every bead has the same on-site frequency): a gap opened at t_e with rate w has grown to
  w sin(t - t_e) at t.
* The energy per bead per swing (:func:`energy_per_swing`): the time average of each bead's energy over each
  swing period 2 pi, [2 pi k, 2 pi (k+1)).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.models.lattice import V0, bond_elongations


def _arrays(t: ArrayLike, x: ArrayLike,
            v: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    v = np.asarray(v, dtype=float)
    if t.ndim != 1 or x.ndim != 2 or x.shape != v.shape or x.shape[0] != t.size:
        raise ValueError(f"t (T,), x and v (T, N) expected, got t {t.shape}, x {x.shape}, v {v.shape}")
    return t, x, v


def bead_energies(x: ArrayLike, v: ArrayLike, alpha: float = 1.5) -> NDArray[np.float64]:
    """Each bead's energy (module docstring), shape of ``x``: beads on the last axis, free ends."""
    x = np.asarray(x, dtype=float)
    v = np.asarray(v, dtype=float)
    bond = V0(bond_elongations(x, "free"), alpha)   # bond n: beads n, n+1; the last is absent (0)
    half = 0.5 * bond
    left = np.roll(half, 1, axis=-1)
    left[..., 0] = 0.0
    return 0.5 * (v**2 + x**2) + half + left


def out_fractions(t: ArrayLike, x: ArrayLike, v: ArrayLike, lifted: int,
                  alpha: float = 1.5) -> tuple[NDArray[np.floating], NDArray[np.float64]]:
    """(times k pi, f_k) for k = 1 .. floor(t_end / pi): the share of the energy carried at the stored time
    nearest k pi by the ``lifted`` outermost balls of the right end (k odd) or the left end (k even)."""
    t, x, v = _arrays(t, x, v)
    N = x.shape[1]
    if not 1 <= lifted < N:
        raise ValueError(f"lifted = {lifted!r}: must be in [1, N - 1] with N = {N}")
    ks = np.arange(1, int(np.floor(t[-1] / np.pi + 1e-9)) + 1)
    times = ks * np.pi
    idx = np.clip(np.searchsorted(t, times), 1, t.size - 1)
    idx = np.where(np.abs(t[idx - 1] - times) <= np.abs(t[idx] - times), idx - 1, idx)
    e = bead_energies(x[idx], v[idx], alpha)
    right = e[:, N - lifted:].sum(axis=1)
    left = e[:, :lifted].sum(axis=1)
    out = np.where(ks % 2 == 1, right, left) / e.sum(axis=1)
    return times, out


@dataclass(frozen=True)
class PatternHold:
    """How long one-out-one-out holds under ``threshold``: ``swings`` out-swings in a row from the first with
    f_k >= threshold, broken at ``t_break`` = (swings + 1) pi (NaN: it held through the run, ``measured``
    out-swings)."""

    threshold: float
    swings: int
    t_break: float
    measured: int


def pattern_hold(t: ArrayLike, x: ArrayLike, v: ArrayLike, lifted: int, threshold: float,
                 alpha: float = 1.5) -> PatternHold:
    """The one-out-one-out duration under ``threshold`` (in (0, 1)) from :func:`out_fractions`."""
    if not 0.0 < threshold < 1.0:
        raise ValueError(f"threshold = {threshold!r}: must be in (0, 1) (a share of the energy)")
    times, f = out_fractions(t, x, v, lifted, alpha)
    below = np.flatnonzero(f < threshold)
    if below.size == 0:
        return PatternHold(threshold, int(f.size), float("nan"), int(f.size))
    return PatternHold(threshold, int(below[0]), float(times[below[0]]), int(f.size))


def cascade_end(t: ArrayLike, x: ArrayLike) -> tuple[float, float, int]:
    """(t_start, t_end, index of t_end): the first stored time with a compressed bond (x_{n+1} < x_n) and the
    first stored time after it with none. NaN (and -1) where the run has no compression (hard spheres:
    contacts take no time) or it never ends."""
    t = np.asarray(t, dtype=float)
    d = np.diff(np.asarray(x, dtype=float), axis=-1)
    compressed = np.any(d < 0.0, axis=1)
    hits = np.flatnonzero(compressed)
    if hits.size == 0:
        return float("nan"), float("nan"), -1
    after = np.flatnonzero(~compressed[hits[0]:])
    if after.size == 0:
        return float(t[hits[0]]), float("nan"), -1
    i = int(hits[0] + after[0])
    return float(t[hits[0]]), float(t[i]), i


def line_state(t: ArrayLike, x: ArrayLike, v: ArrayLike, at: float) -> tuple[float, np.ndarray, np.ndarray]:
    """(stored time nearest ``at``, gaps x_{n+1} - x_n (N-1,), velocities (N,)) there."""
    t, x, v = _arrays(t, x, v)
    i = int(np.argmin(np.abs(t - at)))
    return float(t[i]), np.diff(x[i]), v[i].copy()


def energy_per_swing(t: ArrayLike, x: ArrayLike, v: ArrayLike,
                     alpha: float = 1.5) -> tuple[NDArray[np.floating], NDArray[np.float64]]:
    """(window starts 2 pi k, E (K, N)): each bead's energy averaged over the stored times of each swing period
    [2 pi k, 2 pi (k+1)) that ends by the last stored time, k = 0 .. K-1 (times from the release, t = 0; on a
    uniform grid the sample mean is the time average; a window holding no stored time gives a row of NaN)."""
    t, x, v = _arrays(t, x, v)
    K = int(np.floor(t[-1] / (2.0 * np.pi) + 1e-9))
    e = bead_energies(x, v, alpha)
    k = np.floor(t / (2.0 * np.pi) + 1e-12).astype(int)
    out = np.full((K, x.shape[1]), np.nan)
    for i in range(K):
        rows = e[k == i]
        if rows.size:
            out[i] = rows.mean(axis=0)
    return 2.0 * np.pi * np.arange(K), out
