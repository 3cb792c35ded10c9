"""Figure beyond the paper: how long and how well DpS describes the lattice (dps-validity).

Drawn by :func:`draw` from results/dps-validity/[full/]dps-validity.nc (:mod:`cradle.analyses.dps_validity`).

(a) the relative sup-norm error against eps at T = 1, every family, at the reference alpha (1.5 when
    computed), with the law eps^(alpha-1) dotted; (b) the relative error against T for the noisy
    unstable wave, one curve per eps (the colour bar): parallel (spaced by eps^(alpha-1)) while the law holds, bent
    to the O(1) ceiling where the instability has amplified the mismatch (dashed: the level called
    lost); (c) the power of eps fitted over the smaller half of each range against T, every family
    and alpha, with its standard error, the consistency order alpha as horizontal lines; (d) the
    relative error against eps at T = 1 for every alpha (q = pi/5 wave).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from cradle.figures import AnalysisTree, figure, legend_outside

if TYPE_CHECKING:
    from matplotlib.colors import Colormap
    from matplotlib.figure import Figure

_MARKERS = ("o", "s", "^", "D", "v", "P")

#: finite points each data panel holds at least (tests/figures/test_figures_render.py): a few eps and T
MIN_POINTS = 3


def _reference_alpha(alphas: ArrayLike) -> int:
    near = np.abs(np.asarray(alphas) - 1.5)
    return int(np.argmin(near))


def _k_of(Ts: ArrayLike, T: float = 1.0) -> int:
    """Index of the stored slow time closest to T (the theorem's fixed T)."""
    return int(np.argmin(np.abs(np.log(np.asarray(Ts) / T))))


def draw(tree: AnalysisTree) -> Figure:
    """The four panels above from the groups /errors and /fits of the dps-validity file."""
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import LogNorm

    fig, ax = figure(2, 2, width=10.0, height=7.6)
    err, fits, checks = tree["errors"], tree["fits"], tree["checks"]
    fams = [s.strip() for s in str(tree.attrs["family_names"]).split(",")]
    alphas = np.asarray(err["alpha"].values, dtype=float)
    Ts = np.asarray(err["T"].values, dtype=float)
    eps = np.asarray(err["eps"].values)          # (alpha, i_eps)
    rel = np.asarray(err["rel_error"].values)    # (family, alpha, i_eps, T)
    p, se = np.asarray(fits["exponent"].values), np.asarray(fits["exponent_stderr"].values)
    ps, pse = np.asarray(fits["exponent_small"].values), np.asarray(fits["exponent_small_stderr"].values)
    ia, k1 = _reference_alpha(alphas), _k_of(Ts)
    al = alphas[ia]
    lost = float(tree.attrs.get("lost_level", 0.5))
    # (a)
    A = ax[0, 0]
    for jf, fam in enumerate(fams):
        # each family drawn thinner than the one before: two that coincide (a wave and the same wave with a
        # little noise) both stay in sight
        A.loglog(eps[ia], rel[jf, ia, :, k1], "-" + _MARKERS[jf % 6], ms=max(7.0 - 1.5 * jf, 2.5),
                 lw=max(2.6 - 0.6 * jf, 0.8), label=f"{fam}: p = {p[jf, ia, k1]:.3f} $\\pm$ {se[jf, ia, k1]:.3f}")
    ref = rel[0, ia, 0, k1] * (eps[ia] / eps[ia, 0]) ** (al - 1.0)
    A.loglog(eps[ia], ref, ":", color="0.3", label=r"$\propto \varepsilon^{\alpha-1}$")
    A.set_xlabel(r"$\varepsilon$")
    A.set_ylabel(r"sup$_t$ max$_n |x_n - x_n^{app}|$ / $2\varepsilon$")
    A.set_title(rf"(a) $\alpha$ = {al:g}, $t \leq T \varepsilon^{{1-\alpha}}$, T = {Ts[k1]:g}" "\n"
                "(p: fitted power of the absolute error)", fontsize=9)
    legend_outside(A)
    # (b)
    B = ax[0, 1]
    jf = fams.index("mi-4pi5-noise") if "mi-4pi5-noise" in fams else 0
    cmap = _cmap()
    # one curve per eps, coloured by log eps (the eps are log-spaced): the colour bar names every curve
    norm = LogNorm(vmin=float(eps[ia].min()), vmax=float(eps[ia].max()))
    for ie in range(eps.shape[1]):
        B.semilogy(Ts, rel[jf, ia, ie], "-o", ms=3, color=cmap(norm(eps[ia, ie])))
    B.axhline(lost, color="0.3", lw=0.7, ls="--")
    bar = B.figure.colorbar(ScalarMappable(norm=norm, cmap=cmap), ax=B, pad=0.02)
    bar.set_label(r"$\varepsilon$ (one curve each)", fontsize=8)
    bar.set_ticks(eps[ia], labels=[f"{e:.0e}" for e in eps[ia]])
    bar.ax.tick_params(labelsize=7)
    g = float(fits["dps_growth_rate"].values[jf, ia])
    B.set_xlabel(r"slow time T = $\varepsilon^{\alpha-1} t$")
    B.set_ylabel("relative sup-norm error")
    B.set_title(rf"(b) {fams[jf]}, $\alpha$ = {al:g}, DpS growth {g:.3g}/$\tau$:" "\n"
                r"curves parallel while E $\sim \varepsilon^\alpha$" f"; dashed: relative error {lost:g} (lost)",
                fontsize=8)
    # the dashed line said in the title: a key inside would sit on the curves' ends, which reach every corner
    # (c)
    C = ax[1, 0]
    for ja, a in enumerate(alphas):
        C.axhline(a, color=f"C{ja}", lw=0.7, ls=":")
        for jf, fam in enumerate(fams):
            C.errorbar(Ts * (1.0 + 0.03 * (jf - 1.5)), ps[jf, ja], yerr=pse[jf, ja], fmt=_MARKERS[jf % 6], ms=4,
                       color=f"C{ja}", mfc="none" if jf % 2 else None, capsize=2,
                       label=(f"{fam}" if ja == 0 else None))
    C.set_xscale("log")
    C.set_xlabel(r"slow time T = $\varepsilon^{\alpha-1} t$")
    C.set_ylabel(r"fitted power p of $\varepsilon$, smaller half of the range")
    C.set_title(r"(c) p against T; dotted: $\alpha$ = " + ", ".join(f"{a:g}" for a in alphas)
                + " (colours)", fontsize=9)
    legend_outside(C)   # the markers fill the panel at every p and T: no corner is free
    # (d)
    D = ax[1, 1]
    jf = fams.index("tw-pi5") if "tw-pi5" in fams else 0
    for ja, a in enumerate(alphas):
        D.loglog(eps[ja], rel[jf, ja, :, k1], "-o", ms=3, color=f"C{ja}",
                 label=rf"$\alpha$ = {a:g}: p = {p[jf, ja, k1]:.3f} $\pm$ {se[jf, ja, k1]:.3f}")
    D.set_xlabel(r"$\varepsilon$")
    D.set_ylabel("relative sup-norm error")
    ratio = float(np.nanmax(checks["halving_ratio"].values[jf, :, k1]))
    D.set_title(f"(d) {fams[jf]}, T = {Ts[k1]:g}, every alpha;\nlattice dt-halving error "
                f"/ E $\\leq$ {ratio:.1g}", fontsize=8)
    legend_outside(D)   # the largest alpha's curve rises through the lower right corner
    return fig


def _cmap() -> Colormap:
    from matplotlib import colormaps

    return colormaps["viridis"]
