"""Figures fft106, fftseuil, fft344: spatial spectra |x_hat_k(t)| on Gamma* (section 4.2).

The spectra are the paper's DFT x_hat_k(t) = sum_n x_n(t) e^{-i n k}, k in
Gamma* = (2 pi / N){-N/2+1, ..., N/2} (:func:`cradle.compare.spatial_dft`),
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

from ..compare import spatial_dft

TIME_TOL = 1e-6          # a requested time must be stored to within this
EXCLUDE_BINS = 3         # half-width (in bins of 2 pi / N) of the windows left out by sideband_ratio
MODELS = (("exact", "spectrum_exact", "exact"), ("dps", "spectrum_dps", "approx. (DpS)"))


# --------------------------------------------------------------------------- measures (pure numpy)

def wrap(k):
    """Wavenumbers brought into the band (-pi, pi] (Gamma* for N even)."""
    k = np.asarray(k, dtype=float)
    w = np.mod(k + np.pi, 2.0 * np.pi) - np.pi       # in [-pi, pi)
    return np.where(np.isclose(w, -np.pi, rtol=0.0, atol=1e-12), np.pi, w)


def harmonics(q: float) -> dict:
    """Where the lattice's harmonics of a wave of wavenumber q fall in (-pi, pi].

    ``{"2(q-pi)": (k, -k), "3q-2pi": (k, -k)}``: the second harmonic 2q and the
    third 3q, wrapped into the band (section 4.2: k = +-2(q - pi), +-(3q - 2 pi)).
    """
    return {"2(q-pi)": tuple(wrap([2.0 * (q - np.pi), -2.0 * (q - np.pi)])),
            "3q-2pi": tuple(wrap([3.0 * q - 2.0 * np.pi, -(3.0 * q - 2.0 * np.pi)]))}


def _bins(k):
    """Integer bin index j = k N / (2 pi) of each k on the full grid Gamma* (any order)."""
    k = np.asarray(k, dtype=float)
    N = k.size
    j = k * N / (2.0 * np.pi)
    if not np.allclose(j, np.round(j), atol=1e-6) or np.unique(np.round(j) % N).size != N:
        raise ValueError("k must be the full grid Gamma* = (2 pi / N) {-N/2+1, ..., N/2} (in any order)")
    return np.round(j).astype(int) % N, N


def sideband_peak(k, spectrum, q: float, exclude_bins: int = EXCLUDE_BINS, exclude_harmonics: bool = True):
    """(ratio, k_peak): :func:`sideband_ratio` and the wavenumber where the sideband maximum sits.

    For a ``spectrum`` of shape (..., N), both are arrays of shape (...).
    ``k_peak`` is NaN where every wavenumber is excluded.
    """
    jk, N = _bins(k)
    k = np.asarray(k, dtype=float)
    spectrum = np.asarray(spectrum, dtype=float)
    if spectrum.shape[-1] != N:
        raise ValueError(f"spectrum has {spectrum.shape[-1]} wavenumbers, k has {N}")
    if exclude_bins < 0:
        raise ValueError(f"exclude_bins must be >= 0, got {exclude_bins!r}")
    centres = [q, -q]
    if exclude_harmonics:
        centres += [c for pair in harmonics(q).values() for c in pair]
    excluded = np.zeros(N, dtype=bool)
    for c in centres:
        jc = int(np.round(wrap(c) * N / (2.0 * np.pi))) % N
        d = np.abs(jk - jc) % N
        excluded |= np.minimum(d, N - d) <= exclude_bins        # circular distance in bins
    jq = [int(np.round(wrap(c) * N / (2.0 * np.pi))) % N for c in (q, -q)]
    carrier = np.max(spectrum[..., np.isin(jk, jq)], axis=-1)
    kept = np.where(excluded, -np.inf, spectrum)
    imax = np.argmax(kept, axis=-1)
    side = np.take_along_axis(kept, imax[..., None], axis=-1)[..., 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(np.isfinite(side), side / carrier, np.nan)
    k_peak = np.where(np.isfinite(side), k[imax], np.nan)
    return ratio, k_peak


def sideband_ratio(k, spectrum, q: float, exclude_bins: int = EXCLUDE_BINS, exclude_harmonics: bool = True):
    """Sideband-to-carrier ratio of a spatial spectrum |x_hat_k| on Gamma*.

    ratio = max |x_hat_k| over the k kept / |x_hat_{+-q}|, where the carrier
    |x_hat_{+-q}| is the larger of the two values at the bins of k = q and
    k = -q (equal for a real x_n), and the k kept are every k of Gamma* except

    * the ``exclude_bins`` bins on each side of +-q (and +-q themselves): the
      carrier and its immediate neighbourhood;
    * with ``exclude_harmonics`` (the default), the same windows around the
      lattice's harmonics of section 4.2: the second harmonic
      k = +-2(q - pi) and the third harmonic k = +-(3q - 2 pi), wrapped into
      (-pi, pi] (:func:`harmonics`).

    Distances are counted in bins of 2 pi / N around the circle (k = pi and
    k = -pi + 2 pi/N are neighbours). k = 0 is kept. The ratio is ~0 for a pure
    carrier, and equals h for a carrier plus one sideband of relative height h
    outside the windows; it grows as modulational instability transfers energy
    from +-q to the band around it.

    Parameters
    ----------
    k : (N,) array, the full grid Gamma* = (2 pi / N){-N/2+1, ..., N/2}, in any order.
    spectrum : (..., N) array, |x_hat_k| on that grid (e.g. ``spectrum_exact`` of
        ``results/metrics/<scene>.nc`` at one or several times).
    q : carrier wavenumber (radians); need not lie in (-pi, pi].
    exclude_bins : half-width of each left-out window, in bins (>= 0).
    exclude_harmonics : also leave out the windows around +-2(q - pi) and +-(3q - 2 pi).

    Returns
    -------
    float array of shape ``spectrum.shape[:-1]`` (a 0-d array for one
    spectrum); NaN if every k is excluded; inf if the carrier is 0.
    """
    return sideband_peak(k, spectrum, q, exclude_bins, exclude_harmonics)[0]


def envelope(x):
    """Envelope |x_n + i H[x]_n| of a profile x_n (periodic analytic signal, pure numpy).

    Used to measure the large-scale modulation of fft344's profiles: for
    x_n = a cos(q n - w t) the envelope is a at every n.
    """
    x = np.asarray(x, dtype=float)
    N = x.shape[-1]
    h = np.zeros(N)
    h[0] = 1.0
    if N % 2 == 0:
        h[N // 2] = 1.0
        h[1:N // 2] = 2.0
    else:
        h[1:(N + 1) // 2] = 2.0
    return np.abs(np.fft.ifft(np.fft.fft(x, axis=-1) * h, axis=-1))


# --------------------------------------------------------------------------- reading

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
                             gridspec_kw={"bottom": 0.07, "top": 0.94, "hspace": 0.55, "wspace": 0.25,
                                          "left": 0.08, "right": 0.98})
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


def _profile_panel(ax, sim, model, t):
    s = _at(sim[model], t)
    n, x = s["n"].values, s["x"].values
    env = envelope(x)
    ax.plot(n, x, "-", color="k" if model == "exact" else "C3", lw=0.7)
    ax.set_xlim(n[0], n[-1])
    ax.set_xlabel("$n$")
    ax.set_ylabel("$x_n(t)$")
    label = dict((m, lab) for m, _, lab in MODELS)[model]
    ax.set_title(f"{label}, $t = {t:g}$: envelope min/max = {env.min() / env.max():.2f}", fontsize=8)


def draw_fft344(data, options):
    """q = 57 pi/100. Upper: spectra at times[0] (exact, DpS); middle: exact x_n at times[1], times[2];
    lower: DpS x_n at times[2]."""
    (name,) = options["scenes"]
    t_spec, t1, t2 = [float(t) for t in options["times"]]
    sim = data[name]
    fig = plt.figure(figsize=(9.0, 8.0))
    gs = fig.add_gridspec(3, 4, bottom=0.07, top=0.93, hspace=0.6, wspace=0.5, left=0.08, right=0.98)
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


FIGURES = {"fft106": draw_fft106, "fftseuil": draw_fftseuil, "fft344": draw_fft344}
