"""Figure bcsc: three homoclinic solutions of (dpsstn), mu = 1, N = 50, periodic."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.figures import figure

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

#: finite points each data panel holds at least (tests/figures/test_figures_render.py): N sites
MIN_POINTS = 20


def _profile(ax: Axes, ds: xr.Dataset, title: str) -> None:
    n, a = ds["n"].values, ds["a"].values
    ax.plot(n, a, "o-", ms=3, lw=0.8)
    ax.set_xlabel("$n$")
    ax.set_ylabel("$a_n$")
    ax.set_title(f"{title} (residual {ds.attrs['residual']:.1e})", fontsize=9)


def draw_bcsc(data: dict, options: dict) -> Figure:
    """Top left: site-centred solution; top right: log10|a_n| of it on every site, the
    tails continued far below machine precision (super-exponential decay; the paper
    shows 18 <= n <= 34, shaded); bottom left: bond-centred; bottom
    right: double-humped. ``options['scenes']`` gives the three names in that order."""
    site, bond, double = (data[name] for name in options["scenes"])
    fig, axes = figure(2, 2, width=8.0, height=6.0)
    _profile(axes[0, 0], site, "site-centred")
    n, log10a = site["n"].values, site["log10_abs_a"].values
    ax = axes[0, 1]
    ax.plot(n, log10a, "o-", ms=3, lw=0.8)
    ax.axhline(np.log10(np.finfo(float).eps * float(np.max(np.abs(site["a"].values)))), color="C3", lw=0.6, ls="--")
    ax.axvspan(18, 34, color="0.9", zorder=0)
    ax.set_xlabel("$n$")
    ax.set_ylabel("$\\log_{10}|a_n|$")
    ax.set_yscale("symlog", linthresh=10)
    # above the largest point by more than a marker: the centre's log10|a_n| is near 0
    finite = log10a[np.isfinite(log10a)]
    # a margin beyond the extreme points (symlog: a tenth of the span below), so that no marker is cut
    ax.set_ylim(float(finite.min()) * 1.1 - 1.0, max(1.0, float(finite.max()) + 1.5))
    ax.set_xlim(float(n.min()) - 1.5, float(n.max()) + 1.5)
    ax.set_title("site-centred, $\\log_{10}|a_n|$; shaded: the paper's $18 \\leq n \\leq 34$;\n"
                 "dashed: machine precision; tails: (dpsstn) in log variables", fontsize=8)
    _profile(axes[1, 0], bond, "bond-centred")
    _profile(axes[1, 1], double, "double-humped")
    fig.suptitle(f"(dpsstn): $\\alpha$ = {float(site.attrs['alpha']):g}, $\\mu$ = {float(site.attrs['mu']):g}, "
                 f"N = {int(site.attrs['N'])}, {site.attrs['bc']}", fontsize=9)
    return fig
