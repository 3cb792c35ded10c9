"""The discrete p-Schrödinger (DpS) equation (dfnls) and its explicit solutions.

    2 i tau0 dA_n/dtau = g(A_{n+1} - A_n) - g(A_n - A_{n-1}),  g(z) = z |z|^(alpha-1)   (dfnls)

It is the modulation equation of the ansatz (ansatz)
x_n(t) ~ eps (A_n(tau) e^{it} + c.c.), tau = eps^(alpha-1) t.

Contents: the coefficient tau0(alpha) (tau0) and the Wallis integral c_alpha
(wallis)/(cal)/(thec); the right-hand side; the invariants (squared l2 norm,
Hamiltonian H, P = sum A_n); the plane waves (ansatz3) with the dispersion
relation (ds) and the amplitude-frequency relation (freq) of the
approximate travelling waves (ansatzapprox).

The coefficients (c_alpha, tau0) and :func:`amplitude_from_omega` check alpha (``@checked``); the
right-hand side, the invariants and the plane waves are formulas that solvers call in loops, and
trust their caller (alpha > 1, bc periodic or free).
"""
from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.specs.checked import checked


@checked
def c_alpha(alpha: float) -> float:
    """Wallis integral with fractional index alpha+1, closed form (thec).

    c_alpha = 2 alpha Gamma(alpha/2) / (sqrt(pi) (alpha^2 - 1) Gamma((alpha-1)/2)).
    Evaluated through log-Gamma so that alpha -> 1+ (Gamma((alpha-1)/2) -> inf)
    stays finite.
    """
    log_c = (
        math.log(2.0 * alpha)
        + math.lgamma(alpha / 2.0)
        - 0.5 * math.log(math.pi)
        - math.log(alpha**2 - 1.0)
        - math.lgamma((alpha - 1.0) / 2.0)
    )
    return math.exp(log_c)


@checked
def c_alpha_wallis(alpha: float) -> float:
    """c_alpha = (2/pi) int_0^{pi/2} cos(t)^(alpha+1) dt by quadrature (wallis)."""
    from scipy.integrate import quad  # imported here: scipy.integrate costs 0.5 s at start-up

    val, _ = quad(lambda t: np.cos(t) ** (alpha + 1.0), 0.0, np.pi / 2.0, epsabs=0.0, epsrel=1e-13, limit=200)
    return 2.0 / np.pi * val


@checked
def tau0(alpha: float) -> float:
    """tau0 = 2^(1-alpha) / c_alpha   (tau0); tau0(3/2) = 5 Gamma(1/4)^2/(24 sqrt(pi)) ~ 1.545."""
    return 2.0 ** (1.0 - alpha) / c_alpha(alpha)


def _g(z: np.ndarray, alpha: float) -> np.ndarray:
    """g(z) = z |z|^(alpha-1), written so that z = 0 gives 0 for any alpha > 1."""
    return z * np.abs(z) ** (alpha - 1.0)


def differences(A: ArrayLike, bc: str = "periodic") -> np.ndarray:
    """Forward differences A_{n+1} - A_n along the last axis (0 past a free end)."""
    A = np.asarray(A)
    D = np.roll(A, -1, axis=-1) - A
    if bc == "free":
        D[..., -1] = 0.0
    return D


def p_laplacian(A: ArrayLike, alpha: float, bc: str = "periodic") -> np.ndarray:
    """The discrete p-Laplacian g(A_{n+1} - A_n) - g(A_n - A_{n-1}), p = alpha + 1, along the last axis.

    The coupling of (dfnls), and of the stationary equations (dpsst)/(dpsstn)
    for real A; past a free end the missing bond contributes nothing.
    """
    G = _g(differences(A, bc), alpha)
    G_left = np.roll(G, 1, axis=-1)
    if bc == "free":
        G_left[..., 0] = 0.0
    return G - G_left


def rhs(A: ArrayLike, alpha: float, bc: str = "periodic", tau0_value: float | None = None) -> NDArray[np.complex128]:
    """dA_n/dtau of (dfnls): (g(A_{n+1}-A_n) - g(A_n-A_{n-1})) / (2 i tau0)."""
    t0 = tau0(alpha) if tau0_value is None else tau0_value
    return p_laplacian(A, alpha, bc) / (2j * t0)


def l2_norm_squared(A: ArrayLike) -> np.float64 | NDArray[np.float64]:
    """Squared l2 norm sum_n |A_n|^2, conserved by (dfnls)."""
    return np.sum(np.abs(A) ** 2, axis=-1)


def hamiltonian(A: ArrayLike, alpha: float, bc: str = "periodic") -> np.float64 | NDArray[np.float64]:
    """DpS Hamiltonian H = -1/((alpha+1) tau0) sum_n |A_{n+1} - A_n|^(alpha+1)."""
    D = differences(A, bc)
    return -np.sum(np.abs(D) ** (alpha + 1.0), axis=-1) / ((alpha + 1.0) * tau0(alpha))


def momentum(A: ArrayLike) -> np.complex128 | NDArray[np.complex128]:
    """P = sum_n A_n (complex), conserved by (dfnls)."""
    return np.sum(A, axis=-1)


def plane_wave_frequency(R: float, q: float, alpha: float) -> float:
    """Omega of the plane wave (ansatz3) from the dispersion relation (ds).

    tau0 Omega = 2^alpha R^(alpha-1) |sin(q/2)|^(alpha+1).
    """
    return 2.0**alpha * R ** (alpha - 1.0) * abs(np.sin(q / 2.0)) ** (alpha + 1.0) / tau0(alpha)


def plane_wave(n: ArrayLike, tau: ArrayLike, R: float, q: float, phi: float, alpha: float) -> NDArray[np.complex128]:
    """A_n(tau) = R exp(i (Omega tau - q n - phi))   (ansatz3) with Omega from (ds).

    ``n`` and ``tau`` broadcast (e.g. tau[:, None], n[None, :]).
    """
    Om = plane_wave_frequency(R, q, alpha)
    return R * np.exp(1j * (Om * np.asarray(tau) - q * np.asarray(n) - phi))


def omega_tw(a: float, q: float, alpha: float) -> float:
    """Frequency of the approximate travelling wave of amplitude a   (freq).

    omega_tw = 1 + (2 / tau0) a^(alpha-1) |sin(q/2)|^(alpha+1).
    """
    return 1.0 + 2.0 / tau0(alpha) * a ** (alpha - 1.0) * abs(np.sin(q / 2.0)) ** (alpha + 1.0)


@checked
def amplitude_from_omega(omega: float, q: float, alpha: float) -> float:
    """Invert (freq): the amplitude a > 0 whose travelling wave has frequency omega.

    Needs omega > 1 and sin(q/2) != 0 (for q = 0 every amplitude has omega = 1).
    """
    if not omega > 1.0:
        raise ValueError(f"omega_tw must be > 1 to derive a from (freq), got omega_tw={omega!r}")
    s = abs(np.sin(q / 2.0))
    if s == 0.0:
        raise ValueError("q = 0: (freq) gives omega_tw = 1 for every a; give a instead of omega_tw")
    return ((omega - 1.0) * tau0(alpha) / (2.0 * s ** (alpha + 1.0))) ** (1.0 / (alpha - 1.0))


def mu_from_omega_sw(omega_sw: float, alpha: float) -> float:
    """mu = (omega_sw - 1) 2^alpha tau0 of the standing waves (dpsst)/(ansatzapproxst2)."""
    return (omega_sw - 1.0) * 2.0**alpha * tau0(alpha)


def omega_sw_from_mu(mu: float, alpha: float) -> float:
    """Inverse of :func:`mu_from_omega_sw`."""
    return 1.0 + mu / (2.0**alpha * tau0(alpha))
