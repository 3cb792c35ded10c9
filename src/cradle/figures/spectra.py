"""Figures fft106, fftseuil, fft344: spatial spectra |x_hat_k(t)| on Gamma* (section 4.2).

The spectra are the paper's DFT x_hat_k(t) = sum_n x_n(t) e^{-i n k}, k in
Gamma* = (2 pi / N){-N/2+1, ..., N/2} (:func:`cradle.measurements.compare.spatial_dft`),
read from ``results/metrics/<scene>.nc`` (``spectrum_exact``, ``spectrum_dps``)
with what the panels print, measured by the metrics stage at every stored time
(:func:`cradle.scenes.stages.travelling_metrics`): the sideband-to-carrier
ratio and the wavenumber of the largest sideband (``sideband_ratio_<model>``,
``sideband_k_<model>``, :func:`cradle.measurements.sidebands.sideband_peak`) and
the carrier's share of a profile's power (``carrier_share_<model>``).
Axes are linear, as in the paper.

* fft106: q = 4 pi/5, exact (left) and DpS (right) at four times (the last
  row at 541.95 for the exact solution and 543.7 for the DpS one);
* fftseuil: q = 52 pi/100, 51 pi/100, pi/2 (rows), both models at t = 913.7;
* fft344: q = 57 pi/100: spectra at 344.95, exact profiles x_n at 402.95 and
  407.2, the DpS profile at 407.2.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from matplotlib.figure import Figure
from numpy.typing import ArrayLike, NDArray

from cradle.figures import scene_caption

if TYPE_CHECKING:
    from collections.abc import Iterable

    import xarray as xr
    from matplotlib.axes import Axes

#: finite points each data panel holds at least (tests/figures/test_figures_render.py): N wavenumbers or beads
MIN_POINTS = 20

TIME_TOL = 1e-6          # a requested time must be stored to within this
MODELS = (("exact", "spectrum_exact", "exact"), ("dps", "spectrum_dps", "approx. (DpS)"))


def _at(ds: xr.Dataset, t: float) -> xr.Dataset:
    """The stored state at time t (a time not stored to within TIME_TOL is an error)."""
    s = ds.sel(t=t, method="nearest")
    if abs(float(s["t"]) - t) > TIME_TOL:
        raise ValueError(f"time {t:g} is not stored (nearest: {float(s['t']):g}); add it to the scene's snapshots")
    return s


def _stored(m: xr.Dataset, name: str) -> xr.DataArray:
    if name not in m:
        raise ValueError(f"scene '{m.attrs.get('scene', '?')}': no {name} in its metrics file: rebuild the metrics")
    return m[name]


def spectrum(sim: dict, model: str, t: float) -> tuple[np.ndarray, np.ndarray]:
    """(k, |x_hat_k(t)|) of ``model`` ('exact' or 'dps') from the metrics file."""
    var = dict((m, v) for m, v, _ in MODELS)[model]
    m = _at(sim["metrics"], t)
    return m["k"].values, m[var].values


def sideband(sim: dict, model: str, t: float) -> tuple[float, float]:
    """(ratio, k of the largest sideband) of ``model``'s spectrum at t, from the metrics file."""
    m = _at(sim["metrics"], t)
    return float(_stored(m, f"sideband_ratio_{model}")), float(_stored(m, f"sideband_k_{model}"))


def wrap(k: ArrayLike) -> NDArray[np.float64]:
    """Wavenumbers brought into the band (-pi, pi] (where to draw the carrier lines)."""
    k = np.asarray(k, dtype=float)
    w = np.mod(k + np.pi, 2.0 * np.pi) - np.pi       # in [-pi, pi)
    return np.where(np.isclose(w, -np.pi, rtol=0.0, atol=1e-12), np.pi, w)


def carrier(sim: dict) -> float:
    """The scene's wavenumber q (attribute of exact.nc)."""
    return float(sim["exact"].attrs["q"])


def _q_label(sim: dict[str, xr.Dataset]) -> str:
    expr = str(sim["exact"].attrs.get("q_expr", f"{carrier(sim):.4g}"))
    return expr.replace("pi", r"\pi")


# --------------------------------------------------------------------------- drawing

def _spectrum_panel(ax: Axes, sim: dict[str, xr.Dataset], model: str, t: float, title_prefix: str = "") -> float:
    k, sp = spectrum(sim, model, t)
    q = carrier(sim)
    ratio, k_peak = sideband(sim, model, t)
    ax.plot(k, sp, "-", color="k" if model == "exact" else "C3", lw=0.8)
    for kq in (-q, q):
        ax.axvline(float(wrap(kq)), color="0.6", lw=0.5, ls=":", zorder=0)
    ax.set_xlim(-np.pi, np.pi)
    ax.set_ylim(bottom=0.0)
    ax.set_xticks(np.pi * np.array([-1, -0.5, 0, 0.5, 1]), [r"$-\pi$", r"$-\pi/2$", "0", r"$\pi/2$", r"$\pi$"])
    ax.set_xlabel("$k$")
    ax.set_ylabel(r"$|\hat{x}_k(t)|$")
    label = dict((m, lab) for m, _, lab in MODELS)[model]
    ax.set_title(f"{title_prefix}{label}, $t = {t:g}$: $r = {float(ratio):.3g}$ at $k = {float(k_peak):.3f}$",
                 fontsize=8)
    return float(ratio)


def _same_ylim(axes: Iterable[Axes]) -> None:
    """One linear y-range [0, top] for the exact and DpS panels of a row."""
    top = max(a.get_ylim()[1] for a in axes)
    for a in axes:
        a.set_ylim(0.0, top)


def _ratio_note(fig: Figure, sim: dict[str, xr.Dataset]) -> None:
    m = sim["metrics"]
    if "sideband_exclude_bins" not in m.attrs:
        raise ValueError(f"scene '{m.attrs.get('scene', '?')}': no sideband_exclude_bins in its metrics file: "
                         "rebuild the metrics")
    bins = int(m.attrs["sideband_exclude_bins"])
    fig.text(0.5, 0.0, r"$r$ = max $|\hat{x}_k|$ outside $\pm$" f"{bins}" r" bins of $k = \pm q$, $\pm 2(q-\pi)$, "
             r"$\pm(3q-2\pi)$, divided by $|\hat{x}_{\pm q}|$; dotted lines: $k = \pm q$",
             ha="center", va="bottom", fontsize=7, color="0.3")


def _new(nrows: int, ncols: int, width: float, height: float) -> tuple[Figure, np.ndarray]:
    fig = Figure(figsize=(width, height))   # outside pyplot, as cradle.figures.figure
    axes = fig.subplots(nrows, ncols, squeeze=False,
                        gridspec_kw={"bottom": 0.75 / height, "top": 1.0 - 0.55 / height, "hspace": 0.6,
                                          "wspace": 0.25, "left": 0.08, "right": 0.98})
    return fig, axes


def draw_fft106(data: dict, options: dict) -> Figure:
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
    fig.suptitle(f"{scene_caption(name, sim['exact'])} (left: exact, right: approx. DpS)", fontsize=9)
    _ratio_note(fig, sim)
    return fig


def draw_fftseuil(data: dict, options: dict) -> Figure:
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
    first = data[names[0]]["exact"].attrs
    wave = f", $\\omega_{{tw}} = {float(first['omega_tw']):g}$" if "omega_tw" in first else ""
    fig.suptitle(f"fftseuil: $t = {t:g}$, $N = {data[names[0]]['exact'].sizes['n']}${wave} "
                 "(left: exact, right: approx. DpS)", fontsize=10)
    _ratio_note(fig, data[names[0]])
    return fig


def _profile_panel(ax: Axes, sim: dict[str, xr.Dataset], model: str, t: float) -> None:
    s = _at(sim[model], t)
    n, x = s["n"].values, s["x"].values
    ax.plot(n, x, "-", color="k" if model == "exact" else "C3", lw=0.7)
    ax.set_xlim(n[0], n[-1])
    ax.set_xlabel("$n$")
    ax.set_ylabel("$x_n(t)$")
    label = dict((m, lab) for m, _, lab in MODELS)[model]
    share = float(_stored(_at(sim["metrics"], t), f"carrier_share_{model}"))
    ax.set_title(f"{label}, $t = {t:g}$: carrier share of power {share:.2f}", fontsize=8)


def draw_fft344(data: dict, options: dict) -> Figure:
    """q = 57 pi/100. Upper: spectra at times[0] (exact, DpS); middle: exact x_n at times[1], times[2];
    lower: DpS x_n at times[2]."""
    (name,) = options["scenes"]
    t_spec, t1, t2 = [float(t) for t in options["times"]]
    sim = data[name]
    fig = Figure(figsize=(9.0, 8.0))
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
    fig.suptitle(scene_caption(name, sim['exact']), fontsize=10)
    _ratio_note(fig, sim)
    return fig


__all__ = ["sideband", "spectrum", "draw_fft106", "draw_fftseuil", "draw_fft344"]
