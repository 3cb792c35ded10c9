"""Figure beyond the paper: exact breathers of (nc) against the DpS breathers (breathers).

Reads results/breathers/[full/]breathers.nc (:mod:`cradle.analyses.breathers`), listed in
:data:`cradle.figures.DATASET_FIGURES`.

(a) amplitude max|x_n(0)| against omega_b, exact families and DpS (ansatzapproxst2); (b) the pinning
    Floquet exponent: growth rate of the unstable family, frequency of the stable one's pinning pair, exact
    (solid) and DpS (dashed); (c) distance exact - DpS against omega_b - 1 with the fitted power law;
    (d) Peierls-Nabarro barrier E_bond - E_site at equal action, exact and DpS; (e) log10 |x_n(0)| of the
    breathers at pn_omega, exact and DpS; (f) the kicked breather's velocity and radiation against the kick.
"""
from __future__ import annotations

import numpy as np

from cradle.figures import figure


def breathers(tree):
    """The six panels above from the groups /families, /profiles, /pn, /kick."""
    fig, ax = figure(2, 3, width=13.0, height=7.4)
    at = tree.attrs
    fam = tree["families"]
    om = tree["omega"].values
    names = [s.strip() for s in at["family_names"].split(",")]
    al = float(at["alpha"])
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
        lat = np.where(u, fam["pinning_exponent"].values[f], fam["pinning_frequency"].values[f])
        dp = np.where(fam["dps_pinning_exponent"].values[f] > 0, fam["dps_pinning_exponent"].values[f],
                      fam["dps_pinning_frequency"].values[f])
        kind = "growth" if np.any(u) else "frequency"
        B.loglog(om - 1, lat, "o-", ms=3, color=f"C{f}", label=f"{name}: pinning {kind}, exact")
        B.loglog(om - 1, dp, "--", color=f"C{f}", lw=0.8, label=f"{name}: DpS")
    B.set_xlabel(r"$\omega_b - 1$")
    B.set_ylabel("pinning exponent (1/t)")
    B.set_title("(b) stability: site unstable (real pair), bond stable", fontsize=9)
    B.legend(fontsize=6.5)
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
    C.set_title("(c) distance to the DpS breather of the same omega_b", fontsize=9)
    C.legend(fontsize=7)
    # (d) PN barrier
    D = ax[1, 0]
    pn = tree["pn"]
    J = pn["action_pn"].values
    if J.size:
        D.loglog(J, np.abs(pn["barrier"].values), "o-", ms=3, label="exact lattice")
        D.loglog(J, np.abs(pn["barrier_dps"].values), "--", label="DpS")
    D.set_xlabel("action J")
    D.set_ylabel(r"$|E_{bond} - E_{site}|$ at equal J")
    D.set_title(f"(d) Peierls-Nabarro barrier; at omega_b = {at['pn_omega']:g}: {at['pn_barrier_at_pn_omega']:.3g} "
                f"(DpS {at['pn_barrier_dps_at_pn_omega']:.3g})", fontsize=8)
    D.legend(fontsize=7)
    # (e) profiles at pn_omega
    E = ax[1, 1]
    w = int(np.argmin(np.abs(om - float(at["pn_omega"]))))
    n = tree["profiles"]["n"].values
    for f, name in enumerate(names):
        x = tree["profiles"]["x0"].values[f, w]
        xd = tree["profiles"]["x0_dps"].values[f, w]
        with np.errstate(divide="ignore"):
            E.plot(n, np.log10(np.abs(x)), "o-", ms=3, color=f"C{f}", label=f"exact, {name}")
            E.plot(n, np.log10(np.abs(xd)), "--", color=f"C{f}", lw=0.8)
    E.set_ylim(bottom=-300)
    E.set_xlabel("n")
    E.set_ylabel(r"log$_{10} |x_n(0)|$")
    E.set_title(rf"(e) profiles at $\omega_b$ = {at['pn_omega']:g} (DpS dashed); double-exponential tails, "
                rf"DpS slope ln $\alpha$ = {np.log(al):.3f}", fontsize=8)
    E.legend(fontsize=7)
    # (f) kicked breather
    F = ax[1, 2]
    k = tree["kick"]["kick"].values
    if k.size:
        F.semilogx(k, tree["kick"]["velocity"].values, "o-", label="velocity (beads / t)")
        G = F.twinx()
        G.semilogx(k, tree["kick"]["radiation"].values, "s--", color="C3", label="radiated fraction")
        G.set_ylabel("radiated energy fraction", color="C3")
        F.legend(fontsize=7, loc="upper left")
    else:
        F.text(0.5, 0.5, "no kicked runs in this form", ha="center", transform=F.transAxes)
    F.set_xlabel("kick / max|x(0)|")
    F.set_ylabel("velocity")
    F.set_title(f"(f) {at['kick_family']} breather at omega_b = {at['kick_omega']:g} kicked along its pinning mode",
                fontsize=8)
    return fig
