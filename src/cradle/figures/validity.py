"""Figure beyond the paper: how long and how well DpS describes the lattice (dps-validity).

Reads results/validity/[full/]dps-validity.nc (:mod:`cradle.analyses.dpsvalidity`), so it is listed
in :data:`cradle.figures.DATASET_FIGURES` and drawn by :func:`cradle.figures.draw_dataset`.

(a) the relative sup-norm error against eps at the largest T, every family, at the reference alpha
    (1.5 when computed), with the law eps^(alpha-1) dotted; (b) the same error divided by
    eps^(alpha-1), one curve per T, for the noisy unstable wave (flat where the law holds, bent where
    the instability has amplified the mismatch to O(1)); (c) the fitted power of eps against T, every
    family and alpha, with its standard error, the consistency order alpha as horizontal lines;
    (d) the relative error against eps at the largest T for every alpha (q = pi/5 wave).
"""
from __future__ import annotations

import numpy as np

from cradle.figures import figure

_MARKERS = ("o", "s", "^", "D", "v", "P")


def _reference_alpha(alphas) -> int:
    near = np.abs(np.asarray(alphas) - 1.5)
    return int(np.argmin(near))


def dps_validity(tree):
    """The four panels above from the groups /errors and /fits of the dps-validity file."""
    fig, ax = figure(2, 2, width=10.0, height=7.6)
    err, fits, checks = tree["errors"], tree["fits"], tree["checks"]
    fams = [s.strip() for s in str(tree.attrs["family_names"]).split(",")]
    alphas = np.asarray(err["alpha"].values, dtype=float)
    Ts = np.asarray(err["T"].values, dtype=float)
    eps = np.asarray(err["eps"].values)          # (alpha, i_eps)
    rel = np.asarray(err["rel_error"].values)    # (family, alpha, i_eps, T)
    law = np.asarray(err["law_ratio"].values)
    p, se = np.asarray(fits["exponent"].values), np.asarray(fits["exponent_stderr"].values)
    ia = _reference_alpha(alphas)
    al = alphas[ia]
    # (a)
    A = ax[0, 0]
    for jf, fam in enumerate(fams):
        A.loglog(eps[ia], rel[jf, ia, :, -1], "-" + _MARKERS[jf % 6], ms=4,
                 label=f"{fam}: p = {p[jf, ia, -1]:.3f} $\\pm$ {se[jf, ia, -1]:.3f}")
    ref = rel[0, ia, 0, -1] * (eps[ia] / eps[ia, 0]) ** (al - 1.0)
    A.loglog(eps[ia], ref, ":", color="0.3", label=r"$\propto \varepsilon^{\alpha-1}$")
    A.set_xlabel(r"$\varepsilon$")
    A.set_ylabel(r"sup$_t$ max$_n |x_n - x_n^{app}|$ / $2\varepsilon$")
    A.set_title(rf"(a) $\alpha$ = {al:g}, $t \leq T \varepsilon^{{1-\alpha}}$, T = {Ts[-1]:g} "
                "(p: fitted power of the absolute error)", fontsize=9)
    A.legend(fontsize=7, loc="lower right")
    # (b)
    B = ax[0, 1]
    jf = fams.index("mi-4pi5-noise") if "mi-4pi5-noise" in fams else 0
    for k, T in enumerate(Ts):
        B.loglog(eps[ia], law[jf, ia, :, k], "-o", ms=3, label=f"T = {T:g}")
    B.set_xlabel(r"$\varepsilon$")
    B.set_ylabel(r"relative error / $\varepsilon^{\alpha-1}$")
    B.set_title(rf"(b) {fams[jf]}, $\alpha$ = {al:g}: flat where E $\sim \varepsilon^\alpha$; "
                f"DpS growth {float(fits['dps_growth_rate'].values[jf, ia]):.3g}/$\\tau$", fontsize=9)
    B.legend(fontsize=7, ncol=2)
    # (c)
    C = ax[1, 0]
    for ja, a in enumerate(alphas):
        C.axhline(a, color=f"C{ja}", lw=0.7, ls=":")
        for jf, fam in enumerate(fams):
            C.errorbar(Ts * (1.0 + 0.03 * (jf - 1.5)), p[jf, ja], yerr=se[jf, ja], fmt=_MARKERS[jf % 6], ms=4,
                       color=f"C{ja}", mfc="none" if jf % 2 else None, capsize=2,
                       label=(f"{fam}" if ja == 0 else None))
    C.set_xscale("log")
    C.set_xlabel(r"slow time T = $\varepsilon^{\alpha-1} t$")
    C.set_ylabel(r"fitted power p of $\varepsilon$ (absolute error)")
    C.set_title(r"(c) p against T; dotted: $\alpha$ = " + ", ".join(f"{a:g}" for a in alphas)
                + " (colours)", fontsize=9)
    C.legend(fontsize=7, loc="best")
    # (d)
    D = ax[1, 1]
    jf = fams.index("tw-pi5") if "tw-pi5" in fams else 0
    for ja, a in enumerate(alphas):
        D.loglog(eps[ja], rel[jf, ja, :, -1], "-o", ms=3, color=f"C{ja}",
                 label=rf"$\alpha$ = {a:g}: p = {p[jf, ja, -1]:.3f} $\pm$ {se[jf, ja, -1]:.3f}")
    D.set_xlabel(r"$\varepsilon$")
    D.set_ylabel("relative sup-norm error")
    ratio = float(np.nanmax(checks["halving_ratio"].values))
    D.set_title(f"(d) {fams[jf]}, T = {Ts[-1]:g}, every alpha; lattice dt-halving error "
                f"/ E $\\leq$ {ratio:.1g}", fontsize=9)
    D.legend(fontsize=7, loc="lower right")
    return fig
