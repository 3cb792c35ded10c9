"""Figure theorem1: Theorem 1 measured, the exact travelling waves of (nc) with V = V0 against the DpS
relation (wleadingorder), from results/theorem1/theorem1.nc."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.figures import AnalysisTree, figure, legend_outside, plain_log_ticks

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: finite points each data panel holds at least (tests/figures/test_figures_render.py): a few amplitudes a and modes J
MIN_POINTS = 5


def _qlabel(q: float) -> str:
    """q as a label: a fraction of pi where it is one (pi/5, 4pi/5), else 3 digits."""
    frac = q / np.pi
    for den in (1, 2, 3, 4, 5, 6, 8, 10):
        num = round(frac * den)
        if abs(frac * den - num) < 1e-9:
            if num == 0:
                return "0"
            top = "" if num == 1 else str(num)
            return rf"${top}\pi$" if den == 1 else rf"${top}\pi/{den}$"
    return f"{q:.3g}"


def draw(tree: AnalysisTree) -> Figure:
    """Exact frequencies against (wleadingorder), the relative correction, v_a against (va), convergence.

    ``tree``: the groups /waves, /profiles, /convergence, /scenes of the theorem1 file."""
    fig, ax = figure(2, 2, width=10.0, height=7.6)
    ds, scenes = tree["waves"], tree["scenes"]
    prof, conv = tree["profiles"], tree["convergence"]
    alphas, qs, a = ds["alpha"].values, ds["q"].values, ds["a"].values
    ia = int(np.argmin(np.abs(alphas - 1.5)))
    colors = [f"C{i}" for i in range(len(qs))]
    # (a) omega_a - 1 against a, alpha = alphas[ia]
    A = ax[0, 0]
    for iq, q in enumerate(qs):
        A.loglog(a, ds["omega"].values[ia, iq] - 1.0, "-", color=colors[iq], label=f"exact, q = {_qlabel(q)}")
        A.loglog(a, ds["omega_dps"].values[ia, iq] - 1.0, "--", color=colors[iq], lw=0.8)
    A.set_xlabel("a")
    A.set_ylabel(r"$\omega_a - 1$")
    A.set_title(rf"(a) exact (solid) vs DpS (dashed), $\alpha$ = {alphas[ia]:g}", fontsize=9)
    A.legend(fontsize=7)
    if scenes.sizes.get("scene", 0):
        lines = [f"{n}: a={scenes['a'].values[i]:.4g}, drift {scenes['drift'].values[i]:.3g} rad"
                 for i, n in enumerate(str(s) for s in scenes["scene"].values)]
        A.text(0.98, 0.02, "\n".join(lines), transform=A.transAxes, ha="right", va="bottom", fontsize=6.5)
    # (b) relative correction
    B = ax[0, 1]
    styles = ["-", "--", ":", "-."]
    sign_changes = False
    for ja, al in enumerate(alphas):
        for iq, q in enumerate(qs):
            signed = ds["rel_correction"].values[ja, iq]
            r = np.abs(signed)
            eps = a ** (al - 1.0)
            ok = eps >= 1e-7
            B.loglog(a[ok], r[ok], styles[ja % 4], color=colors[iq], lw=1.0,
                     label=rf"$\alpha$={al:g}, q={_qlabel(q)}, slope {ds['correction_slope'].values[ja, iq]:.3f}")
            # where the correction changes sign |.| dips towards 0 between two amplitudes: marked, not a kink
            flip = np.flatnonzero(ok[:-1] & ok[1:] & (np.sign(signed[:-1]) * np.sign(signed[1:]) < 0))
            if flip.size:
                B.plot(np.sqrt(a[flip] * a[flip + 1]), np.sqrt(r[flip] * r[flip + 1]), "x", color=colors[iq],
                       ms=6, mew=1.2)
                sign_changes = True
    B.set_xlabel("a")
    B.set_ylabel(r"$|\omega_a - \omega_{DpS}| / (\omega_{DpS} - 1)$")
    if sign_changes:
        B.plot([], [], "x", color="0.3", ms=6, mew=1.2, label="x: the correction changes sign\n(|.| dips to 0 there)")
    B.set_title(r"(b) relative correction, expected slope $\alpha - 1$", fontsize=9)
    legend_outside(B, fontsize=5.5)
    # (c) profile correction against (va)
    C = ax[1, 0]
    xi = prof["xi"].values
    for iq, q in enumerate(qs):
        C.plot(xi, prof["va_leading"].values[ia, iq], "-", color=colors[iq], lw=2.2, alpha=0.4)
        C.plot(xi, prof["v_small"].values[ia, iq], "--", color=colors[iq], lw=1.0,
               label=f"q = {_qlabel(q)}")
        C.plot(xi, prof["v_large"].values[ia, iq], ":", color=colors[iq], lw=1.0)
    C.set_xlabel(r"$\xi$")
    C.set_ylabel(r"$v_a(\xi)$")
    C.plot([], [], "-", color="0.3", lw=2.2, alpha=0.4, label="leading order (va)")
    C.plot([], [], "--", color="0.3", lw=1.0, label=f"exact, a = {a[0]:.0e}")
    C.plot([], [], ":", color="0.3", lw=1.0, label=f"exact, a = {a[-1]:g}")
    C.set_title("(c) profile correction $v_a(\\xi)$ of (ansatzu),\nexact and its leading order (va)", fontsize=9)
    legend_outside(C, fontsize=7)
    # (d) convergence in the number of modes
    D = ax[1, 1]
    modes = conv["modes"].values
    for ja, al in enumerate(alphas):
        for iq, q in enumerate(qs):
            e = conv["profile_error"].values[ja, iq]
            rate = conv["decay_rate"].values[ja, iq]
            D.loglog(modes[e > 0], e[e > 0], styles[ja % 4] + "o", color=colors[iq], ms=3, lw=0.8,
                     label=rf"$\alpha$={al:g}, q={_qlabel(q)}: $|v_j| \sim j^{{-{rate:.2f}}}$")
    D.set_xlabel("modes J")
    D.set_ylabel(r"$\max_\xi |v_J - v_{ref}|$")
    D.set_title(f"(d) convergence at a = {tree.attrs.get('convergence_a', np.nan):g} "
                f"(ref. J = {tree.attrs.get('reference_modes', '')})", fontsize=9)
    legend_outside(D, fontsize=5.5)
    for panel in ax.flat:
        plain_log_ticks(panel)
    return fig
