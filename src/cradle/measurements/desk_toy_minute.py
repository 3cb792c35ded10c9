"""Measurements of a desk toy watched for a minute: order parameters of in-phase motion, balls out per swing.

On stored states (t, x, v) of (nc), (ncdamped) or the hard-sphere cradle in (nc)'s variables (time in units of
1/omega_0, every ball the linear oscillator x'' + x = 0 between contacts).

* **Phase coherence** R(t) (:func:`phase_coherence`). Between contacts each ball is a free harmonic oscillator,
  x_n = a_n cos(t + phi_n), v_n = -a_n sin(t + phi_n), so z_n = x_n - i v_n = a_n e^{i(t + phi_n)} is its analytic
  signal exactly (what a Hilbert transform of x_n estimates from samples) and arg z_n its phase. R = |sum_n
  z_n / |z_n|| / N, the Kuramoto order parameter of the phases: 1 when every ball has the same phase, whatever
  its amplitude; a ball at rest (z_n = 0) counts as a phase of its own that agrees with none (its term is 0).
* **Centre-of-mass share** S(t) (:func:`com_share`): the share of the on-site energy sum_n |z_n|^2 / 2 carried by
  the centre-of-mass swing mode, N |Z|^2 / 2 with Z = sum_n z_n / N. Since sum |z_n|^2 = N |Z|^2 +
  sum |z_n - Z|^2, S is in [0, 1] and S = 1 exactly when every ball has the same phase AND amplitude (the balls
  swing as one). Contacts conserve momentum, so the centre of mass is the free (or linearly damped) oscillator
  whatever happens inside the line: N |Z|^2 / 2 starts at (lifted / N) H(0) for the released desk toy and keeps
  it up to the on-site damping, and S(t) -> 1 means every other mode has been dissipated.
* **Time to in-phase motion** (:func:`settle_time`): the time after which an order parameter stays at or above a
  threshold to the end of the run, the last upward crossing interpolated linearly between samples (NaN: below at
  the end). It depends on the order parameter and on the threshold: both are arguments, the analysis reports
  two of each.
* **Balls out per swing** (:func:`balls_out`): at each out-swing t = k pi (the largest swings of the ideal cradle:
  :mod:`cradle.measurements.desk_toy`), the number of balls whose swing amplitude |z_n| is at least ``fraction``
  of the largest one: ``lifted`` in the one-out-one-out pattern, N when the balls swing together.
"""
from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray


def analytic(x: ArrayLike, v: ArrayLike) -> NDArray[np.complex128]:
    """z_n = x_n - i v_n: the analytic signal of each free ball (module docstring), shape of ``x``."""
    return np.asarray(x, dtype=float) - 1j * np.asarray(v, dtype=float)


def phase_coherence(x: ArrayLike, v: ArrayLike) -> NDArray[np.float64]:
    """R = |sum_n z_n / |z_n|| / N along the last axis (balls); a ball at rest contributes 0."""
    z = analytic(x, v)
    a = np.abs(z)
    unit = np.divide(z, a, out=np.zeros_like(z), where=a > 0.0)
    return np.abs(unit.mean(axis=-1))


def com_share(x: ArrayLike, v: ArrayLike) -> NDArray[np.float64]:
    """S = N |Z|^2 / sum_n |z_n|^2, Z = mean_n z_n: the centre-of-mass mode's share of the on-site energy."""
    z = analytic(x, v)
    N = z.shape[-1]
    total = np.sum(np.abs(z) ** 2, axis=-1)
    return N * np.abs(z.mean(axis=-1)) ** 2 / total


def settle_time(t: ArrayLike, q: ArrayLike, threshold: float) -> float:
    """The time after which ``q`` stays >= ``threshold`` to the last sample: t[0] if it always does, NaN if the
    last sample is below; else the last upward crossing, linear between the two samples around it."""
    t = np.asarray(t, dtype=float)
    q = np.asarray(q, dtype=float)
    below = np.flatnonzero(~(q >= threshold))   # NaN counts as below
    if below.size == 0:
        return float(t[0])
    i = int(below[-1])
    if i == t.size - 1:
        return math.nan
    q0, q1 = q[i], q[i + 1]
    if not np.isfinite(q0):
        return float(t[i + 1])
    return float(t[i] + (t[i + 1] - t[i]) * (threshold - q0) / (q1 - q0))


def swing_indices(t: ArrayLike) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """(index of the stored time nearest k pi, k pi) for every out-swing k = 1 .. floor(t_end / pi)."""
    t = np.asarray(t, dtype=float)
    times = np.pi * np.arange(1, int(np.floor(t[-1] / np.pi + 1e-9)) + 1)
    idx = np.clip(np.searchsorted(t, times), 1, t.size - 1)
    idx = np.where(np.abs(t[idx - 1] - times) <= np.abs(t[idx] - times), idx - 1, idx)
    return idx.astype(np.int64), times.astype(np.float64)


def balls_out(x: ArrayLike, v: ArrayLike, fraction: float = 0.5) -> NDArray[np.int64]:
    """Balls whose amplitude |z_n| is >= ``fraction`` (in (0, 1]) of the largest, along the last axis."""
    if not 0.0 < fraction <= 1.0:
        raise ValueError(f"fraction = {fraction!r}: must be in (0, 1] (a share of the largest amplitude)")
    a = np.abs(analytic(x, v))
    return np.sum(a >= fraction * a.max(axis=-1, keepdims=True), axis=-1).astype(np.int64)


def separation(x_a: ArrayLike, v_a: ArrayLike, x_b: ArrayLike, v_b: ArrayLike) -> NDArray[np.float64]:
    """The distance between two runs' states, sqrt(sum_n (x_n - x'_n)^2 + (v_n - v'_n)^2) along the last axis
    ((nc)'s units, where a velocity is a length: omega_0 = 1)."""
    dx = np.asarray(x_a, dtype=float) - np.asarray(x_b, dtype=float)
    dv = np.asarray(v_a, dtype=float) - np.asarray(v_b, dtype=float)
    return np.sqrt(np.sum(dx**2 + dv**2, axis=-1))


def growth_rate(t: ArrayLike, d: ArrayLike, low: float, high: float) -> float:
    """The exponential growth rate of a separation ``d`` (:func:`separation`): the least-squares slope of log d
    against t over its first stretch from ``low`` to ``high`` (from the last sample at or below ``low`` before d
    first reaches ``high``, to that sample). ``low`` above the integrator's error, ``high`` below the saturation
    (the swing): the stretch where a small difference grows as e^(lambda t). NaN when d never reaches ``high``
    or the stretch has fewer than 3 samples."""
    if not 0.0 < low < high:
        raise ValueError(f"low = {low!r}, high = {high!r}: need 0 < low < high")
    t = np.asarray(t, dtype=float)
    d = np.asarray(d, dtype=float)
    reach = np.flatnonzero(d >= high)
    if reach.size == 0:
        return math.nan
    end = int(reach[0])
    under = np.flatnonzero(d[:end] <= low)
    start = int(under[-1]) if under.size else 0
    seg = slice(start, end + 1)
    ok = d[seg] > 0.0
    if np.count_nonzero(ok) < 3:
        return math.nan
    return float(np.polyfit(t[seg][ok], np.log(d[seg][ok]), 1)[0])
