"""Figure breathers: exact breathers of (nc) against the DpS breathers, from results/breathers/breathers.nc
(or results/breathers/full/breathers.nc; :mod:`cradle.analyses.breathers`).

(a) amplitude max|x_n(0)| against omega_b, exact families and DpS (ansatzapproxst2); (b) the pinning
    Floquet exponent: growth rate of the unstable family, frequency of the stable one's pinning pair, exact
    (solid) and DpS (dashed); (c) distance exact - DpS against omega_b - 1 with the fitted power law;
    (d) Peierls-Nabarro barrier |E_bond - E_site| at equal action, exact and DpS; (e) log10 max_t |x_n| of the
    breathers at pn_omega far below machine precision, exact and DpS; (f) the kicked breather's velocity
    and radiation against the kick.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.figures import AnalysisTree, figure, legend_outside, plain_log_ticks

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: finite points each data panel holds at least (tests/figures/test_figures_render.py): a few omega_b of each
#: family, a few kicks
MIN_POINTS = 2

#: the radiated fraction below which a kicked run radiates nothing measurable (rounding of the energies)
RADIATION_FLOOR = 1e-17


def draw(tree: AnalysisTree) -> Figure:
    """The six panels above from the groups /families, /profiles, /pn, /tails, /exchanges, /kick."""
    fig, ax = figure(2, 3, width=13.0, height=7.4)
    at = tree.attrs
    fam = tree["families"]
    om = tree["omega"].values
    names = [s.strip() for s in at["family_names"].split(",")]
    # (a) amplitudes
    A = ax[0, 0]
    for f, name in enumerate(names):
        A.loglog(om - 1, fam["amplitude"].values[f], "o-", ms=3, color=f"C{f}", label=f"exact, {name}")
        A.loglog(om - 1, np.max(np.abs(tree["profiles"]["x0_dps"].values[f]), axis=-1), "--", color=f"C{f}", lw=0.8)
    A.set_xlabel(r"$\omega_b - 1$")
    A.set_ylabel(r"max$_n |x_n(0)|$")
    A.set_title("(a) families; DpS (ansatzapproxst2) dashed", fontsize=9)
    A.legend(fontsize=7)
    # (b) pinning exponents
    B = ax[0, 1]
    for f, name in enumerate(names):
        if not name.startswith("ring"):
            continue
        u = fam["unstable"].values[f] > 0.5
        g, nu = fam["pinning_exponent"].values[f], fam["pinning_frequency"].values[f]
        # the site's growth and the bond's frequency agree to 4 digits: the site's marks are larger and open, so
        # that the bond's show inside them, and the DpS lines differ in style for the same reason
        site = "site" in name
        ms, mfc = (9, "none") if site else (4, f"C{f}")
        B.loglog(om - 1, np.where(u, g, np.nan), "o", ms=ms, mfc=mfc, color=f"C{f}",
                 label=f"{name}: growth (unstable)")
        B.loglog(om - 1, np.where(u, np.nan, nu), "D" if site else "x", ms=ms, mfc=mfc, color=f"C{f}",
                 label=f"{name}: frequency (stable)")
        dp = np.where(fam["dps_pinning_exponent"].values[f] > 0, fam["dps_pinning_exponent"].values[f],
                      fam["dps_pinning_frequency"].values[f])
        B.loglog(om - 1, dp, "-" if site else "--", color=f"C{f}", lw=2.0 if site else 0.8, alpha=0.5 if site else 1,
                 label=f"{name}: DpS")
    if "exchanges" in tree.children:
        for k, w in enumerate(tree["exchanges"]["omega_exchange"].values):
            B.axvline(w - 1, color="0.7", lw=0.6, ls=":", label="stability exchange" if k == 0 else None)
    B.set_xlabel(r"$\omega_b - 1$")
    B.set_ylabel("pinning exponent (1/t)")
    B.set_title("(b) pinning pair: growth (unstable) / frequency (stable)", fontsize=8)
    legend_outside(B, fontsize=6.5)
    # (c) distance to DpS
    C = ax[0, 2]
    for f, name in enumerate(names):
        C.loglog(om - 1, fam["dps_distance"].values[f], "o", ms=3, color=f"C{f}", label=name)
    p, c = at["dps_distance_exponent"], at["dps_distance_prefactor"]
    if np.isfinite(p):
        x = om - 1
        C.loglog(x, c * x**p, "k-", lw=0.7, label=rf"fit $\propto (\omega_b-1)^{{{p:.3f}}}$")
    C.set_xlabel(r"$\omega_b - 1$")
    C.set_ylabel(r"max$|x - x^{DpS}|$ / max$|x|$")
    C.set_title("(c) distance to DpS at the same omega_b", fontsize=8)
    C.legend(fontsize=7)
    # (d) PN barrier
    D = ax[1, 0]
    pn = tree["pn"]
    J = pn["action_pn"].values
    if J.size:
        D.loglog(J, np.abs(pn["barrier"].values), "o-", ms=3, label="exact lattice")
        D.loglog(J, np.abs(pn["barrier_dps"].values), "--", label="DpS")
    D.set_xlabel("action J")
    if J.size:
        neg = pn["barrier"].values < 0
        D.loglog(J[neg], np.abs(pn["barrier"].values[neg]), "o", mfc="none", color="C0", ms=7,
                 label="exact < 0 (site higher)")
        D.loglog(J, pn["barrier_uncertainty"].values, ":", color="0.5", label="resolution check")
    D.set_ylabel(r"$|E_{bond} - E_{site}|$ at equal J")
    D.set_title(f"(d) PN barrier at omega_b = {at['pn_omega']:g}:\n{at['pn_barrier_at_pn_omega']:.3g} "
                f"(DpS {at['pn_barrier_dps_at_pn_omega']:.3g})", fontsize=8)
    legend_outside(D, fontsize=6.5)   # the points sit at rounding level: where they fall depends on the machine
    # (e) tails at pn_omega, in log variables
    E = ax[1, 1]
    tl = tree["tails"]
    j = tl["j"].values
    for f, name in enumerate(names):
        E.plot(j, tl["log10_amplitude"].values[f], "o-", ms=3, color=f"C{f}", label=f"exact, {name}")
        E.plot(j, tl["log10_amplitude_dps"].values[f], "--", color=f"C{f}", lw=0.8)
    if np.nanmin(tl["log10_amplitude_dps"].values) < -10:  # tails far below machine precision: symlog
        E.set_yscale("symlog", linthresh=10)
    E.set_xlabel("beads from the centre")
    E.set_ylabel(r"log$_{10}$ max$_t |x_n|$")
    E.set_title(rf"(e) tails at $\omega_b$ = {at['pn_omega']:g} (DpS dashed)", fontsize=8)
    E.legend(fontsize=7)
    # (f) kicked breather
    F = ax[1, 2]
    k = tree["kick"]["kick"].values
    note = ""
    if k.size:
        F.loglog(k, np.abs(tree["kick"]["velocity"].values), "o-", label="|velocity| (beads / t)")
        radiated = tree["kick"]["radiation"].values
        if np.nanmax(radiated) > RADIATION_FLOOR:
            F.loglog(k, np.maximum(radiated, RADIATION_FLOOR), "s--", color="C3",
                     label=f"radiated energy fraction (floored at {RADIATION_FLOOR:g})")
        else:   # all at the floor: a line along the panel's bottom would only stretch the velocity's axis
            note = f"; radiated energy < {RADIATION_FLOOR:g} at every kick"
        if k.size < 3:
            note += f"\n{k.size} kicks here: the full form kicks over four decades"
        legend_outside(F)
    else:
        F.text(0.5, 0.5, "no kicked runs in this form", ha="center", transform=F.transAxes)
    F.set_xlabel("kick / max|x(0)|")
    F.set_ylabel("|velocity| (beads / t)" if note.startswith("; radiated") else "velocity, radiated fraction")
    F.set_title(f"(f) {at['kick_family']} breather, $\\omega_b$ = {at['kick_omega']:g},\n"
                f"kicked along its pinning mode{note}", fontsize=8)
    ring = tree["profiles"].sizes["n"]
    fig.suptitle(f"exact breathers of (nc), $\\alpha$ = {at.get('alpha', 1.5):g}, ring N = {ring}", fontsize=10)
    for panel in ax.flat:
        plain_log_ticks(panel)
    return fig
