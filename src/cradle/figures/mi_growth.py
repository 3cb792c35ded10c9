"""Figure mi-growth: the modulational-instability growth rates measured in the scenes' runs (exact (nc) and
DpS (dfnls)) against the linear DpS theory (ansatz3), from results/mi-growth/mi-growth.nc."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.figures import MODEL_STYLE, AnalysisTree, figure, legend_outside

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: finite points each data panel holds at least (tests/figures/test_figures_render.py): the sideband spectrum of a scene
MIN_POINTS = 5


def draw(tree: AnalysisTree) -> Figure:
    """Per scene: linear DpS rate against p with the measured rates; the fitted series; the growth-rate diagram.

    ``tree``: the mi-growth file, one row per scene and model at the root, groups /sidebands, /series
    and /theory."""
    ds, sb, series, theory = tree.to_dataset(), tree["sidebands"], tree["series"], tree["theory"]
    names = [str(s) for s in ds["scene"].values]
    S = len(names)
    models = [str(m) for m in ds["model"].values]
    ncol = 4
    nrow = int(np.ceil((S + 2) / ncol))
    fig, ax = figure(nrow, ncol, width=3.2 * ncol, height=2.9 * nrow)
    ax = np.atleast_1d(ax).ravel()
    alpha = float(ds.attrs["alpha"])
    for i, name in enumerate(names):
        A = ax[i]
        p = sb["p"].values[i]
        ok = np.isfinite(p)
        A.plot(p[ok] / np.pi, sb["growth_theory"].values[i][ok], "k-", lw=1.2, label="linear DpS")
        for j, m in enumerate(models):
            st = MODEL_STYLE[m]
            A.plot(p[ok] / np.pi, sb["growth"].values[i, j][ok], st["marker"], color=st["color"], ms=2.5,
                   alpha=0.6, label=st["label"])
            ps = ds["p_star"].values[i, j] / np.pi
            A.plot([ps], [ds["growth"].values[i, j]], st["marker"], color=st["color"], ms=9, mew=2)
        A.axhline(0.0, color="0.7", lw=0.6)
        q = float(ds["q"].values[i])
        lines = [f"{m}: {ds['growth'].values[i, j]:.4f} vs {ds['growth_theory'].values[i, j]:.4f}"
                 + ("" if ds["exponential"].values[i, j] else " (no exp. phase)") for j, m in enumerate(models)]
        # the measured rates in the title: a note inside the panel would cover sideband points
        A.set_title(f"{name}: q = {q / np.pi:.2f}$\\pi$, N = {int(ds['N'].values[i])}\n"
                    "measured vs theory at p*: " + "\n".join(lines), fontsize=6.5)
        A.set_xlabel(r"$p/\pi$", fontsize=8)
        A.set_ylabel("growth rate per unit t", fontsize=8)
        # every point of the panel inside its frame: the sidebands' measured rates can exceed the fitted ones
        top = np.nanmax([np.nanmax(sb["growth_theory"].values[i]), np.nanmax(ds["growth"].values[i]),
                         np.nanmax(sb["growth"].values[i])])
        A.set_ylim(-0.6 * top if top > 0 else -0.01, 1.5 * top if top > 0 else 0.01)
        A.set_xlim(-0.04, 1.04)
        if i == 0:   # above the sidebands beyond the band, which lie near 0 (the headroom of set_ylim)
            A.legend(fontsize=6, loc="upper right")
    # the fitted series
    B = ax[S]
    t = series["t"].values
    for i, name in enumerate(names):
        for j, m in enumerate(models):
            y = series["pair"].values[i, j]
            ls = "-" if m == "exact" else "--"
            B.semilogy(t, y, ls, color=f"C{i}", lw=0.8, label=name if j == 0 else None)
            ta, tb = ds["window_start"].values[i, j], ds["window_end"].values[i, j]
            sel = (t >= ta) & (t <= tb)
            B.semilogy(t[sel], y[sel], ls, color=f"C{i}", lw=2.2)
    B.axhline(float(ds.attrs["saturation"]), color="k", lw=0.6, ls=":")
    B.set_xlabel("t", fontsize=8)
    B.set_ylabel(r"$S_{p^*}(t)$ (thick: fit window)", fontsize=8)
    B.set_title("sideband pair / carrier: exact solid, DpS dashed", fontsize=8)
    B.legend(fontsize=5.5, loc="upper left", ncols=2)   # two columns: short, above the curves' early growth
    # the growth-rate diagram: max_p lambda tau0 R^(1-alpha) against q, measured points rescaled
    C = ax[S + 1]
    C.plot(theory["q"].values / np.pi, theory["max_growth"].values, "k-", lw=1.2,
           label=r"$\max_p$ linear DpS")
    scale = ds["growth_scale"].values      # per unit t -> lambda tau0 R^(1-alpha)
    for j, m in enumerate(models):
        st = MODEL_STYLE[m]
        C.plot(ds["q"].values / np.pi, ds["growth"].values[:, j] * scale, st["marker"], color=st["color"],
               ms=7, mew=1.5, ls="none", label=f"measured, {st['label']}")
        C.plot(ds["q"].values / np.pi, ds["growth_theory"].values[:, j] * scale, "s", mfc="none",
               color=st["color"], ms=7, ls="none", label=f"theory at the p* of {m}")
    C.axvline(0.5, color="0.5", ls="--", lw=0.8)
    C.set_xlabel(r"$q/\pi$", fontsize=8)
    C.set_ylabel(r"$\lambda \tau_0 R^{1-\alpha}$", fontsize=8)
    C.set_title(rf"growth-rate diagram ($\alpha$ = {alpha:g});" "\n" r"$q_c = \pi/2$ dashed", fontsize=8)
    legend_outside(C, fontsize=5.5)
    for k in range(S + 2, ax.size):
        ax[k].set_visible(False)
    return fig


