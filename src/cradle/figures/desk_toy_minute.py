"""Figure beyond the paper: a desk toy watched for a minute (desk-toy-minute), in SI.

Drawn by :func:`draw` from results/desk-toy-minute/[full/]desk-toy-minute.nc (:mod:`cradle.analyses.desk_toy_minute`).

The main desk toy is the 5-ball cradle with one ball lifted (else the first of the file). (a) its energy over its
initial energy against time, every case (colour: the restitution e; line style: the drag rate, or the hard
spheres: dotted with a constant e, dash-dotted with the contact's own e(v)), the grey line at lifted / N the share
of the centre-of-mass swing mode, which the contacts cannot dissipate; (b) its centre-of-mass share S (thick) and
phase coherence R (thin), the first (ncdamped) case and the hard spheres of constant e; (c) each ball's swing
amplitude (mm) at every out-swing against the logarithm of time, the first (ncdamped) case; (d) the balls out at
every out-swing, every lifted count of the main chain (first (ncdamped) case solid, the hard spheres of its constant
e dotted); (e) the one-out-one-out share f_k of the same runs, the pattern thresholds grey; (f) the time to in-phase
motion (S above its first threshold) against the number of balls, every lifted count (marker) and restitution
(colour), (ncdamped) at the lower drag filled, the hard spheres with the contacts' law e(v) open; drawn when some
run got there.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.figures import figure

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

#: finite points each data panel holds at least (tests/figures/test_figures_render.py)
MIN_POINTS = 3

_DRAG_STYLES = ("-", "--", "-.", (0, (5, 1, 1, 1)))
_MARKERS = ("o", "s", "^", "D", "v", "P")
#: the line style of the hard spheres with the contact's restitution law e(v)
_LAW_STYLE = (0, (4, 1, 1, 1, 1, 1))


def _groups(tree: xr.DataTree) -> list:
    return [tree[s.strip()] for s in str(tree.attrs["desk_toys"]).split(",") if s.strip()]


def _main(groups: list) -> xr.DataTree:
    for g in groups:
        if int(g.attrs["n_beads"]) == 5 and int(g.attrs["lifted"]) == 1:
            return g
    return groups[0]


def _styles(g: xr.DataTree) -> list[tuple[str, object, str]]:
    """(colour, line style, label) of every case of a group."""
    names = [str(c) for c in np.asarray(g["case"].values)]
    es_all, rates_all = np.asarray(g["restitution"].values), np.asarray(g["drag_rate"].values)
    es = sorted({float(e) for e in es_all})
    rates = sorted({float(r) for r, n in zip(rates_all, names, strict=True) if n.startswith("nc")})
    out: list[tuple[str, object, str]] = []
    for name, e, r in zip(names, es_all, rates_all, strict=True):
        colour = f"C{es.index(float(e))}"
        if name.startswith("hard e(v)"):
            out.append((colour, _LAW_STYLE, f"hard, e(v) of the same A (e = {float(e):g})"))
        elif name.startswith("hard"):
            out.append((colour, ":", f"hard, constant e = {float(e):g}"))
        else:
            i = rates.index(float(r))
            out.append((colour, _DRAG_STYLES[i % 4], f"(ncdamped) e = {float(e):g}, drag {float(r):.3g}/s"))
    return out


def _first(g: xr.DataTree, model: str) -> int:
    names = [str(c) for c in np.asarray(g["case"].values)]
    return next(i for i, n in enumerate(names) if n.startswith(model))


def draw(tree: xr.DataTree) -> Figure:
    """The panels above from the groups of the desk-toy-minute file."""
    from matplotlib import colormaps
    from matplotlib.lines import Line2D
    from matplotlib.ticker import NullFormatter

    groups = _groups(tree)
    main = _main(groups)
    N, lifted = int(main.attrs["n_beads"]), int(main.attrs["lifted"])
    fig, ax = figure(2, 3, width=14.0, height=8.4, squeeze=False)
    styles = _styles(main)
    t = np.asarray(main["t"].values)
    E = np.asarray(main["energy"].values)
    A = ax[0, 0]
    for c, (colour, ls, _) in enumerate(styles):
        A.plot(t, E[c] / E[c, 0], ls=ls, color=colour, lw=1.1)
    A.axhline(lifted / N, color="0.6", lw=0.8)
    A.set_title(f"(a) {N} balls, {lifted} lifted: energy / initial energy;\ngrey: the centre-of-mass share "
                f"{lifted}/{N}", fontsize=9)
    A.set_xlabel("time (s)")
    A.set_ylabel("$H(t) / H(0)$")
    A.set_ylim(0.0, 1.05)

    B = ax[0, 1]
    for model in ("nc", "hard"):
        c = _first(main, model)
        colour, ls, _ = styles[c]
        B.plot(t, np.asarray(main["com_share"].values)[c], ls=ls, color=colour, lw=1.3)
        B.plot(t, np.asarray(main["phase_coherence"].values)[c], ls=ls, color=colour, lw=0.6, alpha=0.7)
    B.set_title("(b) centre-of-mass share S (thick), phase coherence R (thin);\nfirst (ncdamped) case and first "
                "hard spheres", fontsize=9)
    B.set_xlabel("time (s)")
    B.set_ylabel("S, R")
    B.set_ylim(-0.02, 1.05)

    C = ax[0, 2]
    c = _first(main, "nc")
    ts = np.asarray(main["swing_time"].values)
    amp = np.asarray(main["amplitude"].values)[c] * 1e3
    cmap = colormaps["viridis"]
    for n in range(N):
        C.plot(ts, amp[:, n], ".-", ms=2.5, lw=0.7, color=cmap(n / max(1, N - 1) * 0.9))
    C.set_title(f"(c) swing amplitude of each ball at every out-swing (mm);\n{styles[c][2]}", fontsize=9)
    C.set_xscale("log")   # the break-up of the first swings and the settling beside each other
    ticks = [v for v in (0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0, 300.0) if ts[0] <= v <= ts[-1]]
    C.set_xticks(ticks, [f"{v:g}" for v in ticks])
    C.xaxis.set_minor_formatter(NullFormatter())   # the minor labels of a short span run into each other
    C.set_xlabel("time (s, logarithmic)")
    C.set_ylabel("amplitude (mm)")
    C.legend(handles=[Line2D([], [], color=cmap(n / max(1, N - 1) * 0.9), lw=2, label=f"ball {n}")
                      for n in range(N)], fontsize=6, loc="upper left", bbox_to_anchor=(1.01, 1.0),
             borderaxespad=0, title="ball (colour)", title_fontsize=6)

    D, F = ax[1, 0], ax[1, 1]
    same = [g for g in groups if int(g.attrs["n_beads"]) == N]
    for j, g in enumerate(same):
        k = int(g.attrs["lifted"])
        tsg = np.asarray(g["swing_time"].values)
        for model, ls in (("nc", "-"), ("hard", ":")):
            c = _first(g, model)
            D.plot(tsg, np.asarray(g["balls_out"].values)[c] + 0.08 * j, ls=ls, marker=_MARKERS[j % 6], ms=2.5,
                   lw=0.8, color=f"C{j + 2}", drawstyle="steps-mid")
            F.plot(tsg, np.asarray(g["share"].values)[c], ls=ls, marker=_MARKERS[j % 6], ms=2.5, lw=0.8,
                   color=f"C{j + 2}", label=f"{k} lifted" if model == "nc" else None)
    D.set_title(f"(d) {N} balls: balls out at every out-swing\n(each lifted count shifted up by 0.08 from the "
                "previous)", fontsize=9)
    D.set_xlabel("time (s)")
    D.set_ylabel("balls out")
    D.set_ylim(0.5, N + 0.5)
    for th in np.asarray(main["pattern_threshold"].values):
        F.axhline(th, color="0.6", lw=0.6)
    F.set_title(f"(e) {N} balls: one-out-one-out share $f_k$;\ngrey: thresholds "
                + ", ".join(f"{v:g}" for v in np.asarray(main["pattern_threshold"].values)), fontsize=9)
    F.set_xlabel("time (s)")
    F.set_ylabel("$f_k$")
    F.set_ylim(-0.02, 1.05)
    F.legend(handles=[Line2D([], [], color=f"C{j + 2}", marker=_MARKERS[j % 6], ls="none",
                             label=f"{int(g.attrs['lifted'])} lifted") for j, g in enumerate(same)]
             + [Line2D([], [], color="0.3", ls="-", label=styles[_first(main, 'nc')][2]),
                Line2D([], [], color="0.3", ls=":", label=styles[_first(main, 'hard')][2])],
             fontsize=6, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0,
             title="(d), (e): lifted (colour, marker)", title_fontsize=6)

    G = ax[1, 2]
    _inphase_panel(G, groups, tree)
    handles = [Line2D([], [], color=colour, ls=ls, lw=1.2, label=label) for colour, ls, label in styles]
    fig.legend(handles=handles, fontsize=7, loc="outside lower center", ncols=min(2, len(handles)), frameon=False,
               title="case, panel (a) (colour: e at the reference speed; line style: the drag, or the hard "
                     "spheres' e); (b): the first (ncdamped) case and the hard spheres of constant e",
               title_fontsize=7)
    fig.suptitle(f"A desk toy watched for {float(tree.attrs['duration_s']):g} s: {tree.attrs['cradle']}, released "
                 f"from {float(tree.attrs['angle_deg']):g}°", fontsize=10)
    return fig


def _inphase_panel(G: Axes, groups: list, tree: xr.DataTree) -> None:
    from matplotlib.lines import Line2D

    points = []
    for g in groups:
        N, k = int(g.attrs["n_beads"]), int(g.attrs["lifted"])
        names = [str(c) for c in np.asarray(g["case"].values)]
        es = sorted({float(e) for e in np.asarray(g["restitution"].values)})
        low = min(float(r) for r, n in zip(np.asarray(g["drag_rate"].values), names, strict=True) if n.startswith("nc"))
        for c, name in enumerate(names):
            hard = name.startswith("hard")
            if name.startswith("hard e=") or not hard and float(np.asarray(g["drag_rate"].values)[c]) != low:
                continue
            ti = float(np.asarray(g["inphase_time_share"].values)[c, 0])
            points.append((N, ti, k, es.index(float(np.asarray(g["restitution"].values)[c])), hard))
    finite = [p for p in points if np.isfinite(p[1])]
    if len(finite) < MIN_POINTS:
        G.set_visible(False)
        return
    lifts = sorted({p[2] for p in points})
    for N, ti, k, ie, hard in finite:
        m = _MARKERS[lifts.index(k) % 6]
        G.plot([N + 0.12 * (lifts.index(k) - 1)], [ti], m, color=f"C{ie}", ms=5,
               mfc="none" if hard else f"C{ie}")
    th = float(np.asarray(groups[0]["share_threshold"].values)[0])
    G.set_title(f"(f) time to in-phase motion (S stays >= {th:g})\nagainst the number of balls",
                fontsize=9)
    G.set_xlabel("balls N")
    G.set_ylabel("time (s)")
    G.set_yscale("log")
    G.legend(handles=[Line2D([], [], color="0.3", marker=_MARKERS[i % 6], ls="none", label=f"{k} lifted")
                      for i, k in enumerate(lifts)]
             + [Line2D([], [], color="0.3", marker="o", ls="none", label="(ncdamped), lower drag"),
                Line2D([], [], color="0.3", marker="o", mfc="none", ls="none", label="hard spheres, e(v)")],
             fontsize=6, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0,
             title="marker; colour: e as (a)", title_fontsize=6)
