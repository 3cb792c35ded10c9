"""Exact travelling breathers of (nc), x_n(t + T) = x_{n-1}(t), one at a time (issue 37, item 2): the DpS member
that starts them through (ansatz), the lattice TB at one eps, its matched DpS TB and the pair launched side by side,
a TB carried to a larger ring, and the per-member numbers every lattice group stores
(:mod:`cradle.integrators.lattice_travelling`).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.travelling_breathers.dps_family import static_profiles, verdict
from cradle.analyses.travelling_breathers.in_motion import MOTION_CORE

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from cradle.analyses.protocol import Log
    from cradle.analyses.travelling_breathers import TravellingBreathers
    from cradle.integrators.dps_travelling import TravellingBreather
    from cradle.integrators.lattice_travelling import LatticeTB


#: multipliers modulo shift of a lattice TB at 1: the time shift in a Jordan block with the energy, and the carrier's
#: phase (DpS's phase symmetry, broken weakly in (nc)) in one with the near-conserved wave action
LATTICE_TRIVIAL = 4


def lattice_source(spec: TravellingBreathers, fam: list[TravellingBreather]) -> TravellingBreather:
    """The DpS member at ``lattice_source`` on the ring of ``lattice_N``: from the family when that is its ring, else
    solved on it as :func:`family` starts (the pushed static breather) and continued to that c."""
    from cradle.integrators import dps_travelling as DT

    if spec.lattice_N == spec.N:
        return fam[int(np.argmin([abs(b.c - spec.lattice_source) for b in fam]))]
    phi, _ = static_profiles(spec.lattice_N, spec.alpha, spec.norm)["site"]
    A, T, theta = DT.start(phi, spec.kick, spec.alpha)
    first = DT.newton(A, T, theta, spec.alpha, spec.norm, tol=spec.newton_tol, rtol=spec.rtol)
    members, _ = DT.continue_family(first, [spec.lattice_source], spec.newton_tol, spec.rtol)
    if not first.converged or not members:
        raise RuntimeError(f"lattice travelling breathers: no DpS TB at c = {spec.lattice_source} on the ring of "
                           f"{spec.lattice_N}")
    return members[0]


def lattice_tb(spec: TravellingBreathers, source: TravellingBreather, eps: float,
               log: Log | None = None) -> tuple[LatticeTB, dict]:
    """The exact TB of (nc) from the ansatz of the DpS member ``source`` at ``eps``: the ansatz run by (nc) for its time
    per site T_d eps^(1-alpha); the period T of the solve is the time when the run comes closest to the shifted start
    (:func:`LT.launch_period`: the lattice breather is slower than DpS's, issue 37 item 3)."""
    from cradle.integrators import lattice_travelling as LT

    z, T_hop = LT.ansatz_start(source.A, source.T, spec.alpha, eps)
    T, start_res = LT.launch_period(z, T_hop, spec.alpha)
    b = LT.newton(z, T, spec.alpha, tol=spec.newton_tol, max_iter=20, log=log)
    if not b.converged:
        raise RuntimeError(f"lattice travelling breathers: no TB from the ansatz of c = {source.c:.4g} at eps = {eps} "
                           f"(residual {b.residual:.3g} after {b.iterations} iterations)")
    return b, {"T_hop": T_hop, "start_residual": start_res}


def matched_dps(spec: TravellingBreathers, source: TravellingBreather, b: LatticeTB) -> TravellingBreather:
    """The DpS TB at the lattice TB's own parameters through the ansatz: norm ``spec.norm``, period
    T_d = T eps_b^(alpha-1), eps_b = :attr:`LatticeTB.eps` / sqrt(norm) (continued from ``source``)."""
    from cradle.integrators import dps_travelling as DT

    eps_b = b.eps / math.sqrt(spec.norm)
    c_d = 1.0 / (b.T * eps_b ** (spec.alpha - 1.0))
    members, _ = DT.continue_family(source, [c_d], spec.newton_tol, spec.rtol)
    if not members:
        raise RuntimeError(f"lattice travelling breathers: no DpS TB at c = {c_d:.6g} (the lattice TB's through the "
                           "ansatz)")
    return members[0]


def launched_pair(spec: TravellingBreathers, source: TravellingBreather, b: LatticeTB, eps: float) -> dict:
    """Item 3's comparison at ``eps``: the DpS member ``source`` launched in (nc) through (ansatz) and the exact TB
    ``b`` launched the same way (its N beads on the ring of ``motion_ring``, centred at N/2, zeros elsewhere), both run
    by (nc) (srkn6c) over the lattice time of ``motion_sites`` DpS periods and measured as in :func:`motion`: speeds in
    units of the DpS TB's c eps^(alpha-1), the radiation at the end."""
    from cradle.integrators import integrate_lattice
    from cradle.measurements import breather_motion as BM
    from cradle.models import tb_launch

    al, S, per = spec.alpha, spec.motion_sites, spec.motion_samples
    s = np.linspace(0.0, float(S), S * per + 1)
    t = s * source.T / eps ** (al - 1.0)
    ini = tb_launch.launch(source.A, eps, al, spec.motion_ring)
    xi = tb_launch.embedded(b.envelope, spec.motion_ring)
    out: dict = {}
    for key, (x0, v0) in {"dps": (ini.x0, ini.v0), "exact": (2.0 * xi.real, -2.0 * xi.imag)}.items():
        sol = integrate_lattice(x0, v0, t, alpha=al)
        e = BM.energy_density(sol.x, sol.v, al)
        p = BM.track(e, MOTION_CORE)
        rad = BM.radiation(e, p, spec.motion_window)
        out |= {f"{key}_speed": BM.velocity(s, p), f"{key}_radiation": float(rad[-1]),
                f"{key}_radiation_max": float(np.max(rad)), f"{key}_energy_drift": float(sol.energy_drift),
                f"{key}_distance": p - p[0]}
    out["s"] = s
    return out


#: the per-member variables of /lattice_rings, (ring, eps_lattice) and, with the suffix _family, (ring, c_step)
RING_MEMBER = ("period", "eps_tb", "dps_c", "residual", "iterations", "tail", "energy", "trivial_defect",
               "growth_rate", "unstable", "reciprocal_defect", "smallest_singular")


def by_step(cs: NDArray[np.float64], members: list[LatticeTB]) -> list[LatticeTB | None]:
    """The members of a continuation at the grid's c (None where it was not reached)."""
    return [next((b for b in members if math.isclose(b.c, c, rel_tol=1e-12)), None) for c in cs]


def ring_member(b: LatticeTB | None, spec: TravellingBreathers) -> dict[str, float]:
    """The stored numbers of one lattice TB (:data:`RING_MEMBER`; NaN for a member not reached); dps_c the velocity
    of the DpS TB through the ansatz, 1 / (T eps_b^(alpha-1)), eps_b = eps / sqrt(norm)."""
    from cradle.integrators import lattice_breathers as LB
    from cradle.models import dps_travelling as M

    out = dict.fromkeys(RING_MEMBER, math.nan)
    if b is None:
        return out
    eps_b = b.eps / math.sqrt(spec.norm)
    out |= {"period": b.T, "eps_tb": eps_b, "dps_c": 1.0 / (b.T * eps_b ** (spec.alpha - 1.0)),
            "residual": b.residual, "iterations": b.iterations, "tail": M.tail_amplitude(b.envelope),
            "energy": b.energy, "smallest_singular": b.smallest_singular}
    if b.multipliers.size:    # a converged member's
        triv, growth, unstable, _ = verdict(b, spec.stability_threshold, LATTICE_TRIVIAL)
        out |= {"trivial_defect": triv, "growth_rate": growth, "unstable": int(unstable),
                "reciprocal_defect": LB.multiplier_checks(b.multipliers)["reciprocal"]}
    return out


def _padded(members: list[LatticeTB | None], width: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(x, v) of the members as rows of ``width`` sites, NaN beyond each ring and for a member not reached."""
    x, v = np.full((len(members), width), np.nan), np.full((len(members), width), np.nan)
    for i, b in enumerate(members):
        if b is not None:
            N = b.z.size // 2
            x[i, :N], v[i, :N] = b.z[:N], b.z[N:]
    return x, v


def carried(spec: TravellingBreathers, b: LatticeTB, N: int, log: Log | None) -> LatticeTB | None:
    """The TB ``b`` of a smaller ring solved again on the ring of N (:func:`LT.embed`; the phase condition about the
    carried state), or None when Newton does not converge."""
    from cradle.integrators import lattice_travelling as LT

    out = LT.newton(LT.embed(b.z, N), b.T, spec.alpha, tol=spec.newton_tol, log=log)
    return out if out.converged else None
