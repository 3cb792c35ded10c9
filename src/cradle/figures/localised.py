"""Figures plot18, loc1 and fini: localised initial conditions (section 4.3).

* plot18: one breather (ansatzapproxst2)/(breatherdps) from the bond-centred
  homoclinic solution of (dpsstn), N = 50, periodic, zero velocities. Top
  left: x_n(0); top right: exact at t = 569.4 (line) against approximate at
  565.95 (dots); bottom left: forces of the exact run in grey levels; bottom
  right: exact at t = 293.2 for the large amplitude (omega_sw ~ 1.6).
* loc1: a packet modulating a binary oscillation (left) and two static
  breathers (right), at rest: initial profiles, then the forces of the exact
  and approximate runs on one colour scale per column, and the merging time
  of the two breathers in breather periods.
* fini: a breather on a 10-bead chain with free ends: bead displacements
  against t, each bead offset by its label n = 1..10, in an early window and
  after ~250 breather periods, exact (left) and approximate (right).

Space-time diagrams are raster images (``imshow``): forces f_n =
V0'(x_{n+1} - x_n) <= 0 in grey levels, white = beads apart (f = 0), black =
the most negative force; bond index n horizontal, time t upwards.

Every measurement shown (half-period shift, radiated amplitude, peak
compression per period, merging times) is read from the scene's metrics file
(results/metrics/<scene>.nc, :func:`cradle.scenes.stages.localised_metrics`).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.figures import dps_range_note, figure
from cradle.figures.spacetime import FORCE_LABEL, _at, common_vmin as _vmin, period_minimum, spacetime

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

# plot18 (bottom left): the paper likens this diagram to the detail plot28 (the central breather of
# the q = pi instability), a 100-time-unit, 20-bond window. We show the last 100 time units of the
# run (the breather is still intact at the end) on the 20 bonds 16..35 around the breather.
PLOT18_SPAN = 100.0
PLOT18_BONDS = (16, 35)

#: finite points each data panel holds at least (tests/figures/test_figures_render.py): a profile of N beads,
#: a space-time image, N traces of a window
MIN_POINTS = {"plot18": 10, "loc1": 20, "fini": 100}

FINI_DELTA_X = 0.02                # displacement of one unit of vertical offset (the paper's scale bar)


# --------------------------------------------------------------------------- drawing helpers

def _profile(ax: Axes, ds: xr.Dataset, t: float, style: str = "o-", label: str | None = None, color: str = "k",
             ms: float = 3) -> float:
    s = _at(ds, t)
    ax.plot(s["n"].values, s["x"].values, style, color=color, ms=ms, lw=0.9, label=label)
    ax.set_xlabel("$n$")
    ax.set_ylabel("$x_n(t)$")
    return float(s["t"])


def _omega(ds: xr.Dataset) -> float:
    return float(ds.attrs["omega_sw"])


def _stored(metrics: xr.Dataset, name: str) -> xr.DataArray:
    """A measurement of the scene's metrics file (a clear error when the file predates it)."""
    if name not in metrics:
        raise ValueError(f"scene '{metrics.attrs.get('scene', '?')}': no {name} in its metrics file: "
                         "rebuild the metrics")
    return metrics[name]


def shift(metrics: xr.Dataset) -> dict[str, float]:
    """The stored frequencies of exact and approximate runs and their half-period shift."""
    return {key: float(_stored(metrics, key)) for key in ("omega_exact", "omega_approx", "half_shift_periods")}


# --------------------------------------------------------------------------- plot18

def _dps_range(fig: Figure, runs: list[tuple[str, xr.Dataset]], title: str = "") -> None:
    """The figure's title: ``title`` (none when empty) and a line for each scene of ``runs`` (name, exact run)
    whose amplitude is outside DpS's measured range (:func:`cradle.figures.dps_range_note`)."""
    lines = ([title] if title else []) + [n for n in (dps_range_note(name, ds) for name, ds in runs) if n]
    if lines:
        fig.suptitle("\n".join(lines), fontsize=9)


def draw_plot18(data: dict, options: dict) -> Figure:
    """plot18. ``options['scenes']`` = [small, large]; ``times`` = [0, t_approx, t_exact, t_large]
    (0, 565.95, 569.4, 293.2 in the paper)."""
    small, large = options["scenes"]
    t0, t_app, t_ex, t_large = options["times"]
    ex, ap = data[small]["exact"], data[small]["dps"]
    exl = data[large]["exact"]
    w = _omega(ex)
    fig, axes = figure(2, 2, width=9.0, height=7.0)

    ax = axes[0, 0]
    _profile(ax, ex, t0)
    x0 = _at(ex, t0)["x"].values
    k = int(np.argmax(np.abs(x0)))
    top = np.flatnonzero(np.isclose(np.abs(x0), abs(x0[k]), rtol=1e-9, atol=0.0))
    ax.set_title(f"$x_n(0)$: max $|x_n(0)|$ = {abs(x0[k]):.3g} at $n$ = {', '.join(map(str, top))}\n"
                 f"$\\omega_{{sw}}$ = {w:.4f}, $\\mu$ = {float(ex.attrs['mu']):.4f}", fontsize=8)

    ax = axes[0, 1]
    te = _profile(ax, ex, t_ex, "-", label="exact")
    ta = _profile(ax, ap, t_app, ".", label="approx. (DpS)", color="C3", ms=5)
    sh = shift(data[small]["metrics"])
    ax.legend(fontsize=7, loc="upper right")
    ax.set_title(f"exact $t$ = {te:g} (line), approx. $t$ = {ta:g} (dots)\n"
                 f"$\\omega$ exact {sh['omega_exact']:.4f}, approx. {sh['omega_approx']:.4f}:\n"
                 f"half-period shift after {sh['half_shift_periods']:.0f} periods", fontsize=8)

    ax = axes[1, 0]
    t_end = float(ex["t"].values[-1])
    t_range = (max(0.0, t_end - PLOT18_SPAN), t_end)
    img = spacetime(ax, ex, _vmin(ex, t_range=t_range), t_range=t_range, n_range=PLOT18_BONDS,
                    title=f"exact forces, $t \\in [{t_range[0]:g}, {t_range[1]:g}]$, bonds "
                          f"{PLOT18_BONDS[0]}..{PLOT18_BONDS[1]}")
    fig.colorbar(img, ax=ax, label=FORCE_LABEL)

    ax = axes[1, 1]
    tl = _profile(ax, exl, t_large, "o-", ms=2)
    xl0 = _at(exl, 0.0)["x"].values
    kl = int(np.argmax(np.abs(xl0)))
    radiated = float(_at(_stored(data[large]["metrics"], "radiated_exact"), t_large))
    ax.set_title(f"exact, $t$ = {tl:g}, $|x_{{{kl}}}(0)|$ = {abs(xl0[kl]):.3g}, $\\omega_{{sw}}$ = "
                 f"{_omega(exl):.4f}\nmax $|x_n|$ beyond 6 sites of the core: {radiated:.2e}", fontsize=8)
    _dps_range(fig, [(small, ex)])   # the large breather is drawn without DpS
    return fig


# --------------------------------------------------------------------------- loc1

def loc1_merging_times(sim: dict[str, xr.Dataset]) -> dict[str, float]:
    """Merging times (breather periods 2 pi / omega_sw) of the exact and approximate runs of a scene,
    as stored in its metrics file."""
    return {m: float(_stored(sim["metrics"], f"merging_time_{m}")) for m in ("exact", "dps")}


#: outcome codes of cradle.measurements.interactions.OUTCOMES (stored as outcome_{exact,dps}; the figure
#: modules import no numerical module, so the names are restated here and checked by a test)
OUTCOME_NAMES = ("merge", "bound", "repel", "transmit", "none")
#: the paper's merging times of loc1 (right): "around 175 multiples of the breather period for the exact
#: solution, and twice more for the approximate solution"
PAPER_MERGING = {"exact": "~175", "dps": "~350"}


def _periods_text(value: float, total: float, outcome: xr.DataArray | int | None = None) -> str:
    if np.isfinite(value):
        return f"after {value:.0f} periods"
    what = f" ({OUTCOME_NAMES[int(outcome)]})" if outcome is not None else ""
    return f"none within {total:.0f} periods{what}"


def draw_loc1(data: dict, options: dict) -> Figure:
    """loc1: 3 rows x 2 columns. Row 1: x_n(0); rows 2 and 3: exact and approximate forces on
    one colour scale per column. ``options['scenes']`` = [packet, pair]; the merging time of
    the pair (column 2) is printed in its titles."""
    names = options["scenes"]
    fig, axes = figure(3, len(names), width=9.0, height=11.0, squeeze=False)
    for j, name in enumerate(names):
        ex, ap = data[name]["exact"], data[name]["dps"]
        ax = axes[0, j]
        _profile(ax, ex, 0.0, "o-", ms=2)
        x0 = ex["x"].values[0]
        t_end = float(ex["t"].values[-1])
        info = f"max $|x_n(0)|$ = {np.max(np.abs(x0)):.3g}"
        if "omega_sw" in ex.attrs:
            info += (f", $\\omega_{{sw}}$ = {_omega(ex):.4f}, "
                     f"$t_{{end}}$ = {t_end * _omega(ex) / (2 * np.pi):.0f} periods")
        ax.set_title(f"{name}: $x_n(0)$, $v_n(0) = 0$\n{info}", fontsize=8)
        vmin = _vmin(ex, ap)
        m = data[name]["metrics"]
        omega = float(_stored(m, "breather_omega"))   # rows binned by one breather period (1.1 for the packet)
        period = 2.0 * np.pi / omega
        merge = loc1_merging_times(data[name]) if "merging_time_exact" in m else None
        for i, (ds, label, key) in enumerate(((ex, "exact (nc)", "exact"), (ap, "approx. (DpS)", "dps")), start=1):
            title = f"{label}\nmin force per period $2\\pi/{omega:.4g}$"
            if merge is not None:
                outcome = _stored(m, f"outcome_{key}") if f"outcome_{key}" in m else None
                title += (f"\nmerging: {_periods_text(merge[key], t_end / period, outcome)} "
                          f"(paper: {PAPER_MERGING[key]})")
            img = spacetime(axes[i, j], ds, vmin, title=title, binned=period_minimum(m, key))
        fig.colorbar(img, ax=axes[1:, j], label=FORCE_LABEL, shrink=0.8, location="bottom", aspect=30)
    _dps_range(fig, [(name, data[name]["exact"]) for name in names])
    return fig


# --------------------------------------------------------------------------- fini

def _traces(ax: Axes, ds: xr.Dataset, t_range: tuple[float, float], delta: float = FINI_DELTA_X,
            title: str = "") -> None:
    """Bead displacements on t_range, bead n (0..N-1, the index of the files and of every other figure) drawn at
    height n + x_n(t)/delta."""
    s = ds["x"].sel(t=slice(*t_range))
    t = s["t"].values
    N = s.sizes["n"]
    for n in range(N):
        ax.plot(t, n + s.values[:, n] / delta, "-", color="k", lw=0.7)
    ax.set_xlim(*t_range)
    ax.set_ylim(-0.7, N - 0.1)
    ax.set_yticks(np.arange(N))
    ax.set_xlabel("$t$")
    ax.set_ylabel("bead $n$")
    # scale bar: one unit of offset is delta in displacement, at the top of the vertical axis
    xb = t_range[0] + 0.015 * (t_range[1] - t_range[0])
    ax.annotate("", xy=(xb, N - 0.15), xytext=(xb, N - 1.15),
                arrowprops={"arrowstyle": "<->", "lw": 0.8, "shrinkA": 0, "shrinkB": 0})
    ax.text(xb, N - 0.65, f"  $\\delta x = {delta:g}$", fontsize=7, va="center")
    if title:
        ax.set_title(title, fontsize=8)


def draw_fini(data: dict, options: dict) -> Figure:
    """fini: rows = the windows [times[0], times[1]] and [times[2], times[3]]; left exact, right approx."""
    (name,) = options["scenes"]
    ex, ap = data[name]["exact"], data[name]["dps"]
    times = options["times"]
    windows = [(times[i], times[i + 1]) for i in range(0, len(times) - 1, 2)]
    w = _omega(ex)
    period = 2.0 * np.pi / w
    sh = shift(data[name]["metrics"])
    fig, axes = figure(len(windows), 2, width=9.0, height=4.0 * len(windows), squeeze=False)
    for i, win in enumerate(windows):
        p0, p1 = win[0] / period, win[1] / period
        for j, (ds, label) in enumerate(((ex, "exact (nc), free ends"), (ap, "approx. (DpS)"))):
            _traces(axes[i, j], ds, win, title=f"{label}, $t \\in [{win[0]:g}, {win[1]:g}]$ "
                                               f"({p0:.1f}-{p1:.1f} periods)")
    _dps_range(fig, [(name, ex)],
               f"N = {ex.sizes['n']}, free ends, $\\omega_{{sw}}$ = {w:.4f}, max $|x_n(0)|$ = "
               f"{np.max(np.abs(ex['x'].values[0])):.3g}; $\\omega$ exact {sh['omega_exact']:.4f}, approx. "
               f"{sh['omega_approx']:.4f}: half-period shift after {sh['half_shift_periods']:.0f} periods")
    return fig
