"""Measurements of the trapping analysis on stored runs (t, x, v) of the (imperfect) cradle: the energy per bead,
the static-breather detector and the energy budget of a chain hit by an incident wave.

* The energy per bead (:func:`site_energies`): the generalised (ham) of (ncimperfect) with harmonic on-site
  potential and no precompression, split per bead,

      e_n = m_n v_n^2 / 2 + m_n omega_n^2 x_n^2 / 2 + (k_{n-1} V0(x_n - x_{n-1}) + k_n V0(x_{n+1} - x_n)) / 2,

  each bond's Hertz energy V0 of (vhertz) shared half and half by its two beads (free ends: the end beads have
  one bond), so that sum_n e_n = H. With m = omega = k = 1 it is (ham) of (nc) split as
  :func:`cradle.measurements.desk_toy.bead_energies` does.
* The static-breather detector (:func:`static_breathers`), at a measurement time T with a window W and a
  threshold theta (both choices: the analysis reports every pair it is given):

  1. the window means e_bar_n of e_n(t) over the samples with T - W <= t <= T;
  2. the peaks: local maxima p of e_bar above theta E_ref (E_ref: the energy put in), strongest first, each
     taking the region R = [p - r, p + r] (``radius`` r, clipped to the chain and to the regions already
     taken); a peak within r of a stronger one is part of its breather;
  3. a region is localised when e_bar at its outer ends (inside the chain) is below ``contrast`` e_bar_p: a
     peak, not the plateau of an extended state (the wake a striker leaves behind);
  4. it holds a static breather when its energy centre c_R(t) = sum_{n in R} n e_n(t) / E_R(t),
     E_R(t) = sum_{n in R} e_n(t), read at every sample of the window, moves by at most ``max_shift`` beads
     (max c_R - min c_R): a breather moving faster than max_shift / W beads per unit time is mobile (its mean
     energy is smeared along its path and its centre moves).

  The energy trapped is sum over the static regions of E_R(T), the energy they hold at the measurement time.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.models.lattice import V0


def site_energies(x: ArrayLike, v: ArrayLike, alpha: float, omega: ArrayLike | None = None,
                  mass: ArrayLike | None = None, stiffness: ArrayLike | None = None) -> NDArray[np.float64]:
    """e_n of the module docstring, shape of ``x`` (beads on the last axis, free ends): ``omega``, ``mass`` (N,)
    and ``stiffness`` (N - 1 bonds, or N with the last ignored) default to 1."""
    x = np.asarray(x, dtype=float)
    v = np.asarray(v, dtype=float)
    N = x.shape[-1]
    m = np.ones(N) if mass is None else np.asarray(mass, dtype=float)
    w = np.ones(N) if omega is None else np.asarray(omega, dtype=float)
    k = np.ones(N - 1) if stiffness is None else np.asarray(stiffness, dtype=float)[: N - 1]
    half = 0.5 * k * V0(np.diff(x, axis=-1), alpha)          # bond n: beads n, n+1
    e = 0.5 * m * (v**2 + w**2 * x**2)
    e[..., :-1] += half
    e[..., 1:] += half
    return e


class Detected(NamedTuple):
    """The static breathers found at one measurement time: their regions [start, stop) (bead indices), the
    energy E_R(T) each holds, its mean centre over the window and how far that centre moved."""

    start: np.ndarray
    stop: np.ndarray
    energy: np.ndarray
    centre: np.ndarray
    shift: np.ndarray

    @property
    def total(self) -> float:
        """The energy trapped: the sum of the static regions' energies at the measurement time."""
        return float(np.sum(self.energy))


def regions(e_bar: ArrayLike, level: float, radius: int, contrast: float) -> list[tuple[int, int, int]]:
    """The candidate regions of steps 2-3 of the detector: (peak, start, stop) for every local maximum p of
    ``e_bar`` above ``level``, strongest first, that is not within ``radius`` of a stronger one; its region
    [p - radius, p + radius] is clipped to the chain and to the regions already taken, and it is kept only when
    e_bar at each outer end of the full region inside the chain is below ``contrast`` e_bar_p (a peak, not a
    plateau)."""
    e_bar = np.asarray(e_bar, dtype=float)
    N = e_bar.size
    padded = np.concatenate([[-np.inf], e_bar, [-np.inf]])
    peaks = np.flatnonzero((e_bar > level) & (e_bar >= padded[:-2]) & (e_bar >= padded[2:]))
    taken = np.zeros(N, dtype=bool)
    out: list[tuple[int, int, int]] = []
    for p in peaks[np.argsort(-e_bar[peaks], kind="stable")]:
        if taken[p] or any(abs(p - q) <= radius for q, _, _ in out):
            continue
        ends = [n for n in (p - radius, p + radius) if 0 <= n < N]
        if any(e_bar[n] >= contrast * e_bar[p] for n in ends):
            continue
        a, b = max(p - radius, 0), min(p + radius + 1, N)
        while taken[a]:
            a += 1
        while taken[b - 1]:
            b -= 1
        taken[a:b] = True
        out.append((int(p), a, b))
    return out


def static_breathers(t: ArrayLike, e: ArrayLike, t_meas: float, window: float, level: float, *, radius: int,
                     contrast: float, max_shift: float) -> Detected:
    """The static breathers at ``t_meas`` (module docstring) in the site energies ``e`` (T, N) sampled at ``t``
    (T,), with the absolute energy ``level`` (theta E_ref); the last sample at or before t_meas is the
    measurement time. A window holding fewer than two samples is an error."""
    t = np.asarray(t, dtype=float)
    e = np.asarray(e, dtype=float)
    sel = np.flatnonzero((t >= t_meas - window - 1e-9) & (t <= t_meas + 1e-9))
    if sel.size < 2:
        raise ValueError(f"window [{t_meas - window:g}, {t_meas:g}] holds {sel.size} sample(s) of t "
                         f"[{t[0]:g}, {t[-1]:g}]: need >= 2")
    ew = e[sel]
    out: list[tuple[int, int, float, float, float]] = []
    for _, a, b in regions(ew.mean(axis=0), level, radius, contrast):
        part = ew[:, a:b]
        E = part.sum(axis=1)
        c = (part @ np.arange(a, b, dtype=float)) / np.where(E > 0, E, 1.0)
        shift = float(c.max() - c.min())
        if shift <= max_shift:
            out.append((a, b, float(E[-1]), float(c.mean()), shift))
    cols = list(zip(*out, strict=True)) if out else [(), (), (), (), ()]
    return Detected(np.array(cols[0], dtype=int), np.array(cols[1], dtype=int), np.array(cols[2], dtype=float),
                    np.array(cols[3], dtype=float), np.array(cols[4], dtype=float))


def zone_energies(e: ArrayLike, bounds: Sequence[int]) -> np.ndarray:
    """sum_n e_n over each zone [bounds[i], bounds[i+1]) of the chain, on the last axis of ``e``: shape
    ``e.shape[:-1] + (len(bounds) - 1,)``."""
    e = np.asarray(e, dtype=float)
    return np.stack([e[..., a:b].sum(axis=-1) for a, b in zip(bounds[:-1], bounds[1:], strict=True)], axis=-1)


def reach(e: ArrayLike, edge: int, e_ref: float) -> float:
    """max over the samples of the energy of the last ``edge`` beads, over ``e_ref``: what reached the far end
    (0 up to rounding when nothing did, so that no energy can have come back from it)."""
    return float(np.max(np.asarray(e, dtype=float)[:, -edge:].sum(axis=1)) / e_ref)
