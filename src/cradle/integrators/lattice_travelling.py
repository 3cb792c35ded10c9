"""Exact travelling breathers of the lattice (nc) on a ring: Newton on the shooting map modulo shift, continuation
in the velocity, Floquet multipliers modulo shift, and the DpS travelling breather they are close to.

A travelling breather (TB) of (nc) on a ring of N beads moves one site per period T:

    x_n(t + T) = x_{n-1}(t),   v_n(t + T) = v_{n-1}(t)                                   (tbnc)

i.e. z = (x(0), v(0)) is a zero of the shooting map modulo shift R(z) = S^{-1} Phi_T(z) - z, with Phi_T the flow
of (nc) and (S z)_n = z_{n-1} acting on x and v alike. The time shift maps a TB to a TB (the neutral direction
dz/dt, removed by the phase condition <f(z_ref), z - z_ref> = 0, f the vector field of (nc)); the energy (ham) is
conserved and shift-invariant, so one of R's 2N equations is dependent at a solution. At fixed T the 2N + 1
equations in 2N unknowns are solved in least squares (Gauss-Newton, as :mod:`cradle.integrators.dps_travelling`
solves (tb)); unlike DpS, (nc) has no scaling and no phase symmetry, so the family left is the one in T (the
velocity c = 1/T), along which the amplitude changes.

The Jacobian S^{-1} DPhi_T(z) - I comes from the variational equations of (nc), integrated with the orbit over one
period by :func:`cradle.integrators.lattice_breathers.flow` (scipy's DOP853 over the project's compiled right-hand
side and Jacobian); the same matrix is the monodromy modulo shift whose eigenvalues are the Floquet multipliers
(Xu, Cuevas-Maraver, Kevrekidis and Vainchtein, arXiv 1701.04882: a travelling wave is a periodic orbit modulo
shift). The time shift gives a multiplier 1 in a Jordan block with the energy: two trivial multipliers at 1.
S is a permutation of the (x_n, v_n) pairs, so the monodromy is symplectic and its multipliers come in pairs
mu, 1/mu (and conj mu).

Start: a DpS TB A_n(tau + T_d) = e^{i theta} A_{n-1}(tau) (:mod:`cradle.models.dps_travelling`) through the ansatz
x_n(t) ~ 2 eps Re(A_n(eps^(alpha-1) t) e^{it}) (:func:`cradle.models.initial.lattice_state`) satisfies (tbnc) when
the lattice period T = T_d eps^(1-alpha) is resonant with the carrier, theta + T = 2 pi m (m an integer, about the
breathing periods per site): given the DpS member and m, T = 2 pi m - theta and eps = (T_d / T)^(1/(alpha-1))
(:func:`resonant_start`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from cradle.integrators import lattice_breathers as LB
from cradle.integrators.dps_travelling import _weighted_lstsq
from cradle.models import lattice

if TYPE_CHECKING:
    from collections.abc import Callable

    from numpy.typing import ArrayLike, NDArray

    from cradle.integrators._types import Floats

RTOL = 1e-13    # DOP853 relative tolerance of the shooting (shift-map residuals ~1e-12)
DAMPED = 1e-3   # residual above which a Newton step is damped until the residual decreases


def unshift(z: ArrayLike) -> Floats:
    """S^{-1} on states z = (x, v) (and on 2N x m matrices of them, along the first axis): (S^{-1} z)_n = z_{n+1}."""
    z = np.asarray(z, float)
    N = z.shape[0] // 2
    return np.concatenate([np.roll(z[:N], -1, axis=0), np.roll(z[N:], -1, axis=0)])


def vector_field(z: ArrayLike, alpha: float) -> Floats:
    """f(z) = (v, -x + f_n - f_{n-1}) of (nc) on the ring."""
    z = np.asarray(z, float)
    N = z.size // 2
    return np.concatenate([z[N:], lattice.acceleration(z[:N], alpha, "periodic")])


def energy(z: ArrayLike, alpha: float) -> float:
    """The energy (ham) of the state z = (x, v) on the ring."""
    z = np.asarray(z, float)
    N = z.size // 2
    return float(lattice.hamiltonian(z[:N], z[N:], alpha, "periodic"))


def flow(z: ArrayLike, T: float, alpha: float, rtol: float = RTOL) -> Floats:
    """Phi_T(z) of (nc) on the ring."""
    z = np.asarray(z, float)
    N = z.size // 2
    x, v, _, _ = LB.flow(z[:N], z[N:], T, alpha, "periodic", None, rtol)
    return np.concatenate([x, v])


def monodromy(z: ArrayLike, T: float, alpha: float, rtol: float = RTOL) -> tuple[Floats, Floats]:
    """(M, Phi_T(z)): the 2N x 2N monodromy modulo shift S^{-1} DPhi_T(z) and the state one period later."""
    z = np.asarray(z, float)
    N = z.size // 2
    x, v, _, Phi = LB.flow(z[:N], z[N:], T, alpha, "periodic", np.eye(2 * N), rtol)
    return unshift(Phi), np.concatenate([x, v])


def relative_residual(z: ArrayLike, zT: ArrayLike) -> float:
    """max |S^{-1} Phi_T(z) - z| / max |z|: the shift-map residual of a TB, zT = Phi_T(z)."""
    z = np.asarray(z, float)
    return float(np.max(np.abs(unshift(zT) - z)) / np.max(np.abs(z)))


@dataclass
class LatticeTB:
    """One TB of (tbnc): the state z = (x(0), v(0)) and period T; how Newton got there, the multipliers modulo shift
    of its last monodromy and the tangent dz/dT of the family."""

    z: Floats
    T: float
    alpha: float
    residual: float             # max |R| / max |z| of the last evaluation
    converged: bool
    iterations: int
    multipliers: NDArray[np.complex128] = field(default_factory=lambda: np.zeros(0, complex))
    dz_dT: Floats | None = None

    @property
    def c(self) -> float:
        return 1.0 / self.T

    @property
    def energy(self) -> float:
        return energy(self.z, self.alpha)

    @property
    def envelope(self) -> NDArray[np.complex128]:
        """xi_n = (x_n - i v_n) / 2, which the ansatz makes eps A_n e^{it} to leading order."""
        N = self.z.size // 2
        return np.asarray(0.5 * (self.z[:N] - 1j * self.z[N:]), dtype=np.complex128)

    @property
    def eps(self) -> float:
        """The eps of the ansatz at unit DpS norm: sqrt(sum |xi_n|^2) (= eps sqrt(sum |A_n|^2) to leading order)."""
        return float(np.sqrt(np.sum(np.abs(self.envelope) ** 2)))

    def predict(self, T: float) -> Floats:
        """z of the member at period T along the tangent (Euler predictor); its own z without one."""
        return self.z if self.dz_dT is None else self.z + (T - self.T) * self.dz_dT


def newton(z_guess: ArrayLike, T: float, alpha: float, reference: ArrayLike | None = None, tol: float = 1e-11,
           max_iter: int = 12, rtol: float = RTOL, log: Callable[[str], object] | None = None,
           save: Callable[[Floats], object] | None = None) -> LatticeTB:
    """Solve (tbnc) at period T for z by Gauss-Newton from ``z_guess``, with the phase condition about
    ``reference`` (default: the guess). Converged when max |R| <= tol max |z|; the multipliers of the last monodromy
    and the family's tangent there come with it. Stops early when the residual grows tenfold."""
    z = np.asarray(z_guess, float).copy()
    n2 = z.size
    ref = z.copy() if reference is None else np.asarray(reference, float)
    d_time = vector_field(ref, alpha)
    res, best, mu = np.inf, np.inf, np.zeros(0, complex)
    for it in range(max_iter + 1):
        Mm, zT = monodromy(z, T, alpha, rtol)
        R = unshift(zT) - z
        res = float(np.max(np.abs(R)) / np.max(np.abs(z)))
        mu = np.linalg.eigvals(Mm).astype(complex)
        if log:
            log(f"lattice travelling breathers: T = {T:.12g}, iteration {it}: residual {res:.3g}")
        J = np.vstack([Mm - np.eye(n2), d_time[None, :]])
        if res <= tol:
            # the tangent: dR/dT = S^{-1} f(Phi_T(z)), the phase condition unchanged
            dF = np.concatenate([unshift(vector_field(zT, alpha)), [0.0]])
            return LatticeTB(z, T, alpha, res, True, it, mu, _weighted_lstsq(J, -dF, n2))
        if it == max_iter or not np.isfinite(res) or res > 10.0 * best:
            break
        best = min(best, res)
        F = np.concatenate([R, [d_time @ (z - ref)]])
        step = _weighted_lstsq(J, -F, n2)
        lam = 1.0
        # damped far from the solution only: near it the tail beads, barely in contact, make the map C^{1,alpha-1}
        # there, and full steps converge where a line search stalls
        while res > DAMPED and lam > 1e-3:
            if relative_residual(z + lam * step, flow(z + lam * step, T, alpha, rtol)) < res:
                break
            lam *= 0.5
        z = z + lam * step
        if save is not None:
            save(z)
    return LatticeTB(z, T, alpha, res, False, it, mu)


def ansatz_start(A: ArrayLike, T_d: float, alpha: float, eps: float) -> tuple[Floats, float]:
    """(z, T_hop): the ansatz (x(0), v(0)) of the DpS TB (A, T_d) at eps (:func:`cradle.models.initial.lattice_state`)
    and its time per site T_d eps^(1-alpha) in t."""
    from cradle.models.initial import lattice_state

    x0, v0 = lattice_state(A, eps, alpha, "periodic")
    return np.concatenate([x0, v0]), T_d * eps ** (1.0 - alpha)


def resonant_start(A: ArrayLike, T_d: float, theta: float, alpha: float, m: int) -> tuple[Floats, float, float]:
    """(z, T, eps): the ansatz of the DpS TB (A, T_d, theta) at the resonance theta + T = 2 pi m (theta taken in
    (-pi, pi]), eps = (T_d / T)^(1/(alpha-1)), z = (x(0), v(0)) of :func:`cradle.models.initial.lattice_state`."""
    from cradle.models.initial import lattice_state

    T = 2.0 * math.pi * m - math.remainder(theta, 2.0 * math.pi)
    if T <= 0:
        raise ValueError(f"resonance m = {m} gives the period T = {T:.4g} <= 0")
    eps = (T_d / T) ** (1.0 / (alpha - 1.0))
    x0, v0 = lattice_state(A, eps, alpha, "periodic")
    return np.concatenate([x0, v0]), T, eps


def launch_period(z: ArrayLike, T_hop: float, alpha: float, window: float = 0.25, samples_per_unit: int = 50,
                  rtol: float = 1e-11) -> tuple[float, float]:
    """(T, residual): the time in [(1 - window) T_hop, (1 + window) T_hop] at which the run of (nc) from z comes
    closest to S z (min over the samples of max |S^{-1} z(t) - z| / max |z|), the period of the first Newton solve:
    the ansatz's carrier is off resonance by the lattice's frequency correction beyond DpS, which this absorbs."""
    from cradle.integrators import integrate_lattice

    z = np.asarray(z, float)
    N = z.size // 2
    t = np.linspace(0.0, (1.0 + window) * T_hop, int(samples_per_unit * (1.0 + window) * T_hop) + 1)
    run = integrate_lattice(z[:N], z[N:], t, alpha=alpha, method="dop853_numba", rtol=rtol)
    Z = np.concatenate([np.roll(np.asarray(run.x), -1, axis=1), np.roll(np.asarray(run.v), -1, axis=1)], axis=1)
    res = np.max(np.abs(Z - z), axis=1) / np.max(np.abs(z))
    res[t < (1.0 - window) * T_hop] = np.inf
    i = int(np.argmin(res))
    return float(t[i]), float(res[i])


def continue_family(first: LatticeTB, cs: ArrayLike, tol: float = 1e-11, rtol: float = RTOL,
                    min_step: float = 0.02, log: Callable[[str], object] | None = None
                    ) -> tuple[list[LatticeTB], float | None]:
    """TBs of (tbnc) at the velocities ``cs`` (in order, from ``first``'s c): each predicted along the family's
    tangent at the previous member and corrected by :func:`newton` with the previous member as the phase reference.
    A failed step is halved down to ``min_step`` (relative to c); returns the members reached at the grid's c and
    the last c reached."""
    from cradle.integrators.continuation import continue_in_c

    def correct(cur: LatticeTB, c2: float) -> LatticeTB:
        T2 = 1.0 / c2
        return newton(cur.predict(T2), T2, first.alpha, cur.z, tol, max_iter=8, rtol=rtol)

    return continue_in_c(first, cs, correct, min_step, log or (lambda *a: None), "lattice travelling breathers",
                         lambda b: f"eps = {b.eps:.4g}, residual {b.residual:.2g}")


def direct_run(b: LatticeTB, periods: int, rtol: float = RTOL) -> dict:
    """The member run by (nc) over ``periods`` periods, one period at a time: the energy drift |H(kT) - H(0)| / |H(0)|
    and the residual of (tbnc) after k periods, max |z(kT) - S^k z(0)| / max |z|."""
    z0 = b.z
    N = z0.size // 2
    H0 = b.energy
    z, res, drift = z0, [0.0], [0.0]
    for k in range(1, periods + 1):
        z = flow(z, b.T, b.alpha, rtol)
        back = np.concatenate([np.roll(z[:N], -k), np.roll(z[N:], -k)])
        res.append(float(np.max(np.abs(back - z0)) / np.max(np.abs(z0))))
        drift.append(abs(energy(z, b.alpha) - H0) / abs(H0))
    return {"k": np.arange(periods + 1), "residual": np.array(res), "energy_drift": np.array(drift)}


def ansatz_distance(b: LatticeTB, A: ArrayLike, T_d: float, samples: int = 64, rtol: float = 1e-12) -> dict:
    """The distance of the lattice TB to the DpS TB (A, T_d) through the ansatz: eps from the TB's own amplitude
    (:attr:`LatticeTB.eps` over sqrt(sum |A_n|^2)), then min over the DpS time s in one period (``samples``), the
    site shifts k and the phase phi (least squares on xi_n = (x_n - i v_n) / 2) of
    max |z - z_ansatz(e^{i phi} A_{n-k}(s), eps)| / max |z|. Returns the distance, eps and the T_d eps^(1-alpha)
    that the ansatz gives as the time per site (to set against the TB's T)."""
    from cradle.integrators import integrate_dps
    from cradle.models.initial import lattice_state

    A = np.asarray(A, complex)
    N = A.size
    eps = b.eps / float(np.sqrt(np.sum(np.abs(A) ** 2)))
    run = integrate_dps(A, np.linspace(0.0, T_d, samples, endpoint=False), alpha=b.alpha, rtol=rtol)
    xi = b.envelope
    best = np.inf
    for As in run.A:
        for k in range(N):
            Ak = np.roll(As, k)
            phi = float(np.angle(np.sum(np.conj(Ak) * xi)))
            x0, v0 = lattice_state(np.exp(1j * phi) * Ak, eps, b.alpha, "periodic")
            best = min(best, float(np.max(np.abs(np.concatenate([x0, v0]) - b.z))))
    return {"distance": best / float(np.max(np.abs(b.z))), "eps": eps, "T_ansatz": T_d * eps ** (1.0 - b.alpha)}
