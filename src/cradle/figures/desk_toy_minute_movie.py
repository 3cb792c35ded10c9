"""The minute as a movie: a desk toy drawn to scale, a minute of real time, chosen impacts in slow motion.

Drawn from a run of :func:`cradle.analyses.desk_toy_minute_movie.movie_run` only. Each frame shows:

* the desk toy: the balls as discs of the cradle's radius R hanging on strings of its length L from a frame (a top
  bar with a post at each end), touching at rest (pivots 2R apart), ball n's centre at (2 R n + x_n,
  -sqrt(L^2 - x_n^2)) (:func:`cradle.figures.desk_toy_movie.ball_centres`): one scale for both axes, nothing
  magnified; a scale bar of 1 cm;
* beside it, the contact force of each bond in N (Hertz with Kuwabara-Kono damping, as integrated);
* under both, the minute's timeline: the centre-of-mass share S(t), the phase coherence R(t) and the energy
  H(t)/H(0) of the analysis's run, the slow-motion impacts shaded, the time S settles above its first threshold
  marked, and a cursor at the frame's time;
* the clock in seconds and the playback speed (:func:`cradle.figures.desk_toy_movie.playback_speed`): real time
  between impacts; during a slow-motion impact a red label says so, why the impact was chosen, and how slow.

:func:`render` yields the frames, :func:`still_frames` picks three (the first impact at its largest force, the
break-up at its largest force, late in-phase swinging), :func:`write_stills` writes frames as PNG files and
:func:`animate` writes the MP4 and GIF.
"""
from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from cradle.figures.desk_toy_movie import BALL, EDGE, FORCE, MM, CradleFrames, ball_centres

if TYPE_CHECKING:
    from collections.abc import Iterator, Mapping, Sequence

    import xarray as xr
    from numpy.typing import NDArray

SLOW = "#c0392b"
#: the names of the three stills (:func:`still_frames`), in the order the movie rule lists their files
STILLS = ("impact", "breakup", "late")
#: the late still: this long before the end of the run (s)
LATE_LEAD = 2.0


def _speed_text(speed: float) -> str:
    """The playback speed in words."""
    if speed < 0.95:
        return f"slow motion: 1 s of movie = {speed * 1e3:.3g} ms of the cradle (1/{1.0 / speed:.0f} of real time)"
    return "real time"


class MinuteFigure(CradleFrames):
    """The figure of the movie's run ``ds`` (module docstring) and its moving artists: :meth:`show` puts them at a
    frame. ``fig`` (:class:`~cradle.figures.desk_toy_movie.CradleFrames`), ``moving`` (the artists :meth:`show`
    changes)."""

    def __init__(self, ds: xr.Dataset, width: int = 1280, height: int = 720) -> None:
        from matplotlib.collections import LineCollection
        from matplotlib.patches import Circle

        super().__init__(ds, width, height)
        a = ds.attrs
        R, L = self.R, self.L
        self.slow = np.asarray(ds["slow"].values, dtype=np.int64)
        self.labels = [str(s) for s in ds["impact_label"].values]
        n_beads = self.x.shape[-1]
        force_max = float(self.force.max()) if self.force.max() > 0 else 1.0

        fig = self.fig
        fig.text(0.5, 0.972, f"A desk toy watched for a minute: {n_beads} {a['material']} balls of radius "
                 f"{R * MM:g} mm on strings of {L * MM:g} mm, {int(a['lifted'])} lifted to "
                 f"{float(a['angle_deg']):g}° and released", ha="center", va="center", fontsize=12)
        fig.text(0.5, 0.937, f"lattice (ncdamped): Hertz contacts with Kuwabara-Kono damping (e = "
                 f"{float(a['restitution']):g} at {float(a['restitution_speed']):g} m/s, assumed), linear air drag "
                 f"{float(a['drag_rate_per_s']):.3g} /s ({a['drag_source']})", ha="center", va="center", fontsize=10,
                 color="0.3")

        # the desk toy
        ax = fig.add_axes((0.03, 0.34, 0.56, 0.48))
        reach = float(np.max(np.abs(self.x))) + R
        left, right = -reach - 0.3 * R, 2.0 * R * (n_beads - 1) + reach + 0.3 * R
        ax.set_xlim(left * MM, right * MM)
        ax.set_ylim(-(L + 2.2 * R) * MM, 0.6 * R * MM)
        ax.set_aspect("equal", adjustable="box")
        ax.axis("off")
        post: dict[str, Any] = {"color": "0.25", "lw": 4, "solid_capstyle": "butt"}
        ax.plot([left * MM, right * MM], [0.0, 0.0], **post)
        for xp in (left, right):
            ax.plot([xp * MM, xp * MM], [0.0, -(L + 2.0 * R) * MM], **post)
        ax.plot([(left - 0.2 * R) * MM, (right + 0.2 * R) * MM], [-(L + 2.0 * R) * MM] * 2, color="0.25", lw=6,
                solid_capstyle="butt")
        bar_x0 = (right - 1.0 * R) * MM - 10.0
        ax.plot([bar_x0, bar_x0 + 10.0], [-(L + 1.5 * R) * MM] * 2, color="k", lw=2.5, solid_capstyle="butt")
        ax.text(bar_x0 + 5.0, -(L + 1.35 * R) * MM, "1 cm", ha="center", va="bottom", fontsize=9)
        rest_x, rest_y = ball_centres(np.zeros(n_beads), R, L)
        self.pivots = np.column_stack([rest_x, np.zeros(n_beads)])
        self.strings = LineCollection([], colors="0.45", linewidths=0.8)
        ax.add_collection(self.strings)
        self.balls: list[Any] = [
            ax.add_patch(Circle((float(cx), float(cy)), R * MM, facecolor=BALL, edgecolor=EDGE, lw=0.8))
            for cx, cy in zip(rest_x, rest_y, strict=True)]
        self.clock = fig.text(0.03, 0.895, "", ha="left", va="center", fontsize=12, family="monospace")
        self.badge = fig.text(0.03, 0.855, "", ha="left", va="center", fontsize=10, color=SLOW, fontweight="bold")

        # the contact forces
        fa = fig.add_axes((0.68, 0.42, 0.29, 0.36))
        bonds = np.arange(n_beads - 1)
        self.bars = fa.bar(bonds, np.zeros(n_beads - 1), width=0.6, color=FORCE)
        fa.set_xticks(bonds, [f"{b + 1}|{b + 2}" for b in bonds], fontsize=9)
        fa.set_xlabel("contact between balls (numbered from the lifted end)", fontsize=9)
        fa.set_ylabel("contact force (N)", fontsize=9)
        fa.set_ylim(0.0, 1.1 * force_max)
        fa.tick_params(labelsize=8)
        fa.set_title("force of each contact\n(its compression, micrometres, is not visible to scale)", fontsize=9)
        self.note = fa.text(0.02, 0.97, "", transform=fa.transAxes, ha="left", va="top", fontsize=9)

        # the timeline
        ta = fig.add_axes((0.06, 0.08, 0.91, 0.2))
        tl = np.asarray(ds["t_line"].values, dtype=float)
        ta.plot(tl, ds["com_share"].values, color="C0", lw=1.2, label="centre-of-mass share S")
        ta.plot(tl, ds["phase_coherence"].values, color="C2", lw=0.8, label="phase coherence R")
        ta.plot(tl, ds["energy_share"].values, color="0.2", lw=1.2, ls="--", label="energy H(t) / H(0)")
        for k, (a0, b0) in enumerate(zip(ds["impact_start"].values, ds["impact_end"].values, strict=True)):
            ta.axvspan(float(a0), float(b0) + 0.002 * tl[-1], color=SLOW, alpha=0.35, lw=0,
                       label="impacts in slow motion" if k == 0 else None)
        settle = [float(v) for v in np.atleast_1d(a["inphase_time_share_s"])]
        thresholds = [float(v) for v in np.atleast_1d(a["share_thresholds"])]
        if settle and np.isfinite(settle[0]):
            ta.axvline(settle[0], color="C0", lw=0.8, ls=":",
                       label=f"S stays >= {thresholds[0]:g} from {settle[0]:.1f} s")
        ta.set_xlim(0.0, tl[-1])
        ta.set_ylim(0.0, 1.05)
        ta.set_xlabel("time since the release (s)", fontsize=9)
        ta.tick_params(labelsize=8)
        ta.legend(fontsize=8, loc="lower left", bbox_to_anchor=(0.0, 1.01), ncol=5, frameon=False,
                  borderaxespad=0.0, handlelength=1.6, columnspacing=1.2)
        self.cursor = ta.axvline(0.0, color="k", lw=1.2)
        self.moving: list[Any] = [self.strings, *self.balls, self.clock, self.badge, *self.bars, self.note,
                                  self.cursor]

    def show(self, k: int) -> None:
        """Put the moving artists at frame ``k``."""
        cx, cy = ball_centres(self.x[k], self.R, self.L)
        for ball, px, py in zip(self.balls, cx, cy, strict=True):
            ball.set_center((float(px), float(py)))
        self.strings.set_segments(list(np.stack([self.pivots, np.column_stack([cx, cy])], axis=1)))
        for bar, value in zip(self.bars, self.force[k], strict=True):
            bar.set_height(float(value))
        peak = float(self.force[k].max())
        self.note.set_text(f"largest: {peak:.3g} N" if peak > 0 else "no ball compressed")
        self.cursor.set_xdata([self.t[k], self.t[k]])
        speed = float(self.speed[k])
        self.clock.set_text(f"t = {self.t[k]:10.6f} s   {_speed_text(speed)}")
        slow = int(self.slow[k])
        self.badge.set_text(f"SLOW MOTION: {self.labels[slow]}" if slow >= 0 else "")


def render(ds: xr.Dataset, width: int = 1280, height: int = 720,
           indices: Sequence[int] | NDArray[np.int64] | None = None) -> Iterator[Any]:
    """Yield the frames (height x width x 3 uint8 arrays) of the movie's run ``ds`` at the frames ``indices`` (all
    by default), and as the generator's first item a dict describing them (``times`` in s, ``size``)."""
    mf = MinuteFigure(ds, width, height)
    idx = np.arange(mf.t.size) if indices is None else np.asarray(indices, dtype=np.int64)
    yield {"times": mf.t[idx], "indices": idx, "size": (width, height), "axes": mf.fig.axes}
    from cradle.figures.movie import blitted

    yield from blitted(mf, idx)


def still_frames(ds: xr.Dataset) -> dict[str, int]:
    """Three frames: ``impact`` (the first slow-motion impact at its largest force), ``breakup`` (the slow-motion
    impact chosen for the break-up, else the last one, at its largest force) and ``late`` (the real-time frame
    :data:`LATE_LEAD` s before the end)."""
    t = np.asarray(ds["t"].values, dtype=float)
    slow = np.asarray(ds["slow"].values, dtype=np.int64)
    force = np.asarray(ds["force"].values, dtype=float).max(axis=1)
    labels = [str(s) for s in ds["impact_label"].values]
    if not labels:
        raise ValueError("the run has no slow-motion impact")

    def peak(j: int) -> int:
        inside = np.flatnonzero(slow == j)
        return int(inside[np.argmax(force[inside])])

    brk = next((j for j, s in enumerate(labels) if s.startswith("the break-up")), len(labels) - 1)
    late = int(np.searchsorted(t, t[-1] - LATE_LEAD))
    return {"impact": peak(0), "breakup": peak(brk), "late": min(late, t.size - 1)}


def write_stills(ds: xr.Dataset, paths: Mapping[int, str | os.PathLike], width: int = 1280,
                 height: int = 720) -> list[Path]:
    """Write the frames ``paths`` names (frame index -> PNG path) of the movie's run ``ds``."""
    from cradle.figures.movie import write_stills_with

    return write_stills_with(render, ds, paths, width, height)


def animate(ds: xr.Dataset, out: str | os.PathLike, width: int = 1280, height: int = 720,
            gif: str | os.PathLike | None = None, gif_fps: int = 10, gif_duration: float = 8.0,
            gif_width: int = 480) -> dict:
    """Write the movie of the run ``ds`` to ``out`` (.mp4, every frame, at the frame rate the run was made for)
    and, if ``gif`` is a path, a GIF of ``gif_duration`` s at ``gif_fps``, its frames evenly spaced in frame index;
    returns what :func:`render` describes."""
    from cradle.figures.movie import animate_with

    return animate_with(render, ds, out, width, height, gif, gif_fps, gif_duration, gif_width)
