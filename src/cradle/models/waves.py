"""Exact periodic travelling waves of (nc) with V = V0: the advance-delay equation (ad) solved.

Travelling waves x_n(t) = u(q n - omega t) solve the advance-delay equation (ad)

    omega^2 u'' + u = N(u),   N(u)(xi) = V0'(u(xi+q)-u(xi)) - V0'(u(xi)-u(xi-q))   (ad), (defn)

for u odd and 2 pi-periodic. With the splitting (ansatzu) u = a sin(xi) + a^alpha v,
v orthogonal to sin (the first sine coefficient of u is exactly a), and the
scaling omega^2 - 1 = a^(alpha-1) lambda of section 3, the positive
homogeneity V0'(a d) = a^alpha V0'(d) gives, with eps = a^(alpha-1) and
w = sin + eps v, the scale-free problem

    lambda = -zeta*(N(w))                                   (adcentral)-(f0)
    (1 - omega^2 j^2) v_j = N_j(w),  j >= 2                 (projection on X_h)

where N_j are the sine coefficients. We discretise v by J sine modes
(j = 2..J; all j, since V0' is not odd and u(xi+pi) != -u(xi) unless q = pi),
evaluate N(w) on a fine uniform grid of M points (the shifts xi +- q are exact:
they are phase factors on the sine coefficients) and solve by Newton with an
analytic Jacobian (dN/dw uses V0''), starting from the fixed point of
(fpe) at eps -> 0 and continuing in a. N(w) is only C^1 where a contact opens
(V0' ~ |d|^alpha H(-d)), so N_j decays like j^-(alpha+1), v_j like
j^-(alpha+3), and the trapezoidal sine coefficients carry an aliasing error
~ M^-(alpha+1): M = 2^16 keeps it below 1e-11.


:class:`Wave` is one solution, :func:`solve` finds it by Newton, :func:`branch` continues it in
a; :mod:`cradle.analyses.theorem1` measures them against Theorem 1 and
:mod:`cradle.analyses.floquet` linearises (nc) about them.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.specs.checked import checked

DEFAULT_M = 2**16


def dV0(d: NDArray[np.float64], alpha: float) -> NDArray[np.float64]:
    """V0'(d) = -|d|^alpha H(-d): the Hertz contact force of a bond of elongation d (V = V0)."""
    c = np.maximum(-d, 0.0)
    return -(c**alpha)


def d2V0(d: NDArray[np.float64], alpha: float) -> NDArray[np.float64]:
    """V0''(d) = alpha |d|^(alpha-1) H(-d): the stiffness of a bond of elongation d."""
    c = np.maximum(-d, 0.0)
    return alpha * c ** (alpha - 1.0)


def grid(M: int) -> np.ndarray:
    return 2.0 * np.pi * np.arange(M) / M


def synth(c: ArrayLike, M: int, shift: float = 0.0) -> np.ndarray:
    """u(xi_m + shift) on the M-point grid for u = sum_{j>=1} c_j sin(j xi) (c[0] is c_1)."""
    c = np.asarray(c, dtype=float)
    J = c.size
    if J > M // 2 - 1:
        raise ValueError(f"{J} modes need M > {2 * J + 2} grid points")
    j = np.arange(1, J + 1)
    X = np.zeros(M // 2 + 1, dtype=complex)
    # Re sum Z_j e^{i j xi} with Z_j = -i c_j e^{i j shift}; irfft(X)[m] = Re sum 2 X_j/M e^{i j xi_m}
    X[1:J + 1] = -1j * c * np.exp(1j * j * shift) * (M / 2.0)
    return np.fft.irfft(X, n=M)


def sine_coefficients(f: ArrayLike, J: int) -> np.ndarray:
    """(1/pi) int f sin(j xi), j = 1..J, by the trapezoidal rule on the uniform grid of f."""
    f = np.asarray(f, dtype=float)
    M = f.size
    return -2.0 / M * np.fft.rfft(f)[1:J + 1].imag


def N_grid(c: ArrayLike, q: float, alpha: float,
           M: int) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """N(u) (defn) on the grid, and the bond elongations d+ = u(xi+q)-u(xi), d- = u(xi)-u(xi-q)."""
    u = synth(c, M)
    dp = synth(c, M, q) - u
    dm = u - synth(c, M, -q)
    return dV0(dp, alpha) - dV0(dm, alpha), dp, dm


@dataclass
class Wave:
    """One exact travelling wave: u = a (sin xi + eps sum_{j>=2} v_j sin j xi), omega^2 = 1 + eps lambda."""
    a: float
    q: float
    alpha: float
    lam: float
    v: np.ndarray          # v_j, j = 1..J (v_1 = 0)
    residual: float        # max_j |residual_j| of the discrete equations (scale-free units)
    iterations: int
    M: int

    @property
    def eps(self) -> float:
        return self.a ** (self.alpha - 1.0)

    @property
    def omega(self) -> float:
        return float(np.sqrt(1.0 + self.eps * self.lam))

    @property
    def modes(self) -> int:
        return self.v.size

    def coefficients(self) -> np.ndarray:
        """Sine coefficients c_j of u (c_1 = a)."""
        c = self.a ** self.alpha * self.v
        c[0] = self.a
        return c

    def profile(self, xi: ArrayLike) -> np.ndarray:
        xi = np.asarray(xi, dtype=float)
        j = np.arange(1, self.modes + 1)
        return np.sin(np.multiply.outer(xi, j)) @ self.coefficients()


def _w(v: ArrayLike, eps: float) -> NDArray[np.float64]:
    w = eps * np.asarray(v, dtype=float)
    w[0] = 1.0
    return w


def residual(x: NDArray[np.float64], a: float, q: float, alpha: float, J: int, M: int) -> NDArray[np.float64]:
    """Residual of the scale-free equations for x = (lambda, v_2..v_J)."""
    eps = a ** (alpha - 1.0)
    lam, v = x[0], np.concatenate([[0.0], x[1:]])
    Nw, _, _ = N_grid(_w(v, eps), q, alpha, M)
    Nj = sine_coefficients(Nw, J)
    j = np.arange(1, J + 1)
    om2 = 1.0 + eps * lam
    r = (1.0 - om2 * j**2) * v - Nj
    r[0] = lam + Nj[0]
    return r


def jacobian(x: NDArray[np.float64], a: float, q: float, alpha: float, J: int, M_jac: int) -> NDArray[np.float64]:
    """Analytic Jacobian of :func:`residual` (dN/dw by V0''), on an M_jac-point grid."""
    eps = a ** (alpha - 1.0)
    lam, v = x[0], np.concatenate([[0.0], x[1:]])
    w = _w(v, eps)
    u = synth(w, M_jac)
    dp = synth(w, M_jac, q) - u
    dm = u - synth(w, M_jac, -q)
    kp, km = d2V0(dp, alpha), d2V0(dm, alpha)
    xi = grid(M_jac)
    j = np.arange(1, J + 1)
    S = np.sin(np.outer(xi, j))
    Sp = np.sin(np.outer(xi + q, j))
    Sm = np.sin(np.outer(xi - q, j))
    dN = kp[:, None] * (Sp - S) - km[:, None] * (S - Sm)      # dN/dw_k on the grid
    G = 2.0 / M_jac * S.T @ dN                                 # dN_j/dw_k
    om2 = 1.0 + eps * lam
    Jm = np.diag(1.0 - om2 * j**2) - eps * G
    Jm[0, :] = eps * G[0, :]
    Jm[:, 0] = -eps * j**2 * v
    Jm[0, 0] = 1.0
    return Jm


@checked
def solve(a: float, q: float, alpha: float, modes: int = 128, M: int = DEFAULT_M, guess: Wave | None = None,
          tol: float = 1e-13, max_iter: int = 40) -> Wave:
    """The exact wave of amplitude a (first sine coefficient) and wavenumber q, by Newton.

    ``guess``: a nearby solution (continuation); otherwise the eps -> 0 fixed point.
    """
    if not a > 0:
        raise ValueError(f"amplitude a must be > 0, got {a!r}")
    J = int(modes)
    M_jac = int(min(M, max(1024, 8 * J)))
    x = np.zeros(J)
    if guess is not None:
        g = np.zeros(J)
        n = min(J, guess.modes)
        g[:n] = guess.v[:n]
        x[1:] = g[1:]
        x[0] = guess.lam
    else:  # leading order: v0 = K_h P_h N(sin), lambda0 = -zeta*(N(sin))
        Nj = sine_coefficients(N_grid(np.r_[1.0, np.zeros(J - 1)], q, alpha, M)[0], J)
        j = np.arange(1, J + 1)
        x[1:] = Nj[1:] / (1.0 - j[1:] ** 2)
        x[0] = -Nj[0]
    r = residual(x, a, q, alpha, J, M)
    scale = np.maximum(1.0, np.arange(1, J + 1) ** 2.0)
    it = 0
    Jm = None
    best = np.max(np.abs(r / scale))
    while best > tol and it < max_iter:
        if Jm is None or it % 4 == 0:
            Jm = jacobian(x, a, q, alpha, J, M_jac)
        x_new = x - np.linalg.solve(Jm, r)
        r_new = residual(x_new, a, q, alpha, J, M)
        res_new = np.max(np.abs(r_new / scale))
        it += 1
        if not np.isfinite(res_new):
            break
        if res_new >= best and it > 6 and res_new < 1e3 * tol:
            break  # stagnation at round-off level
        x, r, best = x_new, r_new, res_new
    v = np.concatenate([[0.0], x[1:]])
    return Wave(a=float(a), q=float(q), alpha=alpha, lam=float(x[0]), v=v, residual=float(best), iterations=it,
                M=int(M))


def branch(amplitudes: ArrayLike, q: float, alpha: float, modes: int = 128, M: int = DEFAULT_M) -> list[Wave]:
    """Solutions along increasing amplitudes, each Newton started from the previous one."""
    out, prev = [], None
    for a in np.sort(np.asarray(amplitudes, dtype=float)):
        prev = solve(a, q, alpha, modes=modes, M=M, guess=prev)
        out.append(prev)
    return out


def wave_max(w: Wave) -> float:
    """max_xi u(xi): at xi = pi/2 for q = pi (u(pi - xi) = u(xi)); on a fine grid otherwise."""
    if abs(abs(w.q) - np.pi) < 1e-14:
        j = np.arange(1, w.modes + 1)
        return float(np.sin(j * np.pi / 2.0) @ w.coefficients())
    return float(np.max(synth(w.coefficients(), max(4096, 8 * w.modes))))
