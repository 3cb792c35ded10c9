"""Figure beyond the paper: collisions of two breathers, exact (nc) against DpS (breather-interactions).

Reads results/breather-interactions/[full/]breather-interactions.nc (:mod:`cradle.analyses.breather_interactions`):
row by profile pair, (a) and (b) the modal outcome over the seeds on (spacing, theta), exact and
DpS side by side, with the share of seeds whose outcome the two models share (the outcome key beside (b));
(c) the median merging time against the spacing at theta = 0, both models, each seed an open dot beside its
median (exact left, DpS right); (d) the exact/DpS ratio of the merging times of every case where both merge,
against the spacing. Panels are lettered on through the rows.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from matplotlib.colors import BoundaryNorm, ListedColormap

from cradle.figures import AnalysisTree, figure, legend_outside, plain_log_ticks

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: as cradle.measurements.interactions.OUTCOMES (a figure module imports no numerical module)
OUTCOMES = ("merge", "bound", "repel", "transmit", "none")
COLOURS = ("#1b9e77", "#7570b3", "#d95f02", "#e7298a", "#bbbbbb")

#: finite points each data panel holds at least (tests/figures/test_figures_render.py): one case of an outcome
#: (a panel gathers the cases of one pair kind and outcome; the reduced form runs four cases)
MIN_POINTS = 1


def draw(tree: AnalysisTree) -> Figure:
    """The figure of the module docstring from the breather-interactions file ``tree`` (/cases, /maps)."""
    maps, cases = tree["maps"], tree["cases"]
    pairs = [str(p) for p in maps["pair"].values]
    theta = maps["theta"].values
    fig, ax = figure(len(pairs), 4, width=15.0, height=3.4 * len(pairs) + 0.6, squeeze=False)
    cmap = ListedColormap(COLOURS)
    norm = BoundaryNorm(np.arange(-0.5, len(OUTCOMES) + 0.5), cmap.N)
    letters = iter("abcdefghijklmnopqrstuvwxyz")
    for i, pair in enumerate(pairs):
        sel = cases["pair"].values == pair
        sp = np.unique(cases["spacing"].values[sel])
        for j, m in enumerate(("exact", "dps")):
            A = ax[i, j]
            M = maps[f"modal_outcome_{m}"].values[i]
            A.pcolormesh(theta / np.pi, sp, M, cmap=cmap, norm=norm, shading="nearest")
            agree = maps["agreement"].values[i]
            A.set_title(f"({next(letters)}) {pair}, {'exact (nc)' if m == 'exact' else 'DpS'}: modal outcome"
                        + (f"\nmodels agree on {np.nanmean(agree):.0%} of seeds" if j == 1 else ""), fontsize=8)
            A.set_xlabel(r"$\theta/\pi$")
            A.set_ylabel("spacing (sites)")
        handles = [A.scatter([], [], color=c, marker="s", label=o) for o, c in zip(OUTCOMES, COLOURS, strict=True)]
        legend_outside(ax[i, 1], handles=handles, fontsize=6, title="outcome", title_fontsize=6)
        # (c) merging time against spacing at theta = 0
        C = ax[i, 2]
        th0 = sel & (cases["sweep"].values == 0) & np.isclose(cases["theta"].values, 0.0)
        n_seeds = 0
        for m, style, dx in (("exact", "o-", -0.08), ("dps", "s--", 0.08)):
            med = []
            colour = "C0" if m == "exact" else "C3"
            for s in sp:
                v = cases[f"merge_period_{m}"].values[th0 & (cases["spacing"].values == s)]
                n_seeds = max(n_seeds, v.size)
                v = v[np.isfinite(v)]
                med.append(np.median(v) if v.size else np.nan)
                # beside the median, not under it: one seed would otherwise sit exactly on its median's marker
                C.plot(np.full(v.size, s + dx), v, "o", color=colour, mfc="none", ms=4, lw=0, zorder=3,
                       label=f"{m}: each seed" if s == sp[0] else None)
            C.plot(sp, med, style, color=colour, ms=5, label=f"{m}: median")
        C.set_xlabel("spacing (sites)")
        C.set_ylabel(r"merging time (breather periods)")
        C.set_xlim(sp.min() - 0.5, sp.max() + 0.5)
        C.set_title(rf"({next(letters)}) {pair}: merging time at $\theta$ = 0," + f"\n{n_seeds} seed"
                    + ("" if n_seeds == 1 else "s") + " per spacing", fontsize=8)
        legend_outside(C, fontsize=6)
        # (d) exact / DpS ratio
        D = ax[i, 3]
        r = cases["merge_ratio"].values[sel]
        s_r = cases["spacing"].values[sel]
        ok = np.isfinite(r) & (r > 0)
        D.semilogy(s_r[ok], r[ok], "o", color="k", mfc="none", ms=4, alpha=0.7)
        D.axhline(0.5, color="C2", lw=0.8, ls=":", label="paper: exact/DpS ~ 1/2")
        D.axhline(1.0, color="0.6", lw=0.6, label="equal times")
        D.set_xlim(sp.min() - 0.5, sp.max() + 0.5)
        span = np.concatenate([r[ok], [0.5, 1.0]])
        D.set_ylim(span.min() / 1.4, span.max() * 1.4)   # every case and both reference lines, off the frame
        D.set_xlabel("spacing (sites)")
        D.set_ylabel("merging time exact / DpS")
        D.set_title(f"({next(letters)}) {pair}: {int(ok.sum())} case{'' if int(ok.sum()) == 1 else 's'} "
                    "where both merge", fontsize=8)
        legend_outside(D, fontsize=6)
        plain_log_ticks(D)
    fig.suptitle(f"breather-interactions: {int(tree.attrs['n_cases'])} cases, outcome the same in both models for "
                 f"{float(tree.attrs['outcome_agreement']):.0%}", fontsize=9)
    return fig
