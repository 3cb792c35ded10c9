"""The outcome classification of breather-interactions taken over all periods at once gives bitwise what the
period-by-period definitions give: the hump finder of every row (:func:`humps_all`) against :func:`humps`
applied row by row, on synthetic profiles and on the profiles of a real run in both models; the running
median and the per-period peak profile against their window-by-window definitions; the tracking of
:func:`_crossed` against the two-vector form it replaced."""
from __future__ import annotations

import numpy as np
import pytest

from cradle.measurements import breathers, interactions as I

N = 50


def _same(a, b) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and np.array_equal(a, b, equal_nan=a.dtype.kind == "f")


def _rows_agree(P, periodic=True, **kw):
    C, T, n = I.humps_all(P, periodic=periodic, **kw)
    assert C.shape == T.shape and C.shape[0] == P.shape[0] and C.shape[1] >= 2
    for k, p in enumerate(P):
        c, t = I.humps(p, periodic=periodic, **kw)
        assert n[k] == c.size, k
        assert _same(C[k, :n[k]], c) and _same(T[k, :n[k]], t), (k, C[k], c)
        assert np.all(np.isnan(C[k, n[k]:])) and np.all(np.isnan(T[k, n[k]:]))


def _synthetic(rng, K=400, N=N, widest=4.0):
    """Sums of 1 to 5 Gaussian humps of random width and height anywhere on the ring (ragged tops,
    shallow saddles, humps across the seam), plus plateaus, constant, zero and non-finite rows."""
    n = np.arange(N)
    P = np.zeros((K, N))
    for k in range(K):
        for _ in range(rng.integers(1, 6)):
            c, w, h = rng.uniform(0, N), rng.uniform(0.3, widest), rng.uniform(0.05, 1.0)
            d = (n - c + N / 2) % N - N / 2
            P[k] += h * np.exp(-0.5 * (d / w) ** 2)
    P[::7] = np.round(P[::7], 1)          # plateaus and equal tops
    P[1] = 0.3
    P[2] = 0.0
    P[3, 5] = np.nan
    P[4, 9] = np.inf
    return P


@pytest.mark.parametrize("periodic", [True, False])
def test_humps_of_all_rows_are_humps_row_by_row(periodic):
    P = _synthetic(np.random.default_rng(20261127))
    _rows_agree(P, periodic)
    _rows_agree(P, periodic, rel=0.05, dip=0.9)        # more candidates, more joins
    _rows_agree(P[:0], periodic)
    # a large ring with broad humps: half-height windows of more than 128 sites (numpy sums those in
    # halves, pairwise) and the constant row's window of N - 1 sites
    _rows_agree(_synthetic(np.random.default_rng(3), K=40, N=400, widest=80.0), periodic)


@pytest.fixture(scope="module")
def real_profiles():
    """max_t |x_n| per period of one interaction run (site-site pair, spacing 6, theta = pi/2, 150 periods),
    lattice and DpS."""
    from cradle.analyses import pair_runs
    from cradle.models import pairs

    prof = ("site", "site")
    d = pairs.two_breathers(N, 1.5, profiles=prof, centres=pairs.symmetric_centres(N, prof, 6.0), theta=np.pi / 2)
    period = 2 * np.pi / d.info["omega_sw"]
    res = pair_runs.run_pair(d, 150 * period, 1.5, keep=True)
    return {m: (r["t"], r["x"], period) for m, r in res.items()}


def test_real_runs_rows_and_the_outcome_read_from_them(real_profiles):
    for t, x, period in real_profiles.values():
        starts, P = breathers.peak_compression(t, x, period)
        for periodic in (True, False):
            _rows_agree(P, periodic)
            o = I.classify_peaks(starts, P, periodic=periodic)
            per_row = [I.humps(p, periodic=periodic)[0] for p in P]
            assert _same(o.counts, np.array([c.size for c in per_row]))
            assert _same(o.centre, np.array([c[0] if c.size else np.nan for c in per_row]))
            assert _same(o.separation, np.array([I.ring_distance(c[0], c[1], N, periodic) if c.size >= 2 else 0.0
                                                 for c in per_row]))


def _median_by_window(x, half):
    out = np.empty_like(x)
    for k in range(x.size):
        out[k] = np.median(x[max(0, k - half):k + half + 1])
    return out


def test_running_median_is_the_window_by_window_median():
    rng = np.random.default_rng(5)
    for size in (0, 1, 5, 10, 11, 12, 40, 601):
        for half in (0, 1, 5):
            ints = rng.integers(0, 3, size)
            assert _same(I.running_median(ints, half), _median_by_window(ints, half))
            floats = rng.normal(size=size)
            if size > 3:
                floats[3] = np.nan
            assert _same(I.running_median(floats, half), _median_by_window(floats, half))


def _peaks_by_window(t, f, period):
    f = np.abs(f)
    K = int(np.floor((t[-1] - t[0]) / period + 1e-9))
    k = np.floor((t - t[0]) / period + 1e-9).astype(int)
    P = np.full((K, f.shape[1]), np.nan)
    for i in range(K):
        if np.any(k == i):
            P[i] = f[k == i].max(axis=0)
    return P


def test_peak_profile_per_period_is_the_window_by_window_maximum(real_profiles):
    t, x, period = real_profiles["exact"]
    assert _same(breathers.peak_compression(t, x, period)[1], _peaks_by_window(t, x, period))
    # irregular times: windows holding no stored time stay NaN; a NaN in a window propagates
    rng = np.random.default_rng(2)
    t = np.sort(rng.uniform(0, 40, 60))
    f = rng.normal(size=(60, 7))
    f[10, 2] = np.nan
    for period in (0.3, 1.0, 5.7, 40.0):
        assert _same(breathers.peak_compression(t, f, period)[1], _peaks_by_window(t, f, period))


def _crossed_two_vectors(cent, counts, N, periodic):
    """The tracking of the previous implementation, on two-vectors (numpy), for comparison."""
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
            keep = I.ring_distance(c, guess, N, periodic).sum()
            swap = I.ring_distance(c[::-1], guess, N, periodic).sum()
            c = c if keep <= swap else c[::-1]
            if periodic:
                c = guess + ((c - guess + N / 2) % N - N / 2)
            if k > k0:
                vel = 0.7 * vel + 0.3 * (c - pos)
            pos = c
            if start_sign is None:
                start_sign = np.sign(pos[1] - pos[0])
        else:
            pos = guess
    end = pos[1] - pos[0]
    return bool(start_sign is not None and np.sign(end) != start_sign and abs(end) >= 1.0)


def test_crossing_tracks_as_the_two_vector_form():
    rng = np.random.default_rng(11)
    found = set()
    for trial in range(100):
        K = 120
        k = np.arange(K)
        v = rng.uniform(-0.15, 0.15, 2)
        c = np.stack([rng.uniform(0, N) + v[0] * k, rng.uniform(0, N) + v[1] * k], axis=1) + rng.normal(0, 0.3, (K, 2))
        counts = np.where(rng.random(K) < 0.2, 1, 2).astype(np.int64)
        periodic = trial % 3 != 0
        cent = np.mod(c, N) if periodic else c
        cent[counts < 2, 1] = np.nan
        got = I._crossed(cent, counts, N, periodic)
        assert got == _crossed_two_vectors(cent, counts, N, periodic), trial
        found.add(got)
    assert found == {True, False}
