"""Figure beyond the paper: what survives on-site disorder (disorder).

Drawn by :func:`draw` from results/disorder/[full/]disorder.nc (:mod:`cradle.analyses.disorder`).

(a)-(d) the survival measure S of each family (wave: fidelity at the end; mi: break-up time over the homogeneous
one; kicked: travel over the homogeneous travel; static: retention) against sigma / Delta, mean over seeds with a
band of +- one standard deviation, one colour per frequency shift Delta, lattice (ncimperfect) solid with filled
markers, DpS (dpsimperfect) dashed with open markers; the dotted horizontal line is the crossover level and the
grey vertical line sigma = Delta, the crossover the frequency shift predicts. (e) the phase diagram: sigma* (mean
over seeds of the crossings inside the grid, error bars one standard deviation; drawn where at least half the seeds
cross inside the grid) against Delta, per family, with the line sigma = Delta. (f) the static breather's frequency
shift against the first-order prediction, every seed and sigma > 0. (g) the wave's fidelity against time in slow
periods at the median Delta, seed mean per sigma. (h) the mi wave's break-up time against sigma / Delta, mean +-
std over seeds.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.figures import AnalysisTree, figure, legend_outside

if TYPE_CHECKING:

    import xarray as xr
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

FAMILIES = ("wave", "mi", "kicked", "static")
TITLES = {"wave": "wave: fidelity F at the end", "mi": "mi: break-up time / homogeneous",
          "kicked": "kicked breather: travel / homogeneous", "static": "static breather: energy retained"}
_MARKERS = ("o", "s", "^", "D", "v", "P")
#: finite points each data panel holds at least (tests/figures/test_figures_render.py)
MIN_POINTS = 2
#: error bars of one standard deviation are drawn over at least this many seeds
MIN_SEEDS_FOR_BARS = 4


def _values(tree: AnalysisTree, path: str, name: str) -> np.ndarray:
    return np.asarray(tree[path][name].values, dtype=float)


def _stats(y: np.ndarray, axis: int = -1) -> tuple[np.ndarray, np.ndarray]:
    with np.errstate(invalid="ignore"):
        mean = np.nanmean(y, axis=axis)
        std = np.nanstd(y, axis=axis, ddof=1) if y.shape[axis] > 1 else np.zeros_like(mean)
    return mean, std


def _collapse(ax: Axes, tree: AnalysisTree, family: str, sigma: np.ndarray, shifts: np.ndarray,
              level: float, bands: bool) -> None:
    S = _values(tree, family, "survival")           # (model, shift, sigma, seed)
    pos = sigma > 0
    for d, shift in enumerate(shifts):
        c = f"C{d}"
        x = sigma[pos] / shift
        for m, (ls, fill) in enumerate((("-", c), ("--", "none"))):
            mean, std = _stats(S[m, d][pos])
            ax.plot(x, mean, ls, marker=_MARKERS[d % 6], color=c, mfc=fill, ms=4, lw=1.0)
            top = mean + std if family in ("mi", "kicked") else np.minimum(mean + std, 1.0)   # F, retention <= 1
            if bands:
                ax.fill_between(x, mean - std, top, color=c, alpha=0.12 if m == 0 else 0.06, lw=0)
    ax.axhline(level, color="k", ls=":", lw=0.8)
    ax.axvline(1.0, color="0.5", lw=0.8)
    ax.set_xscale("log")
    ax.set_xlabel(r"$\sigma / \Delta$")
    ax.set_ylabel("survival S")


def draw(tree: xr.DataTree) -> Figure:
    """The eight panels above from the groups of the disorder file."""
    from matplotlib.ticker import NullFormatter

    fig, ax = figure(2, 4, width=17.0, height=8.6)
    sigma = np.asarray(tree["sigma"].values, dtype=float)
    shifts = np.asarray(tree["shift"].values, dtype=float)
    level = float(tree.attrs["level"])
    n_seeds = int(tree["seed"].size)
    # a standard deviation over fewer seeds than MIN_SEEDS_FOR_BARS says nothing: no bands, no bars
    bars = n_seeds >= MIN_SEEDS_FOR_BARS
    for k, fam in enumerate(FAMILIES):
        A = ax[0, k]
        _collapse(A, tree, fam, sigma, shifts, level, bars)
        A.set_title(f"({'abcd'[k]}) {TITLES[fam]}", fontsize=9)
    ax[0, 1].set_yscale("log")
    # legend of the collapse panels: colours are Delta, line styles the models
    L = ax[0, 3]
    for d, shift in enumerate(shifts):
        L.plot([], [], "-", marker=_MARKERS[d % 6], color=f"C{d}", ms=4, label=rf"$\Delta$ = {shift:g}")
    L.plot([], [], "k-", marker="o", ms=4, label="lattice (ncimperfect)")
    L.plot([], [], "k--", marker="o", mfc="none", ms=4, label="DpS (dpsimperfect)")
    L.plot([], [], "k:", label=f"crossover level {level:g}")
    L.plot([], [], "-", color="0.5", label=r"$\sigma = \Delta$ (prediction)")
    if bars:
        L.plot([], [], "s", color="0.85", ms=8, label=f"band: +- 1 std over {n_seeds} seeds")
    else:
        L.plot([], [], " ", label=f"mean of {n_seeds} seeds (no band:\ntoo few for a spread)")
    legend_outside(L, fontsize=7)
    # (e) phase diagram
    E = ax[1, 0]
    st = _values(tree, "crossover", "sigma_star_stats")     # (family, model, shift, stat)
    # a point where at least half the seeds cross inside the grid (else the mean of the few that do would stand
    # for all)
    st = np.where(st[..., 5:6] >= n_seeds / 2.0, st, np.nan)
    floor, ceiling = sigma[sigma > 0].min() / 2, sigma.max() * 2
    absent = []
    for f, fam in enumerate(FAMILIES):
        for m, fill in enumerate((f"C{f + 4}", "none")):
            name = f"{fam}, {'lattice' if m == 0 else 'DpS'}"
            mean, std = st[f, m, :, 0], st[f, m, :, 1]
            if not np.isfinite(mean).any():
                absent.append(name)
                continue
            off = 1.0 + 0.04 * (2 * f + m - 3.5)            # side by side: the error bars do not hide each other
            # on the log axis a bar reaching 0 or below ends at the axis instead of leaving the panel
            yerr = np.stack([np.minimum(std, mean - floor * 1.02), np.minimum(std, ceiling / 1.02 - mean)])
            E.errorbar(shifts * off, mean, yerr=yerr if bars else None, fmt=_MARKERS[f],
                       color=f"C{f + 4}", mfc=fill, ms=5, capsize=2, lw=0.8, label=name)
    lo, hi = min(sigma[sigma > 0].min(), shifts.min()) / 2, max(sigma.max(), shifts.max()) * 2
    E.plot([lo, hi], [lo, hi], "-", color="0.5", lw=0.8, label=r"$\sigma = \Delta$")
    E.set_xscale("log")
    E.set_yscale("log")
    E.set_xlim(shifts.min() / 1.6, shifts.max() * 1.6)
    E.set_xticks(shifts, [f"{v:g}" for v in shifts])
    E.xaxis.set_minor_formatter(NullFormatter())   # the minor ticks' labels would cover the grid's
    E.set_ylim(sigma[sigma > 0].min() / 2, sigma.max() * 2)
    E.axhspan(sigma.max(), sigma.max() * 2, color="0.92", lw=0)
    E.axhspan(sigma[sigma > 0].min() / 2, sigma[sigma > 0].min(), color="0.92", lw=0)
    E.set_xlabel(r"frequency shift $\Delta = \omega - 1$")
    E.set_ylabel(r"crossover $\sigma^*$ (S < level)")
    spread = f"mean +- std, {n_seeds} seeds" if bars else f"mean of {n_seeds} seeds"
    E.set_title(f"(e) sigma* ({spread}) where >= half\nthe seeds cross inside the grid (grey: outside)",
                fontsize=9)
    legend_outside(E, fontsize=6, title=("no point:\n" + "\n".join(absent)) if absent else None, title_fontsize=6)
    # (f) frequency shift
    Fp = ax[1, 1]
    meas = _values(tree, "static", "frequency_shift")
    pred = _values(tree, "static", "frequency_shift_predicted")
    for m, fill in enumerate(("C0", "none")):
        for d in range(shifts.size):
            p, y = pred[m, d, sigma > 0].ravel(), meas[m, d, sigma > 0].ravel()
            Fp.plot(p, y, _MARKERS[d % 6], color=f"C{d}", mfc=fill if m else f"C{d}", ms=4)
    Fp.plot([], [], "ko", ms=4, label="lattice")
    Fp.plot([], [], "ko", mfc="none", ms=4, label="DpS")
    both = np.concatenate([pred[:, :, sigma > 0].ravel(), meas[:, :, sigma > 0].ravel()])
    both = both[np.isfinite(both)]
    r = float(np.max(np.abs(both))) * 1.05 if both.size else 1.0
    Fp.plot([-r, r], [-r, r], "-", color="0.5", lw=0.8, label="measured = first order")
    Fp.set_xlabel(r"first order $\sum w_n(\omega_n - 1)/\sum w_n$, over $\Delta$")
    Fp.set_ylabel(r"measured $(\omega_b - \omega_b^{hom}) / \Delta$")
    Fp.set_title("(f) static breather: frequency shift (colours: $\\Delta$)", fontsize=9)
    Fp.legend(fontsize=7, loc="upper left")
    # (g) fidelity series
    G = ax[1, 2]
    d = shifts.size // 2
    s = np.asarray(tree["s"].values, dtype=float)
    Fs = _values(tree, "wave", "fidelity")          # (model, shift, sigma, seed, s)
    for i, sg in enumerate(sigma):
        c = f"C{i % 10}"
        G.plot(s, np.nanmean(Fs[0, d, i], axis=0), "-", color=c, lw=1.0, label=rf"$\sigma$ = {sg:g}")
        G.plot(s, np.nanmean(Fs[1, d, i], axis=0), "--", color=c, lw=1.0)
    G.axhline(0.5, color="k", ls=":", lw=0.8)
    G.set_xlabel(r"t in slow periods $2\pi/\Delta$")
    G.set_ylabel("fidelity F (seed mean)")
    G.set_title(rf"(g) wave at $\Delta$ = {shifts[d]:g}: solid lattice, dashed DpS", fontsize=9)
    legend_outside(G, fontsize=7)
    # (h) mi break-up time
    H = ax[1, 3]
    tb = _values(tree, "mi", "saturation_time")
    pos = sigma > 0
    for dd, shift in enumerate(shifts):
        for m, fill in enumerate((f"C{dd}", "none")):
            mean, std = _stats(tb[m, dd][pos])
            H.errorbar(sigma[pos] / shift, mean, yerr=std if bars else None,
                       fmt=_MARKERS[dd % 6] + ("-" if m == 0 else "--"), color=f"C{dd}",
                       mfc=fill, ms=4, lw=0.8, capsize=2)
        h0 = tb[0, dd][sigma == 0]
        if np.isfinite(h0).any():
            H.axhline(float(np.nanmean(h0)), color=f"C{dd}", lw=0.6, ls="-.")
    H.axvline(1.0, color="0.5", lw=0.8)
    H.set_xscale("log")
    H.set_yscale("log")
    H.set_xlabel(r"$\sigma / \Delta$")
    H.set_ylabel(r"break-up time $t_b$ (slow periods)")
    H.set_title(f"(h) mi wave: break-up time, mean {'+- std ' if bars else ''}over {n_seeds} seeds\n"
                "(dash-dot: homogeneous lattice)", fontsize=9)
    return fig
