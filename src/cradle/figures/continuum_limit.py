"""Figure beyond the paper: the continuum limit alpha -> 1+ (continuum-limit).

Drawn by :func:`draw` from results/continuum-limit/[full/]continuum-limit.nc (:mod:`cradle.analyses.continuum_limit`).

(a) the staggered envelopes b_n / max b of the site-centred DpS breathers against X = sqrt(eps) (n - n_c) at the
largest, a middle and the smallest eps, and the log-NLS Gaussian exp(-X^2); (b) their departure from the Gaussian
divided by eps (site and bond): it settles onto one curve, the distance is O(eps); (c) the max-norm distances of the
three families against eps, log-log, with the fitted powers (fit range shaded) and a line of slope 1; (d), (e) the
same as (a), (b) for the solitary waves of the Hertz chain against the log-KdV Gaussian exp(-Y^2), Y = sqrt(3 eps)
xi; (f) the first-order constants: (nu - 4)/eps of the DpS breathers against 4 ln 2 - 2, and 2 ln max R of the
Hertz waves at c = 1 against 1. Mobility: (g) the peak position of the perturbed unstable site breather against
lambda tau (largest delta), one curve per alpha; (h) the largest displacement against alpha, each delta and each
noise seed, N doubled, the lattice runs (full form), with the thresholds; (i) the growth rate lambda of the
unstable mode against alpha. Near p = 2: (j) the site breather's envelope at the alpha - 1 nearest 0.1, log scale,
against the Gaussian and the three compactons of :mod:`cradle.models.compacton`, each to the edge of its support;
(k) the distance of the site breathers and the Hertz waves to the Gaussians and to the compactons, divided by
alpha - 1. The lattice: (l) sigma / lambda^2 of the pinning mode of the exact site breather of (nc) against its
amplitude (1: DpS; below 0: pinned, oscillating; crosses: Newton not converged), with the outcome of the
small-amplitude lattice runs (full form) as triangles below. The travelling breathers, a fifth row when the file
holds them (group /travelling): (m) the departure of a TB's envelope |B_n| / max|B| from e^{-X^2} (circles) and from
the carrier-corrected Gaussian of :mod:`cradle.models.travelling_continuum` (crosses) at the eps nearest 0.1, against
the static breather's departure from e^{-X^2} (line): the crosses fall on the line; (n) the distances of the TBs at
the largest boost to the boosted Gaussian and compactons (circles) and to the same narrowed by the lattice's carrier
(crosses), divided by eps, against the static breather's (dotted), with the fitted powers; (o) the TBs' theta
against the boosted Gaussian's, and the residual of the boosted compacton in form (B) (its Galilean defect), against
eps.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from cradle.figures import AnalysisTree, figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: finite points each data panel holds at least (tests/figures/test_figures_render.py)
MIN_POINTS = 4


def _members(tree: AnalysisTree, family: str) -> list[tuple[float, Any]]:
    eps = np.asarray(tree[family]["eps"].values)
    return [(float(e), tree[f"{family}/e{k:02d}"]) for k, e in enumerate(eps)]


def _shown(members: list[tuple[float, Any]]) -> list[tuple[float, Any]]:
    """The largest, a middle and the smallest eps."""
    idx = sorted({0, len(members) // 2, len(members) - 1})
    return [members[i] for i in idx]


def _profiles(ax: Any, members: list[tuple[float, Any]], xname: str, yname: str, lim: float, title: str,
              gauss: str) -> None:
    for j, (e, g) in enumerate(_shown(members)):
        x, y = np.asarray(g[xname].values), np.asarray(g[yname].values)
        keep = np.abs(x) <= lim
        ax.plot(x[keep], y[keep], "o" if xname == "X" else "-", color=f"C{j}", ms=3, lw=1.2,
                label=f"$\\alpha - 1$ = {e:g}")
    X = np.linspace(-lim, lim, 400)
    ax.plot(X, np.exp(-X**2), "k--", lw=1.0, label=gauss)
    ax.set_title(title, fontsize=9)
    ax.set_ylim(-0.05, 1.3)
    ax.legend(fontsize=7, loc="upper right")


def _departures(ax: Any, fams: list[tuple[str, list[tuple[float, Any]]]], xname: str, yname: str, lim: float,
                title: str) -> None:
    styles = ["-", ":"]
    top = 0.0
    for s, (label, members) in enumerate(fams):
        for j, (e, g) in enumerate(_shown(members)):
            x = np.asarray(g[xname].values)
            d = (np.asarray(g[yname].values) - np.asarray(g["gaussian"].values)) / e
            keep = np.abs(x) <= lim
            order = np.argsort(x[keep])
            ax.plot(x[keep][order], d[keep][order], styles[s % 2], color=f"C{j}", lw=1.2,
                    label=f"{label}, $\\alpha - 1$ = {e:g}")
            top = max(top, float(np.max(d[keep])))
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_title(title, fontsize=9)
    # the key above the two humps, where no curve goes
    ax.set_ylim(-0.04 * top, 1.6 * top)
    ax.legend(fontsize=6, loc="upper center", ncol=len(fams))


def draw(tree: AnalysisTree) -> Figure:
    """The panels above."""
    travelling = "travelling" in tree.children and tree["travelling"]["tb_eps"].size > 0
    fig, ax = figure(5, 3, width=14.0, height=20.0) if travelling else figure(4, 3, width=14.0, height=16.0)
    site, bond, hertz = _members(tree, "dps_site"), _members(tree, "dps_bond"), _members(tree, "hertz")

    a = ax[0, 0]
    _profiles(a, site, "X", "envelope", 3.0, "(a) DpS site breathers: staggered envelope", "log-NLS $e^{-X^2}$")
    a.set_xlabel("$X = \\sqrt{\\alpha - 1}\\,(n - n_c)$")
    a.set_ylabel("$b_n / \\max b$")

    b = ax[0, 1]
    _departures(b, [("site", site), ("bond", bond)], "X", "envelope", 3.0,
                "(b) DpS: (envelope $-\\ e^{-X^2}$) / ($\\alpha - 1$)")
    b.set_xlabel("$X$")
    b.set_ylabel("departure / $(\\alpha - 1)$")

    c = ax[0, 2]
    lo = float(tree.attrs["fit_below"])
    c.axvspan(1e-5, lo, color="0.93", lw=0, label=f"fit range $\\alpha - 1 \\leq$ {lo:g}")
    every = []
    for key, label, mark in (("dps_site", "DpS site", "o"), ("dps_bond", "DpS bond", "s"),
                             ("hertz", "Hertz chain", "^")):
        e = np.asarray(tree[key]["eps"].values)
        D = np.asarray(tree[key]["distance"].values)
        every.append(e)
        p = float(tree.attrs[f"{key}_power"])
        u = float(tree.attrs[f"{key}_power_uncertainty"])
        c.loglog(e, D, mark, ms=4, mfc="none", label=f"{label}: power {p:.4f} $\\pm$ {u:.1g}")
    allE = np.concatenate(every)
    ref = np.array([allE.min(), allE.max()])
    c.loglog(ref, 0.15 * ref, "k:", lw=1.0, label="slope 1")
    c.set_xlim(allE.min() / 1.6, allE.max() * 1.6)
    c.set_xlabel("$\\alpha - 1$")
    c.set_ylabel("max-norm distance to the Gaussian")
    c.set_title("(c) distance to the continuum limit", fontsize=9)
    c.legend(fontsize=7, loc="upper left")

    d = ax[1, 0]
    _profiles(d, hertz, "Y", "strain", 3.0, "(d) Hertz chain solitary waves ($c = 1$): strain", "log-KdV $e^{-Y^2}$")
    d.set_xlabel("$Y = \\sqrt{3(\\alpha - 1)}\\,\\xi$")
    d.set_ylabel("$R / \\max R$")

    e_ = ax[1, 1]
    _departures(e_, [("Hertz", hertz)], "Y", "strain", 3.0, "(e) Hertz: ($R/\\max R - e^{-Y^2}$) / ($\\alpha - 1$)")
    e_.set_xlabel("$Y$")
    e_.set_ylabel("departure / $(\\alpha - 1)$")

    f = ax[1, 2]
    for key, label, mark in (("dps_site", "DpS site $(\\nu - 4)/(\\alpha - 1)$", "o"),
                             ("dps_bond", "DpS bond $(\\nu - 4)/(\\alpha - 1)$", "s")):
        f.semilogx(np.asarray(tree[key]["eps"].values), np.asarray(tree[key]["nu_first_order"].values), mark,
                   ms=4, mfc="none", label=label)
    f.axhline(float(tree.attrs["nu_first_order_limit"]), color="C0", ls="--", lw=1.0,
              label=f"$4\\ln 2 - 2$ = {float(tree.attrs['nu_first_order_limit']):.4f}")
    he = np.asarray(tree["hertz"]["eps"].values)
    f.semilogx(he, 2.0 * np.asarray(tree["hertz"]["log_amplitude"].values), "^", ms=4, mfc="none", color="C2",
               label="Hertz $2 \\ln \\max R$ at $c = 1$")
    f.axhline(2.0 * float(tree.attrs["log_amplitude_limit"]), color="C2", ls="--", lw=1.0, label="limit 1")
    f.set_xlabel("$\\alpha - 1$")
    f.set_ylabel("first-order constant")
    f.set_title("(f) the constants of the limit", fontsize=9)
    lo_y = min(0.7, float(np.nanmin(2.0 * np.asarray(tree["hertz"]["log_amplitude"].values))) - 0.05)
    f.set_ylim(lo_y, 1.55)
    f.legend(fontsize=7, loc="upper right")
    _mobility(ax[2], tree)
    _compactons(ax[3, 0], ax[3, 1], tree, site)
    _stability(ax[3, 2], tree)
    if travelling:
        _travelling(ax[4], tree)
    return fig


_MODEL_STYLE = {"gaussian": ("C0", "Gaussian"), "A": ("C1", "compacton (A)"), "B": ("C2", "compacton (B)"),
                "C": ("C4", "compacton (C)")}


def _travelling(ax: Any, tree: AnalysisTree) -> None:
    """(m) the TB's envelope against the Gaussian at the eps nearest 0.1, (n) the distances of the TBs to the
    travelling profiles over eps, (o) theta against the boost's and the boost residual of the compactons."""
    tb = tree["travelling"]
    eps = np.asarray(tb["tb_eps"].values)
    K = np.asarray(tb["boost"].values)
    narrowing = np.asarray(tb["carrier_narrowing"].values)
    c = np.asarray(tb["c"].values)
    i = int(np.argmin(np.abs(np.log(eps / 0.1))))
    e = float(eps[i])
    g = tree[f"travelling/e{i:02d}"]
    m = ax[0]
    lim = 3.0
    Xs, st = np.asarray(g["X_static"].values), np.asarray(g["static"].values)
    keep = np.abs(Xs) <= lim
    o = np.argsort(Xs[keep])
    m.plot(Xs[keep][o], (st[keep][o] - np.exp(-Xs[keep][o] ** 2)) / e, "k-", lw=1.2,
           label="static breather $-\\ e^{-X^2}$ ($c = 0$)")
    X, env = np.asarray(g["X"].values), np.asarray(g["envelope"].values)
    keep = np.abs(X) <= lim
    o = np.argsort(X[keep])
    Xk = X[keep][o]
    for j, k in enumerate(K):
        m.plot(Xk, (env[j][keep][o] - np.exp(-Xk**2)) / e, "o", ms=3.5, mfc="none", color=f"C{j + 1}",
               label=f"TB $-\\ e^{{-X^2}}$, $K$ = {k:g} ($c$ = {c[i, j]:.3g})")
        a = narrowing[i, j]   # the carrier-corrected Gaussian exp(-a X^2) the analysis stored
        m.plot(Xk, (env[j][keep][o] - np.exp(-a * Xk**2)) / e, "x", ms=4.5, color=f"C{j + 1}",
               label=f"TB $-$ carrier Gaussian, $K$ = {k:g}")
    m.axhline(0.0, color="0.6", lw=0.6)
    lo, hi = m.get_ylim()
    m.set_ylim(lo, hi + 0.9 * (hi - lo))   # the key above the curves
    m.set_xlabel("$X = \\sqrt{\\alpha - 1}\\,(n - n_c)$")
    m.set_ylabel("departure of $|B_n|/\\max|B|$ / $(\\alpha - 1)$")
    m.set_title(f"(m) travelling breathers' envelopes, $\\alpha - 1$ = {e:g}", fontsize=9)
    m.legend(fontsize=6.5, loc="upper center", ncol=2)

    n = ax[1]
    D = np.asarray(tb["distance"].values)
    Ds = np.asarray(tb["static_distance"].values)
    P = np.asarray(tb["power"].values)
    models = [str(x) for x in np.asarray(tb["model"].values)]
    for base, (col, label) in _MODEL_STYLE.items():
        b_, c_ = models.index(base), models.index(base + " carrier")
        fitted = f", powers {P[b_, -1]:.3f}, {P[c_, -1]:.3f}" if np.isfinite(P[b_, -1]) else ""
        n.loglog(eps, D[b_, :, -1] / eps, "o-", color=col, ms=3.5, lw=1.0, label=f"{label}{fitted}")
        n.loglog(eps, D[c_, :, -1] / eps, "x--", color=col, ms=5, lw=0.9)
        n.loglog(eps, Ds[b_] / eps, ":", color=col, lw=1.2)
    n.plot([], [], "ko-", ms=3.5, lw=1.0, label=f"TB ($K$ = {K[-1]:g}) to the boosted profile")
    n.plot([], [], "kx--", ms=5, lw=0.9, label="TB to the profile narrowed by the carrier")
    n.plot([], [], "k:", lw=1.2, label="static breather ($c = 0$)")
    n.set_ylim(0.01, 20.0)   # room above the curves for the key
    n.set_xlim(eps.min() / 1.5, eps.max() * 1.5)
    n.set_xlabel("$\\alpha - 1$")
    n.set_ylabel("distance / $(\\alpha - 1)$ (phase included)")
    n.set_title("(n) TBs against the travelling profiles", fontsize=9)
    n.legend(fontsize=6, loc="upper center", ncol=2)

    t = ax[2]
    err = np.abs(np.asarray(tb["theta_error"].values))
    tp = np.asarray(tb["theta_power"].values)
    R = np.asarray(tb["boost_residual"].values)
    eqs = [str(q) for q in np.asarray(tb["equation"].values)]
    for j, k in enumerate(K):
        fitted = f", power {tp[j]:.2f}" if np.isfinite(tp[j]) else ""
        t.loglog(eps, err[:, j], "o-", color=f"C{j + 1}", ms=3.5, lw=1.0,
                 label=f"$|\\theta - \\theta_{{boost}}|$, $K$ = {k:g}{fitted}")
        b = eqs.index("B")
        t.loglog(eps, R[b, :, j], "^--", color=f"C{j + 1}", ms=4, mfc="none", lw=0.9,
                 label=f"boosted compacton's residual in (B), $K$ = {k:g}")
    top = float(np.nanmax([np.nanmax(err), np.nanmax(R[eqs.index("B")])]))
    bottom = float(np.nanmin([np.nanmin(err[err > 0]), np.nanmin(R[eqs.index("B")])]))
    t.set_ylim(bottom / 3.0, top * 300.0)   # room above for the key
    t.set_xlim(eps.min() / 1.5, eps.max() * 1.5)
    t.set_xlabel("$\\alpha - 1$")
    t.set_ylabel("phase error (rad); residual / max$|U|$")
    t.set_title("(o) TB's phase $\\theta$ against the boost; the forms' Galilean defect", fontsize=9)
    t.legend(fontsize=6.5, loc="upper left")


_FORM_STYLE = {"A": ("C1", "-."), "B": ("C2", "-"), "C": ("C4", "--")}


def _compactons(j: Any, k: Any, tree: AnalysisTree, site: list[tuple[float, Any]]) -> None:
    comp = tree["compacton_dps"]
    eps = np.asarray(comp["eps"].values)
    i = int(np.argmin(np.abs(np.log(eps / 0.1))))     # the member nearest alpha - 1 = 0.1
    e, g = site[i]
    y = np.asarray(g["X"].values) / np.sqrt(e)       # n - n_c
    env = np.asarray(g["envelope"].values)
    order = np.argsort(y)
    order = order[env[order] > 1e-16]                  # the frame's floor: the rest is rounding
    j.semilogy(y[order], env[order], "o", ms=3, color="k", mfc="none", label="DpS site breather")
    Y = np.linspace(y.min(), y.max(), 800)
    j.semilogy(Y, np.exp(-e * Y**2), ":", color="C0", lw=1.2, label="log-NLS Gaussian")
    forms = [str(f) for f in np.asarray(comp["form"].values)]
    half = np.asarray(comp["half_width"].values)[:, i]
    for form, hw in zip(forms, half, strict=True):
        col, ls = _FORM_STYLE[form]
        # the stored compacton's closed form, cos^(2/eps)(kappa y) inside its support |y| < pi/(2 kappa) = hw
        inside = np.abs(Y) < hw
        C = np.cos(0.5 * np.pi * Y[inside] / hw) ** (2.0 / e)
        j.semilogy(Y[inside][C > 0], C[C > 0], ls, color=col, lw=1.1,
                   label=f"compacton ({form}), support $\\pm${hw:.1f}")
    j.set_ylim(1e-17, 1e5)   # room above the peak for the key
    j.set_xlabel("$n - n_c$")
    j.set_ylabel("$b_n / \\max b$")
    j.set_title(f"(j) DpS breather and compactons, $\\alpha - 1$ = {e:g}", fontsize=9)
    j.legend(fontsize=6.5, loc="upper center", ncol=2)

    for f_i, form in enumerate(np.asarray(comp["form"].values)):
        col, ls = _FORM_STYLE[str(form)]
        k.loglog(eps, np.asarray(comp["distance_site"].values)[f_i] / eps, "o" + ls, color=col, ms=3.5, mfc="none",
                 lw=0.9, label=f"DpS site to compacton ({form})")
    k.loglog(eps, np.asarray(tree["dps_site"]["distance"].values) / eps, "o:", color="C0", ms=3.5, mfc="none", lw=0.9,
             label="DpS site to Gaussian")
    he = np.asarray(tree["compacton_hertz"]["eps"].values)
    k.loglog(he, np.asarray(tree["compacton_hertz"]["distance"].values) / he, "^-", color="C3", ms=4, mfc="none",
             lw=0.9, label="Hertz to its compacton")
    k.loglog(he, np.asarray(tree["hertz"]["distance"].values) / he, "^:", color="C3", ms=4, mfc="none", lw=0.9,
             label="Hertz to Gaussian")
    k.set_ylim(0.01, 10.0)   # room above the curves for the key
    k.set_xlabel("$\\alpha - 1$")
    k.set_ylabel("max-norm distance / $(\\alpha - 1)$")
    k.set_title("(k) distance to the Gaussians and the compactons", fontsize=9)
    k.legend(fontsize=6.5, loc="upper center", ncol=2)


def _stability(ax: Any, tree: AnalysisTree) -> None:
    st = tree["lattice_stability"]
    es = np.asarray(st["stability_eps"].values)
    S = np.asarray(st["sigma_ratio"].values)
    conv = np.asarray(st["converged"].values).astype(bool)
    for i, a in enumerate(np.asarray(st["stability_alpha"].values)):
        ax.semilogx(es, S[i], "-", color=f"C{i}", lw=0.9, label=f"$\\alpha$ = {a:g}")
        ax.semilogx(es[conv[i]], S[i][conv[i]], "o", color=f"C{i}", ms=4, mfc="none")
        if np.any(~conv[i]):
            ax.semilogx(es[~conv[i]], S[i][~conv[i]], "x", color=f"C{i}", ms=6)
    ax.axhline(1.0, color="0.4", ls="--", lw=0.8, label="DpS ($\\sigma = \\lambda^2$)")
    ax.axhline(0.0, color="0.4", lw=0.6)
    small = tree["lattice_small"]
    sa = np.asarray(small["small_alpha"].values)
    if sa.size:
        D = np.asarray(small["displacement"].values)
        se = np.asarray(small["small_eps"].values)
        al = list(np.asarray(st["stability_alpha"].values))
        for i, a in enumerate(sa):
            col = f"C{al.index(a)}" if a in al else "k"
            # leaving the site is the robust verdict (how many sites follow depends on the ring: the doc's tables)
            left = D[i] > 0.5
            row = -0.25 - 0.12 * i                     # one row of triangles per alpha
            ax.semilogx(se[left], np.full(left.sum(), row), "v", color=col, ms=6)
            ax.semilogx(se[~left], np.full((~left).sum(), row), "v", color=col, ms=6, mfc="none")
        ax.plot([], [], "v", color="0.3", ms=6, label="lattice run leaves its site")
        ax.plot([], [], "v", color="0.3", ms=6, mfc="none", label="lattice run stays (< 0.5 site)")
    ax.set_ylim(-0.25 - 0.12 * max(sa.size, 1) - 0.1, 1.5)
    ax.set_xlabel("amplitude $\\varepsilon$ of the lattice breather")
    ax.set_ylabel("$\\sigma / \\lambda^2$ of the pinning mode")
    ax.set_title("(l) exact lattice site breather: pinning mode against DpS", fontsize=9)
    ax.legend(fontsize=6.5, loc="upper right", ncol=2)


def _mobility(ax: Any, tree: AnalysisTree) -> None:
    mob = tree["mobility"]
    al = np.asarray(mob["alpha"].values)
    g = ax[0]
    for i, a in enumerate(al):
        g.plot(np.asarray(mob["growth"].values[i]), np.asarray(mob["track"].values[i]), color=f"C{i % 10}", lw=1.1,
               label=f"$\\alpha$ = {a:g}")
    g.axhline(0.0, color="0.6", lw=0.6)
    g.set_xlabel("$\\lambda \\tau$ (growth times of the unstable mode)")
    g.set_ylabel("peak position $-$ start (sites)")
    g.set_title(f"(g) perturbed unstable site breather, $\\delta$ = {float(np.max(mob['delta'].values)):g}",
                fontsize=9)
    g.legend(fontsize=7, loc="upper left", ncol=2)
    lo, hi = g.get_ylim()
    g.set_ylim(lo, hi + 0.45 * (hi - lo))

    h = ax[1]
    deltas = np.asarray(mob["delta"].values)
    D = np.asarray(mob["displacement"].values)
    for j, d in enumerate(deltas):
        h.plot(al, D[:, j], "o-", ms=4, mfc="none", lw=0.8, label=f"$\\delta$ = {d:g}")
    Dn = np.asarray(mob["displacement_noise"].values)
    for k in range(Dn.shape[1]):
        h.plot(al, Dn[:, k], "x", ms=5, color="0.3", label="noise added, each seed" if k == 0 else None)
    chk = np.asarray(tree["mobility_checks"]["displacement"].values)
    h.plot(al, chk[:, 1], "+", ms=8, color="C3", label="N doubled")
    lat = tree["lattice"]
    if lat["lattice_alpha"].size:
        h.plot(np.asarray(lat["lattice_alpha"].values), np.asarray(lat["displacement"].values), "D", ms=5,
               mfc="none", color="C4", label="lattice (nc) through the ansatz")
    for t_i, t in enumerate(np.asarray(mob["threshold"].values)):
        h.axhline(float(t), color="k", ls=[":", "--", "-.", "-"][t_i % 4], lw=0.9,
                  label=f"threshold {float(t):g} sites")
    h.set_xlabel("$\\alpha$")
    h.set_ylabel("largest displacement (sites)")
    h.set_title("(h) travels or stays pinned", fontsize=9)
    top = float(np.nanmax(np.concatenate([D.ravel(), Dn.ravel(), chk.ravel(), np.asarray(mob["threshold"].values)])))
    h.set_ylim(-0.08 * top, 1.7 * top)   # room below for the markers of a run that stayed put
    h.legend(fontsize=7, loc="upper right", ncol=2)

    k = ax[2]
    k.semilogy(al, np.asarray(mob["growth_rate"].values), "o-", ms=4, mfc="none")
    k.set_xlabel("$\\alpha$")
    k.set_ylabel("growth rate $\\lambda$ (per unit $\\tau$)")
    k.set_title("(i) instability of the site breather ($\\max|A| = 1/2$)", fontsize=9)
