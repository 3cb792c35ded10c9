"""The desk-toy movie: a Newton's cradle drawn to scale in millimetres, each impact in slow motion.

Drawn from a run of :func:`cradle.analyses.desk_toy_movie.movie_run` only (its frames are the run's stored
times, dense around each impact). Each frame shows, side by side, the lattice (nc) and the hard-sphere cradle
at the same instant:

* the balls as discs of the cradle's radius R hanging on strings of its length L from pivots 2R apart (the
  balls touch at rest), ball n's centre at (2 R n + x_n, -sqrt(L^2 - x_n^2)) in mm, x_n its horizontal
  displacement (:func:`ball_centres`): one scale for both axes, nothing magnified;
* under (nc), the Hertz contact force of each bond in N, a bar at the contact point of the balls at rest;
  under the hard spheres, a mark on each bond that collided since the previous frame (a collision of hard
  spheres lasts no time: it has an impulse, no finite force);
* the clock in seconds and the playback speed (:func:`playback_speed`): about
  1/4000 of real time within an impact, 1/``slowdown`` between impacts.

:func:`render` yields the frames, :func:`impact_frames` picks three frames around the first impact (before
it, at the largest force, after it), :func:`write_stills` writes frames as PNG files and :func:`animate` writes
the MP4 and GIF (:func:`cradle.figures.movie.write_mp4`, :func:`cradle.figures.movie.write_gif`).
"""
from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from collections.abc import Iterator, Mapping, Sequence

    import xarray as xr
    from numpy.typing import ArrayLike, NDArray

DPI = 100
MM = 1e3  # millimetres per metre
BALL, EDGE, FORCE = "#b8c2cc", "#37424d", "#c0392b"
#: the force strip's y label: the contact force in newtons
FORCE_LABEL = "contact force (N)"
#: the stills of an impact (:func:`impact_frames`): before and after it by this much (s), a gap of a few mm at a
#: desk toy's speed, so that the ball coming in and the ball going out are seen to move
STILL_LEAD = 0.01


def ball_centres(x: ArrayLike, radius: float, length: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(horizontal, vertical) position in mm of each ball's centre, pivot n at (2 R n, 0): (2 R n + x_n,
    -sqrt(L^2 - x_n^2)); ``x`` (..., N) in m, ``radius`` R and ``length`` L (pivot to centre) in m."""
    x = np.asarray(x, dtype=float)
    n = np.arange(x.shape[-1])
    return (2.0 * radius * n + x) * MM, -np.sqrt(np.maximum(length**2 - x**2, 0.0)) * MM


def playback_speed(t_frames: ArrayLike, fps: float) -> NDArray[np.float64]:
    """Seconds of the run per second of movie at each frame, (t_k - t_(k-1)) fps (the first frame takes the
    second's): below 1 is slow motion."""
    t_frames = np.asarray(t_frames, dtype=float)
    if t_frames.size < 2:
        return np.ones_like(t_frames)
    dt = np.diff(t_frames)
    return np.concatenate([dt[:1], dt]) * fps


def _speed_text(speed: float) -> str:
    """The playback speed in words: '1/4230 of real time' (slow motion) or '2.0x real time'."""
    if speed < 1.0:
        slower = f"{1.0 / speed:.0f}" if speed < 0.1 else f"{1.0 / speed:.2g}"
        return f"slow motion: 1 s of movie = {speed * 1e3:.3g} ms of the cradle (1/{slower} of real time)"
    return f"1 s of movie = {speed:.3g} s of the cradle"


def impact_frames(ds: xr.Dataset, impact: int = 0, lead: float = 0.0) -> dict[str, int]:
    """Three frames of the impact window ``impact`` that holds a contact of (nc): ``before`` (the last frame
    at least ``lead`` seconds before the first one with a bond compressed, and with none), ``during`` (the
    largest force) and ``after`` (the first frame at least ``lead`` after the last one with a bond compressed,
    and with none)."""
    t = np.asarray(ds["t"].values, dtype=float)
    force = np.asarray(ds["force"].values, dtype=float)
    touching = force.max(axis=1) > 0.0
    starts, ends = np.asarray(ds["window_start"].values), np.asarray(ds["window_end"].values)
    with_contact = [k for k in range(starts.size) if np.any(touching & (t >= starts[k]) & (t <= ends[k]))]
    if impact >= len(with_contact):
        raise ValueError(f"impact = {impact}: the run has {len(with_contact)} impact windows with a contact of (nc)")
    k = with_contact[impact]
    inside = np.flatnonzero(touching & (t >= starts[k]) & (t <= ends[k]))
    first, last = int(inside[0]), int(inside[-1])
    during = first + int(np.argmax(force[first:last + 1].max(axis=1)))
    before = int(np.searchsorted(t, t[first] - lead, side="right")) - 1 if lead > 0 else first - 1
    after = int(np.searchsorted(t, t[last] + lead, side="left")) if lead > 0 else last + 1
    return {"before": max(before, 0), "during": during, "after": min(after, t.size - 1)}


def _collided_in_impact(t: NDArray[np.float64], collided: NDArray[np.bool_], starts: NDArray[np.float64],
                        ends: NDArray[np.float64]) -> NDArray[np.bool_]:
    """(T, bonds): the bonds that collided since the start of the impact window holding each frame, up to it
    (a frame outside every window: since the previous frame)."""
    shown = collided.copy()
    for a, b in zip(starts, ends, strict=True):
        inside = np.flatnonzero((t >= a) & (t <= b + 1e-12 * max(1.0, abs(b))))
        if inside.size:
            # the frame that ends the window carries the collisions of its instant onwards to the window's end
            shown[inside] = np.logical_or.accumulate(collided[inside], axis=0)
    return shown


class CradleFrames:
    """What both desk-toy movies read of their run ``ds`` and draw on: ``R``, ``L`` (m), the stored times ``t`` (s)
    and their ``speed`` of playback, ``x`` ((model,) t, n; m), ``force`` (t, bond; N), and ``fig`` on its own Agg
    ``canvas`` (outside pyplot: the session's backend is left alone)."""

    def __init__(self, ds: xr.Dataset, width: int, height: int) -> None:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure

        a = ds.attrs
        self.R, self.L = float(a["radius_m"]), float(a["length_m"])
        self.t = np.asarray(ds["t"].values, dtype=float)
        self.speed = playback_speed(self.t, float(a["fps"]))
        self.x = np.asarray(ds["x"].values, dtype=float)
        self.force = np.asarray(ds["force"].values, dtype=float)
        self.fig = Figure(figsize=(width / DPI, height / DPI), dpi=DPI)
        self.canvas = FigureCanvasAgg(self.fig)


class MovieFigure(CradleFrames):
    """The figure of the movie's run ``ds`` (module docstring) and its moving artists: :meth:`show` puts them at a
    stored time. ``fig`` (:class:`CradleFrames`), ``moving`` (the artists :meth:`show` changes), ``force_max`` (N,
    the top of the force strip's scale)."""

    def __init__(self, ds: xr.Dataset, width: int = 1280, height: int = 720) -> None:
        from matplotlib.collections import LineCollection
        from matplotlib.patches import Circle

        super().__init__(ds, width, height)
        a = ds.attrs
        R, L = self.R, self.L
        self.collided = _collided_in_impact(self.t, np.asarray(ds["collided"].values) > 0,
                                            np.asarray(ds["window_start"].values),
                                            np.asarray(ds["window_end"].values))
        n_beads = self.x.shape[-1]
        self.force_max = float(self.force.max()) if self.force.size and self.force.max() > 0 else 1.0
        names = [str(m) for m in ds["model"].values]

        fig = self.fig
        fig.text(0.5, 0.965, f"Newton's cradle: {n_beads} {a['material']} balls of radius {R * MM:g} mm on strings "
                 f"of {L * MM:g} mm, {int(a['lifted'])} lifted to {float(a['angle_deg']):g}° and released",
                 ha="center", va="center", fontsize=12)
        reach = float(np.max(np.abs(self.x))) + R
        xlim = ((-reach - 0.1 * R) * MM, (2.0 * R * (n_beads - 1) + reach + 0.1 * R) * MM)
        ylim = (-(L + 1.4 * R) * MM, 0.35 * R * MM)
        self.contacts = (2.0 * np.arange(n_beads - 1) + 1.0) * R * MM   # the contact points of the balls at rest
        rest_x, rest_y = ball_centres(np.zeros(n_beads), R, L)
        self.pivots = np.column_stack([rest_x, np.zeros(n_beads)])
        titles = (f"lattice {names[0]}: Hertz contacts", f"{names[1]}: instantaneous collisions")
        self.panels: list[tuple[Any, list[Any], Any, Any]] = []
        for col, title in enumerate(titles):
            ax = fig.add_axes((0.05 + 0.5 * col, 0.38, 0.43, 0.52))
            ax.set_xlim(*xlim)
            ax.set_ylim(*ylim)
            ax.set_aspect("equal", adjustable="box")
            ax.set_title(title, fontsize=11)
            ax.set_ylabel("height (mm)", fontsize=9)
            ax.tick_params(labelsize=8, labelbottom=False)
            ax.plot([rest_x[0] - R * MM, rest_x[-1] + R * MM], [0.0, 0.0], color="0.2", lw=4, solid_capstyle="butt")
            strings = LineCollection([], colors="0.45", linewidths=0.8)
            ax.add_collection(strings)
            balls = [ax.add_patch(Circle((float(cx), float(cy)), R * MM, facecolor=BALL, edgecolor=EDGE, lw=0.8))
                     for cx, cy in zip(rest_x, rest_y, strict=True)]
            ax.apply_aspect()
            box = ax.get_position()
            # the strip right under the drawing (a long chain makes the drawing flatter), never below the clock
            strip = fig.add_axes((box.x0, max(0.1, box.y0 - 0.27), box.width, 0.2))
            strip.set_xlim(*xlim)
            strip.set_xlabel("horizontal position (mm)", fontsize=9)
            strip.tick_params(labelsize=8)
            if col == 0:
                strip.set_ylim(0.0, 1.15 * self.force_max)
                strip.set_ylabel(FORCE_LABEL, fontsize=9)
                marks: Any = strip.bar(self.contacts, np.zeros(n_beads - 1), width=1.0 * R * MM, color=FORCE)
                note = strip.text(0.01, 0.93, "", transform=strip.transAxes, ha="left", va="top", fontsize=9)
            else:
                strip.set_ylim(0.0, 1.0)
                strip.set_yticks([])
                strip.set_ylabel("collision", fontsize=9)
                marks = strip.scatter(self.contacts, np.full(n_beads - 1, 0.45), s=140, marker="*", color=FORCE)
                strip.text(0.01, 0.93, "★ collided in this impact (an instant: no finite force)",
                           transform=strip.transAxes, ha="left", va="top", fontsize=9)
                note = None
            self.panels.append((strings, balls, marks, note))
        self.clock = fig.text(0.02, 0.02, "", ha="left", va="bottom", fontsize=11, family="monospace")
        self.moving: list[Any] = [self.clock]
        for strings, balls, marks, note in self.panels:
            self.moving += [strings, *balls, *(list(marks) if note is not None else [marks])]
            self.moving += [note] if note is not None else []

    def show(self, k: int) -> None:
        """Put the moving artists at stored time ``k``."""
        for m, (strings, balls, marks, note) in enumerate(self.panels):
            cx, cy = ball_centres(self.x[m, k], self.R, self.L)
            for ball, px, py in zip(balls, cx, cy, strict=True):
                ball.set_center((float(px), float(py)))
            strings.set_segments(list(np.stack([self.pivots, np.column_stack([cx, cy])], axis=1)))
            if note is not None:
                for bar, value in zip(marks, self.force[k], strict=True):
                    bar.set_height(float(value))
                peak = float(self.force[k].max())
                note.set_text(f"largest: {peak:.3g} N" if peak > 0 else "no ball compressed")
            else:
                hit = self.collided[k]
                marks.set_offsets(np.column_stack([self.contacts[hit], np.full(int(hit.sum()), 0.45)]))
        self.clock.set_text(f"t = {self.t[k]:.6f} s    {_speed_text(float(self.speed[k]))}")


def render(ds: xr.Dataset, width: int = 1280, height: int = 720,
           indices: Sequence[int] | NDArray[np.int64] | None = None) -> Iterator[Any]:
    """Yield the frames (height x width x 3 uint8 arrays) of the movie's run ``ds`` (module docstring) at the
    stored times ``indices`` (all by default), and as the generator's first item a dict describing them
    (``times`` in s, ``speed``, ``force_max`` in N, ``size``, the drawing's ``axes``)."""
    mf = MovieFigure(ds, width, height)
    idx = np.arange(mf.t.size) if indices is None else np.asarray(indices, dtype=np.int64)
    yield {"times": mf.t[idx], "indices": idx, "speed": mf.speed[idx], "force_max": mf.force_max,
           "size": (width, height), "axes": mf.fig.axes}

    from cradle.figures.movie import blitted

    yield from blitted(mf, idx)


def write_stills(ds: xr.Dataset, paths: Mapping[int, str | os.PathLike], width: int = 1280,
                 height: int = 720) -> list[Path]:
    """Write the frames ``paths`` names (stored-time index -> PNG path) of the movie's run ``ds``."""
    from cradle.figures.movie import write_stills_with

    return write_stills_with(render, ds, paths, width, height)


def animate(ds: xr.Dataset, out: str | os.PathLike, width: int = 1280, height: int = 720,
            gif: str | os.PathLike | None = None, gif_fps: int = 10, gif_duration: float = 8.0,
            gif_width: int = 480) -> dict:
    """Write the movie of the run ``ds`` to ``out`` (.mp4, every stored time, at the frame rate the run was made
    for) and, if ``gif`` is a path, a GIF of ``gif_duration`` s at ``gif_fps``, its frames evenly spaced in frame
    index (the slow motion kept, the whole faster); returns what :func:`render` describes."""
    from cradle.figures.movie import animate_with

    return animate_with(render, ds, out, width, height, gif, gif_fps, gif_duration, gif_width)
