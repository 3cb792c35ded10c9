"""The DpS family of travelling breathers (tb), A_n(tau + T) = e^{i theta} A_{n-1}(tau), in the velocity c = 1/T
at fixed norm: the first member from a pushed static breather (ansatzapproxst2), the continuation over ``speeds``,
the Floquet verdict modulo shift, the c -> 0 end against the static breathers, the direct run and the scaling check
(groups /family, /static, /checks).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from cradle.models.multipliers import split_trivial

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from cradle.analyses.protocol import Log
    from cradle.analyses.travelling_breathers import TravellingBreathers
    from cradle.integrators.dps_travelling import TravellingBreather
    from cradle.integrators.lattice_travelling import LatticeTB

#: multipliers modulo shift equal to 1 on every TB: phase and time shift, each in a Jordan block with its
#: conserved quantity (norm, H)
TRIVIAL = 4
#: the scaling check starts Newton this fraction of the way from the member towards its neighbour
SCALING_NUDGE = 1e-3
#: a multiplier is real when |Im mu| <= REAL |mu| (a real pair's imaginary parts are rounding)
REAL = 1e-8


def static_profiles(N: int, alpha: float, norm: float) -> dict[str, tuple[NDArray[np.float64], float]]:
    """The static breathers A_n = phi_n e^{i Omega tau} of both parities at the norm: phi = s a (a of (dpsstn),
    mu = 1, as the breathers analysis builds it), Omega = s^(alpha-1) / (2 tau0) (the scaling of (dpsstn))."""
    from cradle.models import dps, homoclinic

    out = {}
    for kind in ("site", "bond"):
        a = homoclinic.solve(homoclinic.initial_guess(N, kind, alpha, 0.1), alpha).a
        s = math.sqrt(norm / float(np.sum(a**2)))
        out[kind] = (s * a, s ** (alpha - 1.0) / (2.0 * dps.tau0(alpha)))
    return out


#: the first TB of each ring (solved from the pushed static breather), by (N, alpha, norm, kick, newton_tol, rtol):
#: the family and the limit scan of the same ring start from it
_FIRST: dict[tuple[int, float, float, float, float, float], TravellingBreather] = {}


def first_member(spec: TravellingBreathers, N: int, rtol: float) -> TravellingBreather:
    """The TB that Newton reaches from the static site breather pushed by ``kick`` on the ring of N (computed once
    per process and parameters: the same numbers each call); where the plain Newton stops short (rings of 128 and
    more), the one :func:`cradle.integrators.dps_travelling.newton_core_first` reaches from the same start."""
    from cradle.integrators import dps_travelling as DT

    key = (N, float(spec.alpha), float(spec.norm), float(spec.kick), float(spec.newton_tol), float(rtol))
    if key not in _FIRST:
        phi, _ = static_profiles(N, spec.alpha, spec.norm)["site"]
        A, T, theta = DT.start(phi, spec.kick, spec.alpha)
        b = DT.newton(A, T, theta, spec.alpha, spec.norm, tol=spec.newton_tol, rtol=rtol)
        if not b.converged:
            b = DT.newton_core_first(A, T, theta, spec.alpha, spec.norm, tol=spec.newton_tol, rtol=rtol)[0]
        _FIRST[key] = b
    return _FIRST[key]


def family(spec: TravellingBreathers, N: int, rtol: float,
           log: Log | None = None) -> tuple[list[TravellingBreather], float]:
    """The members at the spec's speeds (those reached; a missing one is absent) on the ring of N sites, and
    the c of the first guess."""
    from cradle.integrators import dps_travelling as DT

    first = first_member(spec, N, rtol)
    if not first.converged:
        raise RuntimeError(f"travelling breathers: no TB from the pushed breather (kick {spec.kick}, "
                           f"c = {first.c:.4g})")
    cs = np.asarray(spec.speeds, float)
    down, _ = DT.continue_family(first, cs[cs < first.c][::-1], spec.newton_tol, rtol, log=log)
    up, _ = DT.continue_family(first, cs[cs >= first.c], spec.newton_tol, rtol, log=log)
    return down[::-1] + up, first.c


def verdict(b: TravellingBreather | LatticeTB, threshold: float,
            trivial: int = TRIVIAL) -> tuple[float, float, bool, bool]:
    """(trivial defect, growth rate, unstable, real): the ``trivial`` multipliers nearest 1 are the trivial ones (four
    for DpS, :data:`LATTICE_TRIVIAL` for the lattice); their
    largest |mu - 1| is the defect, ln max|mu| / T over the others the growth rate; ``real`` when the unstable
    multiplier is real and > 1 (a pair left +1 along the real axis, the kind the dH/dc criterion is about)
    rather than an oscillatory quartet."""
    mu = b.multipliers
    near_one, others = split_trivial(mu, trivial)
    defect = float(np.abs(mu[near_one[-1]] - 1.0))
    rest = mu[others]
    top = rest[int(np.argmax(np.abs(rest)))]
    rate = float(np.log(np.abs(top)) / b.T)
    unstable = rate > threshold
    return defect, rate, bool(unstable), bool(unstable and top.real > 0 and abs(top.imag) <= REAL * abs(top))


def static_distance(b: TravellingBreather, profiles: dict, samples: int, rtol: float) -> dict[str, float]:
    """min over tau in one period and over shifts k of max_n ||A_n(tau)| - |phi_{n-k}|| / max phi, for each
    parity: how close the moving breather comes to the static one."""
    from cradle.integrators import integrate_dps

    tau = np.linspace(0.0, b.T, samples + 1)
    run = integrate_dps(b.A, tau, alpha=b.alpha, rtol=rtol)
    mod = np.abs(run.A)
    out = {}
    for kind, (phi, _) in profiles.items():
        P = np.stack([np.roll(np.abs(phi), k) for k in range(phi.size)])      # (shift, n)
        d = np.max(np.abs(mod[:, None, :] - P[None, :, :]), axis=2)
        out[kind] = float(np.min(d) / np.max(np.abs(phi)))
    return out


def direct_run(b: TravellingBreather, periods: int, rtol: float) -> dict:
    """The member run by (dfnls) over ``periods`` periods (integrate_dps, dop853_numba): norm and H drifts and
    the residual max_n |A_n(kT) - e^{i k theta} A_{n-k}(0)| / max|A| at each k."""
    from cradle.integrators import integrate_dps
    from cradle.models import dps_travelling as M

    k = np.arange(periods + 1)
    run = integrate_dps(b.A, k * b.T, alpha=b.alpha, rtol=rtol)
    res = np.array([np.max(np.abs(run.A[j] - np.exp(1j * j * b.theta) * M.shift(b.A, int(j)))) for j in k])
    return {"k": k, "residual": res / np.max(np.abs(b.A)), "norm_drift": float(run.max_l2_drift),
            "energy_drift": float(run.max_energy_drift)}


def scaling_check(b: TravellingBreather, other: TravellingBreather, lam: float, spec: TravellingBreathers) -> dict:
    """The TB at (lambda^(1-alpha) T, lambda^2 P) solved by Newton from lambda times a guess moved by
    ``SCALING_NUDGE`` of the way towards ``other`` (another member: a guess that is no TB), with lambda A as the
    phase reference: its distance to lambda A and the change of theta."""
    from cradle.integrators import dps_travelling as DT
    from cradle.models import dps_travelling as M

    A_l, T_l = M.scaled(b.A, b.T, lam, spec.alpha)
    guess = lam * (b.A + SCALING_NUDGE * (other.A - b.A))
    theta = b.theta + SCALING_NUDGE * math.remainder(other.theta - b.theta, 2 * math.pi)
    s = DT.newton(guess, T_l, theta, spec.alpha, lam**2 * spec.norm, A_l, spec.newton_tol, rtol=spec.rtol)
    return {"profile_error": float(np.max(np.abs(s.A - A_l)) / np.max(np.abs(A_l))),
            "theta_error": float(abs(math.remainder(s.theta - b.theta, 2 * math.pi))), "converged": s.converged,
            "residual": s.residual}


def sign_changes(c: NDArray[np.float64], y: NDArray[np.float64]) -> list[float]:
    """The c where y changes sign between grid points (linear interpolation)."""
    out = []
    for i in range(len(c) - 1):
        if np.isfinite(y[i]) and np.isfinite(y[i + 1]) and y[i] * y[i + 1] < 0:
            out.append(float(c[i] - y[i] * (c[i + 1] - c[i]) / (y[i + 1] - y[i])))
    return out


def verdict_changes(c: NDArray[np.float64], unstable: NDArray[np.bool_]) -> list[float]:
    """The midpoints of the grid intervals where the verdict changes."""
    return [float(0.5 * (c[i] + c[i + 1])) for i in range(len(c) - 1) if unstable[i] != unstable[i + 1]]
