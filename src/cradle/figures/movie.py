"""Movies of the cradle: the beads of a scene's exact (nc) and DpS (dfnls)/(ansatz) runs in motion.

Drawn from the stored runs only (:func:`cradle.open_scene`: ``x`` and
``force`` along ``model`` = exact, dps), nothing is integrated here. Each
frame shows both models one above the other, the chain as a row of
pendulums hung from a bar:

* bead n is a disc at n + s x_n(t), where x_n is the displacement of (nc)
  and s a magnification (printed on screen) that makes the largest
  displacement of the movie 0.4 of the bead spacing; at rest the discs
  touch, so an overlap is a compression, a gap a separation;
* under the beads, the bond forces f_n = V0'(x_{n+1} - x_n) <= 0 in colour
  (one colour scale for both models and the whole movie; bond n joins beads
  n and n+1, the periodic ring's bond N-1 is drawn at the right end);
* a grey bar under each bead: the range x_n swept since the previous frame.
  A long run is subsampled (a frame every dt_frame time units, on screen,
  also in periods 2 pi / omega of the scene when it has one): when dt_frame
  exceeds the period the discs are a stroboscope of the fast oscillation,
  the bars show its true amplitude (the envelope |A_n| of (ansatz)).

:func:`frame_indices` picks the stored times, :func:`render` yields RGB
frames, :func:`write_mp4` (H.264 through the ffmpeg binary of
imageio-ffmpeg, or the one ``IMAGEIO_FFMPEG_EXE`` names) and
:func:`write_gif` (Pillow) write them. ``cradle animate SCENE`` and the
workflow's ``movie`` rule (workflow/rules/movies.smk) call :func:`animate`.
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

if TYPE_CHECKING:
    from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence

    import xarray as xr

MAX_SHIFT = 0.4      # largest drawn displacement, in bead spacings: discs of neighbours never pass each other
DPI = 100
GIF_COLOURS = 32   # the GIF is a preview (README, report): 32 colours keep loc1-pair at ~0.7 MB
PANELS = (("exact", "exact lattice (nc)"), ("dps", "DpS approximation (dfnls) through (ansatz)"))
# attributes of a scene shown on screen, in this order, when the run has them
SHOWN = (("alpha", "α"), ("N", "N"), ("bc", "bc"), ("initial_kind", "initial"), ("q", "q"), ("amplitude", "amplitude"),
         ("omega_tw", "ω_tw"), ("omega_sw", "ω_sw"), ("separation", "separation"))


@dataclass(frozen=True)
class MovieSpec:
    """How a movie is drawn: frame rate (1/s), duration (s), frame size (pixels, even), time window."""

    fps: int = 25
    duration: float = 20.0
    width: int = 1280
    height: int = 720
    t_start: float | None = None
    t_end: float | None = None

    def __post_init__(self) -> None:
        for name in ("width", "height"):
            value = getattr(self, name)
            if value < 64 or value % 2:
                raise ValueError(f"movie {name} = {value}: must be an even number of pixels >= 64 (H.264 needs even)")
        if self.fps < 1 or not self.duration > 0:
            raise ValueError(f"movie fps = {self.fps}, duration = {self.duration}: need fps >= 1 and duration > 0")


class EmptyWindow(ValueError):
    """The window [t_start, t_end] of a :class:`MovieSpec` holds no stored time of the run."""


def frame_indices(t: ArrayLike, spec: MovieSpec) -> np.ndarray:
    """Indices into the stored times ``t`` of the frames: fps * duration of them, evenly spaced in index
    over the window [t_start, t_end] (the stored times are evenly spaced), every stored time if there
    are fewer. A run is subsampled, never interpolated: each frame is a stored state."""
    t = np.asarray(t, dtype=float)
    lo = 0 if spec.t_start is None else int(np.searchsorted(t, spec.t_start - 1e-9))
    hi = len(t) - 1 if spec.t_end is None else int(np.searchsorted(t, spec.t_end + 1e-9)) - 1
    if hi < lo:
        raise EmptyWindow(f"no stored time in the window [{spec.t_start}, {spec.t_end}] (run covers "
                         f"[{t[0]:g}, {t[-1]:g}])")
    wanted = max(1, round(spec.fps * spec.duration))
    if hi - lo + 1 <= wanted:
        return np.arange(lo, hi + 1)
    return np.unique(np.rint(np.linspace(lo, hi, wanted)).astype(np.int64))


def _period(attrs: Mapping[Any, Any]) -> float | None:
    for key in ("omega_sw", "omega_tw"):
        if key in attrs and np.isfinite(float(attrs[key])) and float(attrs[key]) > 0:
            return 2 * np.pi / float(attrs[key])
    return None


def _fmt(value: object) -> str:
    if isinstance(value, (float, np.floating)):
        return f"{float(value):.4g}"
    return str(value)


def scene_line(attrs: Mapping[Any, Any]) -> str:
    """The scene's name and parameters, as shown on screen."""
    parts = [f"{label} = {_fmt(attrs[key])}" for key, label in SHOWN if key in attrs]
    return f"scene '{attrs.get('scene', '?')}':  " + ",  ".join(parts)


def render(ds: xr.Dataset, spec: MovieSpec,
           panels: Sequence[tuple[str, str]] = PANELS) -> Iterator[Any]:
    """Yield the frames (height x width x 3 uint8 arrays) of the scene ``ds`` (from :func:`cradle.open_scene`),
    and as the generator's first item a dict describing the movie (frame times, magnification, ...).
    ``panels``: (value of ``model``, title) of the two runs drawn, top and bottom."""
    import matplotlib
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.collections import LineCollection
    from matplotlib.figure import Figure

    t = np.asarray(ds["t"].values, dtype=float)
    idx = frame_indices(t, spec)
    lo, hi = int(idx[0]), int(idx[-1])
    x = {m: np.asarray(ds["x"].sel(model=m).values[lo:hi + 1], dtype=float) for m, _ in panels}
    f = {m: np.asarray(ds["force"].sel(model=m).values[idx], dtype=float) for m, _ in panels}
    n_beads = x[panels[0][0]].shape[1]
    periodic = str(ds.attrs.get("bc", "periodic")) == "periodic"
    n_bonds = n_beads if periodic else n_beads - 1
    xmax = max(float(np.max(np.abs(v))) for v in x.values())
    scale = MAX_SHIFT / xmax if xmax > 0 else 1.0
    fmin = min(float(np.min(v[:, :n_bonds])) for v in f.values())
    fmin = fmin if fmin < 0 else -1.0
    dt_frame = float(np.median(np.diff(t[idx]))) if len(idx) > 1 else 0.0
    period = _period(ds.attrs)
    info = {"times": t[idx], "indices": idx, "magnification": scale, "dt_frame": dt_frame, "period": period,
            "force_min": fmin, "size": (spec.width, spec.height)}
    yield info

    # an Agg canvas of its own, outside pyplot: the session's backend is left alone
    fig = Figure(figsize=(spec.width / DPI, spec.height / DPI), dpi=DPI)
    canvas = FigureCanvasAgg(fig)
    fig.text(0.5, 0.965, scene_line(ds.attrs), ha="center", va="center", fontsize=11)
    # a scene of a real cradle (`cradle:`): its clock in seconds as well (cradle.data.si)
    t_si = float(ds.attrs["scale_time_s"]) if "scale_time_s" in ds.attrs else None
    strobe = f"  ({dt_frame / period:.2g} periods 2π/ω)" if period and dt_frame else ""
    fig.text(0.5, 0.925, f"displacements × {scale:.3g};  one frame = Δt {dt_frame:.3g}{strobe};  grey bars: "
             f"range swept since the previous frame", ha="center", va="center", fontsize=9, color="0.3")
    clock = fig.text(0.02, 0.025, "", ha="left", va="bottom", fontsize=12, family="monospace")
    cmap = matplotlib.colormaps["magma"]
    norm = matplotlib.colors.Normalize(vmin=fmin, vmax=0.0)
    n = np.arange(n_beads, dtype=float)
    artists = {}
    for row, (model, title) in enumerate(panels):
        ax = fig.add_axes((0.03, 0.52 - 0.44 * row, 0.86, 0.36))
        ax.set_xlim(-0.8, n_beads - 0.2)
        ax.set_ylim(-0.55, 1.08)
        ax.set_axis_off()
        ax.set_title(title, fontsize=10, loc="left")
        ax.plot([-0.6, n_beads - 0.4], [1.0, 1.0], color="0.25", lw=3, solid_capstyle="butt")
        px_per_unit = spec.width * 0.86 / (n_beads + 0.6)
        diameter_pt = min(px_per_unit * 0.97, spec.height * 0.36 * 0.32) * 72.0 / DPI
        strings = LineCollection([], colors="0.55", linewidths=0.6)
        ax.add_collection(strings)
        swept = LineCollection([], colors="0.35", linewidths=2.5)
        ax.add_collection(swept)
        discs = ax.scatter(n, np.full(n_beads, 0.25), s=diameter_pt ** 2, c="#9fb3c8", edgecolors="#2b3a4a",
                           linewidths=0.6, zorder=3)
        bonds = ax.imshow(f[model][:1, :n_bonds], cmap=cmap, norm=norm, aspect="auto", interpolation="nearest",
                          extent=(0.0, float(n_bonds), -0.5, -0.3), zorder=2)
        artists[model] = (strings, swept, discs, bonds)
    cax = fig.add_axes((0.91, 0.08, 0.015, 0.8))
    bar = fig.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap), cax=cax)
    bar.set_label("bond force $f_n = V_0'(x_{n+1}-x_n)$", fontsize=9)
    bar.ax.tick_params(labelsize=8)

    # the static parts (titles, bar, colour bar) are drawn once; each frame restores them and draws only
    # the moving artists over them (Agg blitting: ~4x faster than redrawing the figure)
    moving = [a for group in artists.values() for a in group] + [clock]
    for a in moving:
        a.set_animated(True)
    canvas.draw()
    background = canvas.copy_from_bbox(fig.bbox)
    top, rest, low = np.full(n_beads, 1.0), np.full(n_beads, 0.25), np.full(n_beads, -0.12)
    prev = 0
    for k, i in enumerate(idx):
        j = int(i) - lo
        for model, (strings, swept, discs, bonds) in artists.items():
            pos = n + scale * x[model][j]
            seg = x[model][prev:j + 1]
            left, right = n + scale * seg.min(axis=0), n + scale * seg.max(axis=0)
            discs.set_offsets(np.column_stack([pos, rest]))
            strings.set_segments(list(np.stack([np.column_stack([n, top]), np.column_stack([pos, rest])], axis=1)))
            swept.set_segments(list(np.stack([np.column_stack([left, low]), np.column_stack([right, low])],
                                             axis=1)))
            bonds.set_data(f[model][k:k + 1, :n_bonds])
        seconds = f" ({t[i] * t_si:.4g} s)" if t_si else ""
        clock.set_text(f"t = {t[i]:10.2f}{seconds}   frame {k + 1:4d}/{len(idx)}")
        prev = j
        canvas.restore_region(background)
        for a in moving:
            a.axes.draw_artist(a) if a.axes is not None else fig.draw_artist(a)
        yield np.asarray(canvas.buffer_rgba())[..., :3].copy()


def _atomic(path: str | os.PathLike, write: Callable[[Path], object]) -> Path:
    """Write through ``write(tmp)`` to a temporary file beside ``path``, then rename: no half movie."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.tmp{path.suffix}")
    try:
        write(tmp)
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
    return path


def ffmpeg_exe() -> str:
    """The ffmpeg binary: ``IMAGEIO_FFMPEG_EXE``, else the one imageio-ffmpeg ships, else ffmpeg on PATH."""
    try:
        import imageio_ffmpeg
    except ImportError:
        import shutil

        exe = os.environ.get("IMAGEIO_FFMPEG_EXE") or shutil.which("ffmpeg")
        if not exe:
            raise RuntimeError("no ffmpeg: pip install imageio-ffmpeg (the extra `movies`) or install ffmpeg") from None
        return exe
    return imageio_ffmpeg.get_ffmpeg_exe()


def write_mp4(path: str | os.PathLike, frames: Iterable[NDArray[np.uint8]], size: tuple[int, int], fps: int) -> Path:
    """H.264 (yuv420p, one encoder thread, bit-exact flags: the same frames give the same file) to ``path``."""
    import subprocess

    width, height = size

    def write(tmp: Path) -> None:
        cmd = [ffmpeg_exe(), "-y", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgb24",
               "-s", f"{width}x{height}", "-r", str(fps), "-i", "-", "-an", "-c:v", "libx264", "-preset", "medium",
               "-crf", "23", "-pix_fmt", "yuv420p", "-threads", "1", "-fflags", "+bitexact", "-flags", "+bitexact",
               "-map_metadata", "-1", "-movflags", "+faststart", "-f", "mp4", str(tmp)]
        proc = subprocess.Popen(cmd, stdin=subprocess.PIPE, stderr=subprocess.PIPE)
        assert proc.stdin is not None and proc.stderr is not None  # both are pipes
        try:
            for frame in frames:
                proc.stdin.write(np.ascontiguousarray(frame, dtype=np.uint8).tobytes())
        finally:
            proc.stdin.close()
            err = proc.stderr.read().decode(errors="replace")
            if proc.wait() != 0:
                raise RuntimeError(f"ffmpeg failed writing {path}: {' '.join(err.split())[:400]}")

    return _atomic(path, write)


def write_gif(path: str | os.PathLike, frames: Iterable[NDArray[np.uint8]], fps: int, width: int) -> Path:
    """An animated GIF (Pillow), each frame resized to ``width`` pixels, looping."""
    from PIL import Image

    rgb = []
    for frame in frames:
        img = Image.fromarray(frame)
        rgb.append(img.resize((width, max(2, round(img.height * width / img.width))), Image.Resampling.LANCZOS))
    if not rgb:
        raise ValueError("no frames")
    # one palette for every frame (from four of them), no dithering: what does not move keeps its pixels
    # from frame to frame, and the GIF is ~30% smaller than with a palette per frame
    picks = [rgb[i] for i in sorted({0, len(rgb) // 3, 2 * len(rgb) // 3, len(rgb) - 1})]
    sample = Image.new("RGB", (width, sum(im.height for im in picks)))
    for k, im in enumerate(picks):
        sample.paste(im, (0, k * im.height))
    palette = sample.quantize(colors=GIF_COLOURS, method=Image.Quantize.MEDIANCUT)
    images = [img.quantize(palette=palette, dither=Image.Dither.NONE) for img in rgb]
    return _atomic(path, lambda tmp: images[0].save(tmp, format="GIF", save_all=True, append_images=images[1:],
                                                     duration=round(1000 / fps), loop=0))


def animate(ds: xr.Dataset, out: str | os.PathLike, spec: MovieSpec = MovieSpec(),
            gif: str | os.PathLike | None = None, gif_spec: MovieSpec | None = None, gif_width: int = 480,
            panels: Sequence[tuple[str, str]] = PANELS) -> dict:
    """Write the movie of scene ``ds`` to ``out`` (.mp4) and, if ``gif`` is a path, a small GIF drawn with
    ``gif_spec`` (default: ``spec`` at 10 frames per second for 8 s); returns what :func:`render` describes.
    ``panels``: the two runs drawn (:func:`render`)."""
    frames = render(ds, spec, panels)
    info = next(frames)
    write_mp4(out, frames, info["size"], spec.fps)
    info["path"] = Path(out)
    if gif is not None:
        gspec = gif_spec or MovieSpec(fps=10, duration=8.0, width=spec.width, height=spec.height,
                                      t_start=spec.t_start, t_end=spec.t_end)
        gframes = render(ds, gspec, panels)
        ginfo = next(gframes)
        write_gif(gif, gframes, gspec.fps, gif_width)
        info["gif"] = {"path": Path(gif), "frames": len(ginfo["indices"])}
    return info


def write_stills_with(render_frames: Callable[..., Iterator[Any]], ds: xr.Dataset,
                      paths: Mapping[int, str | os.PathLike], width: int, height: int) -> list[Path]:
    """Write the frames ``paths`` names (frame index -> PNG path) of ``ds`` drawn by ``render_frames`` (the desk
    toys' movies: :mod:`cradle.figures.desk_toy_movie`, :mod:`cradle.figures.desk_toy_minute_movie`)."""
    from PIL import Image

    order = sorted(paths)
    frames = render_frames(ds, width, height, order)
    next(frames)
    written = []
    for k, frame in zip(order, frames, strict=True):
        img = Image.fromarray(frame)

        def save(tmp: Path, img: Image.Image = img) -> None:
            img.save(tmp, format="PNG")

        written.append(_atomic(paths[k], save))
    return written


def animate_with(render_frames: Callable[..., Iterator[Any]], ds: xr.Dataset, out: str | os.PathLike, width: int,
                 height: int, gif: str | os.PathLike | None, gif_fps: int, gif_duration: float,
                 gif_width: int) -> dict:
    """Write the movie of ``ds`` drawn by ``render_frames`` to ``out`` (.mp4, every frame, at the run's ``fps``
    attribute) and, if ``gif`` is a path, a GIF of ``gif_duration`` s at ``gif_fps``, its frames evenly spaced in
    frame index; returns what ``render_frames`` describes."""
    frames = render_frames(ds, width, height)
    info = next(frames)
    write_mp4(out, frames, info["size"], int(ds.attrs["fps"]))
    info["path"] = Path(out)
    if gif is not None:
        n = len(info["times"])
        pick = np.unique(np.rint(np.linspace(0, n - 1, min(max(1, round(gif_fps * gif_duration)), n))))
        gframes = render_frames(ds, width, height, pick.astype(np.int64))
        next(gframes)
        write_gif(gif, gframes, gif_fps, gif_width)
        info["gif"] = {"path": Path(gif), "frames": len(pick)}
    return info


def blitted(mf: Any, idx: NDArray[np.int64]) -> Iterator[NDArray[np.uint8]]:
    """The frames of a desk toy's movie figure ``mf`` (``fig``, ``canvas``, ``moving`` artists, ``show(k)``) at
    ``idx``: the static parts drawn once, each frame restoring them and drawing the moving artists (Agg blitting)."""
    for artist in mf.moving:
        artist.set_animated(True)
    mf.canvas.draw()
    background = mf.canvas.copy_from_bbox(mf.fig.bbox)
    for k in idx:
        mf.show(int(k))
        mf.canvas.restore_region(background)
        for artist in mf.moving:
            if artist.axes is not None:
                artist.axes.draw_artist(artist)
            else:
                mf.fig.draw_artist(artist)
        yield np.asarray(mf.canvas.buffer_rgba())[..., :3].copy()
