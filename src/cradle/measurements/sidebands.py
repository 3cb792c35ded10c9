"""Sidebands and harmonics in the paper's spatial spectra |x_hat_k| on Gamma* (section 4.2).

Pure numpy. :func:`sideband_ratio` measures modulational instability as the
largest sideband over the carrier; :func:`harmonics` and
:func:`harmonic_height` locate and measure the lattice's second and third
harmonics k = +-2(q - pi), +-(3q - 2pi) (fft106, fftseuil, fft344);
:func:`carrier_share` is the carrier's share of a profile's power (fft344).
"""
from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.measurements.compare import spatial_dft

EXCLUDE_BINS = 3         # half-width (in bins of 2 pi / N) of the windows left out by sideband_ratio


def wrap(k: ArrayLike) -> NDArray[np.float64]:
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


def _bins(k: ArrayLike) -> tuple[NDArray[np.int_], int]:
    """Integer bin index j = k N / (2 pi) of each k on the full grid Gamma* (any order)."""
    k = np.asarray(k, dtype=float)
    N = k.size
    j = k * N / (2.0 * np.pi)
    if not np.allclose(j, np.round(j), atol=1e-6) or np.unique(np.round(j) % N).size != N:
        raise ValueError("k must be the full grid Gamma* = (2 pi / N) {-N/2+1, ..., N/2} (in any order)")
    return np.round(j).astype(int) % N, N


def sideband_peak(k: ArrayLike, spectrum: ArrayLike, q: float, exclude_bins: int = EXCLUDE_BINS,
                  exclude_harmonics: bool = True) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
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


def sideband_ratio(k: ArrayLike, spectrum: ArrayLike, q: float, exclude_bins: int = EXCLUDE_BINS,
                   exclude_harmonics: bool = True) -> NDArray[np.float64]:
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


# -> Any: an array of shape x.shape[:-1], a numpy scalar for one profile (numpy types this reduction as Any;
# the union would not fit cradle.scenes.stages.travelling_metrics, which stores it beside arrays)
def carrier_share(x: ArrayLike, q: float) -> Any:
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


def envelope(x: ArrayLike) -> NDArray[np.float64]:
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


def harmonic_height(k: ArrayLike, spectrum: ArrayLike, q: float, which: str) -> float:
    """|x_hat| at the harmonic ``which`` ("2(q-pi)" or "3q-2pi", see :func:`harmonics`),
    the larger of its two mirror bins, over the carrier |x_hat_{+-q}|."""
    jk, N = _bins(k)
    spectrum = np.asarray(spectrum, dtype=float)
    def at(c: float) -> NDArray[np.float64] | np.float64:
        return spectrum[..., jk == int(np.round(wrap(c) * N / (2.0 * np.pi))) % N].max(axis=-1)
    carrier = np.maximum(at(q), at(-q))
    return float(np.max([at(c) for c in harmonics(q)[which]]) / carrier)


def harmonic_over_band(k: ArrayLike, spectrum: ArrayLike, q: float, which: str, half: int = 5) -> float:
    """How far the harmonic ``which`` stands above the local band: |x_hat| at its bin over the median
    |x_hat| of the ``half`` bins on each side (the bin itself left out), the larger of the two mirror
    harmonics. A coherent harmonic of the carrier (fft106, fft344, exact) is a narrow peak: this ratio
    is large; the same bin inside a broad band of unstable modes (DpS at t = 344.95 in fft344) is at
    the band's level: the ratio is ~1."""
    jk, N = _bins(k)
    spectrum = np.asarray(spectrum, dtype=float)

    def at(j: int) -> NDArray[np.float64] | np.float64:
        return spectrum[..., jk == j % N].max(axis=-1)

    best = 0.0
    for c in harmonics(q)[which]:
        j = int(np.round(wrap(c) * N / (2.0 * np.pi)))
        band = np.median([at(j + d) for d in range(-half, half + 1) if d != 0])
        best = max(best, float(at(j) / band) if band > 0 else float("inf"))
    return best
