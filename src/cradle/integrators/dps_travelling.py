"""Travelling breathers of (dfnls) on a ring by Newton's method on the shooting map modulo shift, their
continuation in the velocity at fixed norm, and their Floquet multipliers modulo shift.

The equations are those of :mod:`cradle.models.dps_travelling`: R(A, theta) = e^{-i theta} S^{-1} Phi_T(A) - A = 0
at fixed T = 1/c, with the unknowns A (2N reals) and theta, and the conditions

* P(A) = sum |A_n|^2 = P0 (the scaling fixed: the family is the one in c at fixed norm);
* <i A_ref, A - A_ref> = 0 and <dA_ref/dtau, A - A_ref> = 0 (real inner product Re sum conj(u) v), which remove
  the phase rotation and the time shift (A_ref the previous member or the start).

The Jacobian dR/dA = e^{-i theta} S^{-1} DPhi_T(A) - I comes from the variational equations of (dfnls)
(:func:`cradle.models.dps_travelling.linearised_rhs`), compiled with the orbit's right-hand side
(:mod:`cradle.integrators.systems.dps_variational`) and integrated over one period by the project's DOP853
loop; the 2N + 3 equations in 2N + 1 unknowns are consistent at a solution (two of the 2N equations of R are
dependent there, through the conserved norm and H), and are solved in least squares (Gauss-Newton: quadratic
convergence on a consistent system). The same monodromy, composed with the shift, gives the Floquet multipliers
modulo shift.

Starts: the static DpS breather (ansatzapproxst2) of either parity pushed by a phase gradient
(:func:`cradle.models.dps_travelling.kicked`) and integrated until it has moved a few sites: T is the time
per site of the last ones, theta the best-fitting phase, the state the one at the start of that site.

Large rings (128 sites and more): the far sites are nearly still (DpS's coupling vanishes with the amplitude) and
barely held by the equations; a first step of all unknowns puts some 1e-3 of the peak there and Newton stalls near a
TB on a plane-wave tail of that size. :func:`newton_core_first` (the core's sites first) converges there, as does
Newton from a smaller ring's TB set on the larger one (:func:`cradle.models.tb_launch.embedded`). The family in c
folds (it turns back in c); :func:`continue_arclength` follows it through a fold by pseudo-arclength.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from cradle.integrators.continuation import continue_in_c
from cradle.integrators.systems import dps as SD
from cradle.models import dps, dps_travelling as M

if TYPE_CHECKING:
    from collections.abc import Callable

    from numpy.typing import ArrayLike, NDArray

    from cradle.integrators._types import Floats

RTOL = 1e-13    # DOP853 relative tolerance of the shooting (shift-map residuals ~1e-12)
CORE = 1e-6     # sites whose |A_n| is below CORE times the largest are held fixed in newton_core_first's first
CORE_TOL = 1e-5  # stage, which hands over to all unknowns below this residual


def flow(A0: ArrayLike, T: float, alpha: float, columns: ArrayLike | None = None,
         rtol: float = RTOL) -> tuple[NDArray[np.complex128], NDArray[np.complex128] | None]:
    """Phi_T(A0) of (dfnls) on the ring and, if ``columns`` (N x m complex) is given, the perturbations DPhi_T
    applied to them (the variational equations integrated with the orbit). Returns (A(T), V(T) or None).

    The project's DOP853 loop (:func:`cradle.integrators._dop853.run_dop853`) on the compiled system
    :class:`cradle.integrators.systems.dps_variational.DpsVariational`, with the tolerances rtol and
    atol = rtol max|A0|; the columns are integrated multiplied by max|A0| (they are linear), so that this one atol
    is rtol on the columns themselves."""
    from cradle.integrators import _dop853
    from cradle.integrators.systems import dps_variational as DV

    A0 = np.ascontiguousarray(A0, dtype=np.complex128)
    N = A0.size
    V0 = np.zeros((N, 0), complex) if columns is None else np.asarray(columns, complex).reshape(N, -1)
    m = V0.shape[1]
    amp = float(np.max(np.abs(A0)))
    system = DV.dfnls_variational(alpha, 1.0 / (2.0 * dps.tau0(alpha)), m)
    y0 = np.concatenate([A0.view(np.float64), np.ascontiguousarray(amp * V0).view(np.float64).ravel()])
    l2, S, _, _ = SD.dps_invariants(y0[:2 * N], alpha, True)
    stats = np.array([l2, S, 0.0, 0.0])
    try:
        Y, _, _ = _dop853.run_dop853(system, y0, np.array([0.0, float(T)]), rtol, rtol * amp, stats, None)
    except RuntimeError as e:
        raise RuntimeError(f"travelling breather shooting: integration failed ({e})") from None
    yT = Y[-1]
    AT = yT[:2 * N].copy().view(np.complex128)
    VT = None if columns is None else yT[2 * N:].copy().view(np.complex128).reshape(N, m) / amp
    return AT, VT


def _basis(N: int) -> NDArray[np.complex128]:
    """The 2N real directions of C^N as complex columns: e_k, then i e_k (the order of :func:`M.real`)."""
    E = np.eye(N, dtype=complex)
    return np.concatenate([E, 1j * E], axis=1)


def monodromy(A: ArrayLike, T: float, theta: float, alpha: float,
              rtol: float = RTOL) -> tuple[Floats, NDArray[np.complex128]]:
    """(M, Phi_T(A)): the 2N x 2N real matrix of e^{-i theta} S^{-1} DPhi_T(A) (the monodromy modulo shift) and the
    state one period later."""
    A = np.asarray(A, complex)
    B, V = flow(A, T, alpha, _basis(A.size), rtol)
    assert V is not None
    return M.real(np.exp(-1j * theta) * M.shift(V, -1)), B


@dataclass
class TravellingBreather:
    """One TB of (tb): the state A = A(0), its period T = 1/c and phase theta; how Newton got there, the
    multipliers modulo shift of its last monodromy and the tangent (dA/dT, dtheta/dT) of the fixed-norm family."""

    A: NDArray[np.complex128]
    T: float
    theta: float
    alpha: float
    residual: float               # max |R| / max |A| of the last evaluation (shift-map residual)
    converged: bool
    iterations: int
    multipliers: NDArray[np.complex128] = field(default_factory=lambda: np.zeros(0, complex))
    dA_dT: NDArray[np.complex128] | None = None
    dtheta_dT: float = 0.0
    monodromy: Floats | None = None   # the 2N x 2N real monodromy modulo shift of the last evaluation

    @property
    def c(self) -> float:
        return 1.0 / self.T

    @property
    def norm(self) -> float:
        return float(np.sum(np.abs(self.A) ** 2))

    @property
    def energy(self) -> float:
        return float(dps.hamiltonian(self.A, self.alpha))

    def predict(self, T: float) -> tuple[NDArray[np.complex128], float]:
        """(A, theta) of the member at period T along the tangent (Euler predictor); itself without one."""
        if self.dA_dT is None:
            return self.A, self.theta
        return self.A + (T - self.T) * self.dA_dT, self.theta + (T - self.T) * self.dtheta_dT


def _weighted_lstsq(J: Floats, F: Floats, rows: int) -> Floats:
    """The least-squares solution of J x = F with the rows from ``rows`` on (the conditions) scaled to unit
    norm, so that they weigh as the rows of R."""
    w = np.ones(J.shape[0])
    for k in range(rows, J.shape[0]):
        w[k] = 1.0 / max(float(np.linalg.norm(J[k])), 1e-300)
    return np.asarray(np.linalg.lstsq(w[:, None] * J, w * F, rcond=None)[0], dtype=np.float64)


def _bordered(A: NDArray[np.complex128], B: NDArray[np.complex128], R: NDArray[np.complex128], Mm: Floats,
              theta: float, norm: float, ref: NDArray[np.complex128], d_phase: Floats, d_time: Floats,
              cols: slice | NDArray[np.bool_] = slice(None)) -> tuple[Floats, Floats]:
    """(J, F): the 2N + 3 equations of (tb) at (A, theta) with B = Phi_T(A) (its residual R, the norm, the two phase
    conditions about ``ref``) and their Jacobian in the unknowns ``cols`` of (Re A, Im A) and theta, from ``Mm`` (the
    monodromy modulo shift, those columns)."""
    N, m = A.size, Mm.shape[1]
    J = np.zeros((2 * N + 3, m + 1))
    J[:2 * N, :m] = Mm - np.eye(2 * N)[:, cols]
    SB = np.exp(-1j * theta) * M.shift(B, -1)
    J[:2 * N, m] = M.real(-1j * SB)
    J[2 * N, :m] = 2.0 * M.real(A)[cols]
    J[2 * N + 1, :m] = d_phase[cols]
    J[2 * N + 2, :m] = d_time[cols]
    F = np.concatenate([M.real(R), [np.sum(np.abs(A) ** 2) - norm, d_phase @ M.real(A - ref),
                                    d_time @ M.real(A - ref)]])
    return J, F


def _dR_dT(B: NDArray[np.complex128], theta: float, alpha: float) -> Floats:
    """dR/dT of (tb) at fixed (A, theta): e^{-i theta} S^{-1} dA/dtau at B = Phi_T(A)."""
    return M.real(np.exp(-1j * theta) * M.shift(M.rhs(B, alpha, dps.tau0(alpha)), -1))


def newton(A_guess: ArrayLike, T: float, theta_guess: float, alpha: float, norm: float,
           reference: ArrayLike | None = None, tol: float = 1e-11, max_iter: int = 12,
           rtol: float = RTOL, log: Callable[[str], object] | None = None,
           max_amplitude: float | None = None, free: NDArray[np.bool_] | None = None) -> TravellingBreather:
    """Solve (tb) at period T for (A, theta) with sum |A|^2 = ``norm`` and the two phase conditions about
    ``reference`` (default: the guess), by Gauss-Newton from (A_guess, theta_guess) (module docstring).
    Converged when max |R| <= tol max |A|; the multipliers of the last monodromy and the family's tangent
    there are returned with it. Stops early when the residual grows tenfold (a guess outside the basin) and, if
    ``max_amplitude`` is given, when an iterate's max |A| exceeds it (the relative residual does not see an
    iterate running off to large amplitude, whose integration grows ever stiffer). ``free`` (a mask of the N sites):
    the steps move only those sites' A_n (and theta), the others stay at the guess's values, and only their columns
    of the Jacobian are integrated; converged then returns no multipliers and no tangent (:func:`newton_core_first`'s
    first stage)."""
    A = np.asarray(A_guess, complex).copy()
    N = A.size
    ref = A.copy() if reference is None else np.asarray(reference, complex)
    t0 = dps.tau0(alpha)
    d_phase, d_time = M.real(1j * ref), M.real(M.rhs(ref, alpha, t0))
    theta = float(theta_guess)
    res, best, mu = np.inf, np.inf, np.zeros(0, complex)
    cols = slice(None) if free is None else np.concatenate([free, free])   # the moving unknowns' columns
    for it in range(max_iter + 1):
        if free is None:
            Mm, B = monodromy(A, T, theta, alpha, rtol)
            mu = np.linalg.eigvals(Mm).astype(complex)
        else:
            B, V = flow(A, T, alpha, _basis(N)[:, cols], rtol)
            assert V is not None
            Mm = M.real(np.exp(-1j * theta) * M.shift(V, -1))
        R = M.residual(A, B, theta)
        res = float(np.max(np.abs(R)) / np.max(np.abs(A)))
        if log:
            log(f"travelling breathers: T = {T:.12g}, iteration {it}: theta = {theta:.12g}, residual {res:.3g}")
        if free is not None and res <= tol:
            return TravellingBreather(A, T, theta, alpha, res, True, it)
        J, F = _bordered(A, B, R, Mm, theta, norm, ref, d_phase, d_time, cols)
        m = Mm.shape[1]
        if res <= tol:
            # the tangent: dR/dT, the conditions unchanged
            dF = np.concatenate([_dR_dT(B, theta, alpha), np.zeros(3)])
            tan = _weighted_lstsq(J, -dF, 2 * N)
            return TravellingBreather(A, T, theta, alpha, res, True, it, mu, M.complex_(tan[:2 * N]),
                                      float(tan[2 * N]), Mm)
        if it == max_iter or not np.isfinite(res) or res > 10.0 * best:
            break
        if max_amplitude is not None and float(np.max(np.abs(A))) > max_amplitude:
            break
        best = min(best, res)
        step = _weighted_lstsq(J, -F, 2 * N)
        if free is None:
            A = A + M.complex_(step[:2 * N])
        else:
            dA = np.zeros(2 * N)
            dA[cols] = step[:m]
            A = A + M.complex_(dA)
        theta = theta + float(step[m])
    return TravellingBreather(A, T, theta, alpha, res, False, it, mu)


def core_sites(A: ArrayLike, threshold: float = CORE) -> NDArray[np.bool_]:
    """The mask of the core's sites: |A_n| above ``threshold`` times max |A_n|."""
    a = np.abs(np.asarray(A))
    return np.asarray(a > threshold * float(np.max(a)), dtype=np.bool_)


def newton_core_first(A_guess: ArrayLike, T: float, theta_guess: float, alpha: float, norm: float,
                      tol: float = 1e-11, max_iter: int = 12, rtol: float = RTOL,
                      log: Callable[[str], object] | None = None) -> tuple[TravellingBreather, float]:
    """(TB, the first stage's residual): :func:`newton` in two stages from (A_guess, theta_guess), the phase
    conditions about the guess in both: the core's sites (:func:`core_sites`) alone until the residual is below
    CORE_TOL (the far sites kept at the guess's values), then all of them to ``tol``.

    Why (the lattice's remedy, :func:`cradle.integrators.lattice_travelling.newton_core_first`, carried over): on a
    large ring the bordered Jacobian's smallest singular directions live on the far, nearly still sites (the
    coupling of DpS vanishes with the amplitude), and a first step of all unknowns from the pushed breather puts
    some 1e-3 of the peak there; Newton then heads for a TB on a plane-wave tail of that size whose phase is a
    near-neutral direction, and stalls (docs/analyses/travelling-breathers.md, "DpS Newton on large rings")."""
    A0 = np.asarray(A_guess, complex)
    core = newton(A0, T, theta_guess, alpha, norm, A0, CORE_TOL, max_iter, rtol, log, free=core_sites(A0))
    full = newton(core.A, T, core.theta, alpha, norm, A0, tol, max_iter, rtol, log)
    return full, core.residual


def start(profile: ArrayLike, kappa: float, alpha: float, sites: int = 3, rtol: float = 1e-12,
          samples_per_unit: int = 40) -> tuple[NDArray[np.complex128], float, float]:
    """A first guess (A, T, theta) of a TB: the static profile pushed by ``kappa`` (:func:`M.kicked`) and run
    until its centre has moved ``sites + 1`` sites; T is the time of the last site, A the state at its start."""
    from cradle.integrators import integrate_dps

    phi = np.asarray(profile, complex)
    N = phi.size
    c0 = M.centre(phi)
    A0 = M.kicked(phi, kappa, c0)
    # a rough speed from a short run, then a run long enough for sites + 1 sites
    span = 20.0 / max(abs(float(dps.tau0(alpha))) ** -1 * abs(kappa), 1e-6)
    tau = np.linspace(0.0, span, int(samples_per_unit * span) + 1)
    sol = integrate_dps(A0, tau, alpha=alpha, rtol=rtol)
    x = np.unwrap(np.array([M.centre(a) for a in sol.A]) * 2 * np.pi / N) * N / (2 * np.pi) - c0
    x = x * np.sign(kappa)
    if x[-1] < sites + 1:
        raise RuntimeError(f"travelling breather start: kick {kappa} moved the breather {x[-1]:.3g} sites only")
    t_a = float(np.interp(sites, x, tau))
    t_b = float(np.interp(sites + 1, x, tau))
    A = integrate_dps(A0, np.array([0.0, t_a]), alpha=alpha, rtol=rtol).A[-1]
    B = integrate_dps(A, np.array([0.0, t_b - t_a]), alpha=alpha, rtol=rtol).A[-1]
    return A, t_b - t_a, M.phase_of(A, B)


def continue_family(first: TravellingBreather, cs: ArrayLike, tol: float = 1e-11, rtol: float = RTOL,
                    min_step: float = 0.02, log: Callable[[str], object] | None = None
                    ) -> tuple[list[TravellingBreather], float | None]:
    """TBs at the velocities ``cs`` (in order, from ``first``'s c) at ``first``'s norm: each predicted along the
    family's tangent at the previous member (:meth:`TravellingBreather.predict`) and corrected by :func:`newton`
    with the previous member as the phase reference. A failed step is halved down to ``min_step`` (relative to
    c); returns the members reached at the grid's c and the last c reached."""
    P0 = first.norm

    def correct(cur: TravellingBreather, c2: float) -> TravellingBreather:
        A_g, th_g = cur.predict(1.0 / c2)
        return newton(A_g, 1.0 / c2, th_g, first.alpha, P0, cur.A, tol, max_iter=8, rtol=rtol)

    return continue_in_c(first, cs, correct, min_step, log or (lambda *a: None), "travelling breathers",
                         lambda b: f"theta = {b.theta:.12g}, residual {b.residual:.2g}, "
                                   f"tail {M.tail_amplitude(b.A):.3g}")


# ----------------------------------------------------------------- pseudo-arclength: the family through its folds
# Natural continuation in c (continue_family) stops where the family turns back in c (a fold: dA/dT grows without
# bound there, a pair of multipliers meets +1). On a ring the fixed-norm family folds near the instability windows
# along c (docs/analyses/travelling-breathers.md, "the windows are folds"); the branch beyond a fold is followed with
# T as an unknown and the arclength condition <t, x - x_pred> = 0, x = (Re A, Im A, theta, T), t the unit tangent.


def _arc_system(A: NDArray[np.complex128], T: float, theta: float, alpha: float, norm: float,
                ref: NDArray[np.complex128], rtol: float) -> tuple[Floats, Floats, Floats, float]:
    """(J, F, M, residual): the 2N + 3 equations of (tb) with the norm and the two phase conditions about ``ref`` at
    x = (A, theta, T), their Jacobian in (Re A, Im A, theta, T), the monodromy modulo shift and the relative
    residual."""
    Mm, B = monodromy(A, T, theta, alpha, rtol)
    d_phase, d_time = M.real(1j * ref), M.real(M.rhs(ref, alpha, dps.tau0(alpha)))
    R = M.residual(A, B, theta)
    J, F = _bordered(A, B, R, Mm, theta, norm, ref, d_phase, d_time)
    J = np.column_stack([J, np.concatenate([_dR_dT(B, theta, alpha), np.zeros(3)])])
    return J, F, Mm, float(np.max(np.abs(R)) / np.max(np.abs(A)))


def _arc_tangent(J: Floats, rows: int, previous: Floats) -> Floats:
    """The unit null vector of J (its rows from ``rows`` on scaled to unit norm), oriented along ``previous``."""
    w = np.ones(J.shape[0])
    for k in range(rows, J.shape[0]):
        w[k] = 1.0 / max(float(np.linalg.norm(J[k])), 1e-300)
    t = np.linalg.svd(w[:, None] * J)[2][-1]
    return np.asarray(t if float(t @ previous) >= 0.0 else -t, dtype=np.float64)


def _pack(A: ArrayLike, theta: float, T: float) -> Floats:
    return np.concatenate([M.real(A), [theta, T]])


def arc_newton(x_pred: Floats, tangent: Floats, alpha: float, norm: float, ref: NDArray[np.complex128],
               tol: float = 1e-11, max_iter: int = 8, rtol: float = RTOL) -> tuple[TravellingBreather, Floats]:
    """(TB, tangent): Gauss-Newton on (tb), the norm, the phase conditions about ``ref`` and the arclength condition
    <tangent, x - x_pred> = 0 from the predicted x_pred = (Re A, Im A, theta, T); the TB (not converged: the last
    iterate) and the unit tangent of the family at it, oriented along ``tangent``."""
    N = (x_pred.size - 2) // 2
    x = np.array(x_pred, float)
    res, best = np.inf, np.inf
    for it in range(max_iter + 1):
        A, theta, T = M.complex_(x[:2 * N]), float(x[2 * N]), float(x[2 * N + 1])
        J, F, Mm, res = _arc_system(A, T, theta, alpha, norm, ref, rtol)
        if res <= tol:
            mu = np.linalg.eigvals(Mm).astype(complex)
            t = _arc_tangent(J, 2 * N, tangent)
            dT = t[2 * N + 1]
            dA, dth = (M.complex_(t[:2 * N] / dT), float(t[2 * N] / dT)) if abs(dT) > 0 else (None, 0.0)
            return TravellingBreather(A, T, theta, alpha, res, True, it, mu, dA, dth, Mm), t
        if it == max_iter or not np.isfinite(res) or res > 10.0 * best:
            break
        best = min(best, res)
        Jx = np.vstack([J, tangent[None, :]])
        Fx = np.concatenate([F, [tangent @ (x - x_pred)]])
        x = x + _weighted_lstsq(Jx, -Fx, 2 * N)
    A, theta, T = M.complex_(x[:2 * N]), float(x[2 * N]), float(x[2 * N + 1])
    return TravellingBreather(A, T, theta, alpha, res, False, it), tangent


def continue_arclength(first: TravellingBreather, ds: float, steps: int, c_stop: tuple[float, float],
                       tol: float = 1e-11, rtol: float = RTOL, min_ds: float = 1e-6,
                       log: Callable[[str], object] | None = None) -> list[TravellingBreather]:
    """The family from ``first`` (a converged member with its tangent) by pseudo-arclength steps of ``ds`` in
    x = (Re A, Im A, theta, T), towards increasing c at the start: at most ``steps`` members, until c leaves the
    interval ``c_stop``; a failed step is halved down to ``min_ds`` (there the continuation stops), a step that
    succeeds at once lets the next grow by half again up to ``ds``. The members in order of arclength, ``first``
    included; each carries its multipliers and monodromy."""
    assert first.dA_dT is not None, "the first member carries its tangent"
    t = -_pack(first.dA_dT, first.dtheta_dT, 1.0)   # c = 1/T grows as T falls
    t /= np.linalg.norm(t)
    out, cur, h = [first], first, ds
    while len(out) <= steps and c_stop[0] <= cur.c <= c_stop[1]:
        b, t_new = arc_newton(_pack(cur.A, cur.theta, cur.T) + h * t, t, first.alpha, first.norm, cur.A, tol,
                              rtol=rtol)
        if not b.converged:
            h *= 0.5
            if h < min_ds:
                break
            continue
        out.append(b)
        cur, t, h = b, t_new, min(ds, 1.5 * h)
        if log:
            log(f"travelling breathers, arclength: c = {b.c:.7f}, theta = {b.theta:.10f}, H = {b.energy:.13f}, "
                f"residual {b.residual:.2g}")
    return out
