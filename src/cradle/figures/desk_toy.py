"""Figure beyond the paper: the desk-toy experiments (desk-toy), in SI.

Drawn by :func:`draw` from results/desk-toy/[full/]desk-toy.nc (:mod:`cradle.analyses.desk_toy`).

One row per chain length N: one panel per lifted count, the displacement (mm) of every ball against time (s)
over the first swing periods, the lattice (nc) solid and the ideal hard-sphere cradle (its first restitution
coefficient, e = 1 by default) dashed, one colour per ball; the last panel of the row, the one-out-one-out share
f_k of every desk toy of that N and every model against time (s), the thresholds of the measure dotted.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.figures import figure

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.figure import Figure

#: finite points each data panel holds at least (tests/figures/test_figures_render.py)
MIN_POINTS = 3

#: swing periods shown in the displacement panels (the whole run is in the file and in the share panel)
SHOWN_PERIODS = 2

_MODEL_LINES = ("-", "--", ":", "-.")
_LIFTED_MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*", "h", "<")


def _groups(tree: xr.DataTree) -> dict[int, list]:
    names = [s.strip() for s in str(tree.attrs["desk_toys"]).split(",") if s.strip()]
    by_chain: dict[int, list] = {}
    for name in names:
        g = tree[name]
        by_chain.setdefault(int(g.attrs["n_beads"]), []).append((name, g))
    return by_chain


def draw(tree: xr.DataTree) -> Figure:
    """The panels above from the groups of the desk-toy file."""
    from matplotlib import colormaps
    from matplotlib.lines import Line2D

    by_chain = _groups(tree)
    ncols = max(len(v) for v in by_chain.values()) + 1
    nrows = len(by_chain)
    fig, ax = figure(nrows, ncols, width=3.3 * ncols + 1.2, height=3.1 * nrows + 0.6, squeeze=False)
    models = [s.strip() for s in str(tree.attrs["model_names"]).split(",")]
    letters = iter("abcdefghijklmnopqrstuvwxyz")
    for row, (N, groups) in enumerate(sorted(by_chain.items())):
        cmap = colormaps["viridis"]
        colours = [cmap(i / max(1, N - 1) * 0.9) for i in range(N)]
        for col in range(len(groups), ncols - 1):
            ax[row, col].set_visible(False)
        share_ax = ax[row, ncols - 1]
        for col, (_name, g) in enumerate(groups):
            A = ax[row, col]
            t = np.asarray(g["t"].values)
            T = 2.0 * np.pi * float(g.attrs["T_s"])
            show = t <= SHOWN_PERIODS * T + 1e-12
            x = np.asarray(g["x"].values) * 1e3
            for m, style in ((0, "-"), (1, "--")):
                if m >= x.shape[0]:
                    continue
                for n in range(N):
                    A.plot(t[show], x[m][show, n], style, color=colours[n], lw=1.0 if m == 0 else 1.3)
            lifted = int(g.attrs["lifted"])
            A.set_title(f"({next(letters)}) {N} balls, {lifted} lifted", fontsize=9)
            A.set_xlabel("time (s)")
            A.set_ylabel("displacement (mm)")
            share = np.asarray(g["share"].values)
            ts = np.asarray(g["swing_time"].values)
            for m in range(share.shape[0]):
                share_ax.plot(ts, share[m], _MODEL_LINES[m % 4], marker=_LIFTED_MARKERS[col % 10], ms=3,
                              color=f"C{col}", lw=0.9)
        ths = np.asarray(groups[0][1]["threshold"].values)
        for th in ths:
            share_ax.axhline(th, color="0.6", lw=0.6)
        share_ax.set_title(f"({next(letters)}) {N} balls: one-out-one-out\nshare $f_k$ at $t = k\\pi/\\omega_0$",
                           fontsize=9)
        share_ax.set_xlabel("time (s)")
        share_ax.set_ylabel("$f_k$")
        share_ax.set_ylim(-0.02, 1.05)
        # a key per meaning: the lifted counts (colours and markers) with the thresholds beside the share panel,
        # the balls' colours (displacement panels) under the row, the models (line styles) under the figure
        keys = [Line2D([], [], color=f"C{c}", marker=_LIFTED_MARKERS[c % 10], ls="none",
                         label=f"{int(g.attrs['lifted'])} lifted") for c, (_, g) in enumerate(groups)]
        keys.append(Line2D([], [], color="0.6", lw=0.6, label="thresholds " + ", ".join(f"{v:g}" for v in ths)))
        share_ax.legend(handles=keys, fontsize=6, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0,
                        title="$f_k$ of (colour, marker)", title_fontsize=6)
        balls = [Line2D([], [], color=colours[n], lw=2, label=f"ball {n}") for n in range(N)]
        ax[row, 0].legend(handles=balls, fontsize=6, loc="upper left", bbox_to_anchor=(0.0, -0.22), borderaxespad=0,
                          ncols=min(N, 5), title=f"{N} balls: displacement panels (colour), "
                          f"{models[0]} solid, {models[1] if len(models) > 1 else ''} dashed", title_fontsize=6,
                          alignment="left")
    styles = [Line2D([], [], color="0.2", ls=_MODEL_LINES[m % 4], label=mod) for m, mod in enumerate(models)]
    fig.legend(handles=styles, fontsize=7, loc="outside lower center", ncols=len(styles), frameon=False,
               title="model (line style, every panel)", title_fontsize=7)
    fig.suptitle(f"Desk toys: {tree.attrs['cradle']}, lifted to {float(tree.attrs['angle_deg']):g}°; displacements "
                 f"over the first {SHOWN_PERIODS} swing periods", fontsize=10)
    return fig
