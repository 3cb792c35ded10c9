"""Robustness of the DpS TBs' verdicts on rings and tolerances: every member re-solved at each ``check_rtol`` and
the family recomputed on each ring of ``check_N``; a verdict is settled where all agree, and what explains the others
(the unstable mode's extent over the ring, the tail as a plane wave of (dfnls) with its wavenumber q = theta and its
modulational growth rate) (group /robustness).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.travelling_breathers.dps_family import TRIVIAL, family, verdict

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from cradle.analyses.protocol import Log
    from cradle.analyses.travelling_breathers import TravellingBreathers
    from cradle.integrators.dps_travelling import TravellingBreather


#: a member's verdict is settled when the ring of N, every check ring and every check tolerance give it
SETTLED_STABLE, SETTLED_UNSTABLE, RING_DEPENDENT = 0, 1, -1
#: sideband wavenumbers p in (0, pi] over which the tail's plane-wave MI rate is maximised
MI_SIDEBANDS = 512


def far_sites(A: NDArray[np.complex128]) -> NDArray[np.bool_]:
    """The quarter ring farthest from the centre (ring distance >= 3N/8), where the tail is measured."""
    from cradle.models import dps_travelling as M

    N = A.size
    return np.abs((np.arange(N) - M.centre(A) + N / 2) % N - N / 2) >= 3 * N / 8


def tail_wave(A: NDArray[np.complex128]) -> tuple[float, float]:
    """(q, R): the tail as a plane wave R e^{i q n} on the far quarter ring, q = arg sum A_{n+1} conj(A_n) and R the
    rms |A_n| there. A tail that is a plane wave of (dfnls) of small amplitude has frequency ~ R^(alpha-1), so
    (tb) gives q = theta mod 2 pi to that order."""
    far = np.where(far_sites(A))[0]
    q = float(np.angle(np.sum(A[(far + 1) % A.size] * np.conj(A[far]))))
    return q, float(np.sqrt(np.mean(np.abs(A[far]) ** 2)))


def tail_mi_rate(q: float, R: float, alpha: float) -> float:
    """The largest growth rate over the sidebands p of the plane wave R e^{i q n} of (dfnls) on the infinite
    lattice (:func:`cradle.analyses.mi_diagram.growth_rate`): 0 for |q| <= pi/2."""
    from cradle.analyses import mi_diagram

    p = np.linspace(0.0, np.pi, MI_SIDEBANDS + 1)[1:]
    return float(np.max(mi_diagram.growth_rate(q, p, alpha, R)))


def member_checks(b: TravellingBreather, threshold: float) -> dict[str, float]:
    """One member's verdict and what explains it: growth rate, verdict, tail and its plane wave (q, MI rate), and
    the extent of the most unstable mode (participation ratio 1 / sum w_n^2 of its |v_n|^2 = w_n, over N: 1 for
    a mode spread evenly over the ring, ~ (core width) / N for a mode of the core; NaN when stable)."""
    from cradle.measurements import floquet_modes as FM
    from cradle.models import dps_travelling as M

    _, rate, unstable, _ = verdict(b, threshold)
    q, R = tail_wave(b.A)
    extent = np.nan
    if unstable:
        assert b.monodromy is not None
        extent = FM.participation(FM.site_weights(FM.top_mode(b.monodromy, TRIVIAL)[1])) / b.A.size
    return {"growth": rate, "unstable": float(unstable), "tail": M.tail_amplitude(b.A), "theta": b.theta,
            "tail_q": q, "tail_mi": tail_mi_rate(q, R, b.alpha), "extent": extent}


ROBUST_RING = ("growth", "unstable", "tail", "theta", "tail_q", "tail_mi", "extent")


def robustness(spec: TravellingBreathers, fam: list[TravellingBreather], log: Log | None = None) -> dict:
    """The verdicts of the members ``fam`` (on the ring of N, at rtol) on every check ring (the family recomputed
    there: :func:`family`) and at every check tolerance (each member re-solved on the ring of N): arrays (ring, c)
    of :func:`member_checks` (NaN, verdict -1, where a ring's family does not reach the c), (rtol, c) of growth rate
    and verdict, and per c the settled verdict (:data:`SETTLED_STABLE`, :data:`SETTLED_UNSTABLE`,
    :data:`RING_DEPENDENT`)."""
    from cradle.integrators import dps_travelling as DT

    c = np.array([b.c for b in fam])
    rings = [spec.N, *spec.check_N]
    per_ring = {k: np.full((len(rings), c.size), np.nan) for k in ROBUST_RING}
    for i, N in enumerate(rings):
        members = fam if N == spec.N else family(spec, N, spec.rtol, log)[0]
        byc = {round(b.c, 12): b for b in members}
        for j, x in enumerate(c):
            b = byc.get(round(float(x), 12))
            if b is not None:
                for k, v in member_checks(b, spec.stability_threshold).items():
                    per_ring[k][i, j] = v
    rtols = [spec.rtol, *spec.check_rtol]
    growth_tol = np.full((len(rtols), c.size), np.nan)
    growth_tol[0] = per_ring["growth"][0]
    theta_tol = np.full((len(rtols), c.size), np.nan)
    theta_tol[0] = per_ring["theta"][0]
    for i, rt in enumerate(rtols[1:], 1):
        for j, b in enumerate(fam):
            r = DT.newton(b.A, b.T, b.theta, spec.alpha, spec.norm, b.A, spec.newton_tol, rtol=rt)
            if r.converged:
                growth_tol[i, j] = verdict(r, spec.stability_threshold)[1]
                theta_tol[i, j] = r.theta
    unstable_tol = np.where(np.isnan(growth_tol), -1, growth_tol > spec.stability_threshold).astype(int)
    unstable_ring = np.where(np.isnan(per_ring["unstable"]), -1, per_ring["unstable"]).astype(int)
    everything = np.concatenate([unstable_ring, unstable_tol])
    settled = np.where(np.all(everything == 1, axis=0), SETTLED_UNSTABLE,
                       np.where(np.all(everything == 0, axis=0), SETTLED_STABLE, RING_DEPENDENT))
    return {"ring": np.array(rings), "rtol": np.array(rtols), **{f"{k}_ring": v for k, v in per_ring.items()},
            "unstable_ring": unstable_ring, "growth_tol": growth_tol, "unstable_tol": unstable_tol,
            "theta_tol": theta_tol, "settled": settled}


def robustness_attrs(c: NDArray[np.float64], rob: dict) -> dict:
    """The summary of :func:`robustness` stored as attributes: the rings and tolerances, the c of each settled
    verdict, how far the tail's q is from theta (on the ring of N), the smallest extent of an unstable mode."""
    settled = rob["settled"]
    dq = np.abs(np.angle(np.exp(1j * (rob["tail_q_ring"][0] - rob["theta_ring"][0]))))
    extent = rob["extent_ring"]
    return {"rings": ", ".join(str(int(n)) for n in rob["ring"]),
            "rtols": ", ".join(f"{x:g}" for x in rob["rtol"]),
            "verdicts_settled": f"{int(np.sum(settled != RING_DEPENDENT))} of {settled.size}",
            **{f"{name}_c": ", ".join(f"{x:g}" for x in c[settled == v]) or "none"
               for name, v in (("settled_stable", SETTLED_STABLE), ("settled_unstable", SETTLED_UNSTABLE),
                               ("ring_dependent", RING_DEPENDENT))},
            "tail_q_minus_theta_max": float(np.max(dq)),
            "unstable_mode_extent_min": float(np.nanmin(extent)) if np.any(np.isfinite(extent)) else np.nan}
