"""Exact time-periodic breathers of the lattice (nc) by reversible shooting, and their Floquet multipliers.

A breather of frequency omega_b is a solution of (nc) with x_n(t + T) = x_n(t), T = 2 pi / omega_b,
localised in n. We look for time-reversible ones, x_n(-t) = x_n(t): then v_n(0) = 0, and a solution
with v_n(0) = 0 and v_n(T/2) = 0 is even about t = 0 and about t = T/2, hence T-periodic. So the
periodic-orbit equations reduce to

    F(x0) = v(T/2; x0, v0 = 0) = 0,            N equations in the N unknowns x0 = x(0),

solved by Newton's method with the Jacobian dv(T/2)/dx0 from the variational equations of (nc)

    X'' + X = K_n (X_{n+1} - X_n) - K_{n-1} (X_n - X_{n-1}),   K_n = V0''(x_{n+1} - x_n) = alpha (-d_n)_+^(alpha-1),

integrated with the orbit over half a period only (why shooting rather than Fourier-Galerkin: the
Hertz force is only C^{1,alpha-1} at contact onset, so a Fourier series in t converges slowly,
like k^-(alpha+2), while an adaptive integrator (scipy's DOP853, error per period ~ rtol) resolves
the onsets; reversibility halves both the unknowns, N instead of 2N, and the integration time).
The time-translation symmetry is removed by v(0) = 0, and T is fixed. The near-translation (pinning)
direction is removed by solving within a symmetry class of x_n -> -x_{2c-n} (:func:`newton`: bond
breathers x(t) = -S x(t), N/2 unknowns; site breathers x(t + T/2) = -S x(t), conditions at T/4), and
the unknowns are restricted to the core (|x_n| > 1e-14 max|x|; the rest move below the tolerance).

The monodromy matrix over a full period follows from the half-period one by reversibility,
R (x, v) = (x, -v): M(T) = R M(T/2)^{-1} R M(T/2) (:func:`floquet` splits it by the symmetry into
the trivial and the pinning pair's subspaces). Its multipliers come in symplectic quadruples
(mu, 1/mu, conj mu, 1/conj mu) with the trivial pair at +1 (phase and frequency of the family), the
accuracy check of the literature (James, Kevrekidis, Cuevas, Physica D 251, 2013).

The start of a family is the DpS breather (ansatzapproxst2) x_n(0) = mu^(1/(alpha-1)) a_n with a_n
of (dpsstn) and mu = (omega_b - 1) 2^alpha tau0; continuation in omega_b predicts by the DpS scaling
x0 -> ((omega_b' - 1)/(omega_b - 1))^(1/(alpha-1)) x0 of the previous exact breather.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, overload

import numpy as np

from cradle.models.lattice import hamiltonian
from cradle.models.multipliers import split_trivial
from cradle.specs.checked import checked

if TYPE_CHECKING:
    from collections.abc import Callable, Iterable

    from numpy.typing import ArrayLike, NDArray

    from cradle.integrators._types import Floats

RTOL = 1e-13         # DOP853 relative tolerance of the shooting (period residuals 1e-11 .. 2e-9)


def _rhs_factory(N: int, m: int, alpha: float, periodic: bool) -> Callable[[float, Floats], Floats]:
    """Right-hand side of (nc) with the action integrand sum v^2 and m columns of the variational equations.

    The orbit and the stiffnesses come from the project's compiled kernels (``lattice_rhs``,
    ``lattice_jac`` of :mod:`cradle.integrators._kernels`: no new kernel to compile); the m columns
    are advanced by the Jacobian's lower-left block -1 + (K-weighted Laplacian).
    """
    from cradle.integrators import _kernels as K

    mode = K.mode_flag("hertz", alpha)
    f, Fv, dy, J = np.zeros(N), np.zeros(N), np.zeros(2 * N), np.zeros((2 * N, 2 * N))

    def rhs(t: float, y: Floats) -> Floats:
        out = np.empty_like(y)
        K.lattice_rhs(y[:2 * N], dy, f, Fv, alpha, mode, periodic)
        out[:2 * N] = dy
        v = y[N:2 * N]
        out[2 * N] = v @ v
        if m:
            K.lattice_jac(y[:2 * N], J, alpha, mode, periodic)
            X = y[2 * N + 1:2 * N + 1 + N * m].reshape(N, m)
            out[2 * N + 1:2 * N + 1 + N * m] = y[2 * N + 1 + N * m:]
            out[2 * N + 1 + N * m:] = (J[N:, :N] @ X).ravel()
        return out
    return rhs


@overload
def flow(x0: ArrayLike, v0: ArrayLike, t_end: float, alpha: float, bc: str = "periodic", columns: None = None,
         rtol: float = RTOL) -> tuple[Floats, Floats, float, None]: ...


@overload
def flow(x0: ArrayLike, v0: ArrayLike, t_end: float, alpha: float, bc: str, columns: Floats,
         rtol: float = RTOL) -> tuple[Floats, Floats, float, Floats]: ...


def flow(x0: ArrayLike, v0: ArrayLike, t_end: float, alpha: float, bc: str = "periodic", columns: Floats | None = None,
         rtol: float = RTOL) -> tuple[Floats, Floats, float, Floats | None]:
    """Integrate (nc) from (x0, v0) to t_end, with the action integral and, if ``columns`` (2N x m) is
    given, the variational equations along those initial perturbations.

    Returns (x, v, S, Phi) at t_end: S = int_0^t_end sum v^2 dt, Phi the 2N x m propagated perturbations.
    """
    from scipy.integrate import solve_ivp

    x0, v0 = np.asarray(x0, float), np.asarray(v0, float)
    N = x0.size
    m = 0 if columns is None else columns.shape[1]
    y0 = np.concatenate([x0, v0, [0.0]] + ([] if m == 0 else [columns[:N].ravel(), columns[N:].ravel()]))  # type: ignore[index, arg-type, var-annotated]  # m > 0: columns given
    scale = max(float(np.max(np.abs(x0))), float(np.max(np.abs(v0))), 1e-300)
    atol = np.full(y0.size, rtol * scale)
    atol[2 * N] = rtol * scale**2
    if m:
        atol[2 * N + 1:] = rtol
    sol = solve_ivp(_rhs_factory(N, m, alpha, bc == "periodic"), (0.0, t_end), y0, method="DOP853",
                    rtol=rtol, atol=atol)
    if not sol.success:
        raise RuntimeError(f"breather shooting: integration failed ({sol.message})")
    y = sol.y[:, -1]
    Phi = None
    if m:
        Phi = np.concatenate([y[2 * N + 1:2 * N + 1 + N * m].reshape(N, m), y[2 * N + 1 + N * m:].reshape(N, m)])
    return y[:N], y[N:2 * N], float(y[2 * N]), Phi


@dataclass
class Breather:
    omega: float            # omega_b
    x0: np.ndarray          # x_n(0), v_n(0) = 0
    converged: bool
    iterations: int
    half_residual: float    # max |v(T/2)| / max |x0| at the end of Newton
    alpha: float
    bc: str

    @property
    def T(self) -> float:
        return 2.0 * np.pi / self.omega

    @property
    def amplitude(self) -> float:
        return float(np.max(np.abs(self.x0)))

    def energy(self) -> float:
        """The energy (ham) of the breather, v(0) = 0."""
        return float(hamiltonian(self.x0, np.zeros_like(self.x0), self.alpha, self.bc))


def reflection(N: int, centre: float, bc: str = "periodic") -> np.ndarray:
    """The permutation matrix S of the reflection n -> 2 centre - n (modulo N on the ring)."""
    S = np.zeros((N, N))
    for n in range(N):
        m = round(2 * centre - n)
        if bc == "free" and not 0 <= m < N:
            raise ValueError(f"the reflection about {centre} does not map a free chain of N = {N} to itself")
        S[m % N, n] = 1.0
    return S


def _eigenbasis(S: Floats, sign: float) -> Floats:
    """Orthonormal basis (columns) of {x : S x = sign x} for a reflection S."""
    w, V = np.linalg.eigh(0.5 * (S + S.T))
    return V[:, np.abs(w - sign) < 0.5]


@checked
def newton(x_guess: ArrayLike, omega: float, alpha: float, bc: str = "periodic", kind: str | None = None,
           centre: int | None = None, tol: float = 1e-11, max_iter: int = 12, rtol: float = RTOL,
           core_rel: float = 1e-14) -> Breather:
    """Solve the periodic-orbit equations of a time-reversible breather by Newton's method from ``x_guess``.

    (nc) is invariant under x_n -> -x_{2c-n} (the reflection S about c with x -> -x: the Hertz force of the
    reflected, negated chain is the negated force) and under time shifts, so the symmetry classes are

    * ``bond`` (c = centre, reflection about bond (c, c+1)): x(t) = -S x(t) for all t; x0 in Fix(-S)
      (N/2 unknowns) and F = v(T/2) projected on Fix(-S);
    * ``site`` (reflection about bead c): x(t + T/2) = -S x(t) (the DpS site breather a_n cos(omega t)
      has it); with v(0) = 0 this makes t = T/4 a reversal point for (x, v) -> (-S x, S v), so
      F = (x(T/4) on Fix(S), v(T/4) on Fix(-S)) (N equations, a quarter period);
    * ``None``: F = v(T/2), x0 in R^N.

    Imposing a class removes the near-null pinning direction of the Jacobian (the almost vanishing
    Peierls-Nabarro barrier), along which an unconstrained iteration drifts. Converged when
    max|F| <= tol max|x0|; the step is halved while the residual does not decrease.
    """
    x = np.asarray(x_guess, float).copy()
    N = x.size
    S = None
    if kind is None:
        P, t_end = np.eye(N), np.pi / omega
    else:
        c = N // 2 if centre is None else centre
        S = reflection(N, c + 0.5 if kind == "bond" else c, bc)
        if kind == "bond":
            P, t_end = _eigenbasis(S, -1.0), np.pi / omega
        elif kind == "site":
            P, t_end = np.eye(N), 0.5 * np.pi / omega
            Bp, Bm = _eigenbasis(S, 1.0), _eigenbasis(S, -1.0)
        else:
            raise ValueError(f"unknown breather kind {kind!r} (site, bond or None)")
    # unknowns and equations on the core only: beads with |x_n| <= core_rel max|x| (and their images) move
    # by less than core_rel relative to the amplitude, below the residual tolerance
    on = np.zeros(N, bool)
    on[core(Breather(omega, x, False, 0, 0.0, alpha, bc), core_rel, S)] = True

    def inside(B: Floats) -> Floats:
        return B[:, np.all(np.abs(B[~on]) < 1e-12, axis=0)]

    P = inside(P)
    if kind == "site":
        Bp, Bm = inside(Bp), inside(Bm)
    x = P @ (P.T @ x)
    cols = np.vstack([P, np.zeros_like(P)])

    def F(xs: Floats, v: Floats, Phi: Floats | None = None) -> tuple[Floats, Floats | None]:
        if kind == "site":
            r = np.concatenate([Bp.T @ xs, Bm.T @ v])
            J = None if Phi is None else np.vstack([Bp.T @ Phi[:N], Bm.T @ Phi[N:]])
        else:
            r = P.T @ v
            J = None if Phi is None else P.T @ Phi[N:]
        return r, J

    res = np.inf
    for it in range(max_iter + 1):
        xs, v, _, Phi = flow(x, np.zeros(N), t_end, alpha, bc, cols, rtol)
        r, J = F(xs, v, Phi)
        res = float(np.max(np.abs(r))) / float(np.max(np.abs(x)))
        if res <= tol:
            return Breather(omega, x, True, it, res, alpha, bc)
        if it == max_iter or not np.isfinite(res):
            break
        step = P @ np.linalg.solve(J, -r)  # type: ignore[arg-type]  # J: F given Phi
        lam = 1.0
        while lam > 1e-3:                              # damped step: accept when the residual decreases
            xt = x + lam * step
            rt, _ = F(*flow(xt, np.zeros(N), t_end, alpha, bc, None, rtol)[:2])
            if np.max(np.abs(rt)) / max(np.max(np.abs(xt)), 1e-300) < res:
                break
            lam *= 0.5
        x = xt
    return Breather(omega, x, False, it, res, alpha, bc)


def period_residual(b: Breather, rtol: float = RTOL) -> tuple[float, float]:
    """(max |z(T) - z(0)| / max|x0|, action J = int_0^T sum v^2 dt) over one full period integrated from z(0)."""
    N = b.x0.size
    x, v, S, _ = flow(b.x0, np.zeros(N), b.T, b.alpha, b.bc, None, rtol)
    return float(max(np.max(np.abs(x - b.x0)), np.max(np.abs(v))) / b.amplitude), S


def core(b: Breather, rel: float = 1e-9, S: Floats | None = None) -> np.ndarray:
    """Indices of the beads where |x_n(0)| > rel max|x0|, with one neighbour on each side (the breather's
    core), closed under the reflection S if given."""
    N = b.x0.size
    big = np.where(np.abs(b.x0) > rel * b.amplitude)[0]
    idx = set()
    for n in big:
        for m in (n - 1, n, n + 1):
            if b.bc == "periodic" or 0 <= m < N:
                idx.add(m % N)
    if S is not None:
        idx |= {int(np.argmax(S[:, n])) for n in idx}
    return np.array(sorted(idx))


def half_period_map(b: Breather, idx: NDArray[np.intp], rtol: float = RTOL) -> np.ndarray:
    """M(T/2) restricted to the beads ``idx`` (their x then their v): the variational equations of (nc)
    along the breather from (x0, 0) over half a period, started on those coordinates only."""
    N, nc = b.x0.size, len(idx)
    cols = np.zeros((2 * N, 2 * nc))
    cols[idx, np.arange(nc)] = 1.0
    cols[N + idx, nc + np.arange(nc)] = 1.0
    _, _, _, Phi = flow(b.x0, np.zeros(N), b.T / 2, b.alpha, b.bc, cols, rtol)
    return np.concatenate([Phi[idx], Phi[N + idx]])


def monodromy(b: Breather, rtol: float = RTOL,
              rel: float | None = 1e-9) -> tuple[Floats, NDArray[np.complex128], NDArray[np.intp]]:
    """The monodromy matrix M(T) = R M(T/2)^{-1} R M(T/2) (reversibility, R = diag(1, -1)) without symmetry
    reduction, on the core (``rel``, see :func:`floquet`) or on all 2N coordinates (``rel=None``).
    Returns (M, the 2N multipliers, core indices)."""
    N = b.x0.size
    idx = np.arange(N) if rel is None else core(b, rel)
    nc = idx.size
    Mh = half_period_map(b, idx, rtol)
    R = np.diag(np.concatenate([np.ones(nc), -np.ones(nc)]))
    M = R @ np.linalg.solve(Mh, R @ Mh)
    mu = np.concatenate([np.linalg.eigvals(M), np.repeat(np.exp([1j * b.T, -1j * b.T]), N - nc)])
    return M, mu, idx


@dataclass
class Floquet:
    mu: np.ndarray          # all 2N multipliers (core block + exp(+-iT) for the harmonic tail)
    mu_even: np.ndarray     # multipliers of the modes of the breather's symmetry class (holds the trivial pair)
    mu_odd: np.ndarray      # multipliers of the symmetry-breaking modes (holds the pinning pair)
    trivial: float          # max |mu - 1| over the trivial pair (the two even multipliers nearest +1)
    rate: float             # max ln|mu| / T over the non-trivial multipliers (growth rate per unit t)
    mode: np.ndarray        # (x, v) on the core of the fastest-growing non-trivial mode (real part)
    core: np.ndarray        # indices of the core beads
    odd_growing: bool       # is the fastest-growing mode symmetry-breaking
    pin: np.ndarray         # (2 n_core, 2): real and imaginary parts of the odd eigenvector nearest +1 (pinning)


def floquet(b: Breather, kind: str, centre: int | None = None, rtol: float = RTOL, rel: float = 1e-9) -> Floquet:
    """Floquet multipliers of a breather of class ``kind`` (site | bond), split by symmetry.

    The variational equations are integrated over T/2 on the core only (beads with |x_n| <= rel max|x0|
    have stiffness K_n <~ rel^(1/2) and are harmonic to that accuracy: multipliers exp(+-iT)).
    With Q = diag(-S, -S) (the symmetry x -> -S x acting on perturbations) and Mh = M(T/2):

    * bond: M = R Mh^{-1} R Mh commutes with Q; its blocks on Fix(Q) and Fix(-Q) are the even and odd
      multipliers;
    * site: A = Q Mh maps perturbations at t = 0 to t = 0 (x(T/2) = -S x(0)) and A^2 = M; eigenvalues
      nu of A with Re nu >= 0 give the even multipliers mu = nu^2, Re nu < 0 the odd ones.

    The trivial pair (phase and frequency of the family) is even; the pinning (translation) pair odd.
    """
    N = b.x0.size
    c = N // 2 if centre is None else centre
    S = reflection(N, c + 0.5 if kind == "bond" else c, b.bc)
    idx = core(b, rel, S)
    nc = idx.size
    Mh = half_period_map(b, idx, rtol)
    Sc = S[np.ix_(idx, idx)]
    Z = np.zeros_like(Sc)
    Q = -np.block([[Sc, Z], [Z, Sc]])
    if kind == "bond":
        R = np.diag(np.concatenate([np.ones(nc), -np.ones(nc)]))
        M = R @ np.linalg.solve(Mh, R @ Mh)
        Bp, Bm = _eigenbasis(Q, 1.0), _eigenbasis(Q, -1.0)
        mu_e, Ve = np.linalg.eig(Bp.T @ M @ Bp)
        mu_o, Vo = np.linalg.eig(Bm.T @ M @ Bm)
        Ve, Vo = Bp @ Ve, Bm @ Vo
    elif kind == "site":
        nu, V = np.linalg.eig(Q @ Mh)
        even = nu.real >= 0
        mu_e, Ve, mu_o, Vo = nu[even] ** 2, V[:, even], nu[~even] ** 2, V[:, ~even]
    else:
        raise ValueError(f"unknown breather kind {kind!r} (site or bond)")
    tail = np.repeat(np.exp([1j * b.T, -1j * b.T]), N - nc)
    mu = np.concatenate([mu_e, mu_o, tail])
    i_triv, _ = split_trivial(mu_e, 2)
    trivial = float(np.max(np.abs(mu_e[i_triv] - 1.0)))
    keep = np.ones(mu_e.size, bool)
    keep[i_triv] = False
    cand = np.concatenate([mu_e[keep], mu_o])
    vecs = np.concatenate([Ve[:, keep], Vo], axis=1)
    j = int(np.argmax(np.abs(cand)))
    rate = float(np.log(np.abs(cand[j])) / b.T)
    vec = vecs[:, j].real if np.linalg.norm(vecs[:, j].real) > 0.3 * np.linalg.norm(vecs[:, j]) else vecs[:, j].imag
    k = int(np.argmin(np.abs(mu_o - 1.0)))
    pin = np.stack([Vo[:, k].real, Vo[:, k].imag], axis=1)
    return Floquet(mu, mu_e, mu_o, trivial, rate, vec / np.linalg.norm(vec), idx, bool(j >= keep.sum()), pin)


def multiplier_checks(mu: ArrayLike) -> dict:
    """Symplectic structure of the multipliers: the trivial pair (the two closest to +1), the pairing
    mu <-> 1/mu and mu <-> conj mu (max distance of each multiplier to its partner in the set), the top
    modulus and the growth exponent ln max|mu| (per period)."""
    mu = np.asarray(mu, complex)
    d1 = np.sort(np.abs(mu - 1.0))
    inv = np.max(np.min(np.abs(mu[:, None] - 1.0 / mu[None, :]), axis=1))
    conj = np.max(np.min(np.abs(mu[:, None] - np.conj(mu)[None, :]), axis=1))
    return {"trivial": float(d1[1]), "reciprocal": float(inv), "conjugate": float(conj),
            "max_modulus": float(np.max(np.abs(mu))), "log_max_modulus": float(np.log(np.max(np.abs(mu))))}


def dps_start(a_n: ArrayLike, omega: float, alpha: float) -> np.ndarray:
    """x_n(0) of the DpS breather (ansatzapproxst2) of frequency omega_b from a mu = 1 profile a_n of (dpsstn)."""
    from cradle.models import dps

    mu = dps.mu_from_omega_sw(omega, alpha)
    return mu ** (1.0 / (alpha - 1.0)) * np.asarray(a_n, float)


def continue_family(a_n: ArrayLike, omegas: Iterable[float], alpha: float, bc: str = "periodic",
                    kind: str | None = None, centre: int | None = None, tol: float = 1e-11,
                    log: Callable[[str], object] | None = None,
                    min_step: float = 1e-4) -> tuple[list[Breather], float | None]:
    """Exact breathers along ``omegas`` (increasing, > 1), the first from the DpS start, each next predicted
    by the DpS scaling of the previous one. A failed Newton solve halves the step (down to ``min_step``);
    the family is reported to end where it still fails. Returns the list of converged Breathers (an
    omega that could not be reached is absent) and the last omega reached."""
    say = log or (lambda *a: None)
    out: list[Breather] = []
    prev = None
    for om in omegas:
        if prev is None:
            b = newton(dps_start(a_n, om, alpha), om, alpha, bc, kind, centre, tol)
            if not b.converged:
                say(f"breathers: no convergence from the DpS start at omega_b = {om}")
                return out, None
            out.append(b)
            prev = b
            continue
        target, cur = om, prev
        while cur.omega < target - 1e-15:
            step = target - cur.omega
            while True:
                o2 = cur.omega + step
                guess = ((o2 - 1.0) / (cur.omega - 1.0)) ** (1.0 / (alpha - 1.0)) * cur.x0
                b = newton(guess, o2, alpha, bc, kind, centre, tol)
                if b.converged and _same_family(b, cur):
                    cur = b
                    break
                step *= 0.5
                if step < min_step:
                    say(f"breathers: family ends or turns near omega_b = {cur.omega:.6g} (no solution at "
                        f"{cur.omega + 2 * step:.6g})")
                    return out, cur.omega
        out.append(cur)
        prev = cur
    return out, prev.omega if prev else None


def _same_family(b: Breather, prev: Breather) -> bool:
    """The new breather keeps the centre and sign pattern of the previous one (no jump to another branch)."""
    s1, s0 = b.x0 / b.amplitude, prev.x0 / prev.amplitude
    return bool(np.max(np.abs(s1 - s0)) < 0.5)
