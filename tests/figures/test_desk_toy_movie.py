"""The desk-toy movie (cradle.analyses.desk_toy_movie, cradle.figures.desk_toy_movie): its run is dense at the
impacts and sparse between, and what physics fixes holds there: a two-ball impact lasts the Hertz contact time and
peaks at the Hertz force k delta_max^(3/2) (Landau & Lifshitz, Theory of Elasticity, section 9); the drawing is to
scale (balls at rest 2R apart in mm, touching) with the force strip in newtons."""
from __future__ import annotations

import math

import numpy as np
import pytest

from cradle.analyses.desk_toy import DEFAULT_CRADLE, DeskToyRuns
from cradle.analyses.desk_toy_movie import SlowMotion, movie_run
from cradle.figures.desk_toy_movie import FORCE_LABEL, ball_centres, impact_frames, playback_speed, render
from cradle.models import physical as ph
from cradle.specs.declare import from_plain

FPS = 25


@pytest.fixture(scope="module")
def two_balls():
    """Two steel balls, one lifted: one impact per half swing, a pure two-body Hertz collision (the on-site force
    changes it by (t_c / T)^2, ~1e-7 here), stored 32 times per contact time."""
    spec = from_plain(DeskToyRuns, {"chains": [2], "lifted": [1]})
    motion = SlowMotion(swings=1, per_contact=32, margin=2.0, ramp=1.5, slowdown=2.0)
    return motion, movie_run(spec, 2, 1, motion, FPS)


def test_frames_are_dense_at_the_impacts_and_sparse_between(two_balls):
    motion, ds = two_balls
    s = ph.scales(DEFAULT_CRADLE)
    t_c = float(ds.attrs["contact_time_s"])
    t = ds["t"].values
    gaps = np.diff(t)
    starts, ends = ds["window_start"].values, ds["window_end"].values
    # one swing period: the impacts at t = pi/2 and 3 pi/2 (in 1/omega_0), each where (nc) and the hard spheres
    # meet: one window each
    assert starts.size == 2
    for k, when in enumerate((0.5 * math.pi * s.T, 1.5 * math.pi * s.T)):
        assert starts[k] < when < ends[k]
    inside = np.zeros(gaps.size, dtype=bool)
    for a, b in zip(starts, ends, strict=True):
        inside |= (t[:-1] >= a) & (t[1:] <= b)
    assert gaps[inside] == pytest.approx(t_c / motion.per_contact)        # every stored state
    sparse = 1.0 / (FPS * motion.slowdown)                                  # between impacts: evenly, at most
    assert sparse / 2 < gaps.max() <= sparse + t_c / motion.per_contact     # sparse apart (to the grid)
    assert gaps.max() > 1000 * gaps[inside].max()
    # every frame with a compressed bond lies in a window; the hard spheres' collisions fall in windows too
    pressed = ds["force"].values.max(axis=1) > 0
    assert pressed.any() and all(((t[pressed] >= a) & (t[pressed] <= b)).any() for a, b in zip(starts, ends,
                                                                                               strict=True))
    hit = t[ds["collided"].values.any(axis=1)]
    assert hit.size == 2 and all(((hit >= a) & (hit <= b + gaps.max())).any() for a, b in zip(starts, ends,
                                                                                            strict=True))


def test_a_two_ball_impact_lasts_the_hertz_time_and_peaks_at_the_hertz_force(two_balls):
    motion, ds = two_balls
    s = ph.scales(DEFAULT_CRADLE)
    mu = s.m / 2.0                                                       # the pair's reduced mass
    # the released ball meets the line at (nc)'s speed: its linear pendulum's, L sin(theta) omega_0
    v = float(ds.attrs["length_m"]) * math.sin(math.radians(float(ds.attrs["angle_deg"]))) * s.omega0
    delta_max = (5.0 * mu * v**2 / (4.0 * s.k)) ** 0.4
    f = ds["force"].values[:, 0]
    t = ds["t"].values
    first = t < float(ds["window_end"].values[0])
    h = float(ds.attrs["contact_time_s"]) / motion.per_contact
    # a stored state lies within h / 2 of the peak, and mu delta'' = -k delta^(3/2) >= -k delta_max^(3/2): there
    # delta >= delta_max - k delta_max^(3/2) (h / 2)^2 / (2 mu)
    low = delta_max - s.k * delta_max**1.5 * (h / 2.0) ** 2 / (2.0 * mu)
    assert s.k * low**1.5 <= f[first].max() <= s.k * delta_max**1.5 * (1 + 1e-9)
    pressed = t[first][f[first] > 0]
    assert pressed[-1] - pressed[0] == pytest.approx(ph.collision_time(DEFAULT_CRADLE, v), abs=2 * h)


def test_balls_at_rest_touch_in_the_drawing_and_the_force_strip_is_in_newtons(two_balls):
    _, ds = two_balls
    R, L = DEFAULT_CRADLE.radius, DEFAULT_CRADLE.length
    cx, cy = ball_centres(np.zeros(5), R, L)
    assert np.diff(cx) == pytest.approx(2e3 * R) and cy == pytest.approx(-1e3 * L)     # mm: 2R apart, L below
    frames = render(ds, 320, 180, [0])
    info = next(frames)
    shot = next(frames)
    assert shot.shape == (180, 320, 3)
    balls = info["axes"][0].patches
    centres = np.array([b.center for b in balls])
    # at t = 0 ball 1 hangs at rest, ball 0 is lifted to -L sin(theta), L (1 - cos(theta)) higher
    theta = math.radians(float(ds.attrs["angle_deg"]))
    assert centres[1] == pytest.approx([2e3 * R, -1e3 * L])
    assert centres[0] == pytest.approx([-1e3 * L * math.sin(theta), -1e3 * L * math.cos(theta)])
    assert all(b.radius == pytest.approx(1e3 * R) for b in balls)
    assert info["axes"][1].get_ylabel() == FORCE_LABEL and "(N)" in FORCE_LABEL
    assert info["axes"][1].get_ylim()[1] >= info["force_max"] > 0


def test_impact_frames_pick_before_the_largest_force_and_after(two_balls):
    _, ds = two_balls
    f = ds["force"].values.max(axis=1)
    k = impact_frames(ds)
    assert f[k["before"]] == 0 and f[k["after"]] == 0 and f[k["during"]] == f[: k["after"]].max() > 0
    assert k["before"] + 1 == np.flatnonzero(f > 0)[0]
    t = ds["t"].values
    lead = impact_frames(ds, lead=0.01)
    assert t[lead["during"]] - t[lead["before"]] >= 0.01 and t[lead["after"]] - t[lead["during"]] >= 0.01


def test_playback_speed_is_the_frame_spacing_times_the_frame_rate():
    assert playback_speed([0.0, 0.1, 0.3], fps=10) == pytest.approx([1.0, 1.0, 2.0])
