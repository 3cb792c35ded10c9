"""Bloch-Floquet modes of the exact travelling waves of (nc): Hill's method and the ring monodromy.

Linearising (nc) with V = V0 about the exact wave x_n(t) = u(q n - omega t) of :mod:`cradle.models.waves`
(the force of bond n is V0'(x_{n+1} - x_n), see :mod:`cradle.models.lattice`) gives

    y_n'' + y_n = K(xi_n) (y_{n+1} - y_n) - K(xi_n - q) (y_n - y_{n-1}),   xi_n = q n - omega t,   (lin)

with K(xi) = V0''(u(xi + q) - u(xi)) = alpha |d|^(alpha-1) H(-d): continuous for alpha > 1 (Hoelder
alpha - 1 where a contact opens), so the linearisation is legitimate. The coefficients depend on (n, t)
only through xi: (lin) is invariant under t -> t + T (T = 2 pi / omega) and under (n, t) -> (n + 1,
t + q / omega). Joint eigenfunctions of both are the Bloch-Floquet modes

    y_n(t) = e^{lambda t} e^{i p n} W(xi_n),   W 2 pi-periodic,                               (bloch)

and (lin) becomes, for each perturbation wavenumber p, the quadratic eigenvalue problem on the circle

    omega^2 W'' - 2 lambda omega W' + (lambda^2 + 1) W = L_p W,
    L_p W = K(xi) (e^{ip} W(xi + q) - W(xi)) - K(xi - q) (W(xi) - e^{-ip} W(xi - q)),

solved here by Hill's method: W = sum_{|m| <= L} W_m e^{i m xi}, K by its Fourier coefficients (FFT of
K on an M-point grid). L_p is Hermitian and the first-order term skew-Hermitian (a gyroscopic
pencil), also after truncation, so the computed spectrum keeps the Hamiltonian symmetry
lambda -> -conj(lambda): stable modes stay on the imaginary axis (|Re lambda| at round-off).

Labelling. (lambda, p, W) and (lambda + i omega, p - q, e^{i xi} W) are the same lattice solution, so
the pair (lambda, p) is defined modulo (i omega, -q). At a -> 0 the spectrum is lambda = i (m omega
+- 1); exactly two eigenvalues, +-i (omega - 1), lie in the central strip |Im lambda| < omega / 2, with
W = e^{-+i xi}: the lattice modes e^{i(p - q) n + i t} and e^{i(p + q) n - i t}, i.e. the sidebands p of
the DpS plane wave (ansatz3). So g(p) = max Re lambda over the central strip is the lattice
counterpart of the DpS growth rate of sideband p; the other strips at p repeat the central strip at
p + m q. The fastest growth over all perturbations is max_p g(p).

On a ring of N sites with q = 2 pi k / N the wave is T-periodic and (lin) has a 2N x 2N monodromy
matrix; its Floquet exponents ln(mu) / T (mod i omega) are the central-strip eigenvalues of (bloch)
at p = 2 pi j / N, j = 0..N-1 (two per p): :func:`ring_monodromy` computes it by brute force (the
variational equations with DOP853) to check the reduction. Trivial multipliers: time translation
(W = u', p = 0, lambda = 0) and the amplitude family (its Jordan partner) give a double multiplier 1.

Small amplitude: x_n ~ eps (A_n e^{it} + c.c.) with A = R e^{i(...)} and a = 2 eps R, tau = eps^(alpha-1) t,
so a DpS growth rate lambda_tau converts to lattice time as growth_rate(q, p, alpha, R = a / 2)
(homogeneous of degree alpha - 1 in R): :func:`cradle.analyses.floquet.dps_growth`.

The stability analysis built on these (growth over (q, p), thresholds, the DpS comparison) is
:mod:`cradle.analyses.floquet`.
"""
from __future__ import annotations

from typing import Literal, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.models import dps, waves

DEFAULT_HILL_MODES = 32      # L: Fourier modes |m| <= L of W
DEFAULT_GRID_LOG2 = 14       # M = 2^14 points for the Fourier coefficients of K
NOISE_FLOOR = 1e-7           # Re lambda below this (per unit t: e-folding time 1e7) counts as neutral
# The trivial pair at p = 0 (double multiplier 1) splits by the discretisation error, ~1e-5 (see
# trivial_defect), and the splitting leaks to |p| ~ 1e-2: maxima over p leave out p < P_EXCLUDE. Where a
# genuine band reaches p -> 0 its rate grows like p, so its maximum lies further out.
P_EXCLUDE = 0.02 * np.pi


# ----------------------------------------------------------------- the waves

def wave_for(q: float, alpha: float, *, a: float | None = None, omega_tw: float | None = None, modes: int = 128,
             grid_log2: int = 16) -> waves.Wave:
    """The exact wave of (ad) of amplitude a (first sine coefficient), or with a = (freq) inverted at omega_tw.

    The paper's travelling-wave scenes fix omega_tw and take a from (freq); the exact wave with that a
    has a slightly different frequency omega_a (Theorem 1), stored alongside.
    """
    if (a is None) == (omega_tw is None):
        raise ValueError(f"give exactly one of a and omega_tw (got a={a!r}, omega_tw={omega_tw!r})")
    if a is None:
        a = dps.amplitude_from_omega(omega_tw, q, alpha)
    w = waves.solve(float(a), float(q), alpha, modes=modes, M=2 ** int(grid_log2))
    if not w.residual < 1e-10:
        raise RuntimeError(f"exact wave q={q!r} a={a!r}: Newton residual {w.residual:.3g}")
    return w


def coupling(w: waves.Wave, M: int = 2**DEFAULT_GRID_LOG2) -> np.ndarray:
    """K(xi) = V0''(u(xi + q) - u(xi)) on the M-point grid."""
    c = w.coefficients()
    d = waves.synth(c, M, w.q) - waves.synth(c, M)
    return waves.d2V0(d, w.alpha)


def coupling_fourier(w: waves.Wave, M: int = 2**DEFAULT_GRID_LOG2) -> np.ndarray:
    """Fourier coefficients K_hat_j, K(xi) = sum_j K_hat_j e^{i j xi}, as an FFT-ordered array of length M."""
    return np.fft.fft(coupling(w, M)) / M


# ----------------------------------------------------------------- Hill's method for (bloch)

class Hill:
    """The pencil of (bloch) for one wave, truncated to |m| <= L; :meth:`eigenvalues` for any p."""

    def __init__(self, w: waves.Wave, L: int = DEFAULT_HILL_MODES, M: int = 2**DEFAULT_GRID_LOG2) -> None:
        if M < 8 * (2 * L + 1):
            raise ValueError(f"M = {M} grid points too few for L = {L} Hill modes (need M >= 8 (2L + 1))")
        self.w, self.L, self.M = w, int(L), int(M)
        self.omega = w.omega
        Kh = coupling_fourier(w, M)
        m = np.arange(-self.L, self.L + 1)
        self.m = m
        diff = m[:, None] - m[None, :]
        self.Kd = Kh[diff % M]                                   # K_hat_{m - m'}
        self.phase_minus = np.exp(-1j * diff * w.q)              # coefficients of K(xi - q)
        self.eq = np.exp(1j * m * w.q)                           # e^{i m' q}

    def operator(self, p: float) -> np.ndarray:
        """The matrix of L_p on e^{i m xi}, |m| <= L (Hermitian)."""
        ep = np.exp(1j * p) * self.eq[None, :]
        return self.Kd * (ep - 1.0) - self.Kd * self.phase_minus * (1.0 - np.conj(ep))

    @overload
    def eigenvalues(self, p: float, vectors: Literal[False] = False) -> NDArray[np.complex128]: ...

    @overload
    def eigenvalues(self, p: float,
                    vectors: Literal[True]) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]: ...

    def eigenvalues(self, p: float, vectors: bool = False) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
        """All 2 (2L + 1) eigenvalues lambda of the truncated pencil (and the W-parts of the eigenvectors)."""
        n = self.m.size
        A = self.matrix(p)
        if vectors:
            lam, V = np.linalg.eig(A)
            return lam, V[:n]
        return np.linalg.eigvals(A)

    def matrix(self, p: float) -> np.ndarray:
        """The first-order companion matrix of the truncated pencil at p (its eigenvalues are the lambda)."""
        n = self.m.size
        om, m = self.omega, self.m
        D = np.diag(1.0 - om**2 * m**2).astype(complex) - self.operator(p)
        C = np.diag(-2j * om * m)
        A = np.zeros((2 * n, 2 * n), dtype=complex)
        A[:n, n:] = np.eye(n)
        A[n:, :n] = -D
        A[n:, n:] = -C
        return A

    def central(self, p: float) -> np.ndarray:
        """The eigenvalues in the central strip |Im lambda| < omega / 2 (the sidebands p; two expected)."""
        lam = self.eigenvalues(p)
        return lam[np.abs(lam.imag) < 0.5 * self.omega]

    def growth(self, p: ArrayLike) -> np.ndarray:
        """g(p) = max Re lambda over the central strip (0 where every Re lambda < NOISE_FLOOR)."""
        out = []
        for pp in np.atleast_1d(np.asarray(p, dtype=float)):
            c = self.central(pp)
            g = float(np.max(c.real)) if c.size else float("nan")
            out.append(g if g > NOISE_FLOOR else 0.0)
        return np.asarray(out)

    def signed(self, p: float, floor: float = NOISE_FLOOR) -> float:
        """max Re lambda of the central pair if > floor, else -|Im lambda_1 - Im lambda_2| (the distance to
        a collision): continuous in p, so a narrow unstable band opening between grid points is found by
        maximising it."""
        c = self.central(p)
        if c.size != 2:
            return float("nan")
        g = float(np.max(c.real))
        return g if g > floor else -abs(float(c[0].imag - c[1].imag))

    def max_signed(self, n_p: int = 61, floor: float = NOISE_FLOOR) -> tuple[float, float]:
        """(max over p in (0, pi] of :meth:`signed`, its p): grid, then a bounded refinement (p = 0, the
        trivial double multiplier, and its neighbourhood p < P_EXCLUDE are left out)."""
        from scipy.optimize import minimize_scalar

        ps = np.linspace(0.0, np.pi, n_p)
        ps = ps[ps >= P_EXCLUDE]
        s = np.array([self.signed(pp, floor) for pp in ps])
        i = int(np.nanargmax(s))
        lo = ps[i - 1] if i > 0 else ps[0]
        hi = ps[min(i + 1, ps.size - 1)]
        res = minimize_scalar(lambda x: -self.signed(x, floor), bounds=(lo, hi), method="bounded",
                              options={"xatol": 1e-7})
        if np.isfinite(res.fun) and -res.fun > s[i]:
            return float(-res.fun), float(res.x)
        return float(s[i]), float(ps[i])

    def trivial_defect(self) -> float:
        """max |lambda| of the central pair at p = 0 (exactly 0: time translation and its Jordan partner)."""
        return float(np.max(np.abs(self.central(0.0))))

    def max_growth(self, n_p: int = 121) -> tuple[float, float]:
        """(max_p g(p), argmax p in [P_EXCLUDE, pi]): grid search (g(-p) = g(p)), then a bounded refinement."""
        from scipy.optimize import minimize_scalar

        ps = np.linspace(0.0, np.pi, n_p)
        ps = ps[ps >= P_EXCLUDE]                   # p ~ 0: the trivial pair (see trivial_defect)
        g = self.growth(ps)
        i = int(np.argmax(g))
        if not g[i] > 0.0:
            return 0.0, float("nan")
        lo = ps[i - 1] if i > 0 else ps[0]
        hi = ps[min(i + 1, ps.size - 1)]
        res = minimize_scalar(lambda x: -float(self.growth(x)[0]), bounds=(lo, hi), method="bounded",
                              options={"xatol": 1e-6})
        if -res.fun > g[i]:
            return float(-res.fun), float(res.x)
        return float(g[i]), float(ps[i])


# ----------------------------------------------------------------- brute force on a ring

def ring_wavenumber(w: waves.Wave, N: int) -> int:
    """k with q = 2 pi k / N, or ValueError."""
    k = w.q * N / (2.0 * np.pi)
    if abs(k - round(k)) > 1e-9:
        raise ValueError(f"q = {w.q!r} is not 2 pi k / N on a ring of N = {N} sites")
    return int(round(k))


def ring_state(w: waves.Wave, N: int, t: float = 0.0) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(x_n(t), v_n(t)) of the exact wave on the ring, n = 0..N-1."""
    ring_wavenumber(w, N)
    xi = w.q * np.arange(N) - w.omega * t
    j = np.arange(1, w.modes + 1)
    c = w.coefficients()
    x = np.sin(np.multiply.outer(xi, j)) @ c
    v = -w.omega * (np.cos(np.multiply.outer(xi, j)) @ (j * c))
    return x, v


def ring_monodromy(w: waves.Wave, N: int, rtol: float = 1e-11, atol: float = 1e-13) -> np.ndarray:
    """The 2N x 2N monodromy matrix of (lin) over T = 2 pi / omega on a ring (state (y, y')), by DOP853."""
    from scipy.integrate import solve_ivp

    ring_wavenumber(w, N)
    j = np.arange(1, w.modes + 1)
    c = w.coefficients()
    n = np.arange(N)
    om, q, al = w.omega, w.q, w.alpha

    def rhs(t: float, Y: NDArray[np.float64]) -> NDArray[np.float64]:
        Y = Y.reshape(2 * N, 2 * N)
        y, v = Y[:N], Y[N:]
        u = np.sin(np.multiply.outer(q * n - om * t, j)) @ c
        k = waves.d2V0(np.roll(u, -1) - u, al)               # bond n: K(xi_n)
        dy = np.roll(y, -1, axis=0) - y
        f = k[:, None] * dy
        acc = -y + f - np.roll(f, 1, axis=0)
        return np.concatenate([v, acc]).ravel()

    T = 2.0 * np.pi / om
    sol = solve_ivp(rhs, (0.0, T), np.eye(2 * N).ravel(), method="DOP853", rtol=rtol, atol=atol)
    if not sol.success:
        raise RuntimeError(f"monodromy integration failed: {sol.message}")
    return sol.y[:, -1].reshape(2 * N, 2 * N)


def ring_exponents_hill(hill: Hill, N: int) -> np.ndarray:
    """Floquet exponents of the ring from (bloch): the central eigenvalues at p = 2 pi j / N, j = 0..N-1."""
    ring_wavenumber(hill.w, N)
    return np.concatenate([hill.central(2.0 * np.pi * jj / N) for jj in range(N)])


def multipliers(exponents: ArrayLike, T: float) -> np.ndarray:
    return np.exp(np.asarray(exponents) * T)


def match_distance(mu_a: ArrayLike, mu_b: ArrayLike) -> float:
    """max over mu_a of the distance to the nearest mu_b, and conversely (a Hausdorff distance)."""
    d = np.abs(np.asarray(mu_a)[:, None] - np.asarray(mu_b)[None, :])
    return float(max(d.min(axis=1).max(), d.min(axis=0).max()))


# ----------------------------------------------------------------- direct simulation

def direct_growth(w: waves.Wave, N: int, rel_size: float = 1e-9, growth_factor: float = 1e3, method: str = "dop853",
                  rtol: float = 1e-13) -> tuple[float, float, float, np.ndarray, np.ndarray]:
    """Growth rate of the top Floquet mode, measured on a nonlinear run of (nc) with integrate_lattice.

    The exact wave on the ring plus rel_size * a * (the real part of, normalised) the eigenvector of the
    largest brute-force multiplier mu; integrate to t with e^{rate t} = growth_factor. The deviation
    delta(t) from the exact wave is sampled at t = k T; its component on the mode, c_k = l . delta(k T)
    (l the left eigenvector), grows like |mu|^k without the beating that the complex pair (mu, conj mu)
    gives to |delta|. Returns (rate fitted on log|c_k| over the second half, rate fitted on log|delta|,
    Floquet rate ln|mu| / T, t, |delta|).
    """
    from cradle.integrators import integrate_lattice

    Mono = ring_monodromy(w, N)
    mu, V = np.linalg.eig(Mono)
    i = int(np.argmax(np.abs(mu)))
    T = 2.0 * np.pi / w.omega
    rate = float(np.log(np.abs(mu[i])) / T)
    if not rate > 1e-6:
        raise ValueError(f"no unstable Floquet mode on the ring N={N}, q={w.q!r} (top rate {rate:.3g})")
    left = np.linalg.inv(V)[i]
    vec = V[:, i].real if np.linalg.norm(V[:, i].real) > 0.3 else V[:, i].imag
    vec = vec / np.linalg.norm(vec)
    x0, v0 = ring_state(w, N)
    d0 = rel_size * w.a
    n_per = int(np.ceil(np.log(growth_factor) / rate / T))
    t_out = T * np.arange(n_per + 1)
    sol = integrate_lattice(x0 + d0 * vec[:N], v0 + d0 * vec[N:], t_out, alpha=w.alpha, bc="periodic",
                            method=method, rtol=rtol, atol=rtol * w.a * 1e-3)
    xs, vs = np.asarray(sol.x), np.asarray(sol.v)
    delta = np.concatenate([xs - x0[None, :], vs - v0[None, :]], axis=1)   # the wave is T-periodic
    dist = np.linalg.norm(delta, axis=1)
    proj = np.abs(delta @ left)
    sel = t_out >= 0.5 * t_out[-1]
    slope_mode = float(np.polyfit(t_out[sel], np.log(proj[sel]), 1)[0])
    slope_dist = float(np.polyfit(t_out[sel], np.log(dist[sel]), 1)[0])
    return slope_mode, slope_dist, rate, t_out, dist
