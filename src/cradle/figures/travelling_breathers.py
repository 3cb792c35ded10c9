"""Figure beyond the paper: travelling breathers of the DpS equation (travelling-breathers).

Drawn by :func:`draw` from results/travelling-breathers/[full/]travelling-breathers.nc
(:mod:`cradle.analyses.travelling_breathers`).

(a) |A_n(0)| (log scale) of the slowest, a middle and the fastest member, and the static site breather at the
same norm; (b) the tail (max |A_n| on the far quarter ring / max |A_n|) against c, on the ring of N sites and on
every check ring; (c) H against c at fixed norm (dH/dc > 0: H rises with c where it does); (d) the growth rate
ln max|mu| / T of the non-trivial multipliers modulo shift against c (the stability threshold dashed; unstable
members filled), on every ring and at every check tolerance, the settled verdicts marked above; (e) the
multipliers modulo shift of the most unstable member and of the slowest, with the unit circle; (f) the distance
of |A_n(tau)| to the static site and bond breathers against c; the TBs in motion (the member at motion_speed
launched in (nc) through (ansatz) at several eps, and in (dfnls) from the same start): (g) the distance travelled
against tau / T (DpS: one site per T), (h) the lattice's speed deficit 1 - v / (c eps^(alpha-1)) against eps with
the fitted order, (i) the radiation (energy outside the window around the breather over the total) against tau / T.
Then the exact TBs of the lattice (nc) when the file holds them (key ``lattice``; issue 37, items 2 and 3), a row
after the others: (j) their |xi_n| / eps at each eps against the DpS TB through the ansatz, (k) their distance to it
and their residuals against eps, (l) the DpS member and the exact TB launched the same way in (nc): speed deficits
and radiation against eps.
Last, the verdicts in the limit N -> infinity when the file holds them (group /robustness_limit): (m) the growth
rate along the fine grid of c on each ring, with the tail's MI rate, (n) the median growth rate of each member's
neighbourhood on each ring with the limit verdicts, (o) the unstable fraction of the fine grid against N, where the
tail is modulationally unstable and elsewhere. Then the tail rule (group /limit_tail): (p) the envelope of the
growth rates of each member whose tail is MI-stable against N with its fit g_inf + b N^-k and the member's own
growth at c (crosses, its limit verdict in the legend), (q) the tail's MI rate
in closed form against the growth rate measured on each ring, (r) the table of the verdicts on each ring, at each
tolerance and in the limit (median rule, tail rule's envelope, the member at c).
Then the lattice's TBs on larger rings and at larger eps when the file holds them (groups /lattice_rings,
/lattice_large): (s) |xi_n(0)| / max against the distance from the centre on each ring, (t) the tail against eps on
each ring with every TB's residual, (u) the tail along the continuation in c against the DpS velocity through
(ansatz), unstable members filled.
Then the family through its fold near the first member when the file holds it (group /limit_fold): (v) H against c
along the arclength on each ring, (w) the growth rate of a real multiplier above +1 and the largest growth rate
against c, with the extrema of H(c), (x) the tail along the arc.
Last, where the lattice TBs' tail vanishes when the file holds it (group /lattice_zeros): (y), (z) the signed tail
along the fine grid of c through each of its two minima on each ring, the regula falsi's iterates and the zero
located; (aa) the table of the zeros.
Then why the finite rings disagree, when the file holds the members' unstable modes (/limit_tail's
member_core_fraction): for each member whose tail is MI-stable, on every ring, (ab) its growth rate at c against N
with the power of N fitted over the rings where it is unstable, (ac) its top mode's core fraction and participation
ratio over N against N (filled: unstable there, the mode that grows; open: stable, the mode of the largest
non-trivial multiplier on the circle) with the fitted power of the core fraction and N^-1 for reference, (ad) the
table of MODE_RULE's verdicts under each threshold.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from cradle.figures import AnalysisTree, figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: finite points each data panel holds at least (tests/figures/test_figures_render.py)
MIN_POINTS = 3


#: a verdict as the panels write it: 1 unstable, 0 stable (another value: undecided, "?" in grey)
VERDICT_LETTER = {1: "U", 0: "S"}
VERDICT_COLOUR = {1: "C3", 0: "C2"}

def draw(tree: AnalysisTree) -> Figure:
    """The panels above: (g)-(i) when the file holds the TBs in motion, (j)-(l) when it holds the lattice's TBs."""
    lattice = "lattice_eps" in tree.children
    limit = "robustness_limit" in tree.children
    tail = "limit_tail" in tree.children
    on_rings = "lattice_rings" in tree.children
    fold = "limit_fold" in tree.children
    zeros = "lattice_zeros" in tree.children
    modes = tail and "member_core_fraction" in tree["limit_tail"].data_vars
    rows = 3 + int(lattice) + int(limit) + int(tail) + int(on_rings) + int(fold) + int(zeros) + int(modes)
    fig, ax = figure(rows, 3, width=13.5, height=11.2 + 3.7 * (rows - 3))
    fam = tree["family"]
    c = np.asarray(fam["c"].values)
    prof = tree["profiles"]
    A = np.asarray(prof["A_re"].values) + 1j * np.asarray(prof["A_im"].values)
    n = np.asarray(prof["n"].values)
    N = n.size
    attrs = tree.attrs
    thr = float(attrs["stability_threshold"])

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

    rob = tree["robustness"]
    rings = [int(x) for x in rob["ring"].values]
    b = ax[0, 1]
    for i, ring in enumerate(rings):
        b.semilogy(c, rob["tail"].values[i], f"C{i}{'os^v<>'[i % 6]}{'-' if i == 0 else '--'}", ms=4 if i == 0 else 3,
                   mfc=None if i == 0 else "none", lw=1.0, label=f"ring of {ring}")
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
    G = np.asarray(rob["growth_rate"].values, float)
    for i, ring in enumerate(rings):
        gi = np.maximum(G[i], floor)
        un = np.asarray(rob["unstable"].values[i]) == 1
        mk = f"C{i}{'os^v<>'[i % 6]}"
        e.semilogy(c[un], gi[un], mk, ms=6 if i == 0 else 5, label=f"ring of {ring}")
        e.semilogy(c[~un], gi[~un], mk, ms=6 if i == 0 else 5, mfc="none")
    for j, rt in enumerate(rob["rtol"].values[1:], 1):
        gt = np.maximum(np.asarray(rob["growth_rate_tol"].values[j], float), floor)
        e.semilogy(c, gt, ("k+", "kx", "k1")[(j - 1) % 3], ms=6, label=f"ring of {rings[0]}, rtol {float(rt):g}")
    e.axhline(thr, color="0.4", ls="--", lw=0.8, label="stability threshold")
    top = 30.0 * max(float(np.nanmax(G)), thr)
    settled = np.asarray(rob["settled"].values)
    for x, v in zip(c, settled, strict=True):
        e.text(x, floor / 4.0, VERDICT_LETTER.get(int(v), "?"), ha="center", va="center", fontsize=7,
               color=VERDICT_COLOUR.get(int(v), "0.4"))
    e.set_ylim(floor / 12.0, top * 1e3)
    e.set_xlabel("velocity c")
    e.set_ylabel(f"growth rate ln max$|\\mu|$ / T (floor {floor:g})")
    e.set_title("(d) growth rate, filled: unstable; S, U: settled, ?: not", fontsize=9)
    e.legend(fontsize=6, loc="upper left", ncol=2)

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
    f.legend(fontsize=6, loc="upper center", ncol=3, handlelength=1.0, columnspacing=0.8)

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
    if "motion" in tree.children:
        draw_motion(ax[2], tree)
    if lattice:
        _lattice_panels(tree, ax[3])
    if limit:
        draw_limit(ax[3 + int(lattice)], tree)
    if tail:
        draw_tail_rule(ax[3 + int(lattice) + int(limit)], tree)
    if on_rings:
        draw_rings(ax[3 + int(lattice) + int(limit) + int(tail)], tree)
    if fold:
        draw_fold(ax[3 + int(lattice) + int(limit) + int(tail) + int(on_rings)], tree)
    if zeros:
        draw_zeros(ax[rows - 1 - int(modes)], tree)
    if modes:
        draw_modes(ax[rows - 1], tree)
    return fig


def verdict_cells(ax: Any, rows: list[list[str]], heads: list[str], bbox: list[float], size: float) -> None:
    """A table of verdicts on ``ax`` (its cells centred, font ``size``), each "U" and "S" in its verdict's colour."""
    tab = ax.table(cellText=rows, colLabels=heads, cellLoc="center", bbox=bbox)
    tab.auto_set_font_size(False)
    tab.set_fontsize(size)
    for (i, _), cell in tab.get_celld().items():
        text = cell.get_text().get_text()
        if i > 0 and text in ("U", "S"):
            cell.get_text().set_color(VERDICT_COLOUR[1 if text == "U" else 0])


def draw_modes(ax: Any, tree: AnalysisTree) -> None:
    """Panels (ab)-(ad): the unstable mode of each member whose tail is MI-stable against N (module docstring)."""
    lt = tree["limit_tail"]
    thr = float(tree.attrs["stability_threshold"])
    floor = thr / 100.0
    c = np.asarray(tree["c"].values)
    rings = np.asarray(lt["fit_ring"].values, float)
    g = np.asarray(lt["member_growth"].values, float)                  # (c, ring)
    core = np.asarray(lt["member_core_fraction"].values, float)
    share = np.asarray(lt["member_participation"].values, float)
    shown = [j for j in range(c.size) if int(lt["tail_mi_unstable"].values[j]) == 0 and np.isfinite(g[j]).any()]
    fine = np.geomspace(float(rings.min()), float(rings.max()), 50)
    a, b = ax[0], ax[1]
    for k, j in enumerate(shown):
        col, un = f"C{k % 10}", g[j] > thr
        a.loglog(rings[un], g[j][un], "o", color=col, ms=5, label=f"c = {c[j]:g}")
        a.loglog(rings[~un], np.full(int(np.sum(~un)), floor), "o", color=col, ms=5, mfc="none")
        b.loglog(rings[un], core[j][un], "o", color=col, ms=5, label=f"c = {c[j]:g}")
        b.loglog(rings[~un], core[j][~un], "o", color=col, ms=5, mfc="none")
        b.loglog(rings[un], share[j][un], "^", color=col, ms=5)
        b.loglog(rings[~un], share[j][~un], "^", color=col, ms=5, mfc="none")
        for panel, y, key in ((a, g[j], "growth"), (b, core[j], "core")):
            s_, e_ = float(lt[f"mode_{key}_slope"].values[j]), float(lt[f"mode_{key}_slope_error"].values[j])
            if np.isfinite(s_):
                # the least-squares line through the unstable rings' points, at their geometric centre
                n0, y0 = np.exp(np.mean(np.log(rings[un]))), np.exp(np.mean(np.log(y[un])))
                panel.loglog(fine, y0 * (fine / n0) ** s_, "-", color=col, lw=0.8,
                             label=rf"c = {c[j]:g}: $N^{{{s_:.2f} \pm {e_:.2f}}}$")
    b.loglog([], [], "ko", ms=5, label="core fraction")
    b.loglog([], [], "k^", ms=5, label="participation / N")
    b.loglog([], [], "ko", ms=5, mfc="none", label="open: stable ring")
    a.axhline(thr, color="0.4", ls="--", lw=0.8, label="stability threshold")
    a.set_ylim(floor / 3.0, 1e3 * max(float(np.nanmax(g[shown])) if shown else thr, thr))
    a.set_xlabel("sites N of the ring")
    a.set_ylabel(rf"growth rate at c, per unit $\tau$ (open: stable, at {floor:g})")
    a.set_title("(ab) the member's growth rate against N (MI-stable tails)", fontsize=9)
    a.legend(fontsize=6, loc="upper left", ncol=2)
    b.loglog(fine, 2.0 / fine, "k:", lw=0.8, label="2 / N (even, 2 core sites)")
    b.set_ylim(3e-3, 100.0)
    b.set_xlabel("sites N of the ring")
    b.set_ylabel("core fraction (|A| > 1e-2 max), participation / N")
    b.set_title("(ac) where the top mode lives (filled: unstable)", fontsize=9)
    b.legend(fontsize=6, loc="upper left", ncol=2)
    from matplotlib.ticker import FixedLocator, NullFormatter

    # a tick at every ring, a label where it clears the last one labelled
    labelled = [float(rings[0])]
    for x in rings[1:]:
        if x / labelled[-1] >= 1.2:
            labelled.append(float(x))
    for panel in (a, b):
        panel.xaxis.set_major_locator(FixedLocator([float(x) for x in rings]))
        panel.xaxis.set_major_formatter(lambda x, _: f"{x:g}" if x in labelled else "")
        panel.xaxis.set_minor_formatter(NullFormatter())
        panel.tick_params(axis="x", labelsize=7)

    t = ax[2]
    t.axis("off")
    letter = {0: "S", 1: "U", -1: "?"}
    # the readings "delta 0.3", "delta 0.3, resolved" as the columns "0.3", "0.3 r"
    heads = ["c", "unst."] + [str(r).replace("delta ", "").replace(", resolved", " r")
                              for r in lt["mode_reading"].values]
    each = np.asarray(lt["mode_verdict_readings"].values, int)              # (c, reading)
    rows = []
    for j in shown:
        u = g[j] > thr
        rows.append([f"{c[j]:g}", f"{int(np.sum(u))}/{int(np.sum(np.isfinite(g[j])))}"]
                    + [letter[int(v)] for v in each[j]])
    verdict_cells(t, rows or [["–"] * len(heads)], heads, [0.0, 0.35, 1.0, 0.5], 7)
    t.set_title("(ad) MODE_RULE in the limit (S stable: finite-size; U;\n? undecided) under each tolerance δ of the "
                "core\nfraction's slope (r: the growth's fall resolved);\nunst.: rings unstable at c / rings reached",
                fontsize=9)


def draw_fold(ax: Any, tree: AnalysisTree) -> None:
    """Panels (v)-(x), the family through its fold (group /limit_fold), on each ring along the arclength: (v) H
    against c (the fold: c turns; the extrema of H(c) marked), (w) the growth rate of a real multiplier above +1 and
    the largest growth rate against c, the extrema of H(c) as vertical lines, (x) the tail against c."""
    fd = tree["limit_fold"]
    thr = float(tree.attrs["stability_threshold"])
    floor = thr / 100.0
    v, w, x = ax
    for i, ring in enumerate(fd["fold_ring"].values):
        col = f"C{i}"
        c = np.asarray(fd["velocity"].values[i], float)
        ok = np.isfinite(c)
        c, H = c[ok], np.asarray(fd["energy"].values[i], float)[ok]
        v.plot(c, H, "-", color=col, lw=0.8)
        v.plot(c[0], H[0], "o", color=col, ms=8 - 3 * (i % 2), label=f"ring of {int(ring)}: first member")
        zeros = str(tree.attrs[f"fold_{int(ring)}_dH_dc_zero"])
        at = [float(z) for z in zeros.split(", ")] if zeros != "none" else []
        for k, z in enumerate(at):
            j = int(np.argmin(np.abs(c - z)))
            v.plot(c[j], H[j], "D", color=col, ms=5, mfc="none",
                   label=f"ring of {int(ring)}: dH/dc = 0" if k == 0 else "_")
            w.axvline(z, color=col, ls=":", lw=0.8, label=f"ring of {int(ring)}: dH/dc = 0" if k == 0 else "_")
        real = np.asarray(fd["real_growth"].values[i], float)[ok]
        grow = np.asarray(fd["growth"].values[i], float)[ok]
        w.semilogy(c, np.maximum(grow, floor), ".", color=col, ms=3, label=f"ring of {int(ring)}: largest")
        w.semilogy(c, np.maximum(real, floor), "-", color=col, lw=1.2, label=f"ring of {int(ring)}: real, above +1")
        x.semilogy(c, np.asarray(fd["tail"].values[i], float)[ok], ".-", color=col, ms=3, lw=0.6,
                   label=f"ring of {int(ring)}")
    lo, hi = v.get_ylim()
    v.set_ylim(lo - 0.6 * (hi - lo), hi)   # room below the data for the legend
    v.set_xlabel("velocity c")
    v.set_ylabel("H at unit norm")
    v.set_title("(v) the family through its fold: H against c", fontsize=9)
    v.legend(fontsize=6, loc="lower right")
    w.axhline(thr, color="0.4", ls="--", lw=0.8, label="stability threshold")
    w.set_ylim(floor / 3.0, 1e2)
    w.set_xlabel("velocity c")
    w.set_ylabel(rf"growth rate per unit $\tau$ (floor {floor:g})")
    w.set_title("(w) growth along the arc; real multiplier above +1", fontsize=9)
    w.legend(fontsize=6, loc="upper left", ncol=2)
    x.set_xlabel("velocity c")
    x.set_ylabel("tail: max far |A_n| / max |A_n|")
    x.set_title("(x) the tail along the arc", fontsize=9)
    lo, hi = x.get_ylim()
    x.set_ylim(lo, hi * 300.0)   # room above the data for the legend (the arc starts at the top left)
    x.legend(fontsize=6, loc="upper right")


def draw_tail_rule(ax: Any, tree: AnalysisTree) -> None:
    """Panels (p)-(r), the tail rule's verdicts in the limit (group /limit_tail): (p) per member the largest growth
    rate of its neighbourhood (points of its tail's kind) against N with the fit g_inf + b N^-k; (q) the tail's MI
    rate in closed form at the tail amplitudes measured on the rings (bars: smallest to largest) against the growth
    rate measured at the member on each ring; (r) the table of verdicts per ring, tolerance and in the limit."""
    lt = tree["limit_tail"]
    attrs = tree.attrs
    thr = float(attrs["stability_threshold"])
    floor = thr / 100.0
    c = np.asarray(tree["c"].values)
    rings = np.asarray(lt["fit_ring"].values, float)
    env = np.asarray(lt["envelope"].values, float)                 # (c, ring)
    kind = np.asarray(lt["tail_mi_unstable"].values) == 1

    p = ax[0]
    fine = np.linspace(float(rings.min()), 2.0 * float(rings.max()), 200)
    shown = [j for j in range(c.size) if np.sum(np.isfinite(env[j])) >= 2 and not kind[j]]
    member = np.asarray(lt["member_growth"].values, float)         # (c, ring)
    for k, j in enumerate(shown):
        col = f"C{k % 10}"
        p.semilogy(rings, np.maximum(env[j], floor), "o", color=col, ms=5, label=f"c = {c[j]:g}: envelope")
        p.semilogy(rings, np.maximum(member[j], floor), "x", color=col, ms=6,
                   label=f"c = {c[j]:g}: the member at c, verdict "
                         f"{VERDICT_LETTER.get(int(lt['member_verdict'].values[j]), '?')}")
        g0, b, kk = (float(lt[f"fit_{x}"].values[j]) for x in ("g_inf", "b", "k"))
        if np.isfinite(g0):
            e0 = float(lt["fit_g_inf_error"].values[j])
            # no error where a fit leaving out an end ring fails: its standard error, said to be only that
            err = f"{e0:.1e}" if np.isfinite(e0) else f"{float(lt['fit_g_inf_stderr'].values[j]):.1e} (s.e. only)"
            p.semilogy(fine, np.maximum(g0 + b * fine ** (-kk), floor), "-", color=col, lw=0.8,
                       label=rf"fit: $g_\infty$ = {g0:.1e} $\pm$ {err}"
                       + (f" (k = {kk:g}: on a bound)" if float(lt["fit_degenerate"].values[j]) == 1 else ""))
    p.axhline(thr, color="0.4", ls="--", lw=0.8, label="stability threshold")
    # room above the data for the legend (two entries per member and its fit)
    p.set_ylim(floor / 3.0, 1e6 * max(float(np.nanmax(env)) if np.isfinite(env).any() else thr, thr))
    p.set_xlabel("sites N of the ring")
    p.set_ylabel(rf"growth: largest over c $\pm$ {float(attrs['limit_halfwidth']):g}; at c (floor {floor:g})")
    p.set_title("(p) members whose tail is MI-stable: envelope against N", fontsize=9)
    p.legend(fontsize=6, loc="upper left")

    q = ax[1]
    rob = tree["robustness"]
    G = np.asarray(rob["growth_rate"].values, float)
    lo = np.asarray(lt["tail_mi_rate_min"].values, float)
    hi = np.asarray(lt["tail_mi_rate_max"].values, float)
    un = kind & np.isfinite(lo)
    for k, j in enumerate(np.where(un)[0]):
        # a bar from the smallest to the largest rate (a dot where the rings' tails agree)
        q.semilogy([c[j], c[j]], [max(lo[j], floor), max(hi[j], floor)], "k_-", lw=3, ms=6, alpha=0.5,
                   label="tail's MI rate (closed form), over the rings' tails" if k == 0 else "_")
    for i, ring in enumerate(rob["ring"].values):
        q.semilogy(c, np.maximum(G[i], floor), f"C{i}{'os^v<>'[i % 6]}", ms=4, mfc="none",
                   label=f"growth at c, ring of {int(ring)}")
    q.semilogy(c[~kind], np.full(int(np.sum(~kind)), floor / 2.0), "k_", ms=10, mew=2,
               label="tail MI-stable (no MI rate)")
    q.axhline(thr, color="0.4", ls="--", lw=0.8, label="stability threshold")
    q.set_ylim(floor / 4.0, 3e3 * max(float(np.nanmax(hi)), thr))
    q.set_xlabel("velocity c (member)")
    q.set_ylabel(rf"growth rate per unit $\tau$ (floor {floor:g})")
    q.set_title("(q) the tail's modulational instability", fontsize=9)
    q.legend(fontsize=6, loc="upper left")

    r = ax[2]
    r.axis("off")
    rows = verdict_table(tree)
    # the whole panel: every column as wide as its longest header allows
    verdict_cells(r, rows[1:], rows[0], [0.0, 0.0, 1.0, 1.0], 6)
    r.set_title("(r) verdicts per ring N and rtol (ring of N);\nin the limit: median rule, tail rule, "
                "member at c", fontsize=9)


def verdict_table(tree: AnalysisTree) -> list[list[str]]:
    """The rows of panel (r): c, the verdict on each ring of /robustness and at each tolerance, the median rule's
    limit verdict (/robustness_limit), the tail rule's (/limit_tail: the envelope) and the member's own ("at c");
    '-' where a member was not reached."""
    rob, lt = tree["robustness"], tree["limit_tail"]
    c = np.asarray(tree["c"].values)

    def letter(v: float) -> str:
        return VERDICT_LETTER.get(int(v), "?") if np.isfinite(v) else "-"

    head = ["c", *[f"N={int(n)}" for n in rob["ring"].values], *[f"{float(t):g}" for t in rob["rtol"].values[1:]]]
    cols = [np.where(np.asarray(rob["unstable"].values[i]) < 0, np.nan, rob["unstable"].values[i])
            for i in range(rob["ring"].size)]
    cols += [np.where(np.asarray(rob["unstable_tol"].values[i]) < 0, np.nan, rob["unstable_tol"].values[i])
             for i in range(1, rob["rtol"].size)]
    if "robustness_limit" in tree.children:
        head.append("median")
        cols.append(np.asarray(tree["robustness_limit"]["verdict"].values, float))
    head += ["tail", "at c"]
    cols += [np.asarray(lt["verdict"].values, float), np.asarray(lt["member_verdict"].values, float)]
    rows = [head]
    for j, x in enumerate(c):
        rows.append([f"{x:g}", *[letter(float(col[j])) for col in cols]])
    return rows


def _from_centre(xi: np.ndarray) -> np.ndarray:
    """Signed ring distance of each site from the largest |xi_n|."""
    N = xi.size
    return (np.arange(N) - int(np.argmax(np.abs(xi))) + N // 2) % N - N // 2


def draw_rings(ax: Any, tree: AnalysisTree) -> None:
    """The lattice's TBs on other rings and at larger eps (groups /lattice_rings, /lattice_large): (s) |xi_n(0)| /
    max against the distance from the centre on each ring at the first eps, and at the larger eps on the first ring;
    (t) the tail against eps on each ring, with every member's residual; (u) the tail along the continuation in c
    against the DpS velocity through (ansatz), unstable members filled."""
    rg = tree["lattice_rings"]
    rings = np.asarray(rg["ring"].values)
    x, v = np.asarray(rg["x"].values), np.asarray(rg["v"].values)
    large = tree["lattice_large"] if "lattice_large" in tree.children else None
    g = ax[0]
    floor = 1e-14
    for k, N in enumerate(rings):
        xi = 0.5 * (x[k, 0, :N] - 1j * v[k, 0, :N])
        a = np.abs(xi) / np.max(np.abs(xi))
        # a marker per ring, hollow and shrinking, so that rings whose far fields coincide all show
        g.semilogy(_from_centre(xi), np.maximum(a, floor), "osD^v<>"[k % 7], color=f"C{k}", ms=7 - 1.2 * k, mfc="none",
                   mew=0.9, label=f"ring of {N}, $\\varepsilon$ = {float(rg['eps_tb'].values[k, 0]):.3g}")
    if large is not None:
        for j, e in enumerate(np.asarray(large["eps_tb"].values)):
            xi = 0.5 * (np.asarray(large["x"].values[j]) - 1j * np.asarray(large["v"].values[j]))
            a = np.abs(xi) / np.max(np.abs(xi))
            g.semilogy(_from_centre(xi), np.maximum(a, floor), "k" + "x+"[j % 2], ms=5,
                       label=f"ring of {rings[0]}, $\\varepsilon$ = {e:.3g} (core first)")
    g.set_ylim(floor / 10.0, 1e5)
    g.set_xlabel("site n minus the centre's")
    g.set_ylabel("$|\\xi_n(0)|$ / max")
    g.set_title("(s) exact TBs of (nc) on larger rings: the far field", fontsize=9)
    g.legend(fontsize=6.5, loc="upper left", ncol=2)

    h = ax[1]
    for k, N in enumerate(rings):
        h.loglog(np.asarray(rg["eps_tb"].values[k]), np.asarray(rg["tail"].values[k]), "o-", color=f"C{k}", ms=4,
                 lw=1.0, label=f"tail, ring of {N}")
    res = [np.asarray(rg["residual"].values).ravel()]
    eps_all = [np.asarray(rg["eps_tb"].values).ravel()]
    if large is not None:
        h.loglog(np.asarray(large["eps_tb"].values), np.asarray(large["tail"].values), "ks", ms=5, mfc="none",
                 label=f"tail, ring of {rings[0]}, larger $\\varepsilon$ (core first)")
        res.append(np.asarray(large["residual"].values))
        eps_all.append(np.asarray(large["eps_tb"].values))
    h.loglog(np.concatenate(eps_all), np.concatenate(res), "k+", ms=6, label="shift-map residual (each TB)")
    h.set_ylim(1e-14, 1e2)
    h.set_xlabel("$\\varepsilon$ at the TB's amplitude")
    h.set_ylabel("max $|\\xi_n|$ on the far quarter ring / max")
    h.set_title("(t) the tail against $\\varepsilon$ and N", fontsize=9)
    h.legend(fontsize=6.5, loc="upper left", ncol=2)

    i_ = ax[2]
    thr = float(tree.attrs["stability_threshold"])
    for k, N in enumerate(rings):
        dc = np.asarray(rg["dps_c_family"].values[k])
        if not np.any(np.isfinite(dc)):
            continue
        tail = np.asarray(rg["tail_family"].values[k])
        un = np.asarray(rg["growth_rate_family"].values[k]) > thr
        i_.semilogy(dc, tail, "-", color=f"C{k}", lw=1.0)
        i_.semilogy(dc[~un], tail[~un], "o", color=f"C{k}", ms=5, mfc="none", label=f"ring of {N}")
        if np.any(un):
            i_.semilogy(dc[un], tail[un], "o", color=f"C{k}", ms=5)
    i_.semilogy([], [], "ko", ms=5, label=f"filled: unstable (growth > {thr:g} per unit t)")
    top = float(np.nanmax(np.asarray(rg["tail_family"].values)))
    i_.set_ylim(top=1e3 * top)    # room for the legend above the largest tail
    i_.set_xlabel("velocity of the DpS TB through (ansatz), 1 / (T $\\varepsilon^{\\alpha-1}$)")
    i_.set_ylabel("tail (far quarter ring) / max")
    i_.set_title("(u) the tail along the continuation in c", fontsize=9)
    i_.legend(fontsize=6.5, loc="upper left")


def draw_zeros(ax: Any, tree: AnalysisTree) -> None:
    """Where the lattice TBs' tail vanishes (group /lattice_zeros): (y), (z) the signed tail along the fine grid of c
    through each minimum on each ring (symmetric log scale, linear within the largest residual), the regula falsi's
    iterates and the located zero; (aa) the table of the zeros: c with its uncertainty, eps, the DpS velocity through
    (ansatz), |sigma|, the residual and the growth rate there."""
    from matplotlib.ticker import MaxNLocator

    zg = tree["lattice_zeros"]
    rings = [int(N) for N in zg["zero_ring"].values]
    lin = float(np.nanmax(np.asarray(zg["residual_grid"].values)))
    for j, (a, name) in enumerate(((ax[0], "(y) the first"), (ax[1], "(z) the second"))):
        for k, N in enumerate(rings):
            c = np.asarray(zg["c_tb_grid"].values[k, j])
            a.plot(1e3 * c, zg["sigma_grid"].values[k, j], "osD^"[k % 4] + "-", color=f"C{k}", ms=5, mfc="none",
                   lw=1.0, label=f"grid, ring of {N}")
            a.plot(1e3 * np.asarray(zg["c_iterate"].values[k, j]), zg["sigma_iterate"].values[k, j], "+",
                   color=f"C{k}", ms=7)
            a.plot(1e3 * float(zg["c_tb"].values[k, j]), float(zg["sigma"].values[k, j]), "*", color=f"C{k}", ms=11,
                   mec="k", mew=0.5)
        a.plot([], [], "k+", ms=7, label="regula falsi iterates")
        a.plot([], [], "k*", ms=11, label="zero located")
        a.axhspan(-lin, lin, color="0.85", zorder=0, label=f"|$\\sigma$| below the largest residual, {lin:.1g}")
        top = float(np.nanmax(np.abs(zg["sigma_grid"].values[:, j])))
        a.set_yscale("symlog", linthresh=lin)
        decades = 10.0 ** np.arange(np.ceil(np.log10(lin)), np.ceil(np.log10(top)) + 1)
        a.set_yticks([*(-decades[::-1]), 0.0, *decades])
        a.set_ylim(-3.0 * top, 1e3 * top)     # room for the legend above the largest tail
        a.xaxis.set_major_locator(MaxNLocator(5))
        a.set_xlabel("velocity c (sites per unit t) $\\times 10^3$")
        a.set_ylabel("signed tail $\\sigma$ (far field at the antipode / max)")
        a.set_title(f"{name} minimum of the tail: its sign along c", fontsize=9)
        a.legend(fontsize=6.5, loc="upper left", ncol=2)
    t = ax[2]
    t.axis("off")
    head = ["ring", "min.", "c $\\times 10^3$", "$\\varepsilon$", "DpS c", "|$\\sigma$|", "residual", "growth"]
    rows = []
    for k, N in enumerate(rings):
        for j in range(2):
            def val(key: str, k: int = k, j: int = j) -> float:
                return float(zg[key].values[k, j])
            if not np.isfinite(val("c_tb")):
                rows.append([str(N), str(j), "no zero", "", "", "", "", ""])
                continue
            rows.append([str(N), str(j), f"{1e3 * val('c_tb'):.6f}({1e9 * val('c_error'):.0f})",
                         f"{val('eps_tb'):.5f}", f"{val('dps_c'):.4f}", f"{abs(val('sigma')):.1e}",
                         f"{val('residual'):.1e}", f"{val('growth_rate'):.0e}"])
    tab = t.table(cellText=rows, colLabels=head, cellLoc="center", bbox=[0.0, 0.0, 1.0, 1.0],
                  colWidths=[0.07, 0.06, 0.21, 0.12, 0.11, 0.13, 0.15, 0.15])
    tab.auto_set_font_size(False)
    tab.set_fontsize(6)
    t.set_title("(aa) the zeros (c: uncertainty in its last digits;\ngrowth rate per unit t)", fontsize=9)


def draw_limit(ax: Any, tree: AnalysisTree) -> None:
    """Panels (m)-(o), the verdicts in the limit N -> infinity: (m) the growth rate along the fine grid of c on each
    ring (unstable points only) and the tail's MI rate on the largest ring; (n) per member the median growth rate
    of its neighbourhood on each ring, the limit verdict of each member at the bottom; (o) per ring the fraction of
    the fine grid that is unstable, where the tail is modulationally unstable (its MI rate above the threshold) and
    elsewhere."""
    lim = tree["robustness_limit"]
    attrs = tree.attrs
    thr = float(attrs["stability_threshold"])
    floor = thr / 100.0
    rings = [int(x) for x in lim["limit_ring"].values]
    cf = np.asarray(lim["c_fine"].values)
    G = np.asarray(lim["growth_rate"].values, float)
    U = np.asarray(lim["unstable"].values) == 1
    mi = np.asarray(lim["tail_mi_rate"].values, float)
    marks = "os^v<>Dp"

    j = ax[0]
    for i, ring in enumerate(rings):
        j.semilogy(cf[U[i]], G[i][U[i]], f"C{i}{marks[i % 8]}", ms=3.5, mfc="none" if i else None,
                   label=f"unstable, ring of {ring}")
    big = len(rings) - 1
    j.semilogy(cf, np.where(mi[big] > floor, mi[big], np.nan), "k-", lw=0.8,
               label=f"tail's MI rate (ring of {rings[big]})")
    j.axhline(thr, color="0.4", ls="--", lw=0.8, label="stability threshold")
    j.set_ylim(floor, 100.0 * max(float(np.nanmax(np.where(U, G, np.nan))) if U.any() else thr, thr))
    j.set_xlabel("velocity c (fine grid)")
    j.set_ylabel("growth rate ln max$|\\mu|$ / T")
    j.set_title(f"(m) fine scan, step {float(attrs['limit_step']):g}: windows and the tail's MI", fontsize=9)
    j.legend(fontsize=6, loc="upper left", ncol=2)

    k = ax[1]
    c = np.asarray(lim["c"].values)
    typ = np.asarray(lim["typical_growth"].values, float)        # (c, ring)
    for i, ring in enumerate(rings):
        k.semilogy(c, np.maximum(typ[:, i], floor), f"C{i}{marks[i % 8]}", ms=5, mfc="none" if i else None,
                   label=f"ring of {ring}")
    k.axhline(thr, color="0.4", ls="--", lw=0.8, label="stability threshold")
    for x, v in zip(c, np.asarray(lim["verdict"].values), strict=True):
        k.text(x, floor / 4.0, VERDICT_LETTER.get(int(v), "?"), ha="center", va="center", fontsize=7,
               color=VERDICT_COLOUR.get(int(v), "0.4"))
    k.set_ylim(floor / 12.0, 300.0 * max(float(np.nanmax(typ)), thr))
    k.set_xlabel("velocity c (member)")
    k.set_ylabel(f"median growth over c $\\pm$ {float(attrs['limit_halfwidth']):g} (floor {floor:g})")
    k.set_title("(n) the typical member near c; limit verdict S, U (?: undecided)", fontsize=9)
    k.legend(fontsize=6, loc="upper left", ncol=2)

    m = ax[2]
    ok = np.isfinite(G)
    mi_zone = ok & (mi > thr)
    rest = ok & ~(mi > thr)
    f_mi = [float(np.mean(U[i][mi_zone[i]])) if mi_zone[i].any() else np.nan for i in range(len(rings))]
    f_rest = [float(np.mean(U[i][rest[i]])) if rest[i].any() else np.nan for i in range(len(rings))]
    m.plot(rings, f_mi, "C3o-", ms=5, label="where the tail's MI rate > threshold")
    m.plot(rings, f_rest, "C0s-", ms=5, label="elsewhere")
    m.set_ylim(-0.05, 1.15)      # a fraction 0 stays inside the frame
    m.set_xticks(rings)
    m.set_xlabel("sites N of the ring")
    m.set_ylabel("fraction of the fine grid unstable")
    m.set_title("(o) unstable fraction against N", fontsize=9)
    m.legend(fontsize=7, loc="upper right")


def draw_motion(ax: Any, tree: AnalysisTree) -> None:
    """Panels (g)-(i): the TB in motion in (nc) at each eps and in (dfnls)."""
    mo = tree["motion"]
    attrs = tree.attrs
    s = np.asarray(mo["s"].values)
    eps = np.asarray(mo["eps"].values)
    colours = [f"C{k}" for k in range(len(eps))]

    g = ax[0]
    g.plot(s, np.asarray(mo["dps_distance"].values), "k-", lw=2.2, label="DpS (dfnls)")
    for k, e in enumerate(eps):
        g.plot(s, np.asarray(mo["distance"].values[k]), "-", color=colours[k], lw=1.0, label=f"(nc), eps = {e:g}")
    g.set_xlabel("$\\tau / T$ (sites the DpS TB travels)")
    g.set_ylabel("distance travelled (sites)")
    g.set_title(f"(g) TB of c = {float(attrs['motion_c']):.3g} launched by (ansatz), ring of "
                f"{int(attrs['motion_ring'])}", fontsize=9)
    g.legend(fontsize=6.5, loc="upper left")

    h = ax[1]
    d = np.asarray(mo["deficit"].values)
    h.loglog(eps, d, "C3o", ms=5, label="1 - v / (c eps$^{\\alpha-1}$)")
    p, u = float(attrs["motion_order"]), float(attrs["motion_order_uncertainty"])
    if np.isfinite(p):
        K, corr = float(attrs["motion_order_constant"]), float(attrs["motion_order_correction"])
        fine = np.geomspace(float(eps.min()), float(eps.max()), 100)
        al = float(attrs["motion_order_expected"]) + 1.0
        h.loglog(fine, K * fine**p * np.exp(corr * fine ** (al - 1.0)), "k-", lw=0.8,
                 label=f"fit: order {p:.3f} $\\pm$ {u:.1g} (expected {al - 1.0:g})")
    h.set_xlabel("eps of (ansatz)")
    h.set_ylabel("speed deficit of (nc) against DpS")
    h.set_title("(h) the lattice's speed tends to DpS's as eps $\\to$ 0", fontsize=9)
    h.legend(fontsize=7, loc="lower right")

    r = ax[2]
    floor = 1e-3 * float(np.min(mo["radiation_end"].values))
    for k, e in enumerate(eps):
        r.semilogy(s, np.maximum(np.asarray(mo["radiation"].values[k]), floor), "-", color=colours[k], lw=1.0,
                   label=f"(nc), eps = {e:g}")
    r.semilogy(s, np.maximum(np.asarray(mo["dps_radiation"].values), floor), "k--", lw=1.2,
               label="DpS (dfnls)")
    r.set_ylim(floor / 2, 30.0 * float(np.max(mo["radiation"].values)))
    r.set_xlabel("$\\tau / T$")
    r.set_ylabel(f"energy outside $\\pm${int(attrs['motion_window'])} sites / total (floor {floor:.0e})")
    r.set_title("(i) radiation left behind", fontsize=9)
    r.legend(fontsize=6.5, loc="upper left", ncol=2)


def _lattice_panels(tree: AnalysisTree, ax: np.ndarray) -> None:
    """(j) |xi_n(0)| / eps of the lattice's exact TBs at each eps and |A_n(0)| of the DpS TB through the ansatz at
    the smallest (aligned on the peak); (k) their distance to that DpS TB against eps with the fitted power, and
    their shift-map residuals; (l) item 3: the DpS member and the exact TB launched the same way in (nc), their
    speed deficits against the DpS TB's c eps^(alpha-1) and the radiation each leaves, against eps."""
    le, st = tree["lattice_eps"], tree["lattice_states"]
    attrs = tree.attrs
    eps = np.asarray(le["eps_tb"].values)
    xi = 0.5 * (np.asarray(st["x"].values) - 1j * np.asarray(st["v"].values))
    n = np.asarray(st["site"].values)
    A = np.asarray(st["dps_A_re"].values[-1]) + 1j * np.asarray(st["dps_A_im"].values[-1])
    g = ax[0]
    prof = np.abs(xi) / eps[:, None]
    bottom = 0.2 * float(np.min(prof))
    for k, e in enumerate(eps):
        g.semilogy(n, prof[k], "o-", color=f"C{k}", ms=3, lw=1.0, label=f"(nc) TB, $\\varepsilon$ = {e:.3g}")
    dps = np.roll(np.abs(A), int(np.argmax(prof[-1])) - int(np.argmax(np.abs(A))))
    g.semilogy(n, np.where(dps >= bottom, dps, np.nan), "k--", lw=1.0,
               label=f"DpS TB through (ansatz), $\\varepsilon$ = {eps[-1]:.3g}")
    g.set_ylim(bottom, 1e4 * float(np.max(prof)))   # room for the legend above the peak
    g.set_xlabel("site n")
    g.set_ylabel("$|\\xi_n(0)| / \\varepsilon$, $\\xi_n = (x_n - i v_n)/2$")
    g.set_title(f"(j) exact TBs of (nc) from c = {float(attrs['lattice_source_c']):.3g}, ring of {n.size}",
                fontsize=9)
    g.legend(fontsize=6.5, loc="upper left", ncol=2)

    h = ax[1]
    d = np.asarray(le["ansatz_distance"].values)
    h.loglog(eps, d, "C0o", ms=5, label="distance to the DpS TB through (ansatz)")
    p, u = float(attrs["lattice_distance_power"]), float(attrs["lattice_distance_power_error"])
    fine = np.geomspace(float(eps.min()), float(eps.max()), 50)
    K = float(np.exp(np.mean(np.log(d) - p * np.log(eps))))
    h.loglog(fine, K * fine**p, "k-", lw=0.8, label=f"fit $\\propto \\varepsilon^{{{p:.3f} \\pm {u:.1g}}}$ "
             f"(expected {float(attrs['lattice_distance_power_expected']):g})")
    h.loglog(eps, np.asarray(le["residual"].values), "k+", ms=7, label="shift-map residual of the TB")
    h.set_ylim(1e-13, 30.0 * float(np.max(d)))
    h.set_xlabel("$\\varepsilon$ at the TB's amplitude")
    h.set_ylabel("relative to max $|z|$")
    h.set_title("(k) (nc) TBs against DpS's", fontsize=9)
    h.legend(fontsize=6.5, loc="center right")

    i_ = ax[2]
    e0 = np.asarray(le["eps_lattice"].values)
    own = np.asarray(le["ansatz_period"].values) / np.asarray(le["period"].values)
    lines = i_.semilogx(e0, np.asarray(le["dps_speed"].values), "C3o-", ms=5, lw=1.0, label="speed: DpS TB launched")
    lines += i_.semilogx(e0, np.asarray(le["exact_speed"].values), "C0s--", ms=7, lw=1.0, mfc="none",
                         label="speed: exact TB launched")
    lines += i_.semilogx(e0, own, "kx", ms=6, label="$T_d \\varepsilon^{1-\\alpha}$ / T: the exact TB's own")
    i_.set_ylabel("speed / (c $\\varepsilon^{\\alpha-1}$) of the DpS TB")
    i_.set_xlabel("$\\varepsilon$ of (ansatz)")
    lo = float(min(np.min(own), np.min(le["dps_speed"].values)))
    # the speeds in the upper quarter, the radiation in the middle, the legend between them and the floor
    i_.set_ylim(lo - 3.0 * (1.0 - lo), 1.0)
    r = i_.twinx()
    floor = 1e-15
    lines += r.loglog(e0, np.maximum(np.asarray(le["dps_radiation"].values), floor), "C3v:", ms=5, lw=1.0,
                      label="radiation: DpS TB launched")
    lines += r.loglog(e0, np.maximum(np.asarray(le["exact_radiation"].values), floor), "C0^:", ms=5, lw=1.0,
                      mfc="none", label=f"radiation: exact TB launched (floor {floor:g})")
    r.set_ylim(floor / 10.0, 1e6)
    r.set_ylabel("energy outside the window / total, at the end")
    for a, x in ((h, eps), (i_, e0)):
        a.set_xticks([float(v) for v in x], [f"{float(v):.2g}" for v in x])
        a.minorticks_off()
    i_.set_title("(l) launched in (nc): DpS TB against the exact TB", fontsize=9)
    i_.legend(lines, [ln.get_label() for ln in lines], fontsize=6.5, loc="lower left", bbox_to_anchor=(0.0, 0.08))
