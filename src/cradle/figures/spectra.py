"""Figures fft106, fftseuil, fft344: spatial spectra |x_hat_k(t)| on Gamma* (section 4.2).

The spectra are the paper's DFT x_hat_k(t) = sum_n x_n(t) e^{-i n k}, k in
Gamma* = (2 pi / N){-N/2+1, ..., N/2} (:func:`cradle.measurements.compare.spatial_dft`),
read from ``results/metrics/<scene>.nc`` (``spectrum_exact``, ``spectrum_dps``)
and checked against the DFT of the stored displacements before drawing.
Axes are linear, as in the paper; each spectrum panel's title gives the
measured sideband-to-carrier ratio of :func:`sideband_ratio`.

* fft106: q = 4 pi/5, exact (left) and DpS (right) at four times (the last
  row at 541.95 for the exact solution and 543.7 for the DpS one);
* fftseuil: q = 52 pi/100, 51 pi/100, pi/2 (rows), both models at t = 913.7;
* fft344: q = 57 pi/100: spectra at 344.95, exact profiles x_n at 402.95 and
  407.2, the DpS profile at 407.2.
"""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from cradle.measurements.compare import spatial_dft
from cradle.measurements.sidebands import EXCLUDE_BINS, sideband_peak, sideband_ratio, wrap

TIME_TOL = 1e-6          # a requested time must be stored to within this
MODELS = (("exact", "spectrum_exact", "exact"), ("dps", "spectrum_dps", "approx. (DpS)"))


def _at(ds, t: float):
    """The stored state at time t (a time not stored to within TIME_TOL is an error)."""
    s = ds.sel(t=t, method="nearest")
    if abs(float(s["t"]) - t) > TIME_TOL:
        raise ValueError(f"time {t:g} is not stored (nearest: {float(s['t']):g}); add it to the scene's snapshots")
    return s


def spectrum(sim: dict, model: str, t: float):
    """(k, |x_hat_k(t)|) of ``model`` ('exact' or 'dps') from the metrics file, checked against
    the DFT of the stored displacements x_n(t) (a stale metrics file is an error)."""
    var = dict((m, v) for m, v, _ in MODELS)[model]
    m = _at(sim["metrics"], t)
    k, sp = m["k"].values, m[var].values
    k_dft, xh = spatial_dft(_at(sim[model], t)["x"].values)
    ref = np.abs(xh)
    if not (np.allclose(k, k_dft, atol=1e-12) and np.allclose(sp, ref, rtol=1e-9, atol=1e-12 * max(ref.max(), 1e-300))):
        raise ValueError(f"{var} at t = {t:g} differs from |DFT| of {model}.nc x: rebuild the metrics")
    return k, sp


def carrier(sim: dict) -> float:
    """The scene's wavenumber q (attribute of exact.nc)."""
    return float(sim["exact"].attrs["q"])


def _q_label(sim) -> str:
    expr = str(sim["exact"].attrs.get("q_expr", f"{carrier(sim):.4g}"))
    return expr.replace("pi", r"\pi")


# --------------------------------------------------------------------------- drawing

def _spectrum_panel(ax, sim, model, t, title_prefix=""):
    k, sp = spectrum(sim, model, t)
    q = carrier(sim)
    ratio, k_peak = sideband_peak(k, sp, q)
    ax.plot(k, sp, "-", color="k" if model == "exact" else "C3", lw=0.8)
    for kq in (-q, q):
        ax.axvline(wrap(kq), color="0.6", lw=0.5, ls=":", zorder=0)
    ax.set_xlim(-np.pi, np.pi)
    ax.set_ylim(bottom=0.0)
    ax.set_xticks(np.pi * np.array([-1, -0.5, 0, 0.5, 1]), [r"$-\pi$", r"$-\pi/2$", "0", r"$\pi/2$", r"$\pi$"])
    ax.set_xlabel("$k$")
    ax.set_ylabel(r"$|\hat{x}_k(t)|$")
    label = dict((m, lab) for m, _, lab in MODELS)[model]
    ax.set_title(f"{title_prefix}{label}, $t = {t:g}$: $r = {float(ratio):.3g}$ at $k = {float(k_peak):.3f}$",
                 fontsize=8)
    return float(ratio)


def _same_ylim(axes):
    """One linear y-range [0, top] for the exact and DpS panels of a row."""
    top = max(a.get_ylim()[1] for a in axes)
    for a in axes:
        a.set_ylim(0.0, top)


def _ratio_note(fig):
    fig.text(0.5, 0.0, r"$r$ = max $|\hat{x}_k|$ outside $\pm$%d bins of $k = \pm q$, $\pm 2(q-\pi)$, "
             r"$\pm(3q-2\pi)$, divided by $|\hat{x}_{\pm q}|$; dotted lines: $k = \pm q$" % EXCLUDE_BINS,
             ha="center", va="bottom", fontsize=7, color="0.3")


def _new(nrows, ncols, width, height):
    fig, axes = plt.subplots(nrows, ncols, figsize=(width, height), squeeze=False,
                             gridspec_kw={"bottom": 0.75 / height, "top": 1.0 - 0.55 / height, "hspace": 0.6,
                                          "wspace": 0.25, "left": 0.08, "right": 0.98})
    return fig, axes


def draw_fft106(data, options):
    """4 x 2 spectra, q = 4 pi/5: exact (left) at times[0:4], DpS (right) at times[0:3] and times[4]."""
    (name,) = options["scenes"]
    times = [float(t) for t in options["times"]]
    if len(times) != 5:
        raise ValueError(f"fft106 needs 5 times (4 exact rows + the DpS time of row 4), got {times}")
    sim = data[name]
    fig, axes = _new(4, 2, 9.0, 10.5)
    for row in range(4):
        _spectrum_panel(axes[row, 0], sim, "exact", times[row])
        _spectrum_panel(axes[row, 1], sim, "dps", times[row] if row < 3 else times[4])
        _same_ylim(axes[row])
    fig.suptitle(f"fft106: $q = {_q_label(sim)}$, $N = {sim['exact'].sizes['n']}$ "
                 "(left: exact, right: approx. DpS)", fontsize=10)
    _ratio_note(fig)
    return fig


def draw_fftseuil(data, options):
    """3 x 2 spectra at times[0] (913.7): one row per scene (q = 52 pi/100, 51 pi/100, pi/2)."""
    names = list(options["scenes"])
    (t,) = [float(s) for s in options["times"]]
    fig, axes = _new(len(names), 2, 9.0, 2.6 * len(names) + 0.4)
    for row, name in enumerate(names):
        sim = data[name]
        prefix = f"$q = {_q_label(sim)}$, "
        _spectrum_panel(axes[row, 0], sim, "exact", t, prefix)
        _spectrum_panel(axes[row, 1], sim, "dps", t, prefix)
        _same_ylim(axes[row])
    fig.suptitle(f"fftseuil: $t = {t:g}$ (left: exact, right: approx. DpS)", fontsize=10)
    _ratio_note(fig)
    return fig


def carrier_share(x, q: float):
    """Share of the carrier in the power of a profile: sum over k = +-q of |x_hat_k|^2 / sum_k |x_hat_k|^2.

    1 for an unmodulated wave a cos(q n - w t + phi) with q on Gamma*; it falls as the
    profile gets modulated (sidebands, harmonics). ``x`` has shape (..., N).
    """
    k, xh = spatial_dft(x)
    p = np.abs(xh) ** 2
    N = k.size
    jq = {int(np.round(wrap(c) * N / (2.0 * np.pi))) % N for c in (q, -q)}
    on = np.isin(np.round(k * N / (2.0 * np.pi)).astype(int) % N, list(jq))
    return p[..., on].sum(axis=-1) / p.sum(axis=-1)


def _profile_panel(ax, sim, model, t):
    s = _at(sim[model], t)
    n, x = s["n"].values, s["x"].values
    ax.plot(n, x, "-", color="k" if model == "exact" else "C3", lw=0.7)
    ax.set_xlim(n[0], n[-1])
    ax.set_xlabel("$n$")
    ax.set_ylabel("$x_n(t)$")
    label = dict((m, lab) for m, _, lab in MODELS)[model]
    share = float(carrier_share(x, carrier(sim)))
    ax.set_title(f"{label}, $t = {t:g}$: carrier share of power {share:.2f}", fontsize=8)


def draw_fft344(data, options):
    """q = 57 pi/100. Upper: spectra at times[0] (exact, DpS); middle: exact x_n at times[1], times[2];
    lower: DpS x_n at times[2]."""
    (name,) = options["scenes"]
    t_spec, t1, t2 = [float(t) for t in options["times"]]
    sim = data[name]
    fig = plt.figure(figsize=(9.0, 8.0))
    gs = fig.add_gridspec(3, 4, bottom=0.75 / 8.0, top=1.0 - 0.55 / 8.0, hspace=0.6, wspace=0.9,
                          left=0.09, right=0.98)
    se, sa = fig.add_subplot(gs[0, 0:2]), fig.add_subplot(gs[0, 2:4])
    x1, x2 = fig.add_subplot(gs[1, 0:2]), fig.add_subplot(gs[1, 2:4])
    xa = fig.add_subplot(gs[2, 1:3])
    _spectrum_panel(se, sim, "exact", t_spec)
    _spectrum_panel(sa, sim, "dps", t_spec)
    _same_ylim([se, sa])
    _profile_panel(x1, sim, "exact", t1)
    _profile_panel(x2, sim, "exact", t2)
    _profile_panel(xa, sim, "dps", t2)
    lim = max(abs(v) for a in (x1, x2, xa) for v in a.get_ylim())
    for a in (x1, x2, xa):
        a.set_ylim(-lim, lim)
    fig.suptitle(f"fft344: $q = {_q_label(sim)}$, $N = {sim['exact'].sizes['n']}$", fontsize=10)
    _ratio_note(fig)
    return fig


__all__ = ["carrier_share", "sideband_ratio", "spectrum", "draw_fft106", "draw_fftseuil",
           "draw_fft344"]
