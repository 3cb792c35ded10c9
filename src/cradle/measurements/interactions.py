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
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.measurements.breathers import peak_compression

if TYPE_CHECKING:   # only an annotation: the config's declarations import this module, not xarray
    import xarray as xr

#: classes of :func:`classify`, in the order the analyses encode them (outcome code = index)
OUTCOMES = ("merge", "bound", "repel", "transmit", "none")
REL = 0.3            # a hump reaches 30 % of the period's largest peak compression
DIP = 0.7            # and is separated from the next by a dip below 70 % of the smaller top
SMOOTH = 5           # running median over 11 periods
MIN_PERIODS = 20     # the merged state must last >= 20 periods to count
REPEL_SITES = 3.0    # breathers 3 sites farther apart than at the start have repelled
NEAR_MARGIN = 3.0    # after a merge, a hump farther than the initial distance + 3 sites is not of the pair


def humps(profile: ArrayLike, rel: float = REL, dip: float = DIP,
          periodic: bool = True) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
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

    def between(i: int, j: int) -> NDArray[np.int_]:
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


def humps_all(P: ArrayLike, rel: float = REL, dip: float = DIP,
              periodic: bool = True) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.int64]]:
    """:func:`humps` of every row of ``P`` (K, N) at once: (centres (K, H), tops (K, H), counts (K,)), row k's
    humps in its first ``counts[k]`` columns, largest top first, NaN after them (H >= 2).

    The same steps as :func:`humps`, with the loops over rows turned into array operations (the
    remaining Python loops run over the few candidates of a row, or the few sites of a hump's half
    width): bitwise the same centres and tops (the weighted sums are numpy's sums of the same
    contiguous windows, so summed in the same order).
    """
    P = np.asarray(P, dtype=float)
    K, N = P.shape
    centres, tops = np.full((K, 2), np.nan), np.full((K, 2), np.nan)
    counts = np.zeros(K, dtype=np.int64)
    if K == 0 or N == 0:
        return centres, tops, counts
    ok = np.all(np.isfinite(P), axis=1)
    ok[ok] = P[ok].max(axis=1) > 0
    if not ok.any():
        return centres, tops, counts
    if periodic:
        left, right = np.roll(P, 1, axis=1), np.roll(P, -1, axis=1)
    else:
        edge = np.full((K, 1), -np.inf)
        left, right = np.hstack((edge, P[:, :-1])), np.hstack((P[:, 1:], edge))
    with np.errstate(invalid="ignore"):
        cand = (P > left) & (P >= right) & (P >= rel * P.max(axis=1, keepdims=True)) & ok[:, None]
    flat = ok & ~cand.any(axis=1)               # a constant profile: its first largest site
    cand[np.flatnonzero(flat), np.argmax(P[flat], axis=1)] = True
    # the candidates of each row, in increasing site order, padded with the sentinel N (sorts last)
    n = cand.sum(axis=1)
    rows, sites = np.nonzero(cand)
    peaks = np.full((K, int(n.max())), N, dtype=np.int64)
    peaks[rows, np.arange(rows.size) - np.repeat(np.cumsum(n) - n, n)] = sites
    # join neighbours separated by a shallow dip, one pair per row and pass: the first pair (in site
    # order, the wrap-around pair last) whose lowest site between is >= dip x the smaller top
    active = n > 1
    while active.any():
        r = np.flatnonzero(active)
        pk, nr = peaks[r], n[r]
        M = pk.shape[1]
        kk = np.arange(M)[None, :]
        valid = kk < (nr if periodic else nr - 1)[:, None]
        jpos = (kk + 1) % nr[:, None]
        i = np.where(valid, pk, 0)
        j = np.where(valid, np.take_along_axis(pk, jpos, axis=1), 0)
        # the sites strictly between i and j going up, on the row written twice (a gap across the seam)
        start, stop = i + 1, np.where(j > i, j, j + N)
        base = (np.arange(r.size) * 2 * N)[:, None]
        doubled = np.hstack((P[r], P[r])).ravel()
        some = valid & (stop > start)
        bounds = np.stack(((base + start)[some], (base + stop)[some]), axis=1).ravel()
        pi, pj = P[r[:, None], i], P[r[:, None], j]
        smaller = np.minimum(pi, pj)
        low = smaller.copy()
        if bounds.size:
            low[some] = np.minimum.reduceat(doubled, bounds)[::2]
        joined = valid & (low >= dip * smaller)
        hit = joined.any(axis=1)
        active[r[~hit]] = False
        if not hit.any():
            break
        h = np.flatnonzero(hit)
        k = np.argmax(joined[h], axis=1)
        drop_i = pi[h, k] < pj[h, k]
        col = np.where(drop_i, k, jpos[h, k])
        peaks[r[h], col] = N
        peaks[r[h]] = np.sort(peaks[r[h]], axis=1)
        n[r[h]] -= 1
        active[r[h]] &= n[r[h]] > 1
    # each peak's centre: the weighted mean position of the sites around it down to half its top
    rows, pos = np.nonzero(np.arange(peaks.shape[1])[None, :] < n[:, None])
    i = peaks[rows, pos]
    top = P[rows, i]
    half_top = 0.5 * top
    lo, hi = i.copy(), i.copy()
    for step, end in ((-1, lo), (1, hi)):
        going = np.ones(i.size, dtype=bool)
        while going.any():
            nxt = end + step
            inside = nxt > i - N // 2 if step < 0 else nxt < i + N // 2
            if not periodic:
                inside &= (nxt >= 0) & (nxt < N)
            going &= inside & (P[rows, nxt % N] >= half_top)
            end[going] = nxt[going]
    width = hi - lo + 1
    cen = np.empty(i.size)
    for L in np.unique(width):
        at = np.flatnonzero(width == L)
        idx = lo[at, None] + np.arange(L)[None, :]
        w = P[rows[at, None], idx % N]
        cen[at] = np.sum(w * idx, axis=1) / np.sum(w, axis=1)
    if periodic:
        cen = np.remainder(cen, N)
    # per row: largest top first (equal tops: the later peak first, as a reversed stable sort)
    order = np.lexsort((-pos, -top, rows))
    rows, cen, top = rows[order], cen[order], top[order]
    rank = np.arange(rows.size) - np.repeat(np.cumsum(n) - n, n)
    H = max(2, int(n.max()))
    C, T = np.full((K, H), np.nan), np.full((K, H), np.nan)
    C[rows, rank], T[rows, rank] = cen, top
    # two tops whose centres fall within one site of each other are one hump: keep the larger
    keep = np.zeros((K, H), dtype=bool)
    for k in range(H):
        far = k < n
        for m in range(k):
            far &= ~keep[:, m] | (ring_distance(C[:, k], C[:, m], N, periodic) >= 1.0)
        keep[:, k] = far
    counts = keep.sum(axis=1).astype(np.int64)
    r, c = np.nonzero(keep)
    slot = np.arange(r.size) - np.repeat(np.cumsum(counts) - counts, counts)
    centres, tops = np.full((K, H), np.nan), np.full((K, H), np.nan)
    centres[r, slot], tops[r, slot] = C[r, c], T[r, c]
    return centres, tops, counts


def ring_distance(a: ArrayLike, b: ArrayLike, N: int,
                  periodic: bool = True) -> NDArray[np.float64] | np.float64:
    """|a - b|, on a ring of N sites the shorter way round."""
    d = np.abs(np.asarray(a, dtype=float) - np.asarray(b, dtype=float))
    return np.minimum(d, N - d) if periodic else d


def running_median(x: ArrayLike, half: int) -> np.ndarray:
    """Median of x over the window [k - half, k + half] (cut at the ends); integer input, integer output.

    The full windows are taken at once (a median of an odd count is its middle value, the same whether
    taken window by window or along an axis); only the ``2 half`` cut windows at the ends one by one."""
    x = np.asarray(x)
    out = np.empty_like(x)
    width = 2 * half + 1
    if x.ndim == 1 and half >= 0 and x.size >= width:
        out[half:x.size - half] = np.median(np.lib.stride_tricks.sliding_window_view(x, width), axis=1)
        cut = [*range(half), *range(x.size - half, x.size)]
    else:
        cut = list(range(x.size))
    for k in cut:
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


def _unwrap(c: ArrayLike, N: int, periodic: bool) -> NDArray[np.float64]:
    c = np.asarray(c, dtype=float)
    return np.unwrap(c, period=N) if periodic and c.size else c


def _crossed(cent: NDArray[np.float64], counts: NDArray[np.int64], N: int, periodic: bool) -> bool:
    """Whether two tracked humps come out on the other side of each other: the signed distance of the
    two tracks (second minus first, on the ring the shorter way) before the first overlap and after
    the last has opposite signs; during an overlap each track coasts at its last velocity.

    ``cent`` (K, >= 2): the centres of each period's humps, largest first (:func:`humps_all`). The
    tracks are followed in Python floats, element by element the operations of the two-vector form."""
    two = np.flatnonzero(counts >= 2)
    if two.size < 2 or np.all(counts[two[0]:two[-1] + 1] >= 2):
        return False
    k0, k1 = int(two[0]), int(two[-1])
    first, second, many = cent[:, 0].tolist(), cent[:, 1].tolist(), (counts >= 2).tolist()

    def dist(a: float, b: float) -> float:
        d = abs(a - b)
        return min(d, N - d) if periodic else d

    p0, p1 = first[k0], second[k0]
    v0 = v1 = 0.0
    start_sign = None
    for k in range(k0, k1 + 1):
        g0, g1 = p0 + v0, p1 + v1
        if many[k]:
            c0, c1 = first[k], second[k]
            if not dist(c0, g0) + dist(c1, g1) <= dist(c1, g0) + dist(c0, g1):
                c0, c1 = c1, c0
            # unwrap each track next to its guess
            if periodic:
                c0 = g0 + ((c0 - g0 + N / 2) % N - N / 2)
                c1 = g1 + ((c1 - g1 + N / 2) % N - N / 2)
            if k > k0:
                v0, v1 = 0.7 * v0 + 0.3 * (c0 - p0), 0.7 * v1 + 0.3 * (c1 - p1)
            p0, p1 = c0, c1
            if start_sign is None:
                start_sign = np.sign(p1 - p0)
        else:
            p0, p1 = g0, g1
    end = p1 - p0
    return bool(start_sign is not None and np.sign(end) != start_sign and abs(end) >= 1.0)


def _drift(P: NDArray[np.float64], big: NDArray[np.float64], reach: float, periodic: bool) -> float:
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


def classify(t: ArrayLike, field: ArrayLike, period: float, *, periodic: bool = True, rel: float = REL,
             dip: float = DIP, smooth: int = SMOOTH, min_periods: float = MIN_PERIODS,
             repel_sites: float = REPEL_SITES) -> Outcome:
    """Outcome of two interacting breathers from a stored field (T, N) at times ``t``: the displacements
    x_n(t) (a site profile; what :mod:`cradle.analyses.pair_runs` passes) or the bond forces.

    See the module docstring for the classes. ``none``: the first period does
    not show two humps (no pair to classify) or the data hold no complete period.
    """
    starts, P = peak_compression(t, field, period)
    return classify_peaks(starts, P, periodic=periodic, rel=rel, dip=dip, smooth=smooth, min_periods=min_periods,
                          repel_sites=repel_sites)


def classify_peaks(starts: NDArray[np.float64], P: NDArray[np.float64], *, periodic: bool = True, rel: float = REL,
                   dip: float = DIP, smooth: int = SMOOTH,
                   min_periods: float = MIN_PERIODS, repel_sites: float = REPEL_SITES) -> Outcome:
    """:func:`classify` from the profiles max_t |field_n| ``P`` (K, N) of the periods starting at ``starts``
    (:func:`cradle.measurements.breathers.peak_compression`; the streamed scene job accumulates them)."""
    N = P.shape[1]
    K = len(starts)
    if K == 0:
        return Outcome("none")
    cent, _tops, counts = humps_all(P, rel, dip, periodic)
    big = cent[:, 0].copy()
    sep = np.where(counts >= 2, ring_distance(cent[:, 0], cent[:, 1], N, periodic), 0.0)
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
    with np.errstate(invalid="ignore"):      # the NaN after a row's humps are not near
        close = ring_distance(cent[:, 1:], cent[:, :1], N, periodic) <= reach
    near = np.where(counts > 0, 1 + close.sum(axis=1), 0)
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


def _first_coalescence(near: np.ndarray, sm: np.ndarray) -> float:
    """First period of the first single state: where the smoothed count ``sm`` first reads 1, moved back to
    the first single period of the raw count ``near`` (the median lags by < smooth periods). NaN: never."""
    single = np.flatnonzero(sm == 1)
    if not single.size:
        return float("nan")
    k = int(single[0])
    while k > 0 and near[k - 1] == 1:
        k -= 1
    return float(k)


def classify_run(ds: xr.Dataset, period: float | None = None, **kw: Any) -> Outcome:
    """:func:`classify` on a stored run (anything indexable by "t" and "x" with attrs omega_sw and bc): the
    site profile max_t |x_n(t)| per period."""
    if period is None:
        period = 2.0 * np.pi / float(ds.attrs["omega_sw"])
    periodic = str(ds.attrs.get("bc", "periodic")) == "periodic"
    return classify(np.asarray(ds["t"], dtype=float), np.asarray(ds["x"], dtype=float), period,
                    periodic=periodic, **kw)
