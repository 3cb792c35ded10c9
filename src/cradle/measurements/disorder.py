"""Measurements of what survives disorder: coherence of a wave, travel and retention of a breather, crossovers.

Pure numpy on arrays; the last axis is the bead index n (a ring of N beads), a leading axis is time. ``A`` is
the complex amplitude of (ansatz): the DpS A_n(tau) itself, or the lattice's A_n(t) = (x_n - i v_n) e^{-it} /
(2 eps) (:func:`cradle.analyses.mi_growth.lattice_amplitude`).

* :func:`fidelity`: |<A, B>| / (|A| |B|), the overlap of a run with the homogeneous run from the same data (1 for
  equal states up to a global phase);
* :func:`carrier_fraction`: |A_hat_k|^2 / sum_k |A_hat_k|^2, the share of the l2 norm in the wave's own mode;
* :func:`correlation_length`: xi = sum_r |C(r)|^2 with C(r) = sum_n A_{n+r} conj(A_n) / sum_n |A_n|^2 (the
  spatial autocorrelation on the ring); by Wiener-Khinchin xi = N sum_k P_k^2, P_k the share of the norm in mode
  k: xi = N for a plane wave, xi = 1 for a state whose norm is spread evenly over the modes (random phases);
* :func:`participation`: (sum |A_n|^2)^2 / (N sum |A_n|^4): 1 for a state of constant |A_n|, 1/N for one site;
* :func:`first_below`: the first time a series falls below a level (linear interpolation between samples);
* :func:`energy_centre`, :func:`travel`, :func:`retention`: the energy centre of a localised state on a ring
  (circular mean of the site energies), the distance it travelled, the share of energy near a site;
* :func:`overlap_frequency`: the frequency of a state's norm-weighted phase (a breather's frequency however its
  energy moves between the beads of its core);
* :func:`detuning_shift`: the first-order frequency shift sum_n w_n delta_n / sum_n w_n of a standing state with
  weights w_n = |A_n|^2 under on-site detunings delta_n (Hellmann-Feynman for (dfnls) with a detuning term at fixed
  l2 norm);
* :func:`crossover`: the disorder strength at which a survival measure falls below a level;
* :func:`seed_statistics`: mean, standard deviation and quartiles over seeds.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

#: names of the statistics of :func:`seed_statistics`, in the order of their axis
STATISTICS = ("mean", "std", "q25", "median", "q75", "count")

#: a reduction over the last axis: an array, or a numpy scalar for a 1-D input
Reduced = NDArray[np.float64] | np.float64


def _norms(A: ArrayLike) -> Reduced:
    return np.sum(np.abs(A) ** 2, axis=-1)


def fidelity(A: ArrayLike, B: ArrayLike) -> Reduced:
    """|sum_n A_n conj(B_n)| / sqrt(sum |A_n|^2 sum |B_n|^2) along the last axis (NaN where a state is zero)."""
    A, B = np.asarray(A), np.asarray(B)
    den = np.sqrt(_norms(A) * _norms(B))
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.abs(np.sum(A * np.conj(B), axis=-1)) / den


def mode_shares(A: ArrayLike) -> NDArray[np.float64]:
    """P_k = |A_hat_k|^2 / sum_k |A_hat_k|^2 along the last axis (A_hat the DFT, k = 0..N-1)."""
    Ah = np.fft.fft(np.asarray(A), axis=-1)
    p = np.abs(Ah) ** 2
    return p / np.sum(p, axis=-1, keepdims=True)


def carrier_fraction(A: ArrayLike, k: int) -> Reduced:
    """P_k of :func:`mode_shares` at mode ``k`` (mod N): the share of the norm in the carrier."""
    P = mode_shares(A)
    return P[..., int(k) % P.shape[-1]]


def correlation_length(A: ArrayLike) -> Reduced:
    """xi = sum_r |C(r)|^2 = N sum_k P_k^2 (module docstring), in beads: N for a plane wave."""
    P = mode_shares(A)
    return P.shape[-1] * np.sum(P**2, axis=-1)


def participation(A: ArrayLike) -> Reduced:
    """(sum |A_n|^2)^2 / (N sum |A_n|^4) along the last axis, in (0, 1]."""
    w = np.abs(np.asarray(A)) ** 2
    return np.sum(w, axis=-1) ** 2 / (w.shape[-1] * np.sum(w**2, axis=-1))


def first_below(t: ArrayLike, y: ArrayLike, level: float) -> float:
    """First time ``y`` falls below ``level``, linear in y between the two samples around it; ``t[0]`` if it
    starts below, NaN if it never does (the caller reads NaN as: survived the whole run)."""
    t, y = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
    below = np.flatnonzero(y < level)
    if below.size == 0:
        return float("nan")
    i = int(below[0])
    if i == 0:
        return float(t[0])
    return float(t[i - 1] + (t[i] - t[i - 1]) * (y[i - 1] - level) / (y[i - 1] - y[i]))


def energy_centre(e: ArrayLike) -> Reduced:
    """Circular mean position of the site energies e_n (last axis) on a ring of N beads, in (-N/2, N/2]."""
    e = np.asarray(e, dtype=float)
    N = e.shape[-1]
    ang = 2.0 * np.pi * np.arange(N) / N
    return np.angle(np.sum(e * np.exp(1j * ang), axis=-1)) * N / (2.0 * np.pi)


def travel(t: ArrayLike, e: ArrayLike) -> tuple[NDArray[np.float64], float, float]:
    """(path, distance, velocity) of the energy centre of e (T, N) on a ring: the centre unwrapped in time
    (a jump of less than N/2 beads between samples), its displacement path[-1] - path[0] in beads, and its
    velocity (least-squares slope of the path over the second half of the samples, beads per unit t)."""
    t = np.asarray(t, dtype=float)
    N = np.asarray(e).shape[-1]
    c = energy_centre(e)
    path = np.unwrap(c * 2.0 * np.pi / N) * N / (2.0 * np.pi)
    half = t >= t[0] + 0.5 * (t[-1] - t[0])
    vel = float(np.polyfit(t[half], path[half], 1)[0]) if half.sum() >= 2 else float("nan")
    return path, float(path[-1] - path[0]), vel


def ring_distance(N: int, centre: float) -> NDArray[np.float64]:
    """|n - centre| on a ring of N beads, n = 0..N-1."""
    d = np.abs(np.arange(N) - centre) % N
    return np.minimum(d, N - d)


def retention(e: ArrayLike, centre: float, window: float) -> Reduced:
    """Share of the energy e_n (last axis) on the beads within ``window`` of ``centre`` (ring distance)."""
    e = np.asarray(e, dtype=float)
    near = ring_distance(e.shape[-1], centre) <= window
    return np.sum(e[..., near], axis=-1) / np.sum(e, axis=-1)


def site_energy(x: ArrayLike, v: ArrayLike, alpha: float, omega: ArrayLike | None = None) -> NDArray[np.float64]:
    """e_n = (v_n^2 + omega_n^2 x_n^2) / 2 + half the Hertz energy of each of its two bonds (ring): the energy
    density of (ham) with on-site frequencies omega_n (default 1); its sum over n is H."""
    x, v = np.asarray(x, dtype=float), np.asarray(v, dtype=float)
    w2 = 1.0 if omega is None else np.asarray(omega, dtype=float) ** 2
    d = np.roll(x, -1, axis=-1) - x
    bond = np.maximum(-d, 0.0) ** (alpha + 1.0) / (alpha + 1.0)
    return 0.5 * (v**2 + w2 * x**2) + 0.5 * (bond + np.roll(bond, 1, axis=-1))


def phase_frequency(t: ArrayLike, A_site: ArrayLike) -> float:
    """d arg(A)/dt of one site's amplitude (least squares on the unwrapped phase): the frequency of x_n minus 1
    in the rotating frame e^{it} of (ansatz). Needs |d arg A| < pi between samples."""
    t = np.asarray(t, dtype=float)
    ph = np.unwrap(np.angle(np.asarray(A_site)))
    return float(np.polyfit(t, ph, 1)[0])


def overlap_frequency(t: ArrayLike, A: ArrayLike) -> float:
    """Mean frequency of a state's phase, (sum_j arg <A(t_{j+1}), A(t_j)>) / (t_end - t_0), <A, B> = sum_n A_n
    conj(B_n) over the last axis: for a state A_n(t) = a_n e^{i w t} of fixed shape exactly w, and for a state whose
    shape changes (energy moving between the beads of a breather's core) the norm-weighted mean phase velocity
    sum_n |A_n|^2 d arg(A_n)/dt / sum_n |A_n|^2 in the limit of small steps, whose first-order shift under a
    detuning is :func:`detuning_shift`. Needs the overlap's phase to turn by less than pi between samples."""
    t = np.asarray(t, dtype=float)
    A = np.asarray(A)
    inc = np.angle(np.sum(A[1:] * np.conj(A[:-1]), axis=-1))
    return float(np.sum(inc) / (t[-1] - t[0]))


def detuning_shift(weights: ArrayLike, detuning: ArrayLike) -> float:
    """First-order frequency shift sum_n w_n delta_n / sum_n w_n of a standing state of weights w_n = |A_n|^2
    under on-site detunings delta_n (frequency units): exact to first order in delta for (dfnls) with a detuning
    term at fixed l2 norm (Hellmann-Feynman), the leading order for the lattice with omega_n = 1 + delta_n."""
    w = np.asarray(weights, dtype=float)
    return float(np.sum(w * np.asarray(detuning, dtype=float)) / np.sum(w))


def crossover(sigma: ArrayLike, survival: ArrayLike, level: float = 0.5) -> tuple[float, int]:
    """(sigma*, censoring) where the ``survival`` measure (against increasing ``sigma``, first falls below
    ``level``), interpolated linearly in log(sigma) between the two positive grid values around the crossing.

    Censoring: 0 a crossing inside the positive grid; -1 already below at the smallest positive sigma (sigma* is
    NaN: below the grid); +1 never below (sigma* NaN: above the grid). NaN survivals are skipped."""
    s, y = np.asarray(sigma, dtype=float), np.asarray(survival, dtype=float)
    ok = (s > 0) & np.isfinite(y)
    s, y = s[ok], y[ok]
    order = np.argsort(s)
    s, y = s[order], y[order]
    below = np.flatnonzero(y < level)
    if below.size == 0:
        return float("nan"), 1
    i = int(below[0])
    if i == 0:
        return float("nan"), -1
    ls0, ls1 = np.log(s[i - 1]), np.log(s[i])
    f = (y[i - 1] - level) / (y[i - 1] - y[i])
    return float(np.exp(ls0 + f * (ls1 - ls0))), 0


def seed_statistics(values: ArrayLike, axis: int = -1) -> NDArray[np.float64]:
    """Statistics over seeds (``axis``): the stack (mean, std, q25, median, q75, count) of :data:`STATISTICS`
    along a new last axis, NaN values left out (std with ddof = 1; NaN for fewer than two values)."""
    v = np.moveaxis(np.asarray(values, dtype=float), axis, -1)
    n = np.sum(np.isfinite(v), axis=-1)
    out = np.full(v.shape[:-1] + (len(STATISTICS),), np.nan)
    some = n > 0
    if np.any(some):
        vs = v[some]
        with np.errstate(invalid="ignore", divide="ignore"):
            out[some, 0] = np.nanmean(vs, axis=-1)
            q = np.nanpercentile(vs, [25.0, 50.0, 75.0], axis=-1)
        out[some, 2], out[some, 3], out[some, 4] = q
    two = n > 1
    if np.any(two):
        out[two, 1] = np.nanstd(v[two], axis=-1, ddof=1)
    out[..., 5] = n
    return out
