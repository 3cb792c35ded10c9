"""Time integration of the damped DpS equation (dpsdamped) of :mod:`cradle.models.dps_damped`.

    2 i tau0 dA_n/dtau = kappa [g(A_{n+1} - A_n) - g(A_n - A_{n-1})] - i tau0 gamma~ A_n          (dpsdamped)

The state is the real view of A extended by the two amounts the damping removes, Q_l2 (of sum |A_n|^2) and
Q_S (of S = sum |A_{n+1} - A_n|^(alpha+1) = -(alpha+1) tau0 H), integrated with it as quantities of their own
(:func:`cradle.integrators.systems.dps.damped`): l2 + Q_l2 and S + Q_S are then constant, and their
changes measure the integrator's accuracy, never a difference taken as the dissipation. Called by
:func:`cradle.integrators.integrate_dps` when its ``damping`` is active; scipy's DOP853 or RK45 stepped
manually, or DOP853 in numba (:mod:`cradle.integrators._dop853`, the default method "dop853_numba";
it does not resume across blocks as :func:`cradle.integrators.dps_solver.iter_dps` does).
"""
from __future__ import annotations

import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Protocol, TypeVar

import numpy as np

from cradle.integrators import _dop853
from cradle.integrators._scipy_steps import stepped
from cradle.integrators.systems import dps as SD
from cradle.models.dps_damped import DpsDamping, contact_factor
from cradle.specs.declare import from_plain, plain

if TYPE_CHECKING:
    from cradle.integrators._types import Floats

#: the solution class the caller gives (cradle.integrators.dps_solver.DpsSolution, which imports this module)
DpsSolution = TypeVar("DpsSolution")


class _DpsRun(Protocol):
    """What a damped run reads of the validated run (:class:`cradle.integrators.dps_solver._DpsRun`, whose module
    imports this one): its inputs, the invariants of A0 the drifts are measured from and their scales."""

    N: int
    alpha: float
    periodic: bool
    rtol: float
    atol: float
    tau_out: Floats
    y0: Floats
    inv2tau0: float
    l20: float
    S0: float
    P0: complex
    l2_scale: float
    S_scale: float
    P_scale: float
    progress: Callable[[float, float], None] | None


def validated(damping: DpsDamping) -> DpsDamping:
    """``damping`` checked against the declaration of :class:`DpsDamping` (one-line ConfigError otherwise)."""
    if not isinstance(damping, DpsDamping):
        raise ValueError(f"damping must be a DpsDamping (cradle.models.dps_damped; slow_damping converts a lattice "
                         f"Damping), got damping={damping!r}")
    return from_plain(DpsDamping, plain(damping), "damping")


def system(damping: DpsDamping, alpha: float, inv2tau0: float, periodic: bool) -> SD.DpsSystem:
    """The (dpsdamped) of ``damping`` in the DpS family (:mod:`cradle.integrators.systems.dps`)."""
    return SD.damped(alpha, periodic, inv2tau0, damping.gamma, contact_factor(damping.eta, alpha))


class _Balance:
    """The balance residuals of a damped run, measured from A0 (see :class:`DpsSolution`)."""

    def __init__(self, run: _DpsRun, damping: DpsDamping) -> None:
        self.run = run
        self.N = run.N
        self.to_H = -1.0 / ((run.alpha + 1.0) * (0.5 / run.inv2tau0))   # H = -S / ((alpha+1) tau0)
        self.S0 = run.S0
        self.S_scale = run.S_scale
        self.H0 = run.S0 * self.to_H
        self.H_scale = abs(self.H0) if self.H0 != 0.0 else 1.0
        self.half_gamma = 0.5 * damping.gamma

    def row(self, y: Floats, tau: float) -> tuple[float, float, float, float, float, float, float]:
        """(l2, H, Q_l2, Q_H, l2 residual, H residual, P residual) of the extended state y at tau;
        Q_H = -Q_S / ((alpha+1) tau0) is what H has gained, and |S + Q_S - S0| / S0 = |H - Q_H - H0| / |H0|."""
        run, n = self.run, 2 * self.N
        l2, S, pr, pi = SD.dps_invariants(np.ascontiguousarray(y[:n]), run.alpha, run.periodic)
        P_exact = run.P0 * np.exp(-self.half_gamma * tau)
        return (l2, S * self.to_H, y[n], -y[n + 1] * self.to_H, abs(l2 + y[n] - run.l20) / run.l2_scale,
                abs(S + y[n + 1] - self.S0) / self.S_scale, abs(complex(pr, pi) - P_exact) / run.P_scale)


def integrate_damped(run: _DpsRun, damping: DpsDamping, method: str, wall0: float, solution: Callable[..., DpsSolution],
                     scipy_class: str | None) -> DpsSolution:
    """:func:`cradle.integrators.integrate_dps` of (dpsdamped) for the validated run ``run``
    (:class:`cradle.integrators.dps_solver._DpsRun`) with active ``damping``; ``solution`` is the class
    :class:`cradle.integrators.DpsSolution` and ``scipy_class`` the name of scipy's solver (None: DOP853 in
    numba), both given by the caller, which this module does not import."""
    tau_out, T, N = run.tau_out, run.tau_out.size, run.N
    dsys = system(damping, run.alpha, run.inv2tau0, run.periodic)
    rtol, atol = run.rtol, run.atol
    y0 = np.concatenate([run.y0, [0.0, 0.0]])
    balance = _Balance(run, damping)
    rows = np.empty((T, 7))
    Y = np.empty((T, 2 * N + 2))
    if method == "dop853_numba":
        stats = np.array([run.l20, run.S0, 0.0, 0.0])
        Y, n_steps, nfev = _dop853.run_dop853(dsys, y0, tau_out, rtol, atol, stats, run.progress)
        for i in range(T):
            rows[i] = balance.row(Y[i], tau_out[i])
        max_l2, max_E = float(stats[2]), float(stats[3])
        return _solution(solution, Y, rows, max_l2, max_E, n_steps, nfev, run, damping, method, wall0)

    fun = SD.scipy_fun(dsys, y0)

    def store(i: int, y: Floats) -> None:
        Y[i] = y
        rows[i] = balance.row(y, tau_out[i])

    drifts = [0.0, 0.0]   # the largest l2 and energy residuals over every accepted step

    def on_step(y: Floats, tau: float) -> None:
        r = balance.row(y, tau)
        drifts[0] = max(drifts[0], r[4])
        drifts[1] = max(drifts[1], r[5])

    n_steps, nfev = stepped(str(scipy_class), fun, y0, tau_out, rtol, atol, store, on_step, run.progress, method)
    max_l2, max_E = drifts
    return _solution(solution, Y, rows, max_l2, max_E, n_steps, nfev, run, damping, method, wall0)


def _solution(solution: Callable[..., DpsSolution], Y: Floats, rows: Floats, max_l2: float, max_E: float, n_steps: int,
              nfev: int, run: _DpsRun, damping: DpsDamping, method: str, wall0: float) -> DpsSolution:
    A = np.ascontiguousarray(Y[:, :2 * run.N]).view(np.complex128)
    return solution(run.tau_out, A, rows[:, 4].copy(), rows[:, 5].copy(), rows[:, 6].copy(), float(max_l2),
                       float(max_E), int(n_steps), time.perf_counter() - wall0, method, float(run.rtol),
                       float(run.atol), int(nfev), l2=rows[:, 0].copy(), energy=rows[:, 1].copy(),
                       l2_dissipated=rows[:, 2].copy(), energy_dissipated=rows[:, 3].copy(), damping=damping)
