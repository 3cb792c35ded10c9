"""Space-time diagrams of the contact forces and bead profiles (section 4.1-4.2).

Figures plot6-7, plot2-3 (q = pi/5, omega_tw = 1.1), plot1v5st, plot1v5
(omega_tw = 1.5), plot8-11, plot9-10 (q = 4 pi/5, modulational instability),
plot29-30, plot26-27, plot28 (q = pi, static breathers).

Every space-time diagram goes through :func:`spacetime`: the forces
f_n = V0'(x_{n+1} - x_n) <= 0 drawn as a raster image (``imshow``, never a
vector mesh) in grey levels as the paper draws them, white = beads apart
(f = 0), black = the most negative force; bead index n horizontal, time t
upwards. The exact and approximate panels of a figure share one colour scale,
vmin = the most negative force of both, vmax = 0 (:func:`common_vmin`).
"""
from __future__ import annotations

from typing import TYPE_CHECKING, TypeVar

import numpy as np
from matplotlib.ticker import MaxNLocator
from numpy.typing import ArrayLike, NDArray

from cradle.figures import figure, legend_outside, scene_caption

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.image import AxesImage

CMAP = "gray"                     # vmin -> black, vmax = 0 -> white
FORCE_LABEL = "$V_0'(x_{n+1}-x_n)$"

# plot1v5 (left): the zoom on the exact diagram of plot1v5st. The internal
# breathing of the wave starts at t ~ 1 (section 4.1); the first 30 time units
# hold the spots and the first slow waves they release, on every bead.
ZOOM_PLOT1V5 = (0.0, 30.0)

# plot28: a detail of the exact binary-pi diagram. Its bead window is the
# PLOT28_BEADS consecutive bonds (periodically) of largest summed force
# variance over the last PLOT28_SPAN time units stored; its time window is the
# PLOT28_SPAN-long interval ending at the last stored time.
PLOT28_BEADS = 20
PLOT28_SPAN = 100.0

#: finite points each data panel holds at least (tests/figures/test_figures_render.py): a profile of N beads,
#: a space-time image of N beads times its stored times
MIN_POINTS = {"plot6-7": 1000, "plot2-3": 20, "plot1v5st": 1000, "plot1v5": 20, "plot8-11": 20, "plot9-10": 1000,
              "plot29-30": 20, "plot26-27": 1000, "plot28": 500}


# --------------------------------------------------------------------------- helpers
#: a stored run or one of its variables (dims t, ...)
_Stored = TypeVar("_Stored", "xr.Dataset", "xr.DataArray")


def _at(ds: _Stored, t: float) -> _Stored:
    """The stored state nearest to time t (stored times are exact to 1e-9)."""
    return ds.sel(t=t, method="nearest")


def common_vmin(*datasets: xr.Dataset, t_range: tuple[float, float] | None = None) -> float:
    """The most negative force over all datasets (on t_range if given); < 0."""
    lows = []
    for ds in datasets:
        f = ds["force"]
        if t_range is not None:
            f = f.sel(t=slice(*t_range))
        lows.append(float(f.min()))
    low = min(lows)
    return low if low < 0 else -1e-300     # all beads apart: any negative value draws white


def _edges(values: ArrayLike) -> tuple[float, float]:
    """Cell edges of uniformly spaced centres (extent of an imshow)."""
    values = np.asarray(values, dtype=float)
    step = (values[-1] - values[0]) / (len(values) - 1) if len(values) > 1 else 1.0
    return values[0] - step / 2, values[-1] + step / 2


def _columns(size: int, n_range: tuple[int, int] | None = None) -> NDArray[np.int_]:
    """Bond indices of n_range = (n0, n1), inclusive, wrapping around if n0 > n1."""
    if n_range is None:
        return np.arange(size)
    n0, n1 = n_range
    return np.arange(n0, n1 + 1) if n0 <= n1 else np.r_[np.arange(n0, size), np.arange(0, n1 + 1)]


def period_minimum(metrics: xr.Dataset, model: str) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(bin centres, most negative force of every bond in each breather period) of ``model`` ('exact'
    or 'dps'), from the peak compression stored in the scene's metrics file (``t_window``,
    ``breather_omega``, ``peak_compression_<model>``): one row per breather period, so that a long
    run drawn on a few hundred pixels keeps the depth of its black spots instead of averaging them
    with the white half-periods."""
    if f"peak_compression_{model}" not in metrics:
        raise ValueError(f"scene '{metrics.attrs.get('scene', '?')}': no peak_compression_{model} in its "
                         "metrics file (only localised scenes store it): rebuild the metrics")
    period = 2.0 * np.pi / float(metrics["breather_omega"])
    return metrics["t_window"].values + 0.5 * period, -metrics[f"peak_compression_{model}"].values


def spacetime(ax: Axes, ds: xr.Dataset, vmin: float, t_range: tuple[float, float] | None = None,
              n_range: tuple[int, int] | None = None, title: str = "",
              binned: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None,
              interpolation: str = "antialiased") -> AxesImage:
    """Draw the forces of ``ds`` (dims t, n) in grey levels on ``ax``; return the AxesImage.

    ``t_range`` = (t0, t1) and ``n_range`` = (n0, n1) (inclusive) restrict the
    picture; n_range may wrap around a periodic chain (n0 > n1): the bonds are
    then drawn in the order n0..N-1, 0..n1 and labelled by their index. With
    ``binned`` = (bin centres, rows) of :func:`period_minimum`, each image row is
    the most negative force over one breather period (all stored times, no
    ``t_range``); otherwise every stored time is a row.
    ``interpolation`` "antialiased" averages rows when many stored times share a
    pixel (long runs); "nearest" keeps every bond a sharp column (zooms).
    """
    f = ds["force"]
    if t_range is not None:
        if binned is not None:
            raise ValueError("spacetime: binned rows cover every stored time; t_range is not supported with them")
        f = f.sel(t=slice(*t_range))
    t = f["t"].values
    size = f.sizes["n"]
    cols = _columns(size, n_range)
    positions = cols[0] + np.arange(len(cols))              # unwrapped: n0, n0+1, ... (mod N)
    if binned is not None:
        t, rows = binned
        values = rows[:, cols]
    else:
        values = f.values[:, cols]
    img = ax.imshow(values, cmap=CMAP, vmin=vmin, vmax=0.0, origin="lower", aspect="auto",
                    extent=(*_edges(positions), *_edges(t)), interpolation=interpolation,
                    rasterized=True)
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))      # bond indices are integers
    if positions[-1] >= size:                                 # wrapped window: label the true indices
        ax.xaxis.set_major_formatter(lambda value, _pos: f"{int(round(value)) % size}")
    ax.set_xlabel("$n$")
    ax.set_ylabel("$t$")
    if title:
        ax.set_title(title, fontsize=9)
    return img


def spacetime_pair(sim: dict[str, xr.Dataset], width: float = 8.0, height: float = 5.2, suptitle: str = "") -> Figure:
    """Exact (left) and approximate (right) force diagrams on one colour scale, one colourbar."""
    ex, ap = sim["exact"], sim["dps"]
    vmin = common_vmin(ex, ap)
    fig, (left, right) = figure(1, 2, width=width, height=height, sharey=True)
    spacetime(left, ex, vmin, title=f"exact, min force {float(ex['force'].min()):.3g}")
    img = spacetime(right, ap, vmin, title=f"approximate (DpS), min force {float(ap['force'].min()):.3g}")
    right.set_ylabel("")
    fig.colorbar(img, ax=[left, right], label=FORCE_LABEL, shrink=0.9)
    if suptitle:
        fig.suptitle(suptitle, fontsize=10)
    return fig


def _profiles(ax: Axes, sim: dict[str, xr.Dataset], t: float, approx_style: str = "-.", title: str = "") -> None:
    """Exact x_n(t) (continuous line) and approximate (dash-dot line, or dots)."""
    ex, ap = _at(sim["exact"], t), _at(sim["dps"], t)
    n = ex["n"].values
    ax.plot(n, ex["x"].values, "-", color="k", lw=1.0, label="exact")
    if approx_style == ".":
        ax.plot(n, ap["x"].values, ".", color="C3", ms=4, label="approx. (DpS)")
    else:
        ax.plot(n, ap["x"].values, approx_style, color="C3", lw=1.0, label="approx. (DpS)")
    ax.set_xlabel("$n$")
    ax.set_ylabel("$x_n(t)$")
    ax.set_title(f"{title}$t = {float(ex['t']):g}$", fontsize=9)


def _profile_pair(data: dict, options: dict, width: float = 9.0, height: float = 3.4) -> Figure:
    (name,) = options["scenes"]
    fig, axes = figure(1, len(options["times"]), width=width, height=height)
    for ax, t in zip(np.atleast_1d(axes), options["times"], strict=True):
        _profiles(ax, data[name], t)
    legend_outside(np.atleast_1d(axes)[-1])
    fig.suptitle(scene_caption(name, data[name]["exact"]), fontsize=9)
    return fig


def _scene(data: dict, options: dict) -> tuple[str, dict[str, xr.Dataset]]:
    (name,) = options["scenes"]
    return name, data[name]


# --------------------------------------------------------------------------- figures
def draw_plot6_7(data: dict, options: dict) -> Figure:
    """Forces, exact (left) and approximate (right): q = pi/5, omega_tw = 1.1."""
    name, sim = _scene(data, options)
    return spacetime_pair(sim, suptitle=scene_caption(name, sim["exact"]))


def draw_plot2_3(data: dict, options: dict) -> Figure:
    """Profiles of the plot6-7 run at t = 64.95 (left) and 570.95 (right)."""
    return _profile_pair(data, options)


def draw_plot1v5st(data: dict, options: dict) -> Figure:
    """Forces, exact (left) and approximate (right): q = pi/5, omega_tw = 1.5."""
    name, sim = _scene(data, options)
    return spacetime_pair(sim, suptitle=scene_caption(name, sim["exact"]))


def draw_plot1v5(data: dict, options: dict) -> Figure:
    """Left: zoom of the exact diagram of plot1v5st on t in ZOOM_PLOT1V5, all n, on
    plot1v5st's colour scale; right: exact (line) and approximate (dots) at t = 83.7."""
    name, sim = _scene(data, options)
    ex = sim["exact"]
    vmin = common_vmin(ex, sim["dps"])
    fig, (left, right) = figure(1, 2, width=9.0, height=3.8)
    img = spacetime(left, ex, vmin, t_range=ZOOM_PLOT1V5,
                    title=f"exact, zoom $t \\in [{ZOOM_PLOT1V5[0]:g}, {ZOOM_PLOT1V5[1]:g}]$, all $n$")
    fig.colorbar(img, ax=left, label=FORCE_LABEL)
    # room between the colour bar's label and the profile's axis label, which the layout would set side by side
    fig.set_layout_engine("constrained", wspace=0.08)
    (t,) = options["times"]
    _profiles(right, sim, t, approx_style=".")
    legend_outside(right)
    fig.suptitle(scene_caption(name, ex), fontsize=9)
    return fig


def draw_plot8_11(data: dict, options: dict) -> Figure:
    """Profiles of the q = 4 pi/5 run at t = 0 (left) and 331.2 (right)."""
    return _profile_pair(data, options)


def draw_plot9_10(data: dict, options: dict) -> Figure:
    """Forces, exact (left) and approximate (right): q = 4 pi/5, modulational instability."""
    name, sim = _scene(data, options)
    return spacetime_pair(sim, suptitle=scene_caption(name, sim["exact"]))


def draw_plot29_30(data: dict, options: dict) -> Figure:
    """Profiles of the q = pi run at t = 0 (left) and 223 (right)."""
    return _profile_pair(data, options)


def draw_plot26_27(data: dict, options: dict) -> Figure:
    """Forces, exact (left) and approximate (right): q = pi, static breathers."""
    name, sim = _scene(data, options)
    return spacetime_pair(sim, suptitle=scene_caption(name, sim["exact"]))


def plot28_window(ds: xr.Dataset, beads: int = PLOT28_BEADS,
                  span: float = PLOT28_SPAN) -> tuple[tuple[float, float], tuple[int, int]]:
    """(t0, t1), (n0, n1) of plot28: the last ``span`` time units stored, and the
    ``beads`` consecutive bonds (periodic) of largest summed force variance there."""
    t = ds["t"].values
    t1 = float(t[-1])
    t0 = float(t[np.searchsorted(t, t1 - span - 1e-9)])
    var = ds["force"].sel(t=slice(t0, t1)).var("t").values
    width = min(beads, len(var))
    sums = np.array([np.take(var, np.arange(i, i + width), mode="wrap").sum() for i in range(len(var))])
    n0 = int(np.argmax(sums))
    return (t0, t1), (n0, (n0 + width - 1) % len(var))


def draw_plot28(data: dict, options: dict) -> Figure:
    """Detail of the exact diagram of plot26-27 (window from :func:`plot28_window`),
    on its own colour scale: vmin = the most negative force inside the window."""
    name, sim = _scene(data, options)
    ex = sim["exact"]
    t_range, n_range = plot28_window(ex)
    f = ex["force"].sel(t=slice(*t_range))
    vmin = float(f.isel(n=_columns(ex.sizes["n"], n_range)).min())
    vmin = vmin if vmin < 0 else -1e-300
    fig, ax = figure(1, 1, width=5.6, height=5.2)
    img = spacetime(ax, ex, vmin, t_range=t_range, n_range=n_range, interpolation="nearest",
                    title=f"exact, $t \\in [{t_range[0]:g}, {t_range[1]:g}]$, bonds $n = {n_range[0]}..{n_range[1]}$\n"
                          f"({PLOT28_BEADS} bonds of largest force variance on the last {PLOT28_SPAN:g} time units)")
    fig.colorbar(img, ax=ax, label=FORCE_LABEL)
    fig.suptitle(scene_caption(name, ex), fontsize=9)
    return fig
