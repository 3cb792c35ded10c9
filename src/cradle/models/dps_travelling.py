"""Travelling breathers (TBs) of the DpS equation (dfnls): the equations, their symmetries and the linearisation.

A TB of velocity c = 1/T on a ring of N sites is a solution of (dfnls) with

    A_n(tau + T) = e^{i theta} A_{n-1}(tau)                                        (tb)

(it moves one site per T and turns its phase by theta). Written on the initial state A = A(0) with the flow
Phi_T of (dfnls) and the shift (S A)_n = A_{n-1}, (tb) is the zero of the shooting map modulo shift

    R(A, theta) = e^{-i theta} S^{-1} Phi_T(A) - A.

Symmetries (each maps a TB to a TB of the same T and theta): the phase rotation A -> e^{i phi} A and the time
shift A -> Phi_s(A) (both leave R's zero set invariant: two neutral directions, i A and dA/dtau, removed by two
phase conditions); DpS's scaling A -> lambda A, tau -> lambda^(1-alpha) tau maps a TB of (T, theta) to one of
(lambda^(1-alpha) T, theta), so at fixed theta varying T is only this scaling. The one-parameter family that
remains is that of theta at fixed T, or equivalently (the scaling fixes one of the two) the family in c at
fixed squared l2 norm P = sum |A_n|^2, which :mod:`cradle.integrators.dps_travelling` continues; theta is then
an unknown. The invariant combination of velocity and norm is c P^((1-alpha)/2).

Since sum_n A_n is conserved by (dfnls) and (tb) multiplies it by e^{i theta}, a TB with theta != 0 mod 2 pi has
sum_n A_n = 0 (the constant mode A -> A + kappa, a symmetry of (dfnls), is no symmetry of (tb): its multipliers
are e^{+-i theta}).

The Floquet multipliers modulo shift are the eigenvalues of the monodromy of the shooting map composed with
the shift, M = e^{-i theta} S^{-1} DPhi_T(A) (a real-linear map of C^N = R^{2N}); the phase and the time shift
each give an eigenvalue 1 in a Jordan block with the conserved quantity conjugate to it (the norm, H): four
trivial multipliers at 1 (Xu, Cuevas-Maraver, Kevrekidis and Vainchtein, arXiv 1701.04882: a travelling wave is
a periodic orbit modulo shift).

Everything here is a formula on arrays (the right-hand side and its linearisation, the shift, the residual,
the scaling, the tail measure); integration is :mod:`cradle.integrators.dps_travelling`.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.models import dps


def shift(A: ArrayLike, k: int = 1) -> NDArray[np.complex128]:
    """(S^k A)_n = A_{n-k} on the ring, along the first axis (sites first: columns of a matrix shift too)."""
    return np.roll(np.asarray(A), k, axis=0)


def rhs(A: ArrayLike, alpha: float, tau0: float) -> NDArray[np.complex128]:
    """dA_n/dtau of (dfnls) on the ring (:func:`cradle.models.dps.rhs` along the first axis)."""
    return dps.p_laplacian(np.asarray(A), alpha) / (2j * tau0)


def linearised_rhs(A: ArrayLike, V: ArrayLike, alpha: float, tau0: float) -> NDArray[np.complex128]:
    """The variational equation of (dfnls) on the ring: dV/dtau for perturbations V (N, or N x m columns).

    g(z) = z |z|^(alpha-1) is not holomorphic: with s the bond difference and r = |s|,
    Dg(s) w = r^(alpha-1) w + (alpha-1) r^(alpha-3) s Re(conj(s) w) (0 at r = 0, alpha > 1).
    """
    A = np.asarray(A, complex)
    V = np.asarray(V, complex)
    s = np.roll(A, -1) - A
    r = np.abs(s)
    with np.errstate(divide="ignore", invalid="ignore"):
        w1 = np.where(r > 0, r ** (alpha - 1.0), 0.0)
        w2 = np.where(r > 0, (alpha - 1.0) * r ** (alpha - 3.0), 0.0)
    if V.ndim == 2:
        s, w1, w2 = s[:, None], w1[:, None], w2[:, None]
    dV = np.roll(V, -1, axis=0) - V
    G = w1 * dV + w2 * s * np.real(np.conj(s) * dV)
    return (G - np.roll(G, 1, axis=0)) / (2j * tau0)


def residual(A: ArrayLike, B: ArrayLike, theta: float) -> NDArray[np.complex128]:
    """R = e^{-i theta} S^{-1} B - A of (tb), B = Phi_T(A) the state one period later."""
    return np.exp(-1j * theta) * shift(B, -1) - np.asarray(A)


def relative_residual(A: ArrayLike, B: ArrayLike, theta: float) -> float:
    """max_n |R_n| / max_n |A_n|: the shift-map residual of a TB."""
    return float(np.max(np.abs(residual(A, B, theta))) / np.max(np.abs(A)))


def scaled(A: ArrayLike, T: float, lam: float, alpha: float) -> tuple[NDArray[np.complex128], float]:
    """DpS's scaling: the TB (lambda A, lambda^(1-alpha) T) of the same theta,
    B(tau) = lambda A(lambda^(alpha-1) tau)."""
    out = np.asarray(A, dtype=np.complex128) * lam
    return out, float(T * lam ** (1.0 - alpha))


def phase_of(A: ArrayLike, B: ArrayLike) -> float:
    """theta best fitting B = e^{i theta} S A in least squares: arg sum_n conj(A_{n-1}) B_n."""
    return float(np.angle(np.sum(np.conj(shift(A, 1)) * np.asarray(B))))


def centre(A: ArrayLike) -> float:
    """Position of a localised state on the ring: the argument of sum |A_n|^2 e^{2 pi i n/N}, times N / 2 pi
    (in [0, N); unwrap along a run)."""
    w = np.abs(np.asarray(A)) ** 2
    N = w.size
    z = np.sum(w * np.exp(2j * np.pi * np.arange(N) / N))
    return float(np.angle(z) * N / (2 * np.pi) % N)


def tail_amplitude(A: ArrayLike) -> float:
    """max |A_n| over the quarter ring farthest from the TB's centre (ring distance >= 3N/8), relative to
    max |A_n|: its oscillatory tail (the core of a DpS breather decays doubly exponentially, so that far from the
    centre only the tail is left; on a small ring the core's own decay still shows there)."""
    A = np.asarray(A)
    N = A.size
    d = np.abs((np.arange(N) - centre(A) + N / 2) % N - N / 2)   # ring distance to the centre
    far = d >= 3 * N / 8
    return float(np.max(np.abs(A[far])) / np.max(np.abs(A)))


def kicked(profile: ArrayLike, kappa: float, centre_site: float) -> NDArray[np.complex128]:
    """A static breather profile phi_n given the phase gradient e^{i kappa (n - centre)} (a push: it then moves
    with a velocity that grows with kappa)."""
    phi = np.asarray(profile, complex)
    n = np.arange(phi.size)
    return phi * np.exp(1j * kappa * (n - centre_site))


def real(A: ArrayLike) -> NDArray[np.float64]:
    """C^N -> R^{2N}: (Re A, Im A), the real coordinates of the Newton iteration and the monodromy."""
    A = np.asarray(A, complex)
    return np.concatenate([A.real, A.imag], axis=0)


def complex_(y: ArrayLike) -> NDArray[np.complex128]:
    """R^{2N} -> C^N, the inverse of :func:`real` (along the first axis)."""
    y = np.asarray(y, float)
    N = y.shape[0] // 2
    return y[:N] + 1j * y[N:]
