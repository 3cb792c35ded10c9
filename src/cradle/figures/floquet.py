"""Figure floquet: Bloch-Floquet stability of the exact travelling waves, from results/floquet/floquet.nc
(or results/floquet/full/floquet.nc; :mod:`cradle.analyses.floquet`).

(a) max over p of the growth rate against q, lattice (exact waves) and DpS, thresholds marked, the
    fftseuil wavenumbers 50, 51, 52 pi/100 shaded; (b) the lattice growth rate over (q, p), with the DpS
    unstable region outlined; (c) growth against p at the selected q, lattice solid, DpS dashed;
    (d) the lattice threshold against the amplitude (omega_tw - 1), tending to the DpS pi/2.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.figures import AnalysisTree, figure, legend_outside, plain_log_ticks

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: finite points each data panel holds at least (tests/figures/test_figures_render.py): the thresholds at two
#: amplitudes (the reduced form), a coarse (q, p) grid elsewhere
MIN_POINTS = 2


def _frac(q: float) -> str:
    return f"{q / np.pi:.3g}" + r"$\pi$"


def draw(tree: AnalysisTree) -> Figure:
    """The four panels above from the groups /sweep, /profiles, /thresholds of the floquet file."""
    fig, ax = figure(2, 2, width=10.0, height=7.6)
    ds, sweep, prof, thresholds = tree, tree["sweep"], tree["profiles"], tree["thresholds"]
    q, p = sweep["q"].values, sweep["p"].values
    qc = float(ds.attrs["q_threshold_lattice"])
    dq = float(ds.attrs["q_threshold_uncertainty"])
    om = float(ds.attrs["omega_tw"])
    # (a)
    A = ax[0, 0]
    A.plot(q / np.pi, sweep["max_growth"].values, "-", color="C0", label="lattice (exact waves, Bloch-Floquet)")
    A.plot(q / np.pi, sweep["max_growth_dps"].values, "--", color="C3", label="DpS, lattice time (R = a/2)")
    A.axvline(qc / np.pi, color="C0", lw=0.8, ls=":")
    A.axvline(0.5, color="C3", lw=0.8, ls=":")
    for qq in (0.50, 0.51, 0.52):
        A.axvline(qq, color="0.6", lw=0.5)
    A.set_xlabel(r"$q/\pi$")
    A.set_ylabel(r"max$_p$ growth rate (1/t)")
    A.set_title(rf"(a) $\omega_{{tw}}$ = {om:g}: $q_c$(lattice) = {qc / np.pi:.5f}$\pi$ $\pm$ {dq:.1g} rad," "\n"
                rf"$q_c$(DpS) = $\pi/2$ (dotted lines); grey: the q of fftseuil", fontsize=9)
    if np.isfinite(ds.attrs.get("q_dip", np.nan)):
        A.annotate(f"dip {ds.attrs['growth_dip']:.1g}", (ds.attrs["q_dip_over_pi"], 0.0), xytext=(0, 18),
                   textcoords="offset points", fontsize=6.5, ha="center", arrowprops={"arrowstyle": "->", "lw": 0.6})
    legend_outside(A)
    # (b)
    B = ax[0, 1]
    G = sweep["growth"].values
    mesh = B.pcolormesh(q / np.pi, p / np.pi, G.T, shading="nearest", cmap="viridis")
    fig.colorbar(mesh, ax=B, label="lattice growth rate (1/t)")
    Gd = sweep["growth_dps"].values
    if np.any(Gd > 0) and np.any(Gd <= 0):
        B.contour(q / np.pi, p / np.pi, (Gd > 0).T.astype(float), levels=[0.5], colors="w", linewidths=0.8,
                  linestyles="--")
    B.axvline(qc / np.pi, color="w", lw=0.6, ls=":")
    B.set_xlabel(r"$q/\pi$")
    B.set_ylabel(r"$p/\pi$")
    B.set_title("(b) lattice growth over (q, p); DpS unstable region dashed", fontsize=9)
    # (c)
    C = ax[1, 0]
    for i, qq in enumerate(prof["q"].values):
        C.plot(p / np.pi, prof["growth"].values[i], "-", color=f"C{i}", label=f"q = {_frac(qq)}")
        C.plot(p / np.pi, prof["growth_dps"].values[i], "--", color=f"C{i}", lw=0.8)
    C.set_xlabel(r"$p/\pi$")
    C.set_ylabel("growth rate (1/t)")
    C.set_title("(c) growth against p: lattice (solid), DpS (dashed)", fontsize=9)
    C.legend(fontsize=7)
    # (d)
    D = ax[1, 1]
    omt = thresholds["omega_tw"].values
    thr = thresholds["q_threshold"].values
    D.semilogx(omt - 1.0, thr / np.pi, "o-", color="C0", label="lattice threshold")
    D.axhline(0.5, color="C3", ls="--", lw=0.8, label=r"DpS: $\pi/2$")
    for x, y, pp in zip(omt - 1.0, thr / np.pi, thresholds["p_threshold"].values / np.pi, strict=True):
        D.annotate(f"p={pp:.2f}$\\pi$", (x, y), xytext=(0, 7), textcoords="offset points", fontsize=6.5,
                   ha="center")
    # a factor 3 of room on either side in log: the points and their labels stay inside the frame
    D.set_xlim((omt - 1.0).min() / 3, (omt - 1.0).max() * 3)
    D.set_ylim(min(thr.min() / np.pi, 0.5) - 0.005, 0.5 + 0.005)
    D.set_xlabel(r"$\omega_{tw} - 1$ (amplitude from (freq))")
    D.set_ylabel(r"$q_c/\pi$")
    D.set_title(r"(d) lattice threshold $\to \pi/2$ as the amplitude $\to 0$", fontsize=9)
    plain_log_ticks(D)
    D.legend(fontsize=7)
    lines = [f"small amplitude (omega_tw = {ds.attrs['small_omega_tw']:g}): |lattice/DpS - 1| <= "
             f"{ds.attrs['small_max_rel_error']:.2g}",
             f"ring N = {ds.attrs['ring_N']}: |mu_monodromy - mu_Bloch| <= {ds.attrs['ring_multiplier_distance']:.1g}",
             f"direct run: rate {ds.attrs['direct_rate_mode']:.4g} vs Floquet {ds.attrs['direct_rate_floquet']:.4g}"]
    # below the panel: inside it the note would cover threshold points
    D.text(0.0, -0.22, "\n".join(lines), transform=D.transAxes, fontsize=6.5, va="top")
    return fig
