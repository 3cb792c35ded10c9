"""Figure work-precision: error and energy drift of every lattice integrator against wall time.

Drawn by :func:`draw` from results/work-precision/[full/]work-precision.nc
(:mod:`cradle.analyses.work_precision`), one group per scene. One row per
scene; left: error (max over the comparison grid up to t_valid, relative to
the amplitude) against wall time; right: relative
energy drift (max over every step up to t_end) against wall time. The
shaded band is where the two reference runs differ (the error floor of the
comparison).
"""
from __future__ import annotations

import json
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.ticker import NullFormatter

from cradle.figures import figure

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

#: finite points each data panel holds at least (tests/figures/test_figures_render.py): a few settings per method
MIN_POINTS = 3

STYLE = {  # method -> (colour, marker); corrected splittings solid, the rest dashed
    "srkn6c": ("C3", "o"), "srkn4c": ("C1", "s"), "srkn6": ("C0", "o"), "srkn4": ("C9", "s"),
    "strang": ("C2", "^"), "dop853_numba": ("C5", "D"), "dop853": ("C4", "v"), "lsoda": ("C7", "P"),
    "rk45": ("C8", "x"), "radau": ("C6", "*"),
}


def _curve(ax: Axes, ds: xr.Dataset, i: int, var: str) -> None:
    method = str(ds["method"].values[i])
    row = ds.isel(method=i)
    w, y = row["wall_time"].values, row[var].values
    ok = np.isfinite(w) & np.isfinite(y) & (y > 0)
    colour, marker = STYLE.get(method, ("k", "."))
    ls = "-" if method.startswith("srkn") and method.endswith("c") else "--"
    ax.loglog(w[ok], y[ok], ls, color=colour, marker=marker, ms=3.5, lw=1.0, label=method)


def draw(tree: xr.DataTree) -> Figure:
    """The figure of the work-precision file ``tree``: one row per scene group, in the file's order."""
    data = {name: node.to_dataset() for name, node in tree.children.items()}
    scenes = list(data)
    fig, axes = figure(len(scenes), 2, width=11.0, height=2.9 * len(scenes) + 0.4, squeeze=False)
    for r, name in enumerate(scenes):
        ds = data[name]
        left, right = axes[r]
        kinds = json.loads(ds.attrs.get("parameter_kind", "{}"))
        for i in range(ds.sizes["method"]):
            _curve(left, ds, i, "error")
            _curve(right, ds, i, "energy_drift")
        floor = float(ds.attrs["reference_error"])
        if floor > 0:
            left.axhspan(left.get_ylim()[0] if left.has_data() else floor / 10, floor, color="0.85", zorder=0)
        t_valid, t_end = float(ds.attrs["t_valid"]), float(ds.attrs["t_end"])
        upto = f"t <= {t_valid:g}" + (" (reference limit)" if t_valid < t_end else "")
        left.set_title(f"{name}: N = {int(ds.attrs['N'])}, t_end = {t_end:g}; error over {upto}", fontsize=8.5)
        right.set_title(f"{name}: energy drift over [0, {t_end:g}]", fontsize=8.5)
        left.set_ylabel("max error / a")
        right.set_ylabel("max |H - H(0)| / H(0)")
        for ax in (left, right):
            ax.grid(True, which="major", lw=0.3, alpha=0.6)
            # wall times span little more than a decade: labelled minor ticks would run into each other
            ax.xaxis.set_minor_formatter(NullFormatter())
            if r == len(scenes) - 1:
                ax.set_xlabel("wall time [s]")
        if r == 0:
            from matplotlib.patches import Patch

            handles, labels = left.get_legend_handles_labels()
            labels = [f"{lab} ({kinds.get(lab, '')})" if kinds.get(lab) else lab for lab in labels]
            handles.append(Patch(color="0.85"))
            labels.append("shaded: the two reference\nruns differ (error floor)")
            # beside the panels: the note of a reduced form goes below them
            fig.legend(handles, labels, fontsize=7.5, ncol=1, loc="outside right upper")
    if scenes:
        ds = data[scenes[0]]
        fig.suptitle(f"Lattice (nc) integrators, alpha = {float(ds.attrs['alpha']):g}; "
                     f"{ds.attrs.get('machine', '')}, {ds.attrs.get('date', '')}", fontsize=9)
    return fig
