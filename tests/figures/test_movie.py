"""Movies (cradle.figures.movie, cradle animate): the written file decodes to the frames asked for, at the size
asked for, each a stored state; the frame times subsample a long run evenly."""
from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from cradle.figures.movie import MovieSpec, frame_indices, render

imageio_ffmpeg = pytest.importorskip("imageio_ffmpeg", reason="imageio-ffmpeg (extra `movies`) writes and "
                                     "decodes the MP4: pip install -e '.[test]'")


def _scene(n_t=401, n=12, bc="periodic"):
    """Two runs of a standing oscillation x_n(t) = a cos(n pi / 4) cos(t), forces of the Hertz law
    V0'(r) = -|r|^alpha H(-r) on the bonds: a stand-in for cradle.open_scene's Dataset."""
    t = np.linspace(0.0, 100.0, n_t)
    x = 1e-2 * np.cos(np.pi * np.arange(n) / 4)[None, :] * np.cos(t)[:, None]
    r = np.roll(x, -1, axis=1) - x
    force = -np.abs(np.minimum(r, 0.0)) ** 1.5

    def both(a):
        return xr.DataArray(np.stack([a, 0.9 * a]), dims=("model", "t", "n"))

    return xr.Dataset({"x": both(x), "force": both(force)},
                      coords={"model": ["exact", "dps"], "t": t, "n": np.arange(n)},
                      attrs={"scene": "test", "alpha": 1.5, "N": n, "bc": bc, "omega_sw": 1.0})


def test_frame_indices_subsample_evenly_and_never_exceed_the_stored_states():
    t = np.arange(0.0, 1000.5, 0.5)                                     # 2001 stored states
    idx = frame_indices(t, MovieSpec(fps=10, duration=5.0))
    assert len(idx) == 50 and idx[0] == 0 and idx[-1] == 2000
    assert np.ptp(np.diff(idx)) <= 1                                    # evenly spaced, up to rounding
    assert len(frame_indices(t[:20], MovieSpec(fps=10, duration=5.0))) == 20   # short run: every state once
    win = frame_indices(t, MovieSpec(fps=10, duration=1.0, t_start=100.0, t_end=200.0))
    assert t[win[0]] == 100.0 and t[win[-1]] == 200.0 and len(win) == 10
    with pytest.raises(ValueError, match="no stored time"):
        frame_indices(t, MovieSpec(t_start=2000.0))


def test_size_must_be_even():
    with pytest.raises(ValueError, match="even number of pixels"):
        MovieSpec(width=321)


def test_render_magnifies_the_largest_displacement_to_the_declared_fraction():
    frames = render(_scene(), MovieSpec(fps=2, duration=1.0, width=320, height=180))
    info = next(frames)
    assert info["magnification"] == pytest.approx(0.4 / 1e-2)           # max |x| = 1e-2 (exact run, n = 0)
    assert info["dt_frame"] == pytest.approx(100.0)                     # 2 frames over t in [0, 100]
    shots = list(frames)
    assert len(shots) == 2 and shots[0].shape == (180, 320, 3) and shots[0].dtype == np.uint8
    assert not np.array_equal(shots[0], shots[1])                       # the beads moved, the clock changed


@pytest.mark.parametrize("bc", ["periodic", "free"])
def test_mp4_and_gif_decode_to_the_frames_asked_for(tmp_path, bc):
    from PIL import Image

    from cradle.figures.movie import animate

    spec = MovieSpec(fps=5, duration=2.0, width=320, height=180)
    info = animate(_scene(bc=bc), tmp_path / "m.mp4", spec, gif=tmp_path / "m.gif",
                   gif_spec=MovieSpec(fps=4, duration=1.5, width=320, height=180), gif_width=160)
    reader = imageio_ffmpeg.read_frames(str(tmp_path / "m.mp4"))
    meta = next(reader)
    frames = [np.frombuffer(f, np.uint8) for f in reader]
    assert meta["size"] == (320, 180) and meta["fps"] == 5
    assert len(frames) == 10 == len(info["indices"])                    # fps * duration
    assert all(f.size == 320 * 180 * 3 for f in frames)
    gif = Image.open(tmp_path / "m.gif")
    assert gif.n_frames == 6 and gif.size == (160, 90)                  # 4/s * 1.5 s, scaled to 160 px
    assert not list(tmp_path.glob(".*"))                                # no temporary file left


@pytest.mark.parametrize("argv, words", [
    (["--width", "100000"], "--width 100000: must be <= 3840"),
    (["--gif", "--gif-fps", "0"], "--gif-fps 0: must be >= 1"),
    (["--width", "101"], "--width 101: 101 is not a multiple of 2"),
    (["--duration", "1e300"], "--duration 1e+300: must be <= 600"),
    (["--t-end", "inf"], "--t-end inf: must be a finite time"),
    (["--t-start", "5", "--t-end", "1"], "--t-start 5, --t-end 1: need t_start < t_end"),
])
def test_cradle_animate_refuses_bad_flags_before_any_work(tmp_path, capsys, argv, words):
    """A flag outside the bounds of its key of `movies:` is one line naming it, exit 2, before the scene is
    read (there is none here) or a frame drawn."""
    from cradle.pipeline.cli import main

    assert main(["animate", "tw", "--results", str(tmp_path), "--config", str(tmp_path / "none.yaml"), *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("cradle: error: ") and words in err and err.count("\n") == 1, err


@pytest.mark.slow
def test_cradle_animate_on_a_run_of_the_cli(tmp_path, capsys):
    """`cradle animate` reads a scene computed by `cradle run` (tiny, t_end = 5) and writes the MP4."""
    import yaml

    from cradle.pipeline.cli import main

    cfg = {"defaults": {"alpha": 1.5},
           "scenes": {"tw": {"N": 16, "bc": "periodic", "initial": {"kind": "travelling", "q": "pi/4",
                                                                     "omega_tw": 1.01},
                             "t_end": 5.0, "store": {"every": 0.5}}},
           "movies": {"fps": 4, "duration": 1.0, "width": 256, "height": 144}}
    path = tmp_path / "c.yaml"
    path.write_text(yaml.safe_dump(cfg))
    assert main(["run", "tw", "--out", str(tmp_path / "r"), "--config", str(path)]) == 0
    assert main(["animate", "tw", "--results", str(tmp_path / "r"), "--config", str(path), "--gif"]) == 0
    out = capsys.readouterr().out
    assert "4 frames at 4/s, 256x144" in out
    reader = imageio_ffmpeg.read_frames(str(tmp_path / "r" / "movies" / "tw.mp4"))
    assert next(reader)["size"] == (256, 144) and len(list(reader)) == 4
    assert (tmp_path / "r" / "movies" / "tw.gif").exists()
    assert main(["animate", "nope", "--results", str(tmp_path / "r"), "--config", str(path)]) == 2
    assert "scene 'nope': no " in capsys.readouterr().err
    # a window past the run's end: one line naming the flags, no movie written
    out = tmp_path / "late.mp4"
    assert main(["animate", "tw", "--results", str(tmp_path / "r"), "--config", str(path), "--out", str(out),
                 "--t-start", "100"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--t-start/--t-end: no stored time in the window [100.0, None] (run covers " \
        "[0, 5])" in err and "Traceback" not in err and not out.exists(), err
