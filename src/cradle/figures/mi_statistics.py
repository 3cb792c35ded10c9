"""Figure mi-statistics: the modulational-instability threshold over noise seeds, ring sizes and both models
(the fftseuil experiment repeated), from results/mi-statistics/[full/]mi-statistics.nc
(:mod:`cradle.analyses.mi_statistics`)."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.figures import MODEL_STYLE, AnalysisTree, figure, legend_outside

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: finite points each data panel holds at least (tests/figures/test_figures_render.py): a few q of the sweep
MIN_POINTS = 5


def draw(tree: AnalysisTree) -> Figure:
    """Fraction of unstable seeds and crossing-time distributions against q, per N, both models.

    ``tree``: the mi-statistics file, the summary per q at the root and every run in /runs."""
    ds, runs = tree.to_dataset(), tree["runs"]
    Ns = [int(n) for n in ds["N"].values]
    models = [str(m) for m in ds["model"].values]
    q = ds["q"].values / np.pi
    qc = float(ds.attrs.get("dps_threshold_linear_theory", np.pi / 2)) / np.pi
    fig, ax = figure(2, len(Ns), width=4.6 * len(Ns), height=6.4)
    ax = np.asarray(ax).reshape(2, len(Ns))
    off = {"exact": -0.15, "dps": 0.15}
    dq = np.min(np.diff(q)) if q.size > 1 else 0.01
    for c, N in enumerate(Ns):
        A, B = ax[0, c], ax[1, c]
        for j, m in enumerate(models):
            st = MODEL_STYLE[m]
            f = ds["fraction_unstable"].values[c, j]
            lo, hi = ds["fraction_low"].values[c, j], ds["fraction_high"].values[c, j]
            A.errorbar(q + off[m] * dq, f, yerr=[f - lo, hi - f], fmt=st["marker"] + "-", color=st["color"], ms=4,
                       lw=0.8, capsize=2, label=st["label"])
            th = ds["threshold"].values[c, j] / np.pi
            tl, thh = ds["threshold_low"].values[c, j] / np.pi, ds["threshold_high"].values[c, j] / np.pi
            if np.isfinite(th):
                A.axvline(th, color=st["color"], lw=1.0, ls=":")
                A.axvspan(tl if np.isfinite(tl) else q[0], thh if np.isfinite(thh) else q[-1], color=st["color"],
                          alpha=0.12)
            tc = runs["crossing_time"].values[c, j]
            for iq in range(q.size):
                y = tc[iq][np.isfinite(tc[iq])]
                B.plot(np.full(y.size, q[iq] + off[m] * dq), y, st["marker"], color=st["color"], ms=2.5, alpha=0.5,
                       label=st["label"] if iq == 0 else None)
            B.plot(q + off[m] * dq, ds["median_crossing_time"].values[c, j], "-", color=st["color"], lw=1.0)
        for P in (A, B):
            P.axvline(qc, color="k", ls="--", lw=0.8)
            P.set_xlabel(r"$q/\pi$", fontsize=8)
        A.text(qc, 1.02, r" $q_c=\pi/2$ (DpS linear)", fontsize=6, va="bottom")
        A.set_ylim(-0.05, 1.12)
        A.set_ylabel(f"fraction unstable (Wilson 95 %), {runs['seed'].size} seeds", fontsize=8)
        lines = []
        for j, m in enumerate(models):
            th = ds["threshold"].values[c, j] / np.pi
            lines.append(f"{m}: q_th = {th:.4f} pi in [{ds['threshold_low'].values[c, j] / np.pi:.3f}, "
                         f"{ds['threshold_high'].values[c, j] / np.pi:.3f}] pi")
        A.set_title(f"N = {N}: ratio reaches {ds.attrs['fraction']:g} by t = {ds.attrs['t_end']:g}\n"
                    + "\n".join(lines), fontsize=7)
        legend_outside(A, fontsize=6)
        B.set_ylabel("crossing time t (line: median)", fontsize=8)
        B.set_ylim(0.0, float(ds.attrs["t_end"]) * 1.02)
        B.set_xlim(A.get_xlim())
        legend_outside(B, fontsize=6)
    return fig
