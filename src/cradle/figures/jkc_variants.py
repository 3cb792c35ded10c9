"""Figure beyond the paper: JKC 2013's variants of a kicked chain (jkc-variants).

Drawn by :func:`draw` from results/jkc-variants/jkc-variants.nc (:mod:`cradle.analyses.jkc_variants`). One column
per scene (surface mode, boomeron, nanopteron):

(a) space-time map of the local energy log10(e_n / H) of the lattice run (ncimperfect);
(b) the same kick in the harmonic, uncompressed lattice (nc), the reference;
(c) the smoothed energy centre X(t), lattice and DpS, scene and reference; reversals marked (filled:
    spontaneous, open: bounces at a free end), the lattice scene's only; the title says when the kick is outside
    DpS's measured range;
(d) what the scene is about: the energy fraction on the first m beads (surface mode); the core position
    (boomeron); the core and its left and right tails (nanopteron), scene against reference.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.figures import AnalysisTree, dps_range_top, figure, legend_outside

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.image import AxesImage

#: finite points each data panel holds at least (tests/figures/test_figures_render.py)
MIN_POINTS = 50

_TITLES = {"surface": "surface mode", "boomeron": "boomeron", "nanopteron": "nanopteron"}
_STYLE = {"exact": ("C0", "-"), "dps": ("C0", ":"), "reference": ("C3", "-"), "reference_dps": ("C3", ":")}
_LABEL = {"exact": "scene, lattice", "dps": "scene, DpS", "reference": "harmonic kick, lattice",
          "reference_dps": "harmonic kick, DpS"}
#: the floor of the energy maps' colour scale, log10(e_n / H)
FLOOR = -4.0


def _map(ax: Axes, g: AnalysisTree, model: int, title: str) -> AxesImage:
    e = np.asarray(g["energy_map"].values)[model]
    t, n = np.asarray(g["t"].values), np.asarray(g["n"].values)
    z = np.log10(np.maximum(e / e.sum(-1, keepdims=True), 10.0**FLOOR))
    im = ax.imshow(z, origin="lower", aspect="auto", extent=(n[0] - 0.5, n[-1] + 0.5, t[0], t[-1]),
                   vmin=FLOOR, vmax=0.0, cmap="magma", interpolation="nearest")
    ax.set_xlabel("bead n")
    ax.set_ylabel("t")
    ax.set_title(title, fontsize=9)
    return im


def draw(tree: AnalysisTree) -> Figure:
    """The panels above, one column per group of the jkc-variants file."""
    roles = [r for r in ("surface", "boomeron", "nanopteron") if r in tree.children]
    fig, ax = figure(4, len(roles), width=5.2 * len(roles), height=15.0, squeeze=False)
    a = tree.attrs
    im = None
    for j, role in enumerate(roles):
        g = tree[role]

        def letter(row: int, j: int = j) -> str:
            """The panel's letter, running down each column and on through the columns: once per figure."""
            return f"({'abcdefghijklmnopqrstuvwxyz'[j * 4 + row]})"

        models = [str(m) for m in g["model"].values]
        scene = a.get(f"{role}_scene", role)
        what = (rf"$\beta$ = {float(a[f'{role}_beta']):g}" if float(a.get(f"{role}_beta", 0.0)) != 0.0
                else rf"$\delta_0$ = {float(a[f'{role}_delta0']):g}")
        head = f"{_TITLES[role]} ('{scene}': {what}, kick v = {float(a[f'{role}_velocity']):g}, {a[f'{role}_bc']})"
        im = _map(ax[0, j], g, models.index("exact"), f"{letter(0)} {head}\nlattice (ncimperfect)")
        _map(ax[1, j], g, models.index("reference"), f"{letter(1)} the same kick, harmonic uncompressed lattice (nc)")
        t = np.asarray(g["t"].values)
        C = ax[2, j]
        Xs = np.asarray(g["X_smooth"].values)
        for i, m in enumerate(models):
            c, ls = _STYLE[m]
            C.plot(t, Xs[i], ls, color=c, lw=1.0, label=_LABEL[m])
        i = models.index("exact")
        rt = np.asarray(g["reversal_time_centre"].values)[i]
        rs = np.asarray(g["reversal_site_centre"].values)[i]
        sp = np.asarray(g["reversal_spontaneous_centre"].values)[i]
        ok = np.isfinite(rt)
        C.plot(rt[ok & (sp == 1)], rs[ok & (sp == 1)], "ko", ms=6, label="reversal (lattice): spontaneous")
        C.plot(rt[ok & (sp == 0)], rs[ok & (sp == 0)], "ko", mfc="none", ms=6, label="reversal (lattice): bounce")
        C.set_xlabel("t")
        C.set_ylabel("energy centre X (smoothed), bead")
        # a bead kicked from rest: the amplitude (ansatz) counts is its velocity (cradle.measurements.dps_range)
        kick, top = abs(float(a[f"{role}_velocity"])), dps_range_top()
        C.set_title(f"{letter(2)} energy centre X = sum n e_n / sum e_n" + (
            f"\nkick {kick:g} > {top:g}: outside DpS's measured range (dps-validity)" if kick > top else ""),
            fontsize=9)
        D = ax[3, j]
        if role == "surface":
            f = np.asarray(g["boundary_fraction"].values)
            for k, m in enumerate(np.asarray(g["boundary"].values)):
                for i, name in enumerate(models):
                    if name.endswith("dps"):
                        continue
                    c, _ = _STYLE[name]
                    D.plot(t, f[i, k], "-" if k == 0 else "--", color=c, lw=1.0,
                           label=f"{_LABEL[name]}: first {int(m)} beads")
            D.set_ylabel("energy fraction near the boundary")
            D.set_title(f"{letter(3)} energy on the first m beads", fontsize=9)
        elif role == "boomeron":
            p = np.asarray(g["core_smooth"].values)
            for i, name in enumerate(models):
                c, ls = _STYLE[name]
                D.plot(t, p[i], ls, color=c, lw=1.0, label=_LABEL[name])
            w = int(np.asarray(g["halfwidth"].values)[0])
            D.set_ylabel("core position (smoothed), bead")
            D.set_title(f"{letter(3)} centre of the {2 * w + 1}-bead window holding the most energy", fontsize=9)
        else:
            w = int(np.asarray(g["halfwidth"].values)[0])
            for i, name in enumerate(models):
                if name.endswith("dps"):
                    continue
                c, _ = _STYLE[name]
                for key, ls in (("core_fraction", "-"), ("left_tail", "--"), ("right_tail", ":")):
                    D.plot(t, np.asarray(g[key].values)[i, 0], ls, color=c, lw=1.0,
                           label=f"{_LABEL[name]}: {key.replace('_', ' ')}")
            D.set_ylabel("energy fraction")
            D.set_title(f"{letter(3)} core ({2 * w + 1} beads) and the tails on either side", fontsize=9)
        D.set_xlabel("t")
        legend_outside(C, fontsize=6) if j == len(roles) - 1 else None
        D.legend(fontsize=6, loc="upper center", bbox_to_anchor=(0.5, -0.22), ncol=2, borderaxespad=0.0)
    if im is not None:
        bar = fig.colorbar(im, ax=ax[:2, -1], shrink=0.6)
        bar.set_label(r"$\log_{10}(e_n / H)$")
    return fig
