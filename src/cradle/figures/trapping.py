"""Figure beyond the paper: the energy of an incident wave trapped into static breathers (trapping).

Drawn by :func:`draw` from results/trapping/[full/]trapping.nc (:mod:`cradle.analyses.trapping`). Fractions are of
the energy put in, H(0); "main definition": the first threshold and window of the file at its last measurement
time; the small grey marks are the means under every other definition (thresholds x windows x times). Each
panel's key is under it, as wide as the panel.

Top row: the energy per bead e_n / H(0) (log scale) against the bead and the slow time tau = a^(alpha-1) t, for
each incident at its scan amplitude, homogeneous and at the largest sigma (first seed); the dashed lines bound the
target (left of it the launch zone, right of it the lead).
(e) the fraction in static breathers centred in the target against the amplitude a, main length, each sigma: mean
    over the seeds, error bars one standard deviation over the seeds (cut at 0 and 1; drawn over 4 seeds or more),
    open markers to the right the static breathers of the whole chain (the target's and slow reflected ones in the
    launch zone), grey marks to the left the means under the other definitions; (f) the same against
    sigma at the scan amplitudes, each target length; (g) where the energy is at the last measurement time (scan
    amplitudes, main length): the lead (transmitted), the target, the launch zone (wake and reflected), means over
    the seeds; (h) damping: the fraction in static breathers of the target (filled) and the energy dissipated D
    (open) for each damping case, homogeneous and at the damping scan's sigma.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from matplotlib.ticker import NullLocator

from cradle.figures import AnalysisTree, figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

_INC = ("striker", "breather")
_MARK = {0: "o", 1: "s"}
_LINE = {0: "-", 1: "--"}

#: finite points each data panel holds at least (tests/figures/test_figures_render.py)
MIN_POINTS = 2


def _v(group: AnalysisTree, name: str) -> np.ndarray:
    return np.asarray(group[name].values)


def _spacetime(ax: Axes, ex: AnalysisTree, k: int, fig_images: list) -> None:
    e = _v(ex, "site_energy")[k]
    tau = _v(ex, "tau")
    seen = np.flatnonzero(np.nanmax(np.where(np.isfinite(e), e, 0.0), axis=0) > 1e-8)
    ends = _v(ex, "example_target")[k]
    # the beads the wave reached, and the whole target (its bounds are drawn)
    right = max(int(seen.max()) + 10 if seen.size else e.shape[1], int(ends[1]) + 5)
    right = min(right, int(np.sum(np.isfinite(e[0]))))
    img = ax.pcolormesh(np.arange(right), tau, np.log10(np.maximum(e[:, :right], 1e-12)), vmin=-6, vmax=0,
                        shading="auto", cmap="magma", rasterized=True)
    fig_images.append(img)
    ax.set_xlim(-0.5, right - 0.5)
    for b in ends:
        ax.axvline(b - 0.5, color="w", ls="--", lw=0.8)
    inc = _INC[int(_v(ex, "example_incident")[k])]
    sig = float(_v(ex, "example_sigma")[k])
    ax.set_title(f"({'abcd'[k]}) {inc}, a = {float(_v(ex, 'example_amplitude')[k]):g}, "
                 + ("homogeneous" if sig == 0 else f"sigma = {sig:g} (seed 0)"), fontsize=9)
    ax.set_xlabel("bead n")
    ax.set_ylabel(r"slow time $\tau = a^{\alpha-1} t$")


#: error bars of one standard deviation are drawn over at least this many seeds (over fewer they say nothing)
MIN_SEEDS_FOR_BARS = 4


def _bars(mean: np.ndarray, std: np.ndarray, n_seeds: int) -> np.ndarray | None:
    """Error bars of one standard deviation, cut at 0 and 1 (a fraction of H(0)); None over too few seeds."""
    if n_seeds < MIN_SEEDS_FOR_BARS:
        return None
    return np.stack([np.minimum(std, mean), np.minimum(std, 1.0 - mean)])


def _key_below(ax: Axes, ncols: int = 1) -> None:
    """The legend of ``ax`` under its axis labels, as wide as the panel: beside it, it would halve the panel."""
    ax.legend(fontsize=6, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncols=ncols, borderaxespad=0.0)


def _log_frame(ax: Axes, xs: np.ndarray) -> None:
    """A log x axis ticked at the values ``xs`` drawn, with room for a marker on either side."""
    xs = np.unique(xs[np.isfinite(xs) & (xs > 0)])
    ax.set_xscale("log")
    ax.set_xlim(xs.min() / 1.6, xs.max() * 1.6)
    ax.set_xticks(xs, [f"{v:g}" for v in xs])
    ax.xaxis.set_minor_locator(NullLocator())


def _others(ax: Axes, x: float, values: np.ndarray) -> None:
    """Grey marks at x of the means under every definition (values: ..., threshold, window, time)."""
    flat = values.reshape(-1)
    ax.plot(np.full(flat.size, x), flat, "_", color="0.6", ms=5, zorder=1)


def draw(tree: AnalysisTree) -> Figure:
    """The panels above from the groups /runs, /summary and /examples of the trapping file."""
    fig, ax = figure(2, 4, width=17.0, height=10.0)
    ex, sm = tree["examples"], tree["summary"]
    images: list = []
    for k in range(min(4, ex.sizes.get("example", 0))):
        _spacetime(ax[0, k], ex, k, images)
    for k in range(ex.sizes.get("example", 0), 4):
        ax[0, k].set_axis_off()
    if images:
        bar = fig.colorbar(images[0], ax=ax[0, :].tolist(), shrink=0.9, pad=0.01)
        bar.set_label(r"$\log_{10}\, e_n / H(0)$")

    inc, amp, length = _v(sm, "case_incident"), _v(sm, "case_amplitude"), _v(sm, "case_length")
    sigma, gamma, eta = _v(sm, "case_sigma"), _v(sm, "case_gamma"), _v(sm, "case_eta")
    mean, std = _v(sm, "target_mean"), _v(sm, "target_std")
    whole = _v(sm, "fraction_mean")
    main = (0, 0, -1)
    undamped = (gamma == 0) & (eta == 0)
    L0 = int(tree.attrs["main_length"])
    scan = {0: float(tree.attrs["scan_striker"]), 1: float(tree.attrs["scan_breather"])}
    sigmas = np.unique(sigma)
    shades = {s: f"C{j}" for j, s in enumerate(sigmas)}
    th, wd, tm = (float(tree[c].values[i]) for c, i in zip(("threshold", "window", "tau_m"), main, strict=True))
    defn = rf"main definition: $\theta$ = {th:g}, W = {wd:g}, $\tau_m$ = {tm:g}"
    disordered = _v(tree["runs"], "sigma") > 0   # a homogeneous chain is one run whatever its seed
    n_seeds = int(np.unique(_v(tree["runs"], "seed")[disordered]).size) if disordered.any() else 1
    spread = (f"error bars: one standard deviation over {n_seeds} seeds" if n_seeds >= MIN_SEEDS_FOR_BARS
              else f"means over {n_seeds} seeds (no error bars: too few seeds for a spread)")

    E = ax[1, 0]
    for i in (0, 1):
        for s in sigmas:
            m = (inc == i) & undamped & (length == L0) & (sigma == s)
            if not m.any():
                continue
            order = np.argsort(amp[m])
            xs, ys, es = amp[m][order], mean[m][order][:, 0, 0, -1], std[m][order][:, 0, 0, -1]
            E.errorbar(xs, ys, _bars(ys, es, n_seeds), fmt=_MARK[i] + _LINE[i], color=shades[s], ms=5, capsize=2,
                       lw=1, label=f"{_INC[i]}, " + ("homogeneous" if s == 0 else f"sigma = {s:g}"))
            # beside the target's marker, not around it
            E.plot(xs * 1.12, whole[m][order][:, 0, 0, -1], _MARK[i], color=shades[s], mfc="none", ms=5)
            for x, v in zip(xs, mean[m][order], strict=True):
                _others(E, x / 1.12, v)
    E.plot([], [], "o", color="0.3", mfc="none", ms=5, label="open, right: whole chain (launch zone too)")
    E.plot([], [], "_", color="0.6", label="grey, left: every other definition (mean)")
    _log_frame(E, amp[undamped & (length == L0)])
    E.set_xlabel("amplitude a")
    E.set_ylabel("static breathers of the target / H(0)")
    E.set_title(f"(e) against amplitude, target of {L0} beads\n(striker: v_0(0) = a; breather: max |x(0)| = a)",
                fontsize=9)
    E.set_ylim(-0.05, 1.05)   # fractions of H(0); a seed spread is not drawn below 0
    _key_below(E)

    F = ax[1, 1]
    lengths = np.unique(length)
    for i in (0, 1):
        for j, n in enumerate(lengths):
            m = (inc == i) & undamped & (length == n) & (amp == scan[i])
            if not m.any():
                continue
            order = np.argsort(sigma[m])
            step = 0.01 * max(float(np.ptp(sigma)), 0.1)
            xs = sigma[m][order] + step * (j - (len(lengths) - 1) / 2)   # side by side at equal sigma
            ys = mean[m][order][:, 0, 0, -1]
            F.errorbar(xs, ys, _bars(ys, std[m][order][:, 0, 0, -1], n_seeds), fmt=_MARK[i] + _LINE[i],
                       color=f"C{j}", ms=5, capsize=2, lw=1, label=f"{_INC[i]} a = {scan[i]:g}, {n} beads")
            F.plot(xs + 1.5 * step, whole[m][order][:, 0, 0, -1], _MARK[i], color=f"C{j}", mfc="none", ms=5)
            for x, v in zip(xs - 1.5 * step, mean[m][order], strict=True):
                _others(F, x, v)
    F.set_xlabel(r"disorder $\sigma$ (std of $\omega_n - 1$)")
    F.set_ylabel("static breathers of the target / H(0)")
    F.set_title("(f) against sigma and target length,\nat the scan amplitudes", fontsize=9)
    F.set_ylim(-0.05, 1.05)   # fractions of H(0); a seed spread is not drawn below 0
    F.set_xlim(float(sigma.min()) - 0.1 * max(float(np.ptp(sigma)), 0.1),
               float(sigma.max()) + 0.1 * max(float(np.ptp(sigma)), 0.1))
    _key_below(F)

    G = ax[1, 2]
    runs = tree["runs"]
    r_inc, r_amp, r_len = _v(runs, "incident"), _v(runs, "amplitude"), _v(runs, "length")
    r_sig, r_g, r_e = _v(runs, "sigma"), _v(runs, "gamma"), _v(runs, "eta")
    zone = _v(runs, "zone_energy")[:, -1, :]
    for i in (0, 1):
        sel = (r_inc == i) & (r_amp == scan[i]) & (r_len == L0) & (r_g == 0) & (r_e == 0)
        if not sel.any():
            continue
        for z, (name, col) in enumerate(zip(("launch zone", "target", "lead (transmitted)"), ("C2", "C0", "C3"),
                                            strict=True)):
            ys = [float(np.mean(zone[sel & (r_sig == s), z])) for s in sigmas]
            G.plot(sigmas, ys, _MARK[i] + _LINE[i], color=col, ms=5, label=f"{_INC[i]}: {name}")
    G.set_xlabel(r"disorder $\sigma$")
    G.set_ylabel(f"energy of the zone at tau = {tm:g}, over H(0)")
    G.set_title(f"(g) where the energy is, scan amplitudes,\n{L0} beads (mean over the seeds)", fontsize=9)
    G.set_ylim(-0.05, 1.05)
    G.set_xlim(float(sigmas.min()) - 0.1 * max(float(np.ptp(sigmas)), 0.1),
               float(sigmas.max()) + 0.1 * max(float(np.ptp(sigmas)), 0.1))
    _key_below(G, ncols=2)

    H = ax[1, 3]
    cases = sorted({(float(g), float(e)) for g, e in zip(gamma, eta, strict=True)})
    names = ["none" if g == 0 and e == 0 else (rf"$\gamma$ = {g:g}" if g > 0 else rf"$\eta$ = {e:g}") for g, e in cases]
    dis = _v(runs, "dissipated")[:, -1]
    sd = float(tree.attrs["damping_sigma"])
    for i in (0, 1):
        for s, dx, col in ((0.0, -0.15, "C0"), (sd, 0.15, "C1")):
            xs, ys, es, ds = [], [], [], []
            for c, (g, e) in enumerate(cases):
                m = (inc == i) & (gamma == g) & (eta == e) & (amp == scan[i]) & (length == L0) & (sigma == s)
                rm = (r_inc == i) & (r_g == g) & (r_e == e) & (r_amp == scan[i]) & (r_len == L0) & (r_sig == s)
                if not m.any():
                    continue
                xs.append(c + dx + 0.05 * i)
                ys.append(float(mean[m][0, 0, 0, -1]))
                es.append(float(std[m][0, 0, 0, -1]))
                ds.append(float(np.mean(dis[rm])))
            if xs:
                lab = f"{_INC[i]}, " + ("homogeneous" if s == 0 else f"sigma = {s:g}")
                H.errorbar(xs, ys, _bars(np.asarray(ys), np.asarray(es), n_seeds), fmt=_MARK[i], color=col, ms=6,
                           capsize=2, label=f"{lab}: static breathers")
                H.plot(xs, ds, _MARK[i], color=col, mfc="none", ms=8, label=f"{lab}: dissipated D")
    H.set_xticks(range(len(cases)), names, rotation=25)
    H.set_ylabel(f"fraction of H(0) at tau = {tm:g}")
    H.set_title(f"(h) damping, scan amplitudes, {L0} beads:\nstatic breathers (filled), dissipated D (open)",
                fontsize=9)
    H.set_ylim(-0.05, 1.05)   # fractions of H(0); a seed spread is not drawn below 0
    H.set_xlim(-0.6, len(cases) - 0.4)
    H.legend(fontsize=6, loc="upper center", bbox_to_anchor=(0.5, -0.3), ncols=1, borderaxespad=0.0)
    fig.suptitle(f"Energy of an incident wave left in static breathers. Fractions of H(0), {defn}; {spread};\n"
                 "grey marks: the mean under every other definition; "
                 "open markers in (e), (f): static breathers of the whole chain (the target's, and slow reflected "
                 "ones in the launch zone)", fontsize=9)
    return fig
