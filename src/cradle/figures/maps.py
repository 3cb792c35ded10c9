"""Figures traj3 and traj2: orbits of the map G (comp1)-(comp2), alpha = 3/2 (section 2.2)."""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from cradle.figures import figure

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

#: finite points each data panel holds at least (tests/figures/test_figures_render.py): iterates of the orbits
MIN_POINTS = 100

MARKERS = {2: ("o", "period 2"), 3: ("s", "period 3"), 4: ("^", "period 4")}


def _orbits(ax: Axes, ds: xr.Dataset, size: float = 0.55) -> None:
    """Every stored iterate of every orbit as a dot of ``size`` points (NaN: the orbit left the box).

    Markers of a Line2D, rasterised: half the time of a scatter for the ~10^5 dots of traj2."""
    a, b = ds["map_a"].values, ds["map_b"].values
    for i in range(a.shape[0]):
        keep = np.isfinite(a[i]) & np.isfinite(b[i])
        ax.plot(a[i, keep], b[i, keep], ls="none", marker=".", ms=size, mew=0, color=f"C{i % 10}",
                rasterized=True)
    box = float(ds.attrs["box"])
    ax.set_xlim(-box, box)
    ax.set_ylim(-box, box)
    ax.set_xlabel("$a_n$")
    ax.set_ylabel("$b_{n+1}$")


def _marks(ax: Axes, ds: xr.Dataset) -> None:
    """The explicit period-2, -3, -4 orbits of the traj2 caption (mark_a, mark_b, mark_period of the map file)."""
    if "mark_a" not in ds:
        raise ValueError(f"map '{ds.attrs.get('name', '?')}' has marks but no stored mark_a/mark_b: rebuild it")
    a, b, period = ds["mark_a"].values, ds["mark_b"].values, ds["mark_period"].values
    box = float(ds.attrs["box"])
    for p, (marker, label) in MARKERS.items():
        # only the points of the panel: a mark outside the box would be cut by the frame or not drawn at all
        sel = (period == p) & (np.abs(a) < 0.97 * box) & (np.abs(b) < 0.97 * box)
        if sel.any():
            ax.plot(a[sel], b[sel], marker, ms=5, mfc="none", mec="k", mew=0.9, ls="none", label=label)


def draw_traj3(data: dict, options: dict) -> Figure:
    """One orbit of G from a_0 = 0, b_1 = 1e-13: it follows the pair of symmetric homoclinic loops."""
    ds = data[options["scenes"][0]]
    fig, ax = figure(1, 1, width=5.0, height=4.2)
    _orbits(ax, ds, size=1.2)
    a, b = ds["map_a"].values[0], ds["map_b"].values[0]
    box = 1.15 * max(np.nanmax(np.abs(a)), np.nanmax(np.abs(b)))
    ax.set_xlim(-box, box)
    ax.set_ylim(-box, box)
    ax.set_title(f"orbit of G, $\\alpha$ = {float(ds.attrs['alpha']):g}, $a_0 = 0$, $b_1 = 10^{{-13}}$, "
                 f"{a.size - 1} iterates", fontsize=9)
    return fig


def draw_traj2(data: dict, options: dict) -> Figure:
    """Six panels: ||U||_inf <= 0.1 (top), 1 (middle), 8 and 100 (bottom); left periodic
    orbits and invariant tori, right orbits near stable and unstable manifolds; marks for the
    explicit periodic orbits where the entry has ``marks``."""
    fig, axes = figure(3, 2, width=8.0, height=11.5)
    # six panels: a shorter list of scenes leaves the last ones blank
    for ax, name in zip(axes.flat, options["scenes"], strict=False):
        ds = data[name]
        _orbits(ax, ds)
        if ds.attrs.get("marks"):
            _marks(ax, ds)
        ax.set_title(f"$\\|U_n\\|_\\infty \\leq {float(ds.attrs['box']):g}$ ({name})", fontsize=9)
    # one key for the marks of every panel, below the panels: inside a panel it would cover orbits
    keys: dict[str, Any] = {}
    for ax in axes.flat:
        for handle, label in zip(*ax.get_legend_handles_labels(), strict=True):
            keys.setdefault(label, handle)
    if keys:
        order = [label for _, label in MARKERS.values() if label in keys]
        fig.legend(handles=[keys[k] for k in order], labels=[f"{k} orbit (explicit)" for k in order],
                   loc="outside lower center", ncols=len(order), fontsize=8, frameon=False)
    first = data[options["scenes"][0]]
    fig.suptitle(f"orbits of the map G (comp1)-(comp2), $\\alpha$ = {float(first.attrs['alpha']):g}", fontsize=10)
    return fig
