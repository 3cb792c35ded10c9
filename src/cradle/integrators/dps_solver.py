"""Time integration of the discrete p-Schrödinger equation (dfnls).

    2 i tau0 dA_n/dtau = g(A_{n+1} - A_n) - g(A_n - A_{n-1}),  g(z) = z |z|^(alpha-1)   (dfnls)

(conventions of :mod:`cradle.models.dps`: periodic, or free ends with
g(A_N - A_{N-1}) = g(A_0 - A_{-1}) = 0). The equation is not of the
"kinetic + potential" form, so the splittings used for (nc) do not apply;
scipy's adaptive solvers are stepped manually on the real view of A
(2N reals, Re/Im interleaved) with a numba-compiled right-hand side
(:func:`cradle.integrators.systems.dps.dps_rhs`), and the three invariants of
(dfnls) (squared l2 norm, Hamiltonian H, P = sum A_n) are monitored after
every accepted step.

With dissipation, (dpsdamped) of :mod:`cradle.models.dps_damped` (``damping=DpsDamping(...)``), the run is
:mod:`cradle.integrators.dps_damped_solver`'s: the same solvers on the state extended by the two dissipated
amounts, and the drifts become the residuals of the balance laws.

With site-dependent coefficients, (dpsimperfect) of :mod:`cradle.models.dps_sites` (``sites=DpsSites(...)``:
detuning, masses, contact stiffnesses, on-site quartic, precompression), the right-hand side is the same family
with the DpS counterparts of the terms (:func:`cradle.integrators.systems.dps.imperfect`), and the monitored
invariants are the weighted l2 norm sum m_n |A_n|^2 and the H of (dpsimperfect).
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from cradle.integrators import _dop853
from cradle.integrators._scipy_steps import stepped
from cradle.integrators._validate import check_dps_pace, check_state, check_times
from cradle.integrators.systems import dps as SD
from cradle.models.dps import tau0 as _tau0
from cradle.models.dps_damped import DpsDamping
from cradle.models.dps_sites import DpsSites
from cradle.specs.checked import checked

if TYPE_CHECKING:
    from collections.abc import Callable, Iterator

    from numpy.typing import ArrayLike

    from cradle.integrators._types import Floats

#: scipy.integrate classes by name (imported when used)
SCIPY_DPS_METHODS = {"dop853": "DOP853", "rk45": "RK45"}
DPS_METHODS = tuple(SCIPY_DPS_METHODS) + ("dop853_numba",)
DEFAULT_RTOL = 1e-10


@dataclass
class DpsSolution:
    """Result of :func:`integrate_dps`.

    Attributes
    ----------
    tau : ndarray, shape (T,)
        Output slow times (= ``tau_out``).
    A : ndarray, shape (T, N), complex
        A_n(tau).
    l2_drift, energy_drift : ndarray, shape (T,)
        |I(tau) - I(0)| / |I(0)| for I = sum |A_n|^2 and I = H (DpS
        Hamiltonian, -sum |A_{n+1}-A_n|^(alpha+1) / ((alpha+1) tau0));
        absolute when I(0) = 0.
    P_drift : ndarray, shape (T,)
        |P(tau) - P(0)| / max_n |A_n(0)|, P = sum A_n (cradle.data.variables).
    max_l2_drift, max_energy_drift : float
        Same relative drifts, max over every accepted step.

    With damping (``damping`` is an active :class:`cradle.models.dps_damped.DpsDamping`) neither I is
    conserved, and the drifts are the residuals of the balance laws of (dpsdamped), in which the dissipated
    amounts are integrated as quantities of their own: ``l2_drift`` = |l2(tau) + l2_dissipated(tau) - l2(0)|
    / l2(0), ``energy_drift`` = |H(tau) - energy_dissipated(tau) - H(0)| / |H(0)| (H < 0 rises to 0),
    ``P_drift`` = |P(tau) - e^{-gamma~ tau/2} P(0)| / max_n |A_n(0)| (the contact term leaves sum A_n
    alone, the on-site one damps it exactly); all three measure the integrator's accuracy.
    l2, energy, l2_dissipated, energy_dissipated : ndarray, shape (T,), or None
        With damping: sum |A_n|^2, H, and the integrals over [0, tau] of -d(l2)/dtau >= 0 and of dH/dtau >= 0
        (None without damping). With ``sites``: l2 = sum m_n |A_n|^2 and energy = H of (dpsimperfect), the
        invariants the drifts are measured on (``P_drift`` is then that of sum m_n A_n, conserved only without
        detuning and on-site quartic).
    damping : DpsDamping or None
    sites : DpsSites or None
    n_steps : int
        Accepted steps.
    n_rhs_evals : int
    wall_time_s : float
    method : str
    rtol, atol : float
    """

    tau: np.ndarray
    A: np.ndarray
    l2_drift: np.ndarray
    energy_drift: np.ndarray
    P_drift: np.ndarray
    max_l2_drift: float
    max_energy_drift: float
    n_steps: int
    wall_time_s: float
    method: str
    rtol: float
    atol: float
    n_rhs_evals: int = 0
    l2: np.ndarray | None = None
    energy: np.ndarray | None = None
    l2_dissipated: np.ndarray | None = None
    energy_dissipated: np.ndarray | None = None
    damping: DpsDamping | None = None
    sites: DpsSites | None = None


@checked(method="dpsMethod")
def integrate_dps(A0: ArrayLike, tau_out: ArrayLike, *, alpha: float, bc: str = "periodic",
                  method: str = "dop853_numba", rtol: float = DEFAULT_RTOL, atol: float | None = None,
                  progress: Callable[[float, float], None] | None = None, damping: DpsDamping | None = None,
                  sites: DpsSites | None = None) -> DpsSolution:
    """Integrate the DpS equation (dfnls) with tau0 = tau0(alpha) of :mod:`cradle.models.dps`.

    Parameters
    ----------
    A0 : array_like, shape (N,), complex
        Initial amplitudes, N >= 2, finite.
    tau_out : array_like, shape (T,)
        Strictly increasing output times >= 0; integration starts at tau = 0
        (row 0 is A0 when tau_out[0] == 0).
    alpha : float
        Exponent > 1.
    bc : {"periodic", "free"}
    method : {"dop853_numba", "dop853", "rk45"}
        Default "dop853_numba", as ``defaults.dps.method`` of the config.
        scipy explicit Runge-Kutta pair stepped manually (DOP853: order 8
        with dense output of order 7), or "dop853_numba": the same DOP853
        pair and step control fully in numba, steps ending exactly on
        tau_out (several times faster for small N).
    rtol : float
        Relative tolerance (default 1e-10).
    atol : float, optional
        Absolute tolerance, default rtol * max_n |A0_n| (rtol if A0 = 0).
    progress : callable, optional
        ``progress(tau_reached, tau_final)``, about once per second.
    damping : DpsDamping, optional
        gamma~ and eta of (dpsdamped) (:func:`cradle.models.dps_damped.slow_damping` converts a lattice
        :class:`cradle.models.damping.Damping`); None or inactive: (dfnls), exactly the undamped run.
        Integrated by :mod:`cradle.integrators.dps_damped_solver`.
    sites : DpsSites, optional
        The site-dependent coefficients of (dpsimperfect) (:func:`cradle.models.dps_sites.dps_sites` builds them
        from a lattice's masses, frequencies, stiffnesses, on-site term and precompression); None: (dfnls), the
        run above unchanged. Not with an active ``damping``.

    Returns
    -------
    DpsSolution
    """
    wall0 = time.perf_counter()
    if sites is not None:
        if damping is not None and dps_damped_solver_active(damping):
            raise ValueError("integrate_dps: sites and damping together are not implemented (give one of them)")
        return _integrate_sites(_DpsRun(A0, tau_out, alpha, bc, rtol, atol, progress), sites, method, wall0)
    if damping is not None:
        from cradle.integrators import dps_damped_solver

        if dps_damped_solver.validated(damping).active:
            return dps_damped_solver.integrate_damped(_DpsRun(A0, tau_out, alpha, bc, rtol, atol, progress),
                                                      damping, method, wall0, DpsSolution,
                                                      SCIPY_DPS_METHODS.get(method))
    run = _DpsRun(A0, tau_out, alpha, bc, rtol, atol, progress)
    tau_out, T, N = run.tau_out, run.tau_out.size, run.N
    if method == "dop853_numba":
        return run.block(tau_out, wall0)
    alpha, periodic, rtol, atol = run.alpha, run.periodic, run.rtol, run.atol
    l20, S0 = run.l20, run.S0
    l2_scale, S_scale = run.l2_scale, run.S_scale
    y0 = run.y0

    system = run.system

    fun = SD.scipy_fun(system, y0)
    A = np.empty((T, N), dtype=complex)
    l2d = np.empty(T)
    Ed = np.empty(T)
    Pd = np.empty(T)

    def store(i: int, y: Floats) -> None:
        A[i] = y.view(np.complex128)
        l2d[i], Ed[i], Pd[i] = run.drifts(y[None, :])[:, 0]

    drifts = [0.0, 0.0]   # the largest l2 and energy drifts over every accepted step

    def on_step(y: Floats, tau: float) -> None:
        l2, S, _pr, _pi = SD.dps_invariants(y, alpha, periodic)
        drifts[0] = max(drifts[0], abs(l2 - l20) / l2_scale)
        drifts[1] = max(drifts[1], abs(S - S0) / S_scale)

    n_steps, nfev = stepped(SCIPY_DPS_METHODS[method], fun, y0, tau_out, rtol, atol, store, on_step, progress,
                                method)
    max_l2, max_E = drifts
    return DpsSolution(tau_out, A, l2d, Ed, Pd, float(max_l2), float(max_E), n_steps,
                       time.perf_counter() - wall0, method, float(rtol), float(atol), nfev)


def dps_damped_solver_active(damping: DpsDamping) -> bool:
    """Is ``damping`` (validated) an active damping of (dpsdamped)?"""
    from cradle.integrators import dps_damped_solver

    return bool(dps_damped_solver.validated(damping).active)


def _integrate_sites(run: _DpsRun, sites: DpsSites, method: str, wall0: float) -> DpsSolution:
    """(dpsimperfect) from run.y0: the numba DOP853, or scipy's solvers on the same compiled
    right-hand side."""
    from cradle.integrators import _kernels_dps_sites as KS
    from cradle.models import dps_sites as S

    if not isinstance(sites, DpsSites):
        raise ValueError(f"sites must be a cradle.models.dps_sites.DpsSites, got {type(sites).__name__}")
    if sites.N != run.N:
        raise ValueError(f"sites has {sites.N} sites, A0 has {run.N}")
    alpha, periodic = run.alpha, run.periodic
    t0 = _tau0(alpha)
    par = KS.pack(sites, S.contact_tables(alpha) if sites.compressed else None, t0, S.PSI_MAX)
    system = SD.imperfect(alpha, periodic, sites, par)
    l20, H0, pr0, pi0 = KS.dps_sites_invariants(run.y0, alpha, par, periodic)
    P0 = complex(pr0, pi0)
    l2s = l20 if l20 != 0.0 else 1.0
    Hs = abs(H0) if H0 != 0.0 else 1.0
    tau_out, T, N = run.tau_out, run.tau_out.size, run.N

    def invariants(Y: Floats) -> Floats:
        out = np.empty((5, Y.shape[0]))
        for i, y in enumerate(Y):
            l2, H, pr, pi = KS.dps_sites_invariants(np.ascontiguousarray(y), alpha, par, periodic)
            out[:, i] = (abs(l2 - l20) / l2s, abs(H - H0) / Hs, abs(complex(pr, pi) - P0) / run.P_scale, l2, H)
        return out

    if method == "dop853_numba":
        stats = np.array([l20, H0, 0.0, 0.0])
        Y, n_steps, nfev = _dop853.run_dop853(system, run.y0, tau_out, run.rtol, run.atol, stats, run.progress)
        max_l2, max_E = float(stats[2]), float(stats[3])
    else:
        fun = SD.scipy_fun(system, run.y0)
        Y = np.empty((T, 2 * N))
        drifts = [0.0, 0.0]

        def store(i: int, y: Floats) -> None:
            Y[i] = y

        def on_step(y: Floats, tau: float) -> None:
            l2, H, _pr, _pi = KS.dps_sites_invariants(y, alpha, par, periodic)
            drifts[0] = max(drifts[0], abs(l2 - l20) / l2s)
            drifts[1] = max(drifts[1], abs(H - H0) / Hs)

        n_steps, nfev = stepped(SCIPY_DPS_METHODS[method], fun, run.y0, tau_out, run.rtol, run.atol, store, on_step,
                                run.progress, method)
        max_l2, max_E = drifts
    inv = invariants(Y)
    return DpsSolution(tau_out, np.ascontiguousarray(Y).view(np.complex128), inv[0], inv[1], inv[2], float(max_l2),
                       float(max_E), int(n_steps), time.perf_counter() - wall0, method, float(run.rtol),
                       float(run.atol), int(nfev), l2=inv[3], energy=inv[4], sites=sites)


class _DpsRun:
    """One run of (dfnls) from A0 at tau = 0 to tau_out[-1]: its validated inputs, the invariants of
    A0 that every drift is measured from, and (DOP853 in numba) the stepper's state, so the run can
    be computed in consecutive blocks of output times (:func:`iter_dps`). alpha, bc, rtol and atol
    come checked (``@checked`` on :func:`integrate_dps` and :func:`iter_dps`)."""

    def __init__(self, A0: ArrayLike, tau_out: ArrayLike, alpha: float, bc: str, rtol: float, atol: float | None,
                 progress: Callable[[float, float], None] | None) -> None:
        self.alpha = alpha
        self.periodic = bc == "periodic"
        A0 = check_state(A0, "A0", dtype=complex)
        self.tau_out = check_times(tau_out, "tau_out")
        self.rtol = rtol
        amp = float(np.max(np.abs(A0)))
        self.atol = (rtol * amp if amp > 0.0 else rtol) if atol is None else atol
        if progress is not None and not callable(progress):
            raise ValueError(f"progress must be callable or None, got progress={progress!r}")
        self.progress = progress
        check_dps_pace(A0, self.tau_out, alpha)
        self.inv2tau0 = 1.0 / (2.0 * _tau0(self.alpha))
        self.system = SD.dfnls(self.alpha, self.periodic, self.inv2tau0)   # (dfnls) in the numba DOP853
        self.N = A0.size
        self.y0 = np.ascontiguousarray(A0).view(np.float64).copy()
        self.l20, self.S0, pr0, pi0 = SD.dps_invariants(self.y0, self.alpha, self.periodic)
        self.P0 = complex(pr0, pi0)
        self.l2_scale = self.l20 if self.l20 != 0.0 else 1.0
        self.S_scale = self.S0 if self.S0 != 0.0 else 1.0
        self.P_scale = amp if amp > 0.0 else 1.0
        # the numba stepper's state, carried from block to block
        self.y = self.y0.copy()
        self.stats = np.array([self.l20, self.S0, 0.0, 0.0])
        self.state = np.zeros(2)  # [tau, next step]; step 0: chosen on the first block
        self.counts = np.zeros(3, dtype=np.int64)

    def drifts(self, Y: Floats) -> np.ndarray:
        """(3, rows): relative drifts of l2 norm, Hamiltonian and P of each row of Y from A0."""
        out = np.empty((3, Y.shape[0]))
        for i, y in enumerate(Y):
            l2, S, pr, pi = SD.dps_invariants(np.ascontiguousarray(y), self.alpha, self.periodic)
            out[:, i] = (abs(l2 - self.l20) / self.l2_scale, abs(S - self.S0) / self.S_scale,
                         abs(complex(pr, pi) - self.P0) / self.P_scale)
        return out

    def block(self, tau: Floats, wall0: float) -> DpsSolution:
        """The solution at ``tau`` (increasing, after the previous block's last time), DOP853 in numba."""
        n0, f0 = int(self.counts[0]), int(self.counts[1])
        Y, _, _ = _dop853.run_dop853(self.system, self.y, tau, self.rtol, self.atol, self.stats, self.progress,
                                      state=self.state, counts=self.counts, t_bound=float(self.tau_out[-1]))
        self.y = Y[-1].copy()
        l2d, Ed, Pd = self.drifts(Y)
        return DpsSolution(tau, np.ascontiguousarray(Y).view(np.complex128), l2d, Ed, Pd, float(self.stats[2]),
                           float(self.stats[3]), int(self.counts[0]) - n0, time.perf_counter() - wall0,
                           "dop853_numba", float(self.rtol), float(self.atol), int(self.counts[1]) - f0)


@checked
def iter_dps(A0: ArrayLike, tau_out: ArrayLike, rows: int, *, alpha: float, bc: str = "periodic",
             rtol: float = DEFAULT_RTOL, atol: float | None = None,
             progress: Callable[[float, float], None] | None = None) -> Iterator[DpsSolution]:
    """Yield the :class:`DpsSolution` of consecutive blocks of ``rows`` output times of one run of
    :func:`integrate_dps` (method "dop853_numba") from A0 at tau = 0.

    Steps end on every output time and the stepper's state (tau, next step, invariants' running
    maxima) is carried from block to block, so the blocks' rows are bitwise those of the single
    call; memory is one block, whatever the number of output times (the streamed scene job,
    :mod:`cradle.scenes.streamed`). ``max_l2_drift`` / ``max_energy_drift`` of a block are the
    maxima over every step so far; ``n_steps`` counts the block's own.
    """
    run = _DpsRun(A0, tau_out, alpha, bc, rtol, atol, progress)
    rows = max(1, int(rows))
    for i in range(0, run.tau_out.size, rows):
        yield run.block(run.tau_out[i:i + rows], time.perf_counter())
