"""Figure bcsc: three homoclinic solutions of (dpsstn), mu = 1, N = 50, periodic."""
from __future__ import annotations

import numpy as np

from . import figure


def _profile(ax, ds, title):
    n, a = ds["n"].values, ds["a"].values
    ax.plot(n, a, "o-", ms=3, lw=0.8)
    ax.set_xlabel("$n$")
    ax.set_ylabel("$a_n$")
    ax.set_title(f"{title} (residual {ds.attrs['residual']:.1e})", fontsize=9)


def draw_bcsc(data, options):
    """Top left: site-centred solution; top right: |a_n| of it in semi-log scale for
    18 <= n <= 34 (super-exponential decay); bottom left: bond-centred; bottom
    right: double-humped. ``options['scenes']`` gives the three names in that order."""
    site, bond, double = (data[name] for name in options["scenes"])
    fig, axes = figure(2, 2, width=8.0, height=6.0)
    _profile(axes[0, 0], site, "site-centred")
    n, a = site["n"].values, np.abs(site["a"].values)
    keep = (n >= 18) & (n <= 34) & (a > 0)
    axes[0, 1].semilogy(n[keep], a[keep], "o-", ms=3, lw=0.8)
    axes[0, 1].set_xlabel("$n$")
    axes[0, 1].set_ylabel("$|a_n|$")
    axes[0, 1].set_title("site-centred, semi-log", fontsize=9)
    _profile(axes[1, 0], bond, "bond-centred")
    _profile(axes[1, 1], double, "double-humped")
    return fig


FIGURES = {"bcsc": draw_bcsc}
