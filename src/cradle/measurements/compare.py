"""Comparison tools: exact solution of (nc) against the DpS approximation (ansatz).

* :func:`approximate_displacement` rebuilds x_n^app(t) = eps (A_n(tau) e^{it} + c.c.) (ansatz);
* :func:`relative_error` is E(t) = ||x^app(t) - x(t)||_inf / a of figure plot4-5;
* :func:`spatial_dft` is the paper's DFT x_hat_k = sum_n x_n e^{-i n k}, k in Gamma*
  (section 4.2, figures fft106, fftseuil, fft344);
* :func:`linear_wave` is the solution a cos(q n - t) of (nc) linearised at 0 (plotcomplin).
Forces for space-time diagrams are :func:`cradle.models.lattice.bond_forces`.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.specs.checked import checked


@checked
def approximate_displacement(A: ArrayLike, t: ArrayLike, eps: float) -> NDArray[np.float64]:
    """x_n^app(t) = eps (A_n e^{it} + c.c.) = 2 eps Re(A_n e^{it})   (ansatz).

    ``A`` has shape (T, N) (A at tau = eps^(alpha-1) t), ``t`` shape (T,).
    """
    A = np.asarray(A)
    t = np.asarray(t, dtype=float)
    return 2.0 * eps * np.real(A * np.exp(1j * t)[..., None])


@checked(a="amplitude")
def relative_error(x: ArrayLike, x_app: ArrayLike, a: float) -> NDArray[np.float64]:
    """E(t) = a^{-1} max_n |x_n^app(t) - x_n(t)|   (figure plot4-5)."""
    return np.max(np.abs(np.asarray(x_app) - np.asarray(x)), axis=-1) / a


@checked
def gamma_star(N: int) -> NDArray[np.float64]:
    """Gamma* = (2 pi / N) {-N/2 + 1, ..., N/2} (N even), the paper's discretised band.

    For odd N the symmetric set (2 pi / N){-(N-1)/2, ..., (N-1)/2}.
    """
    j = np.arange(-N // 2 + 1, N // 2 + 1) if N % 2 == 0 else np.arange(-(N - 1) // 2, (N - 1) // 2 + 1)
    return 2.0 * np.pi * j / N


def spatial_dft(x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.complex128]]:
    """x_hat_k(t) = sum_{n=0}^{N-1} x_n(t) e^{-i n k} for k in Gamma* (ordered as :func:`gamma_star`).

    Returns (k, x_hat) with x_hat of shape (..., N).
    """
    x = np.asarray(x)
    N = x.shape[-1]
    k = gamma_star(N)
    j = np.round(k * N / (2.0 * np.pi)).astype(int) % N  # FFT bin of each k
    return k, np.fft.fft(x, axis=-1)[..., j]


def linear_wave(n: ArrayLike, t: ArrayLike, a: float, q: float, phi: float = 0.0) -> NDArray[np.float64]:
    """x_n(t) = a cos(q n - t + phi), the wave of (nc) linearised at x = 0 (plotcomplin)."""
    return a * np.cos(q * np.asarray(n) - np.asarray(t)[..., None] + phi)
