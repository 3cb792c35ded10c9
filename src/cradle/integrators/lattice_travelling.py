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

Larger rings and amplitudes. Far from the core a TB's sites are nearly free oscillators of frequency 1 (the Hertz
coupling of amplitude a is of order a^(alpha-1)), so a ring with room for a far field has directions the equations
barely fix there. From the ansatz (residual ~1e-2) a step of all unknowns puts ~1e-3 of the amplitude on the far
sites, and Newton then heads for a TB carrying a plane-wave tail of that size, whose phase is a second near-neutral
direction, and stalls. Two remedies, both converging: :func:`newton_core_first` (the core's unknowns first, the far
sites at the ansatz's values) and :func:`embed` (a TB of a smaller ring carried to a larger one, sites at rest added
on the far side, where its field is already below the residual).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from cradle.integrators.continuation import continue_in_c
from cradle.models import lattice

if TYPE_CHECKING:
    from collections.abc import Callable

    from numpy.typing import ArrayLike, NDArray

    from cradle.integrators._types import Floats

RTOL = 1e-14       # DOP853 (contact events) relative tolerance of the residual's flow (residuals ~1e-12)
JAC_RTOL = 1e-12   # DOP853 relative tolerance of the variational equations (Newton's Jacobian)
RCOND = 1e-9       # singular values of the bordered Jacobian below RCOND times the largest are left out of a step,
GAP = 1e-2         # and the smallest when it is below GAP times the next (the near-symmetry's; module docstring)
DAMPED = 1e-3      # residual above which a Newton step is damped until the residual decreases
CORE = 1e-6        # sites whose |xi_n| is below CORE times the largest are held fixed in newton_core_first's first
CORE_TOL = 1e-5    # stage, which hands over to all unknowns below this residual (above what the far sites hold)


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


def shoot(z: ArrayLike, T: float, alpha: float, columns: Floats | None = None,
          rtol: float = RTOL) -> tuple[Floats, Floats | None]:
    """(Phi_T(z), DPhi_T(z) columns or None): (nc) on the ring from z = (x, v) over T and, if ``columns``
    (2N x m) is given, the variational equations along them.

    The project's DOP853 loop (:func:`cradle.integrators._dop853.run_dop853`) on the compiled system
    :class:`cradle.integrators.systems.lattice_variational.LatticeVariational`, with the tolerances rtol and
    atol = rtol max|z|; the columns are integrated multiplied by max|z| (they are linear), so that this one atol is
    rtol on the columns themselves (as :func:`cradle.integrators.lattice_breathers.flow` weighs them)."""
    from cradle.integrators import _dop853
    from cradle.integrators.systems import lattice_variational as LV

    z = np.ascontiguousarray(z, dtype=float)
    N = z.size // 2
    C = np.zeros((2 * N, 0)) if columns is None else np.asarray(columns, float)
    m = C.shape[1]
    amp = float(np.max(np.abs(z)))
    system = LV.lattice_variational(N, alpha, m)
    y0 = np.concatenate([z, (amp * C[:N]).ravel(), (amp * C[N:]).ravel()])
    stats = np.array([energy(z, alpha), 0.0, 0.0, 0.0])
    try:
        Y, _, _ = _dop853.run_dop853(system, y0, np.array([0.0, float(T)]), rtol, rtol * amp, stats, None)
    except RuntimeError as e:
        raise RuntimeError(f"lattice travelling breather shooting: integration failed ({e})") from None
    yT = Y[-1]
    if columns is None:
        return yT[:2 * N].copy(), None
    Phi = np.concatenate([yT[2 * N:2 * N + N * m].reshape(N, m), yT[2 * N + N * m:].reshape(N, m)]) / amp
    return yT[:2 * N].copy(), Phi


def orbit(z: ArrayLike, ts: ArrayLike, alpha: float, rtol: float = RTOL) -> tuple[Floats, Floats]:
    """(X, V): the states of (nc) on the ring from z = (x, v) at the times ``ts`` (from 0), accurate enough for the
    residual of (tbnc): the project's DOP853 with the steps ending at the contact onsets and releases
    (:mod:`cradle.integrators._dop853_events`, through :func:`cradle.integrators.lattice_adaptive.run_dop853_damped`
    without damping), atol = rtol max|z|. Across the onsets plain DOP853 loses its order (the Hertz force is
    C^{1,alpha-1} there): its Phi_T is too coarse for a residual below 1e-8 (docs/analyses/travelling-breathers.md,
    the lattice section)."""
    from cradle.integrators import _kernels as K
    from cradle.integrators.lattice_adaptive import run_dop853_damped
    from cradle.models.damping import NONE

    z = np.asarray(z, float)
    N = z.size // 2
    amp = float(np.max(np.abs(z)))
    X, V, *_ = run_dop853_damped(z[:N], z[N:], np.asarray(ts, float), rtol, rtol * amp, alpha,
                                 K.mode_flag("hertz", alpha), True, NONE, None)
    return X, V


def flow(z: ArrayLike, T: float, alpha: float, rtol: float = RTOL) -> Floats:
    """Phi_T(z) of (nc) on the ring (:func:`orbit` at T)."""
    X, V = orbit(z, np.array([0.0, float(T)]), alpha, rtol)
    return np.concatenate([X[-1], V[-1]])


def monodromy(z: ArrayLike, T: float, alpha: float, rtol: float = RTOL,
              seed: Floats | None = None) -> tuple[Floats, Floats]:
    """(M, Phi_T(z)): the 2N x 2N monodromy modulo shift S^{-1} DPhi_T(z) and the state one period later;
    ``seed``: the variations carried instead of the identity's columns (M is then S^{-1} DPhi_T(z) seed)."""
    z = np.asarray(z, float)
    zT, Phi = shoot(z, T, alpha, np.eye(z.size) if seed is None else seed, rtol)
    assert Phi is not None
    return unshift(Phi), zT


def relative_residual(z: ArrayLike, zT: ArrayLike) -> float:
    """max |S^{-1} Phi_T(z) - z| / max |z|: the shift-map residual of a TB, zT = Phi_T(z)."""
    z = np.asarray(z, float)
    return float(np.max(np.abs(unshift(zT) - z)) / np.max(np.abs(z)))


@dataclass
class LatticeTB:
    """One TB of (tbnc): the state z = (x(0), v(0)) and period T; how Newton got there, the multipliers modulo shift
    of its last monodromy, the family's tangent dz/dT and the bordered Jacobian's conditioning at the end (its
    smallest singular value over its largest, and how many directions the truncated steps left out)."""

    z: Floats
    T: float
    alpha: float
    residual: float             # max |R| / max |z| of the last evaluation
    converged: bool
    iterations: int
    multipliers: NDArray[np.complex128] = field(default_factory=lambda: np.zeros(0, complex))
    dz_dT: Floats | None = None
    smallest_singular: float = math.nan
    dropped: int = 0

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


def truncated_lstsq(J: Floats, F: Floats, rows: int, rcond: float = RCOND,
                    gap: float = GAP) -> tuple[Floats, float, int]:
    """(x, s_min / s_max, dropped): the least-squares solution of J x = F from the singular values of J above
    ``rcond`` times the largest, the smallest also left out when it is below ``gap`` times the next (the rows from
    ``rows`` on, the conditions, scaled to unit norm as in :func:`cradle.integrators.dps_travelling._weighted_lstsq`).

    Why truncated: (nc) keeps DpS's phase symmetry A -> e^{i phi} A almost exactly (the carrier's phase), so that the
    bordered Jacobian of (tbnc) has a direction besides the time shift whose singular value, set by how weakly the
    symmetry is broken, lies far below the others; a full step along it is the residual over that singular value,
    and the curvature of the shooting map along it turns the move into a residual larger than the one removed."""
    w = np.ones(J.shape[0])
    for k in range(rows, J.shape[0]):
        w[k] = 1.0 / max(float(np.linalg.norm(J[k])), 1e-300)
    U, sv, Vt = np.linalg.svd(w[:, None] * J, full_matrices=False)
    keep = sv > rcond * sv[0]
    if sv.size > 1 and keep[-1] and sv[-1] < gap * sv[-2]:
        keep[-1] = False
    x = Vt[keep].T @ ((U[:, keep].T @ (w * F)) / sv[keep])
    return np.asarray(x, dtype=np.float64), float(sv[-1] / sv[0]), int(np.sum(~keep))


def newton(z_guess: ArrayLike, T: float, alpha: float, reference: ArrayLike | None = None, tol: float = 1e-11,
           max_iter: int = 12, rtol: float = RTOL, log: Callable[[str], object] | None = None,
           save: Callable[[Floats], object] | None = None, jac_rtol: float = JAC_RTOL,
           rcond: float = RCOND, free: NDArray[np.bool_] | None = None) -> LatticeTB:
    """Solve (tbnc) at period T for z by Gauss-Newton from ``z_guess``, with the phase condition about
    ``reference`` (default: the guess). The residual R = S^{-1} Phi_T(z) - z from :func:`flow` at ``rtol`` (contact
    events), the Jacobian S^{-1} DPhi_T - I from the variational equations at ``jac_rtol`` (:func:`monodromy`).

    The step: far from a solution (residual above DAMPED) the truncated step of :func:`truncated_lstsq`, halved until
    the residual decreases; near it the better of the truncated step (on the slice transverse to the near-symmetry)
    and the full least-squares step (along it too: what the slice cannot remove, the near-symmetry's share of R),
    halved until one of them decreases the residual. Converged when max |R| <= tol max |z|; the multipliers of a
    last monodromy at max(rtol, 1e-13) and the family's tangent there come with it. Stops when no step decreases
    the residual near a solution, or when it grows tenfold far from one. ``free`` (a mask of the 2N unknowns): the
    steps move only those, the others stay at the guess's values (:func:`newton_core_first`)."""
    z = np.asarray(z_guess, float).copy()
    n2 = z.size
    ref = z.copy() if reference is None else np.asarray(reference, float)
    d_time = vector_field(ref, alpha)
    res, best, mu, smin, dropped = np.inf, np.inf, np.zeros(0, complex), math.nan, 0

    def residual(y: Floats) -> float:
        return relative_residual(y, flow(y, T, alpha, rtol))

    for it in range(max_iter + 1):
        zT = flow(z, T, alpha, rtol)
        R = unshift(zT) - z
        res = float(np.max(np.abs(R)) / np.max(np.abs(z)))
        if log:
            log(f"lattice travelling breathers: T = {T:.12g}, iteration {it}: residual {res:.3g}")
        if res <= tol:
            Mm, _ = monodromy(z, T, alpha, max(rtol, 1e-13))
            mu = np.linalg.eigvals(Mm).astype(complex)
            J = np.vstack([Mm - np.eye(n2), d_time[None, :]])
            # the tangent: dR/dT = S^{-1} f(Phi_T(z)), the phase condition unchanged
            dF = np.concatenate([unshift(vector_field(zT, alpha)), [0.0]])
            tangent, smin, dropped = truncated_lstsq(J, -dF, n2, rcond)
            return LatticeTB(z, T, alpha, res, True, it, mu, tangent, smin, dropped)
        if it == max_iter or not np.isfinite(res) or res > 10.0 * best:
            break
        best = min(best, res)
        cols = slice(None) if free is None else free   # only the free unknowns' columns of the Jacobian
        eye = np.eye(n2)[:, cols]
        Mm, _ = monodromy(z, T, alpha, jac_rtol, eye)
        J = np.vstack([Mm - eye, d_time[None, cols]])
        F = np.concatenate([R, [d_time @ (z - ref)]])
        step, smin, dropped = truncated_lstsq(J, -F, n2, rcond)
        steps = [step]
        if res <= DAMPED and dropped:
            steps.append(truncated_lstsq(J, -F, n2, 0.0, 0.0)[0])
        if free is not None:
            steps = [_on(free, d) for d in steps]
        lam, k = 1.0, 0
        # far from a solution the truncated step, damped until the residual decreases (or to the last halving)
        while lam > 1e-3:
            r_new, k = min((residual(z + lam * d), j) for j, d in enumerate(steps))
            if r_new < res:
                break
            lam *= 0.5
        else:
            if res <= DAMPED:
                break
        z = z + lam * steps[k]
        if save is not None:
            save(z)
    return LatticeTB(z, T, alpha, res, False, it, mu, None, smin, dropped)


def _on(free: NDArray[np.bool_], d: Floats) -> Floats:
    """The step d of the free unknowns as a step of all 2N (zero on the others)."""
    out = np.zeros(free.size)
    out[free] = d
    return out


def core_unknowns(z: ArrayLike, threshold: float = CORE) -> NDArray[np.bool_]:
    """The mask of the unknowns (x_n, v_n) of the core: the sites where |xi_n| = |x_n - i v_n| / 2 exceeds
    ``threshold`` times its largest value."""
    z = np.asarray(z, float)
    N = z.size // 2
    xi = np.hypot(z[:N], z[N:])
    core = xi > threshold * float(np.max(xi))
    return np.concatenate([core, core])


def newton_core_first(z_guess: ArrayLike, T: float, alpha: float, tol: float = 1e-11, max_iter: int = 12,
                      log: Callable[[str], object] | None = None,
                      reference: ArrayLike | None = None) -> tuple[LatticeTB, float]:
    """(TB, the first stage's residual): :func:`newton` in two stages from ``z_guess`` (the phase condition about
    ``reference``, default the guess, in both): the core's unknowns (:func:`core_unknowns`) alone until the
    residual is below CORE_TOL (the far sites kept at the guess's, the ansatz's doubly exponentially small values),
    then all of them to ``tol``.

    Why: from an ansatz whose residual is the DpS approximation's (some 1e-2), a step of all unknowns puts some 1e-3
    of the amplitude on the far sites (the Jacobian's smallest directions after the carrier phase live there); on a
    ring with room for a tail (24 sites at eps = 0.005, 16 at eps = 0.01) Newton then heads for a TB carrying a
    plane-wave tail of that size, whose tail phase is a second near-neutral direction, and stalls near 2e-7
    (docs/analyses/travelling-breathers.md, the lattice section). With the core solved first the residual left on
    the far sites is the core's own decay, and the full Newton finds the TB without such a tail."""
    z0 = np.asarray(z_guess, float)
    ref = z0 if reference is None else np.asarray(reference, float)
    core = newton(z0, T, alpha, reference=ref, tol=CORE_TOL, max_iter=max_iter, log=log, free=core_unknowns(z0))
    return newton(core.z, T, alpha, reference=ref, tol=tol, max_iter=max_iter, log=log), core.residual


def embed(z: ArrayLike, N: int) -> Floats:
    """The state z = (x, v) of a ring of N0 <= N sites on the ring of N: the breather's centre (the largest |xi_n|)
    moved to site N0 // 2, then (N - N0) // 2 sites at rest added before it and the rest after (the new sites at
    the far side, where a TB's far field is already below rounding of its core)."""
    z = np.asarray(z, float)
    given = z.size // 2   # N0, the state's ring: a relation between the arguments, not a bound of N
    if N < given:
        raise ValueError(f"embed: the ring of N = {N} is smaller than the state's {given}")
    r = given // 2 - int(np.argmax(np.hypot(z[:given], z[given:])))
    before, after = np.zeros((N - given) // 2), np.zeros(N - given - (N - given) // 2)
    return np.concatenate([before, np.roll(z[:given], r), after, before, np.roll(z[given:], r), after])


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
                    min_step: float = 0.02, log: Callable[[str], object] | None = None, core_first: bool = False
                    ) -> tuple[list[LatticeTB], float | None]:
    """TBs of (tbnc) at the velocities ``cs`` (in order, from ``first``'s c): each predicted along the family's
    tangent at the previous member and corrected by :func:`newton` (by :func:`newton_core_first` with
    ``core_first``: on a ring with room for a far field, where the predictor's error would put a tail there) with the
    previous member as the phase reference. A failed step is halved down to ``min_step`` (relative to c); returns the
    members reached at the grid's c and the last c reached."""
    def correct(cur: LatticeTB, c2: float) -> LatticeTB:
        T2 = 1.0 / c2
        if core_first:
            return newton_core_first(cur.predict(T2), T2, first.alpha, tol, reference=cur.z)[0]
        return newton(cur.predict(T2), T2, first.alpha, cur.z, tol, max_iter=12, rtol=rtol)

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
