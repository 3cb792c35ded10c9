"""Outcome of the interaction of two breathers from a stored run (figure loc1, right; the
`breather-interactions` analysis).

Pure numpy. The time axis is cut into breather periods 2 pi / omega_sw; in
each, the localisation profile is the site profile P_n = max_t |x_n(t)|
(:func:`cradle.measurements.breathers.peak_compression` applied to x): a
breather of (nc) or of the ansatz (ansatz) shows as one hump of P, whatever
its phase within the period. (The bond compressions cannot resolve two
breathers one site apart: both bonds of the node bead between them are
compressed, so their profile shows one hump where x shows two.) From the
humps of every period:

* ``repel``: two breathers whose distance grows by at least ``repel_sites``
  sites before they first overlap; the separation velocity (sites per
  period) is the slope of the distance over the periods it takes to grow by
  80 % of that growth;
* ``merge``: the run ends with one breather where the pair was. Merging
  period: the first period from which the *smoothed* count of humps within
  the initial distance + ``NEAR_MARGIN`` of the largest (running median over
  ``2 * smooth + 1`` periods, so a merged breather that shows two humps for
  a few periods, or two breathers that overlap for a few, do not flip the
  count) is 1 until the end, the single state lasting at least
  ``min_periods`` periods (a small breather or radiation the merger sends
  round the ring is not one of the pair);
* first coalescence (any outcome but ``repel`` and ``none``): the first period
  from which that smoothed count is 1, however long it stays so. A bound pair
  breathes (its humps approach, overlap and part), so the first coalescence
  can come long before the final single breather: the two definitions of a
  merging time (``Outcome.first_coalescence``, ``Outcome.merge_period``);
* ``transmit``: two breathers that approach, overlap and come out on the
  other side of each other (tracked positions swap their order);
* ``bound``: two breathers to the end, neither merging nor separating.

A hump is a local maximum of P of at least ``rel`` max P that stands out
from its neighbours: the deepest dip between it and the next is below
``dip`` times the smaller top (two maxima joined by a shallow saddle are one
breather with a ragged top), :func:`humps`.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from cradle.measurements.breathers import peak_compression

#: classes of :func:`classify`, in the order the analyses encode them (outcome code = index)
OUTCOMES = ("merge", "bound", "repel", "transmit", "none")
REL = 0.3            # a hump reaches 30 % of the period's largest peak compression
DIP = 0.7            # and is separated from the next by a dip below 70 % of the smaller top
SMOOTH = 5           # running median over 11 periods
MIN_PERIODS = 20     # the merged state must last >= 20 periods to count
REPEL_SITES = 3.0    # breathers 3 sites farther apart than at the start have repelled
NEAR_MARGIN = 3.0    # after a merge, a hump farther than the initial distance + 3 sites is not of the pair


def humps(profile, rel: float = REL, dip: float = DIP, periodic: bool = True):
    """Humps of one non-negative profile: (centres (H,), tops (H,)), largest top first.

    Candidates are the local maxima (cyclically on a ring; a plateau counts
    once) of at least ``rel`` times the largest value. Two neighbouring
    candidates are one hump when the lowest value between them is at least
    ``dip`` times the smaller of their tops (a ragged top, not two breathers);
    the lower one is then dropped. A centre is the weighted mean position of
    the sites around the top down to half its height (on a ring, reduced
    mod N). All-zero or non-finite profile: no humps.
    """
    p = np.asarray(profile, dtype=float)
    N = p.size
    if N == 0 or not np.all(np.isfinite(p)) or p.max() <= 0:
        return np.empty(0), np.empty(0)
    left = np.roll(p, 1) if periodic else np.concatenate(([-np.inf], p[:-1]))
    right = np.roll(p, -1) if periodic else np.concatenate((p[1:], [-np.inf]))
    # a local maximum; of a plateau, only its first site
    peaks = [int(i) for i in np.flatnonzero((p > left) & (p >= right) & (p >= rel * p.max()))]
    if not peaks:                       # a constant profile
        peaks = [int(np.argmax(p))]

    def between(i, j):
        """Sites strictly between peaks i and j going up (cyclically)."""
        return np.arange(i + 1, j if j > i else j + N) % N

    joined = True
    while joined and len(peaks) > 1:
        joined = False
        count = len(peaks) if periodic else len(peaks) - 1
        for k in range(count):
            i, j = peaks[k], peaks[(k + 1) % len(peaks)]
            gap = p[between(i, j)]
            low = gap.min() if gap.size else min(p[i], p[j])
            if low >= dip * min(p[i], p[j]):
                peaks.remove(i if p[i] < p[j] else j)
                joined = True
                break
    centre_list: list[float] = []
    top_list: list[float] = []
    for i in peaks:
        top = p[i]
        lo = i
        while lo - 1 > i - N // 2 and p[(lo - 1) % N] >= 0.5 * top and (periodic or lo - 1 >= 0):
            lo -= 1
        hi = i
        while hi + 1 < i + N // 2 and p[(hi + 1) % N] >= 0.5 * top and (periodic or hi + 1 < N):
            hi += 1
        idx = np.arange(lo, hi + 1)
        w = p[idx % N]
        c = float(np.sum(w * idx) / np.sum(w))
        centre_list.append(c % N if periodic else c)
        top_list.append(float(top))
    order = np.argsort(top_list, kind="stable")[::-1]
    centres, tops = np.asarray(centre_list)[order], np.asarray(top_list)[order]
    # two tops whose weighted centres fall within one site of each other are one hump
    keep: list[int] = []
    for k in range(centres.size):
        if all(ring_distance(centres[k], centres[m], N, periodic) >= 1.0 for m in keep):
            keep.append(k)
    return centres[keep], tops[keep]


def ring_distance(a, b, N: int, periodic: bool = True):
    """|a - b|, on a ring of N sites the shorter way round."""
    d = np.abs(np.asarray(a, dtype=float) - np.asarray(b, dtype=float))
    return np.minimum(d, N - d) if periodic else d


def running_median(x, half: int):
    """Median of x over the window [k - half, k + half] (cut at the ends); integer input, integer output."""
    x = np.asarray(x)
    out = np.empty_like(x)
    for k in range(x.size):
        out[k] = np.median(x[max(0, k - half):k + half + 1])
    return out


@dataclass
class Outcome:
    """What :func:`classify` found; times in breather periods from the first stored time."""
    outcome: str
    merge_period: float = float("nan")         # merge: first period of the final single breather
    first_coalescence: float = float("nan")    # first period of the first single state (NaN: never one)
    separation_velocity: float = float("nan")  # repel: sites per period
    drift_velocity: float = float("nan")       # merge: velocity of the remaining breather, sites per period
    separation0: float = float("nan")          # distance of the two humps in the first period
    counts: np.ndarray = field(default_factory=lambda: np.empty(0, int))      # humps per period
    separation: np.ndarray = field(default_factory=lambda: np.empty(0))       # two largest humps, per period
    centre: np.ndarray = field(default_factory=lambda: np.empty(0))           # largest hump, per period

    @property
    def code(self) -> int:
        return OUTCOMES.index(self.outcome)


def _unwrap(c, N, periodic):
    c = np.asarray(c, dtype=float)
    return np.unwrap(c, period=N) if periodic and c.size else c


def _crossed(cent, counts, N, periodic) -> bool:
    """Whether two tracked humps come out on the other side of each other: the signed distance of the
    two tracks (second minus first, on the ring the shorter way) before the first overlap and after
    the last has opposite signs; during an overlap each track coasts at its last velocity."""
    two = np.flatnonzero(counts >= 2)
    if two.size < 2 or np.all(counts[two[0]:two[-1] + 1] >= 2):
        return False
    k0, k1 = two[0], two[-1]
    pos = np.array(cent[k0][:2], dtype=float)
    vel = np.zeros(2)
    start_sign = None
    for k in range(k0, k1 + 1):
        guess = pos + vel
        if counts[k] >= 2:
            c = np.asarray(cent[k][:2], dtype=float)
            keep = ring_distance(c, guess, N, periodic).sum()
            swap = ring_distance(c[::-1], guess, N, periodic).sum()
            c = c if keep <= swap else c[::-1]
            # unwrap each track next to its guess
            if periodic:
                c = guess + ((c - guess + N / 2) % N - N / 2)
            if k > k0:
                vel = 0.7 * vel + 0.3 * (c - pos)
            pos = c
            d = pos[1] - pos[0]
            if start_sign is None:
                start_sign = np.sign(d)
        else:
            pos = guess
    end = pos[1] - pos[0]
    return bool(start_sign is not None and np.sign(end) != start_sign and abs(end) >= 1.0)


def _drift(P, big, reach: float, periodic: bool) -> float:
    """Velocity (sites per period) of the merged breather: slope of the P-weighted centre of the sites
    within ``reach`` of a fixed point (the median position of the largest hump, unwrapped), so that a
    merged breather showing a ragged or double top does not jump between its two sides."""
    N = P.shape[1]
    u = _unwrap(big, N, periodic)
    m = float(np.median(u))
    n = np.arange(int(np.floor(m - reach)), int(np.ceil(m + reach)) + 1)
    n = n[np.abs(n - m) <= reach]
    w = P[:, n % N] if periodic else P[:, np.clip(n, 0, N - 1)]
    centre = (w * n).sum(axis=1) / w.sum(axis=1)
    return float(np.polyfit(np.arange(len(centre)), centre, 1)[0])


def classify(t, field, period: float, *, periodic: bool = True, rel: float = REL, dip: float = DIP,
             smooth: int = SMOOTH, min_periods: float = MIN_PERIODS,
             repel_sites: float = REPEL_SITES) -> Outcome:
    """Outcome of two interacting breathers from a stored field (T, N) at times ``t``: the displacements
    x_n(t) (a site profile; what :mod:`cradle.analyses.pair_runs` passes) or the bond forces.

    See the module docstring for the classes. ``none``: the first period does
    not show two humps (no pair to classify) or the data hold no complete period.
    """
    starts, P = peak_compression(t, field, period)
    return classify_peaks(starts, P, periodic=periodic, rel=rel, dip=dip, smooth=smooth, min_periods=min_periods,
                          repel_sites=repel_sites)


def classify_peaks(starts, P, *, periodic: bool = True, rel: float = REL, dip: float = DIP, smooth: int = SMOOTH,
                   min_periods: float = MIN_PERIODS, repel_sites: float = REPEL_SITES) -> Outcome:
    """:func:`classify` from the profiles max_t |field_n| ``P`` (K, N) of the periods starting at ``starts``
    (:func:`cradle.measurements.breathers.peak_compression`; the streamed scene job accumulates them)."""
    N = P.shape[1]
    K = len(starts)
    if K == 0:
        return Outcome("none")
    cent, _tops = zip(*(humps(p, rel, dip, periodic) for p in P), strict=True)
    counts = np.array([len(c) for c in cent])
    big = np.array([c[0] if len(c) else np.nan for c in cent])
    sep = np.array([ring_distance(c[0], c[1], N, periodic) if len(c) >= 2 else 0.0 for c in cent])
    base: dict[str, Any] = {"counts": counts, "separation": sep, "centre": big}
    pair = running_median(np.minimum(counts, 2), smooth)
    if pair[0] < 2 and counts[0] < 2:
        return Outcome("none", **base)
    sep0 = float(sep[0]) if counts[0] >= 2 else float(np.nan)
    two = counts >= 2
    # repel: the distance grows by repel_sites before the two first overlap (on a ring, breathers that
    # repelled meet again on the far side: that later meeting does not change the outcome)
    overlap = np.flatnonzero(pair < 2)
    k_ov = int(overlap[0]) if overlap.size else K
    grown = (np.where(two, sep, np.nan) - sep0)[:k_ov]
    if np.any(np.isfinite(grown)) and np.nanmax(grown) >= repel_sites:
        stop = int(np.flatnonzero(grown >= 0.8 * np.nanmax(grown))[0])
        ks = np.flatnonzero(two[:stop + 1])
        v = np.polyfit(ks, sep[ks], 1)[0] if ks.size >= 2 else np.nan
        return Outcome("repel", separation_velocity=float(v), separation0=sep0, **base)
    # merge: from some period on, no second hump within sep0 + NEAR_MARGIN of the largest (what the
    # merger radiates, or a small breather it emits, travels away and is not one of the pair)
    reach = (sep0 if np.isfinite(sep0) else 0.0) + NEAR_MARGIN
    near = np.array([1 + int(np.sum(ring_distance(c[1:], c[0], N, periodic) <= reach)) if len(c) else 0
                     for c in cent])
    sm = running_median(np.minimum(near, 2), smooth)
    base["first_coalescence"] = _first_coalescence(near, sm)
    multi = np.flatnonzero(sm != 1)
    first_single = int(multi[-1]) + 1 if multi.size else 0
    if sm[-1] == 1 and K - first_single >= min_periods:
        # the first period of the final single state, in the raw counts (the median lags by < smooth)
        k = first_single
        while k > 0 and near[k - 1] == 1:
            k -= 1
        if k == 0:      # two humps in the first period only: merged at the first single one
            k = int(np.flatnonzero(near == 1)[0])
        after = np.arange(k, K)
        drift = _drift(P[after], big[after], reach, periodic) if after.size >= 2 else np.nan
        return Outcome("merge", merge_period=float(k),
                       drift_velocity=float(drift), separation0=sep0, **base)
    if _crossed(cent, counts, N, periodic):
        return Outcome("transmit", separation0=sep0, **base)
    return Outcome("bound", separation0=sep0, **base)


def _first_coalescence(near, sm) -> float:
    """First period of the first single state: where the smoothed count ``sm`` first reads 1, moved back to
    the first single period of the raw count ``near`` (the median lags by < smooth periods). NaN: never."""
    single = np.flatnonzero(sm == 1)
    if not single.size:
        return float("nan")
    k = int(single[0])
    while k > 0 and near[k - 1] == 1:
        k -= 1
    return float(k)


def classify_run(ds, period: float | None = None, **kw) -> Outcome:
    """:func:`classify` on a stored run (anything indexable by "t" and "x" with attrs omega_sw and bc): the
    site profile max_t |x_n(t)| per period."""
    if period is None:
        period = 2.0 * np.pi / float(ds.attrs["omega_sw"])
    periodic = str(ds.attrs.get("bc", "periodic")) == "periodic"
    return classify(np.asarray(ds["t"], dtype=float), np.asarray(ds["x"], dtype=float), period,
                    periodic=periodic, **kw)
