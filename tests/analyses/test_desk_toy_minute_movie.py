"""The minute as a movie (cradle.analyses.desk_toy_minute_movie, cradle.figures.desk_toy_minute_movie).

Numbers fixed by physics or the contract: the small-angle pendulum brings the released ball to the line at exactly
a quarter period, so the first slow-motion impact's first compressed frame lies within one dense step after T/4;
the contacts conserve momentum, so the centre of mass at every frame (real-time frames integrated from the
analysis's stored states, slow-motion frames from a dense rerun of a half swing) is the damped oscillator
X'' + gamma X' + omega_0^2 X = 0 in closed form; between slow-motion impacts the frames are 1 / fps apart.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from cradle.analyses import desk_toy_minute as dm
from cradle.analyses.desk_toy_minute_movie import MinuteMovie, movie_run
from cradle.analyses.protocol import FULL, form_spec
from cradle.specs.declare import from_plain

FPS = 25


@pytest.fixture(scope="module")
def movie():
    spec = form_spec(from_plain(dm.DeskToyMinute, {"chains": [5], "lifted": [1], "duration": 4.0,
                                                  "ensemble": 0}), FULL)
    motion = from_plain(MinuteMovie, {"first_impacts": 1, "contact": 0, "moments": [3.0]})
    return spec, motion, movie_run(spec, 5, 1, motion, FPS)


def test_first_impact_in_slow_motion_starts_at_a_quarter_period(movie):
    _, motion, ds = movie
    quarter = 0.5 * math.pi / float(ds.attrs["omega0_rad_per_s"])
    t = ds["t"].values
    slow = ds["slow"].values
    force = ds["force"].values.max(axis=1)
    first = np.flatnonzero((slow == 0) & (force > 0.0))[0]
    dense = float(ds.attrs["contact_time_s"]) / motion.per_contact
    assert quarter <= t[first] <= quarter + dense * (1.0 + 1e-9)
    assert str(ds["impact_label"].values[0]) == "the first impact"
    assert any(str(s).startswith("the break-up") for s in ds["impact_label"].values)
    assert str(ds["impact_label"].values[-1]) == "near 3 s"


def test_every_frame_is_on_the_damped_centre_of_mass_oscillation(movie):
    spec, _, ds = movie
    t = ds["t"].values * float(ds.attrs["omega0_rad_per_s"])       # (nc)'s time
    x = ds["x"].values
    A = -float(x[0, 0])
    gamma = float(ds.attrs["drag_rate_per_s"]) / float(ds.attrs["omega0_rad_per_s"])
    w = math.sqrt(1.0 - gamma**2 / 4.0)
    X0 = -A / 5.0
    exact = X0 * np.exp(-gamma * t / 2.0) * (np.cos(w * t) + gamma / (2.0 * w) * np.sin(w * t))
    # a global error of a few rtol (2.2 rtol when written); a frame restarted from the wrong stored state or at
    # the wrong time would be off by a share of the swing
    assert np.max(np.abs(x.mean(axis=1) - exact)) / A < 100.0 * spec.rtol


def test_real_time_between_slow_motion_impacts(movie):
    _, _, ds = movie
    t = ds["t"].values
    slow = ds["slow"].values
    assert np.all(np.diff(t) > 0.0)
    real = np.flatnonzero((slow[:-1] == -1) & (slow[1:] == -1))
    assert np.allclose(np.diff(t)[real], 1.0 / FPS, rtol=1e-9)
    inside = np.flatnonzero((slow[:-1] == 0) & (slow[1:] == 0))
    assert np.min(np.diff(t)[inside]) == pytest.approx(float(ds.attrs["contact_time_s"]) / 8.0, rel=1e-9)


def test_stills_are_the_first_impact_the_break_up_and_late_swinging(movie, tmp_path):
    from cradle.figures.desk_toy_minute_movie import STILLS, still_frames, write_stills

    _, _, ds = movie
    frames = still_frames(ds)
    assert tuple(frames) == STILLS
    slow = ds["slow"].values
    assert slow[frames["impact"]] == 0 and slow[frames["late"]] == -1
    paths = write_stills(ds, {frames[k]: tmp_path / f"{k}.png" for k in STILLS}, 320, 180)
    assert len(paths) == 3 and all(p.stat().st_size > 0 for p in paths)


def test_animate_writes_every_frame_and_a_gif_of_the_asked_frames(movie, tmp_path):
    from cradle.figures.desk_toy_minute_movie import animate

    _, _, ds = movie
    info = animate(ds, tmp_path / "m.mp4", 320, 180, gif=tmp_path / "m.gif", gif_fps=5, gif_duration=1.0,
                   gif_width=160)
    assert info["path"].stat().st_size > 0 and info["gif"]["path"].stat().st_size > 0
    assert info["gif"]["frames"] == min(5, len(info["times"])) and len(info["times"]) == ds["t"].size
