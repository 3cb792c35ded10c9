"""Figure beyond the paper: the solitary wave of the Hertz chain and a desk toy's first impact (solitary-wave).

Drawn by :func:`draw` from results/solitary-wave/[full/]solitary-wave.nc (:mod:`cradle.analyses.solitary_wave`).

(a) the exact wave's strain R / R_m and velocity v / v_m against xi (sites), Nesterenko's cos^4 at the same R_m;
(b) its tail: log10(-log R) against xi from xi = 2, the Fourier solution and its continuation, and the line of
slope log10(3/2) of a doubly exponential decay; (c) speed against velocity amplitude in the cradle (SI), log-log:
the exact law c_1 (v_m / v_1)^(1/5), Nesterenko's (16/25)^(1/5) v_m^(1/5), and the pulse measured on each inner
ball of each chain (its peak velocity and local speed); (d) each ball's velocity against time after the impact, in
the desk toy and the longest line; (e) the local pulse speed (m/s) on each ball against the exact wave's speed at
the ball's peak velocity (the first and last inner balls feel the impact and the free end); (f) the pulse's width
(cm) against the exact wave's velocity FWHM.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from cradle.figures import AnalysisTree, figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: finite points each data panel holds at least (tests/figures/test_figures_render.py)
MIN_POINTS = 3


def _impacts(tree: AnalysisTree) -> list[tuple[str, Any]]:
    names = [s.strip() for s in str(tree.attrs["impacts"]).split(",") if s.strip()]
    return [(name, tree[f"impact/{name}"]) for name in names]


def draw(tree: AnalysisTree) -> Figure:
    """The six panels above."""
    fig, ax = figure(2, 3, width=13.5, height=7.6)
    wave = tree["wave"]
    xi = np.asarray(wave["xi"].values)
    R = np.asarray(wave["strain"].values)
    v = np.asarray(wave["velocity"].values)
    Rn = np.asarray(wave["strain_nesterenko"].values)
    show = np.abs(xi) <= 5.0

    a = ax[0, 0]
    a.plot(xi[show], R[show] / R.max(), "C0-", lw=1.6, label="strain $R/R_m$ (exact)")
    a.plot(xi[show], v[show] / v.max(), "C1-", lw=1.2, label="velocity $v/v_m$ (exact)")
    a.plot(xi[show], Rn[show] / Rn.max(), "k--", lw=1.0, label="Nesterenko $\\cos^4(\\sqrt{2/5}\\,\\xi)$")
    a.set_xlabel("$\\xi = n - ct$ (sites)")
    a.set_ylabel("relative to the peak")
    a.set_title("(a) exact solitary wave of the Hertz chain", fontsize=9)
    a.legend(fontsize=7, loc="upper left")
    a.set_ylim(-0.03, 1.25)

    b = ax[0, 1]
    tail = tree["tail"]
    xt = np.asarray(tail["xi_tail"].values)
    logR = np.asarray(tail["log_strain"].values)
    core = (xi >= 2.0) & (R >= 1e-15 * R.max())   # -ln R > 0 there (R_m > 1 at c = 1), above the rounding
    b.plot(xi[core], np.log10(-np.log(R[core])), "C0-", lw=1.6, label="Fourier solution (above 1e-15 $R_m$)")
    b.plot(xt, np.log10(-logR), "C3--", lw=1.2, label="continued in real space")
    x0 = xt[-1]
    y0 = np.log10(-logR[-1])
    ref = np.linspace(xt[0], x0, 20)
    b.plot(ref, y0 + np.log10(1.5) * (ref - x0), "k:", lw=1.0, label="slope $\\log_{10}(3/2)$: $-\\log R \\propto "
           "(3/2)^{\\xi}$")
    b.set_xlabel("$\\xi$ (sites)")
    b.set_ylabel("$\\log_{10}(-\\ln R)$")
    b.set_title("(b) doubly exponential tail", fontsize=9)
    b.legend(fontsize=7, loc="upper left")

    c = ax[0, 2]
    law = tree["law"]
    vl = np.asarray(law["v_m"].values)
    c.loglog(vl, np.asarray(law["speed_exact"].values), "C0-", lw=1.4,
             label=f"exact: $\\propto v_m^{{1/5}}$ (fitted {float(tree.attrs['speed_exponent']):.10f})")
    c.loglog(vl, np.asarray(law["speed_nesterenko"].values), "k--", lw=1.0,
             label="Nesterenko $(16/25)^{1/5} v_m^{1/5}$")
    c.set_xlabel("velocity amplitude $v_m$ (m/s)")
    c.set_ylabel("speed (m/s)")
    c.set_title("(c) speed against amplitude in the cradle", fontsize=9)
    impacts = _impacts(tree)
    d, e, f = ax[1, 0], ax[1, 1], ax[1, 2]
    styles = ("-", "--", ":", "-.")
    for k, (_name, g) in enumerate(impacts):
        t = np.asarray(g["t_stored"].values) * 1e6
        V = np.asarray(g["v"].values)
        N = V.shape[1]
        beads = range(N) if N <= 6 else range(0, N, max(1, N // 6))
        for n in beads:
            d.plot(t, V[:, n], styles[k % 4], color=f"C{n % 10}", lw=1.0)
        bead = np.asarray(g["bead"].values)
        inner = slice(1, N - 1)
        e.plot(bead[inner], np.asarray(g["speed"].values)[inner], styles[k % 4], marker="o", ms=3, color=f"C{k}",
               label=f"{N} balls: measured")
        e.plot(bead[inner], np.asarray(g["speed_exact"].values)[inner], styles[k % 4], marker="x", ms=4,
               color="0.3", lw=0.6, label=f"{N} balls: exact wave at the ball's $v_{{peak}}$")
        f.plot(bead[inner], np.asarray(g["width"].values)[inner] * 100, styles[k % 4], marker="o", ms=3,
               color=f"C{k}", label=f"{N} balls")
        # each chain's circles smaller than the previous one's, drawn above them: a short chain's pulses sit where
        # the first balls of a longer one do, and stay in sight
        c.loglog(np.asarray(g["v_peak"].values)[inner], np.asarray(g["speed"].values)[inner], "o",
                 ms=max(6.0 - 2.5 * k, 2.5), mfc="none", color=f"C{k}", zorder=3 + k,
                 label=f"{N} balls: pulse on each inner ball")
    D = float(impacts[0][1].attrs["diameter_m"])
    quantities = [str(q) for q in np.asarray(tree["nesterenko"]["quantity"].values)]
    vel_fwhm = float(np.asarray(tree["nesterenko"]["exact"].values)[quantities.index("velocity FWHM (sites)")])
    f.axhline(vel_fwhm * D * 100, color="k", ls=":", lw=1.0, label="exact wave: velocity FWHM")
    name, g = impacts[0]
    d.set_title(f"(d) ball velocities after the impact at {float(g.attrs['impact_speed_m_per_s']):.3f} m/s "
                "(solid: first chain)", fontsize=9)
    d.set_xlabel("time since impact (µs)")
    d.set_ylabel("velocity (m/s)")
    from matplotlib.lines import Line2D

    keys = [Line2D([], [], color="0.2", ls=styles[k % 4], label=f"{nm}") for k, (nm, _) in enumerate(impacts)]
    d.legend(handles=keys, fontsize=7, loc="upper center", title="chain (colour: ball)", title_fontsize=7)
    from matplotlib.ticker import MaxNLocator

    for axis in (e, f):
        axis.xaxis.set_major_locator(MaxNLocator(integer=True))
    c.legend(fontsize=7, loc="upper left")
    e.set_title("(e) local pulse speed on each ball", fontsize=9)
    e.set_xlabel("ball n")
    e.set_ylabel("speed (m/s)")
    e.legend(fontsize=7, loc="lower center")
    f.set_title("(f) pulse width on each ball", fontsize=9)
    f.set_xlabel("ball n")
    f.set_ylabel("FWHM of $v_n(t)$ × speed (cm)")
    f.legend(fontsize=7, loc="lower center")
    fig.suptitle(f"The solitary wave of the Hertz chain and the first impact of a desk toy: {tree.attrs['cradle']}, "
                 f"released from {float(tree.attrs['angle_deg']):g}°", fontsize=10)
    return fig
