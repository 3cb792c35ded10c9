"""Figure mi-diagram: the growth-rate map of the DpS plane waves (ansatz3) and its direct checks, from
results/mi-diagram/mi-diagram.nc."""
from __future__ import annotations

from typing import TYPE_CHECKING

from cradle.figures import AnalysisTree, figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: finite points each data panel holds at least (tests/figures/test_figures_render.py): a (q, p) grid, a few runs
MIN_POINTS = 5


def draw(tree: AnalysisTree) -> Figure:
    """Growth-rate maps lambda tau0 R^(1-alpha) over (q, p) for each alpha, and the maximum over p.

    ``tree``: the mi-diagram file, thresholds at the root, groups /map and /checks."""
    ds, mp, chk = tree.to_dataset(), tree["map"], tree["checks"]
    alphas = ds["alpha"].values
    n = len(alphas)
    fig, ax = figure(1, n + 1, width=3.3 * (n + 1), height=3.4)
    q, p = mp["q"].values, mp["p"].values
    for ia, al in enumerate(alphas):
        A = ax[ia]
        G = mp["growth"].values[ia]
        # 181 x 361 cells: a raster inside the PDF (70 kB, not 3 MB of vector patches)
        m = A.pcolormesh(q, p, G.T, shading="auto", cmap="magma", rasterized=True)
        fig.colorbar(m, ax=A, shrink=0.85, label=r"growth $\lambda \tau_0 R^{1-\alpha}$")
        A.axvline(ds["q_threshold"].values[ia], color="w", ls="--", lw=0.8)
        A.plot(q, mp["argmax_p"].values[ia], "c-", lw=0.8)
        A.set_xlabel("q")
        A.set_ylabel("p")
        A.set_title(rf"$\alpha$ = {al:g}: $q_c$ = {ds['q_threshold'].values[ia]:.6f} (dashed)" "\n"
                    "cyan: the most unstable p", fontsize=9)
    B = ax[n]
    for ia, al in enumerate(alphas):
        B.plot(q, mp["max_growth"].values[ia], color=f"C{ia}", label=rf"$\alpha$ = {al:g}")
        B.plot(chk["q"].values[ia], chk["growth_simulated"].values[ia], "x", color=f"C{ia}", ms=6)
        B.plot(chk["q"].values[ia], chk["growth_theory"].values[ia], "o", mfc="none", color=f"C{ia}",
               ms=6)
    B.set_xlabel("q")
    B.set_ylabel(r"$\max_p \lambda \tau_0 R^{1-\alpha}$")
    B.set_title("max over p;\nx: DpS runs, o: theory at their (q, p)", fontsize=8)
    B.legend(fontsize=7)
    return fig
