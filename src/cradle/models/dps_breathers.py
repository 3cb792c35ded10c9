"""The DpS breathers (ansatzapproxst2) beside the exact ones: linear stability, energy at equal action,
distance, tails.

The DpS breather of frequency omega_b is A_n(tau) = phi_n e^{i Omega tau}, phi_n = mu^(1/(alpha-1)) a_n / 2,
eps = 1 (so tau = t), Omega = omega_b - 1 = mu / (2^alpha tau0), a_n the mu = 1 solution of (dpsstn);
in the lattice x_n(t) ~ 2 phi_n cos(omega_b t).

Linear stability of (dfnls) at it: A = e^{i Omega tau} (phi + u + i w), and with s_n = phi_{n+1} - phi_n
the linearised g(z) = z|z|^(alpha-1) is |s|^(alpha-1) (Re + alpha... ) i.e. alpha |s|^(alpha-1) on u and
|s|^(alpha-1) on w:

    2 tau0 u' = (L_1 + 2 tau0 Omega) w,     2 tau0 w' = -(L_alpha + 2 tau0 Omega) u,

L_c the weighted Laplacian with bond weights c |s_n|^(alpha-1). Eigenvalues lambda (per unit tau = t);
a perturbation e^{lambda t} of the envelope multiplies the lattice breather by mu = e^{lambda T}, so
lambda is directly comparable with ln(mu) / T of the exact breather's Floquet multipliers.

Energy at equal action (Peierls-Nabarro barrier): averaging (ham) over the fast phase with
x_n = 2 Re(A_n e^{it}) gives E = J / (2 pi) - 2 H_DpS(A), J = 4 pi sum |A_n|^2 the action, so at equal
action the DpS barrier is E_bond - E_site = -2 (H_bond - H_site) at equal norm; with the mu = 1 profiles
(energy balance sum a^2 = sum |da|^(alpha+1) = S) and P = sum |A|^2,
-2 H = 2 P^((alpha+1)/2) S^((1-alpha)/2) / ((alpha+1) tau0).
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.models import dps


def _laplacian(w: NDArray[np.float64], bc: str) -> NDArray[np.float64]:
    """Matrix of u -> w_n (u_{n+1} - u_n) - w_{n-1} (u_n - u_{n-1}) (bond weights w; none past a free end)."""
    N = w.size
    L = np.zeros((N, N))
    for n in range(N):
        m = (n + 1) % N
        if bc == "free" and n == N - 1:
            continue
        L[n, n] -= w[n]
        L[n, m] += w[n]
        L[m, m] -= w[n]
        L[m, n] += w[n]
    return L


def operators(a_n: ArrayLike, omega: float, alpha: float,
              bc: str = "periodic") -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(A, B): the symmetric operators of the DpS breather of frequency omega linearised in its rotating frame,
    real and imaginary parts of the perturbation (u' = A v, v' = -B u): lambda^2 are the eigenvalues of -A B."""
    mu = dps.mu_from_omega_sw(omega, alpha)
    t0 = dps.tau0(alpha)
    phi = 0.5 * mu ** (1.0 / (alpha - 1.0)) * np.asarray(a_n, float)
    s = dps.differences(phi, bc)
    w = np.abs(s) ** (alpha - 1.0)
    Om = omega - 1.0
    N = phi.size
    A = (_laplacian(w, bc) + 2 * t0 * Om * np.eye(N)) / (2 * t0)
    B = (_laplacian(alpha * w, bc) + 2 * t0 * Om * np.eye(N)) / (2 * t0)
    return A, B


def stability(a_n: ArrayLike, omega: float, alpha: float, bc: str = "periodic",
              odd_basis: NDArray[np.float64] | None = None
              ) -> tuple[NDArray[np.complex128], NDArray[np.complex128] | None]:
    """Eigenvalues lambda (per unit t) of the DpS breather of frequency omega from the mu = 1 profile a_n.

    Returns (lambda of all modes, lambda of the symmetry-breaking modes (on ``odd_basis``, N x m
    orthonormal columns, if given)).
    """
    A, B = operators(a_n, omega, alpha, bc)

    def lam(A_: NDArray[np.float64], B_: NDArray[np.float64]) -> NDArray[np.complex128]:
        ev = np.linalg.eigvals(-A_ @ B_).astype(complex)
        r = np.sqrt(ev)
        return np.concatenate([r, -r])

    out = lam(A, B)
    odd = None
    if odd_basis is not None:
        P = odd_basis
        odd = lam(P.T @ A @ P, P.T @ B @ P)
    return out, odd


def pn_barrier(a_site: ArrayLike, a_bond: ArrayLike, action: NDArray[np.float64], alpha: float) -> NDArray[np.float64]:
    """DpS Peierls-Nabarro barrier E_bond - E_site at equal action J (module docstring), in lattice energy."""
    S_s, S_b = float(np.sum(np.asarray(a_site) ** 2)), float(np.sum(np.asarray(a_bond) ** 2))
    P = np.asarray(action, float) / (4 * np.pi)
    return 2 * P ** ((alpha + 1) / 2) * (S_b ** ((1 - alpha) / 2) - S_s ** ((1 - alpha) / 2)) / ((alpha + 1)
                                                                                               * dps.tau0(alpha))


def omega_of_amplitude(a_n: ArrayLike, amplitude: float, alpha: float) -> float:
    """Frequency of the DpS breather (ansatzapproxst2) whose x_n(0) = mu^(1/(alpha-1)) a_n has max |x_n| = amplitude."""
    mu = (amplitude / float(np.max(np.abs(a_n)))) ** (alpha - 1.0)
    return dps.omega_sw_from_mu(mu, alpha)
