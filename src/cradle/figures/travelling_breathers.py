"""Figure beyond the paper: travelling breathers of the DpS equation (travelling-breathers).

Drawn by :func:`draw` from results/travelling-breathers/[full/]travelling-breathers.nc
(:mod:`cradle.analyses.travelling_breathers`).

(a) |A_n(0)| (log scale) of the slowest, a middle and the fastest member, and the static site breather at the
same norm; (b) the tail (max |A_n| on the far quarter ring / max |A_n|) against c, on the ring of N sites and of
check_N sites; (c) H against c at fixed norm (dH/dc > 0: H rises with c where it does); (d) the growth rate
ln max|mu| / T of the non-trivial multipliers modulo shift against c (the stability threshold dashed; unstable
members filled), on the two rings and at check_rtol; (e) the multipliers modulo shift of the most unstable member
and of the slowest, with the unit circle; (f) the distance of |A_n(tau)| to the static site and bond breathers
against c; (g)-(i) the exact TBs of the lattice (nc) (issue 37, item 2): their |xi_n| against the DpS member's
ansatz, their tails and distances to it against the lattice's velocity, their multipliers modulo shift.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.figures import AnalysisTree, figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: finite points each data panel holds at least (tests/figures/test_figures_render.py)
MIN_POINTS = 3


def draw(tree: AnalysisTree) -> Figure:
    """The six panels above, and (g)-(i) when the file holds the lattice's TBs (key ``lattice``)."""
    lattice = "lattice" in tree.children
    fig, ax = figure(3, 3, width=13.5, height=11.4) if lattice else figure(2, 3, width=13.5, height=7.6)
    fam = tree["family"]
    c = np.asarray(fam["c"].values)
    prof = tree["profiles"]
    A = np.asarray(prof["A_re"].values) + 1j * np.asarray(prof["A_im"].values)
    n = np.asarray(prof["n"].values)
    N = n.size
    attrs = tree.attrs
    thr = float(attrs["stability_threshold"])
    check_N = int(attrs["check_N"])

    a = ax[0, 0]
    picks = sorted({0, len(c) // 2, len(c) - 1})
    # the frame reaches below the smallest tail shown (the TBs' tails are everywhere above rounding)
    bottom = 0.2 * float(np.min(np.abs(A[picks])))
    for k, i in enumerate(picks):
        a.semilogy(n, np.abs(A[i]), "o-", color=f"C{k}", ms=3, lw=1.0, label=f"TB, c = {c[i]:.3g}")
    phi = np.abs(np.asarray(prof["static_site"].values))
    shift = int(np.argmax(np.abs(A[picks[0]]))) - int(np.argmax(phi))
    static = np.roll(phi, shift)
    a.semilogy(n, np.where(static >= bottom, static, np.nan), "k--", lw=1.0, label="static site breather")
    a.set_ylim(bottom, 2.0)
    a.set_xlabel("site n")
    a.set_ylabel("$|A_n(0)|$")
    a.set_title(f"(a) profiles at norm {float(attrs['norm']):g} (ring of {N})", fontsize=9)
    a.legend(fontsize=7, loc="upper left")

    b = ax[0, 1]
    b.semilogy(c, fam["tail"].values, "C0o-", ms=4, label=f"ring of {N}")
    b.semilogy(c, fam["tail_N"].values, "C1s--", ms=3, mfc="none", label=f"ring of {check_N}")
    b.set_xlabel("velocity c (sites per unit $\\tau$)")
    b.set_ylabel("tail: max far $|A_n|$ / max $|A_n|$")
    b.set_title("(b) oscillatory tail against c", fontsize=9)
    b.legend(fontsize=7, loc="lower right")

    d = ax[0, 2]
    d.plot(c, fam["energy"].values, "C2o-", ms=4)
    d.set_xlabel("velocity c")
    d.set_ylabel("H (DpS Hamiltonian)")
    d.set_title(f"(c) H at fixed norm; dH/dc changes sign at: {attrs['dH_dc_sign_changes']}", fontsize=9)

    e = ax[1, 0]
    g = np.asarray(fam["growth_rate"].values)
    floor = thr / 100.0
    un = np.asarray(fam["unstable"].values) == 1
    e.semilogy(c, np.maximum(g, floor), "C3-", lw=1.0)
    e.semilogy(c[un], np.maximum(g[un], floor), "C3o", ms=6, label=f"ring of {N}: unstable")
    e.semilogy(c[~un], np.maximum(g[~un], floor), "C3o", ms=6, mfc="none", label=f"ring of {N}: stable")
    e.semilogy(c, np.maximum(np.asarray(fam["growth_rate_N"].values, float), floor), "C1s", ms=4, mfc="none",
               label=f"ring of {check_N}")
    e.semilogy(c, np.maximum(np.asarray(fam["growth_rate_rtol"].values, float), floor), "k+", ms=6,
               label=f"rtol {float(attrs['check_rtol']):g}")
    e.axhline(thr, color="0.4", ls="--", lw=0.8, label="stability threshold")
    e.set_ylim(floor / 2, 300.0 * max(float(np.nanmax(g)), float(np.nanmax(fam["growth_rate_N"].values)), thr))
    e.set_xlabel("velocity c")
    e.set_ylabel(f"growth rate ln max$|\\mu|$ / T (floor {floor:g})")
    e.set_title("(d) multipliers modulo shift: growth rate", fontsize=9)
    e.legend(fontsize=6.5, loc="upper left", ncol=2)

    f = ax[1, 1]
    mu = np.asarray(tree["multipliers"]["mu_re"].values) + 1j * np.asarray(tree["multipliers"]["mu_im"].values)
    t = np.linspace(0, 2 * np.pi, 400)
    f.plot(np.cos(t), np.sin(t), color="0.6", lw=0.8, label="unit circle")
    iw = int(np.nanargmax(g))
    f.plot(mu[0].real, mu[0].imag, "C0o", ms=5, mfc="none", label=f"c = {c[0]:.3g}")
    f.plot(mu[iw].real, mu[iw].imag, "C3x", ms=5, label=f"c = {c[iw]:.3g} (largest growth)")
    f.set_aspect("equal")
    f.set_xlim(-1.35, 1.35)
    f.set_ylim(-1.35, 1.6)
    f.set_xlabel("Re $\\mu$")
    f.set_ylabel("Im $\\mu$")
    f.set_title("(e) Floquet multipliers modulo shift", fontsize=9)
    f.legend(fontsize=7, loc="upper center", ncol=3, handlelength=1.0, columnspacing=0.8)

    h = ax[1, 2]
    h.loglog(c, fam["static_distance_site"].values, "C0o-", ms=4, label="to the site breather")
    h.loglog(c, fam["static_distance_bond"].values, "C1s--", ms=4, label="to the bond breather")
    from matplotlib.ticker import FixedLocator, NullFormatter

    h.xaxis.set_major_locator(FixedLocator([float(x) for x in c[:: max(1, len(c) // 5)]]))
    h.xaxis.set_major_formatter(lambda x, _: f"{x:g}")
    h.xaxis.set_minor_formatter(NullFormatter())
    h.set_xlabel("velocity c")
    h.set_ylabel("distance to the static profile (relative)")
    h.set_title(f"(f) min over a period of max$_n$ $||A_n| - \\phi_n|$ / max $\\phi$; "
                f"$\\propto c^{{{float(attrs['static_distance_power']):.2f}}}$", fontsize=9)
    h.legend(fontsize=7, loc="lower right")
    if lattice:
        _lattice_panels(tree, ax[2])
    return fig


def _lattice_panels(tree: AnalysisTree, ax: np.ndarray) -> None:
    """(g) |xi_n(0)| of the lattice's TBs and eps |A_n| of the DpS source member (aligned on the peak); (h) their
    tails and distances to the ansatz against the lattice's velocity; (i) the multipliers modulo shift of the
    slowest and the fastest lattice member."""
    lat, st = tree["lattice"], tree["lattice_states"]
    c = np.asarray(lat["c_lattice"].values)
    xi = 0.5 * (np.asarray(st["x"].values) - 1j * np.asarray(st["v"].values))
    A = np.asarray(st["source_A_re"].values) + 1j * np.asarray(st["source_A_im"].values)
    n = np.asarray(st["site"].values)
    eps = np.asarray(lat["eps"].values)
    g = ax[0]
    bottom = 0.2 * float(np.min(np.abs(xi)))
    for k, i in enumerate(sorted({0, len(c) - 1})):
        g.semilogy(n, np.abs(xi[i]), "o-", color=f"C{k + 4}", ms=3, lw=1.0, label=f"(nc) TB, c = {c[i]:.4g}")
    dps = np.roll(eps[0] * np.abs(A), int(np.argmax(np.abs(xi[0]))) - int(np.argmax(np.abs(A))))
    g.semilogy(n, np.where(dps >= bottom, dps, np.nan), "k--", lw=1.0,
               label=f"DpS TB c = {float(tree.attrs['lattice_source_c']):.3g}, $\\varepsilon$ = {eps[0]:.3g}")
    g.set_ylim(bottom, 5.0 * float(np.max(np.abs(xi))))
    g.set_xlabel("site n")
    g.set_ylabel("$|\\xi_n(0)|$, $\\xi_n = (x_n - i v_n)/2$")
    g.set_title(f"(g) exact TBs of (nc), ring of {n.size}", fontsize=9)
    g.legend(fontsize=7, loc="upper left")

    h = ax[1]
    h.semilogy(c, lat["tail"].values, "C4o-", ms=4, label="tail: max far $|\\xi_n|$ / max $|\\xi_n|$")
    h.semilogy(c, lat["ansatz_distance"].values, "C5s--", ms=4, label="distance to the DpS TB's ansatz")
    h.semilogy(c, lat["residual"].values, "k+", ms=6, label="shift-map residual")
    h.set_ylim(None, 3.0)
    h.set_xlabel("lattice velocity c = 1/T (sites per unit t)")
    h.set_ylabel("relative to the peak")
    h.set_title("(h) (nc) TBs: tail and distance to DpS", fontsize=9)
    h.legend(fontsize=7, loc="center right")

    i_ = ax[2]
    mu = np.asarray(st["mu_re"].values) + 1j * np.asarray(st["mu_im"].values)
    t = np.linspace(0, 2 * np.pi, 400)
    i_.plot(np.cos(t), np.sin(t), color="0.6", lw=0.8, label="unit circle")
    i_.plot(mu[0].real, mu[0].imag, "C4o", ms=5, mfc="none", label=f"c = {c[0]:.4g}")
    i_.plot(mu[-1].real, mu[-1].imag, "C5x", ms=5, label=f"c = {c[-1]:.4g}")
    i_.set_aspect("equal")
    i_.set_xlim(-1.35, 1.35)
    i_.set_ylim(-1.35, 1.6)
    i_.set_xlabel("Re $\\mu$")
    i_.set_ylabel("Im $\\mu$")
    rate = float(np.max(lat["growth_rate"].values))
    i_.set_title(f"(i) (nc) multipliers modulo shift (max growth {rate:.2g})", fontsize=9)
    i_.legend(fontsize=7, loc="upper center", ncol=3, handlelength=1.0, columnspacing=0.8)

