"""The interaction outcome measure (figure loc1; breather-interactions): synthetic profiles with one
hump, two humps, humps moving apart, merging, crossing; and runs whose outcome is fixed by symmetry:
an antiphase pair one node apart in DpS stays centred (A_n -> A_{-n} invariance of (dfnls))."""
from __future__ import annotations

import numpy as np
import pytest

from cradle.measurements import interactions as I

N = 50
T = 2 * np.pi / 1.1
n = np.arange(N)


def hump(c, w=0.8):
    d = (n - c + N / 2) % N - N / 2
    return np.exp(-0.5 * (d / w) ** 2)


def run(c1, c2, periods=300, a2=1.0):
    """A field (T, N) whose peak per period is a hump at c1(k) and one at c2(k), k in periods."""
    t = np.arange(0.0, periods * T, 0.5)
    k = t / T
    f = np.array([hump(c1(kk)) + a2 * hump(c2(kk)) for kk in k]) * np.abs(np.cos(1.1 * t))[:, None]
    return t, f


def test_humps_of_one_two_and_ragged_profiles():
    c, top = I.humps(hump(10) + hump(16))
    assert sorted(np.round(c, 6)) == [10.0, 16.0] and top == pytest.approx([1.0, 1.0], abs=1e-6)
    # a shallow saddle (dip above 70 % of the smaller top) is one ragged hump
    ragged = hump(20, 1.5) + 0.1 * hump(22, 0.5)
    assert I.humps(ragged)[0].size == 1
    # across the seam of the ring
    c, _ = I.humps(hump(0.0))
    assert c.size == 1 and I.ring_distance(c[0], 0.0, N) < 1e-9
    assert I.humps(hump(5.0), periodic=False)[0].size == 1
    # below rel of the largest: not a breather
    assert I.humps(hump(10) + 0.2 * hump(30))[0].size == 1
    assert I.humps(np.zeros(N))[0].size == 0
    assert I.humps(np.full(N, np.nan))[0].size == 0


def test_two_static_humps_are_bound():
    t, f = run(lambda k: 20.0, lambda k: 27.0)
    o = I.classify(t, f, T)
    assert o.outcome == "bound" and o.separation0 == pytest.approx(7.0, abs=1e-6)
    assert np.all(o.counts == 2)


def test_one_hump_throughout_is_no_pair():
    t, f = run(lambda k: 20.0, lambda k: 20.0)
    assert I.classify(t, f, T).outcome == "none"


def test_humps_moving_apart_repel_with_their_velocity():
    v = 0.04   # sites per period, each
    t, f = run(lambda k: 22.0 - v * k, lambda k: 28.0 + v * k, periods=200)
    o = I.classify(t, f, T)
    assert o.outcome == "repel"
    assert o.separation_velocity == pytest.approx(2 * v, rel=0.02)


def test_merge_period_and_drift_of_what_remains():
    # the humps close in linearly and become one at period 150 (distance 0); drift 0.01 sites/period after
    def c1(k):
        return 25.0 - 4.0 * max(0.0, 1 - k / 150) + 0.01 * max(0.0, k - 150)

    def c2(k):
        return 25.0 + 4.0 * max(0.0, 1 - k / 150) + 0.01 * max(0.0, k - 150)

    t, f = run(c1, c2, periods=400)
    o = I.classify(t, f, T)
    assert o.outcome == "merge"
    # one hump once the distance 8 (1 - k/150) falls below ~3 sites (dip of two w = 0.8 Gaussians)
    assert 90 <= o.merge_period <= 150
    assert o.merge_period == float(np.flatnonzero(o.counts == 2)[-1] + 1)
    assert o.drift_velocity == pytest.approx(0.01, rel=0.1)


def test_a_merged_breather_that_shows_two_humps_briefly_still_merged():
    """A few two-hump periods after the merge (a merged breather's ragged top) do not move the merging
    period: the count is smoothed over 11 periods."""
    def c2(k):
        if k < 100:
            return 31.0
        return 24.0 if 180 <= k < 183 else 25.0

    t, f = run(lambda k: 25.0, c2, periods=300)
    o = I.classify(t, f, T)
    assert o.outcome == "merge" and o.merge_period == 100.0


def test_a_breathing_bound_pair_coalesces_first_long_before_its_final_merge():
    """The two definitions of a merging time: the pair is one hump over periods 40-69 (a bound state that
    breathes), two again, and one from 150 on: first coalescence 40, final single breather 150; a short
    overlap the 11-period median smooths away (periods 20-22) is not a coalescence. A pair that never
    overlaps has none."""
    def c2(k):
        return 25.0 if 40 <= k < 70 or k >= 150 or 20 <= k < 23 else 31.0

    t, f = run(lambda k: 25.0, c2, periods=300)
    o = I.classify(t, f, T)
    assert o.outcome == "merge" and o.merge_period == 150.0 and o.first_coalescence == 40.0
    t, f = run(lambda k: 20.0, lambda k: 30.0, periods=100)
    o = I.classify(t, f, T)
    assert o.outcome == "bound" and np.isnan(o.first_coalescence)


def test_breathers_that_overlap_and_come_apart_are_not_merged():
    # they approach, overlap for ~30 periods and pass through each other: transmit, not merge
    t, f = run(lambda k: 10.0 + 0.1 * k, lambda k: 30.0 - 0.1 * k, periods=300)
    o = I.classify(t, f, T)
    assert o.outcome == "transmit"
    # and a run that ends in an overlap shorter than min_periods is not a merge
    t, f = run(lambda k: 10.0 + 0.1 * k, lambda k: 30.0 - 0.1 * k, periods=105)
    assert I.classify(t, f, T).outcome != "merge"


def test_outcome_codes_are_the_index_in_OUTCOMES():
    assert [I.Outcome(o).code for o in I.OUTCOMES] == list(range(len(I.OUTCOMES)))


def test_the_loc1_figure_names_the_outcomes_as_the_measure_codes_them():
    from cradle.figures import localised

    assert localised.OUTCOME_NAMES == I.OUTCOMES
