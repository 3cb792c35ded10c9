"""Figure beyond the paper: lifetimes and frequency drift in the damped cradle (dissipation).

Drawn by :func:`draw` from results/dissipation/[full/]dissipation.nc (:mod:`cradle.analyses.dissipation`).

(a) the time to half the energy against the on-site gamma, log-log, every family: lattice (ncdamped) (filled),
    DpS (dpsdamped) (open), each family's markers smaller than the previous one's (they coincide on-site), the
    closed form ln 2 / gamma (lines, drawn down to the steel cradle's gamma, the vertical dash-dotted line, where
    its value is a star); (b) the same against the Kuwabara-Kono eta, the
    closed form of the plane waves (lines, one per wave; none for the breather); (c) the breather's frequency
    omega - 1 over time windows, on-site cases: lattice (markers), DpS (solid), the exact law of (dpsdamped)
    (dashed); (d) omega - 1 against the window's amplitude, every case, with the DpS breather law
    (omega_sw(0) - 1)(a / a(0))^(alpha-1).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.figures import AnalysisTree, figure, legend_outside

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

_MARKERS = ("o", "s", "^", "D")

#: the breather's frequency is drawn only over windows where its amplitude is above FLOOR times its initial one
FLOOR = 0.01

#: finite points each data panel holds at least (tests/figures/test_figures_render.py): a few damping values
MIN_POINTS = 2


def _shades(name: str, n: int) -> list:
    """n colours of a sequential colormap, from light to dark (its palest end left out)."""
    from matplotlib import colormaps

    return [colormaps[name](0.4 + 0.6 * k / max(1, n - 1)) for k in range(n)]


def _names(tree: AnalysisTree, key: str) -> list[str]:
    return [s.strip() for s in str(tree.attrs[key]).split(",")]


def _lifetimes(ax: Axes, tree: AnalysisTree, term: int, symbol: str, steel: float) -> None:
    lt = tree["lifetimes"]
    fams = _names(tree, "family_names")
    terms = np.asarray(lt["term_of_case"].values)
    m = terms == term
    values = np.asarray(lt["damping"].values)[m]
    lat = np.asarray(lt["lifetime_lattice"].values)[:, m, 0]
    dps = np.asarray(lt["lifetime_dps"].values)[:, m, 0]
    closed = np.asarray(lt["lifetime_closed"].values)[:, m, 0]
    steel_life = np.asarray(tree["steel"]["lifetime_closed_steel"].values)[:, term, 0]
    lo = min(values.min(), steel) / 2.0
    grid = np.geomspace(lo, values.max() * 1.5, 60)
    # a closed form the same for every family (on-site: ln 2 / gamma) is drawn once, in black
    shared = bool(np.isfinite(closed).all() and np.allclose(closed, closed[:1]))
    for jf, fam in enumerate(fams):
        c = f"C{jf}"
        # where the families' lifetimes coincide (on-site damping: ln 2 / gamma for every one) each family's
        # markers are smaller than the one's before, drawn over it: every marker stays in sight
        size = 5.0 + 3.0 * (len(fams) - 1 - jf)
        ax.loglog(values, lat[jf], _MARKERS[jf % 4], color=c, ms=size, label=f"{fam}: lattice (ncdamped)")
        ax.loglog(values, dps[jf], _MARKERS[jf % 4], color=c, ms=size + 4.0, mfc="none", mew=1.2,
                  label=f"{fam}: DpS (dpsdamped)")
        if shared:
            if jf == 0:
                xs, ys = np.concatenate([[steel], values]), np.concatenate([[steel_life[0]], closed[0]])
                ax.loglog(xs, ys, "-", color="k", lw=0.8, label="every family: closed form")
                ax.loglog([steel], [steel_life[0]], "*", color="k", ms=10,
                          label=f"every family: closed form at the steel cradle ({steel_life[0]:.2g})")
        elif np.isfinite(closed[jf]).all() and np.isfinite(steel_life[jf]):
            # the closed forms are powers of the damping (on-site: 1/gamma; contact: 1/Im kappa ~ alpha/eta),
            # drawn through the grid's values and the steel cradle's
            xs = np.concatenate([[steel], values])
            ys = np.concatenate([[steel_life[jf]], closed[jf]])
            order = np.argsort(xs)
            ax.loglog(xs[order], ys[order], ("-", "--", ":", "-.")[jf % 4], color=c, lw=0.8,
                      label=f"{fam}: closed form")
            ax.loglog([steel], [steel_life[jf]], "*", color=c, ms=10,
                      label=f"{fam}: closed form at the steel cradle ({steel_life[jf]:.2g})")
    ax.axvline(steel, color="0.3", ls="-.", lw=0.8, label=f"steel cradle: {symbol} = {steel:.2g}")
    ax.set_xlim(grid[0], grid[-1])
    ax.set_xlabel(symbol)
    ax.set_ylabel("time to half the energy (units 1/omega_0)")


def draw(tree: AnalysisTree) -> Figure:
    """The four panels above from the groups /lifetimes, /drift and /steel of the dissipation file."""
    fig, ax = figure(2, 2, width=12.0, height=8.4)
    st = tree["steel"]
    alpha = float(tree.attrs["alpha"])
    # (a), (b)
    _lifetimes(ax[0, 0], tree, 0, r"$\gamma$", float(st["gamma_steel"].values[0]))
    ax[0, 0].set_title("(a) on-site damping alone: closed form ln 2 / $\\gamma$ (exact for DpS)", fontsize=9)
    legend_outside(ax[0, 0], fontsize=6)
    _lifetimes(ax[0, 1], tree, 1, r"$\eta$", float(st["eta_steel"].values[0]))
    ax[0, 1].set_title("(b) Kuwabara-Kono damping alone: closed form for the plane waves\n"
                       "(steel: restitution assumed, docs/dissipation.md)", fontsize=9)
    legend_outside(ax[0, 1], fontsize=6)
    # (c), (d): the breather's frequency
    lt, dr = tree["lifetimes"], tree["drift"]
    terms = np.asarray(lt["term_of_case"].values)
    values = np.asarray(lt["damping"].values)
    w = float(tree.attrs["window_length"])
    mid = np.asarray(dr["window_start"].values) + 0.5 * w
    wl, wd = np.asarray(dr["omega_lattice"].values), np.asarray(dr["omega_dps"].values)
    wc = np.asarray(dr["omega_closed"].values)
    al, ad = np.asarray(dr["amplitude_lattice"].values), np.asarray(dr["amplitude_dps"].values)
    fams = _names(tree, "family_names")
    jb = fams.index("breather") if "breather" in fams else 0
    w0 = float(np.asarray(lt["omega0_family"].values)[jb])
    C, D = ax[1, 0], ax[1, 1]
    a0 = float(tree.attrs["breather_amplitude"])
    # below a hundredth of its initial amplitude the lattice's breather is lost in what it radiated
    keep_l, keep_d = al > FLOOR * a0, ad > FLOOR * a0
    shade = {0: _shades("Blues", int(np.sum(terms == 0))), 1: _shades("Reds", int(np.sum(terms == 1)))}
    colour = [shade[int(terms[kc])][int(np.sum(terms[:kc] == terms[kc]))] for kc in range(values.size)]
    for jc in np.flatnonzero(terms == 0):
        c = colour[jc]
        C.semilogy(mid[keep_l[jc]], wl[jc, keep_l[jc]] - 1.0, "o", color=c, ms=4, label=rf"$\gamma$ = {values[jc]:g}")
        C.semilogy(mid[keep_d[jc]], wd[jc, keep_d[jc]] - 1.0, "-", color=c, lw=1.0)
        C.semilogy(mid[keep_d[jc]], wc[jc, keep_d[jc]] - 1.0, "--", color="k", lw=0.7)
    C.plot([], [], "ko", ms=4, label="markers: lattice (ncdamped)")
    C.plot([], [], "k-", lw=1.0, label="solid: DpS (dpsdamped)")
    C.plot([], [], "k--", lw=0.7, label="dashed: exact law of (dpsdamped)")
    C.set_xlabel("window centre t")
    C.set_ylabel(r"breather frequency $\omega - 1$")
    C.set_title(f"(c) on-site damping, windows of {w:g} (amplitude > {FLOOR:g} a(0));\n"
                rf"dashed: $\omega - 1 = (\omega_{{sw}}(0) - 1)\, e^{{-(\alpha-1)\gamma t/2}}$", fontsize=9)
    legend_outside(C, fontsize=6)
    for kc in range(values.size):
        name = (r"$\gamma$" if terms[kc] == 0 else r"$\eta$") + f" = {values[kc]:g}"
        D.loglog(al[kc, keep_l[kc]], wl[kc, keep_l[kc]] - 1.0, _MARKERS[terms[kc] % 4], color=colour[kc], ms=4,
                 label=name)
        D.loglog(ad[kc, keep_d[kc]], wd[kc, keep_d[kc]] - 1.0, "x", color=colour[kc], ms=4)
    a = np.geomspace(FLOOR * a0, a0, 50)
    D.loglog(a, (w0 - 1.0) * (a / a0) ** (alpha - 1.0), "k-", lw=0.8,
             label=r"DpS breather: $(\omega_{sw}(0)-1)(a/a_0)^{\alpha-1}$")
    D.plot([], [], "ko", ms=4, label="lattice: circles on-site, squares contact")
    D.plot([], [], "kx", ms=4, label="crosses: DpS (dpsdamped)")
    D.set_xlabel("window mean amplitude a of the breather's largest bead")
    D.set_ylabel(r"breather frequency $\omega - 1$")
    D.set_title(f"(d) frequency against amplitude, every case (amplitude > {FLOOR:g} a(0))", fontsize=9)
    legend_outside(D, fontsize=6, ncol=1)
    return fig
