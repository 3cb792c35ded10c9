"""cradle.measurements.slow_motion: the frames of a movie chosen from its impact times. Every stored state inside
an impact window, a spacing that grows by the ramp factor per frame away from it, at most `sparse` between."""
from __future__ import annotations

import numpy as np
import pytest

from cradle.measurements.slow_motion import frame_indices, impact_windows, ramp_offsets


def test_windows_widen_each_contact_and_instant_by_the_margin_and_merge_overlaps():
    t = np.arange(0.0, 10.01, 0.01)
    touching = (np.abs(t - 2.0) < 0.055) | (np.abs(t - 2.3) < 0.015)     # [1.95, 2.05] and [2.29, 2.31]
    w = impact_windows(t, touching, margin=0.15, instants=[7.0, 9.98])
    # the two contacts lie 0.24 apart, closer than twice the margin: one window; 9.98 + 0.15 is clipped to t_end
    assert w == pytest.approx(np.array([[1.8, 2.46], [6.85, 7.15], [9.83, 10.0]]))
    # with a margin of 0.1 they stay apart
    assert impact_windows(t, touching, margin=0.1) == pytest.approx(np.array([[1.85, 2.15], [2.19, 2.41]]))
    assert impact_windows(t, np.zeros_like(t, dtype=bool), 0.1).shape == (0, 2)
    with pytest.raises(ValueError, match="one flag per stored time"):
        impact_windows(t, touching[:-1], 0.1)


def test_ramp_offsets_are_the_partial_sums_of_a_geometric_spacing():
    d = ramp_offsets(h=1.0, sparse=10.0, ramp=2.0)
    assert d == pytest.approx([1.0, 3.0, 7.0, 15.0])      # spacings 1, 2, 4, 8: the last one below 10
    with pytest.raises(ValueError, match="must be > 1"):
        ramp_offsets(1.0, 10.0, 1.0)


def test_frames_take_every_state_in_a_window_and_grow_geometrically_outside():
    h, sparse, ramp = 1e-3, 0.5, 1.5
    t = h * np.arange(20001)                                             # [0, 20]
    windows = np.array([[5.0, 5.02], [12.0, 12.01]])
    idx = frame_indices(t, windows, sparse, ramp)
    tf = t[idx]
    assert idx[0] == 0 and idx[-1] == t.size - 1
    for a, b in windows:                                                 # every stored state of each window
        inside = np.flatnonzero((t >= a - 1e-12) & (t <= b + 1e-12))
        assert np.isin(inside, idx).all()
    gaps = np.diff(tf)
    assert gaps.max() <= sparse + h                                      # never sparser than asked (grid rounding)
    # after the first window, frames at 5.02 + d_j, d_j = h (ramp^j - 1) / (ramp - 1): spacings h ramp^(j-1), each
    # time rounded to the grid (to within h / 2)
    d = h * (ramp ** np.arange(1, 16) - 1.0) / (ramp - 1.0)
    d = d[h * ramp ** np.arange(0, 15) < sparse]
    after = tf[(tf > 5.02 + h / 2) & (tf <= 5.02 + d[-1] + h / 2)]
    assert after.size == d.size and np.abs(after - (5.02 + d)).max() <= h / 2 + 1e-12
    # denser at an impact than between them: h within a window, near sparse more than 2 away from any
    inside = ((tf[:-1] >= 5.0) & (tf[1:] <= 5.02 + h / 2)) | ((tf[:-1] >= 12.0) & (tf[1:] <= 12.01 + h / 2))
    far = np.min(np.abs(tf[:-1, None] - windows.ravel()[None, :]), axis=1) > 2.0
    assert gaps[inside] == pytest.approx(h) and np.all(gaps[far] > 0.5 * sparse)
    with pytest.raises(ValueError, match="uniform grid"):
        frame_indices(np.array([0.0, 1.0, 3.0]), windows, sparse, ramp)
