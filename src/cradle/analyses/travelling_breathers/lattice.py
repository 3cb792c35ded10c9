"""The groups of the exact travelling breathers of (nc) (issue 37, item 2): /lattice and /lattice_motion on the ring
of ``lattice_N``; /lattice_rings (each ring carried from the one before, sites at rest added on the far side, and
the continuation in c on some of them); /lattice_large (TBs at larger eps solved the core first,
:func:`cradle.integrators.lattice_travelling.newton_core_first`); and through :mod:`.tail_zeros` /lattice_zeros.
"""
from __future__ import annotations

import math
import time as _time
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.travelling_breathers.dps_family import verdict
from cradle.analyses.travelling_breathers.lattice_members import (
    LATTICE_TRIVIAL,
    RING_MEMBER,
    _padded,
    by_step,
    carried,
    lattice_source,
    lattice_tb,
    launched_pair,
    matched_dps,
    ring_member,
)
from cradle.analyses.travelling_breathers.tail_zeros import lattice_zeros

if TYPE_CHECKING:

    from cradle.analyses.protocol import Log
    from cradle.analyses.travelling_breathers import TravellingBreathers
    from cradle.integrators.dps_travelling import TravellingBreather
    from cradle.integrators.lattice_travelling import LatticeTB


def lattice_groups(spec: TravellingBreathers, fam: list[TravellingBreather],
                   log: Log | None = None) -> tuple[dict, dict]:
    """The groups /lattice (the continuation in c at the first of ``lattice_eps``), /lattice_eps (one exact TB at
    eps: residual, tail, multipliers, distance to the DpS TB through the ansatz, and item 3's launched pair),
    /lattice_states and /lattice_motion, and their attributes (prefixed ``lattice_``)."""
    from cradle.integrators import lattice_breathers as LB, lattice_travelling as LT
    from cradle.models import dps_travelling as M

    t0 = _time.process_time()
    say = log or (lambda *a: None)
    source = lattice_source(spec, fam)
    tbs, starts, dist, dps_m, pairs = [], [], [], [], []
    for eps in spec.lattice_eps:
        b, info = lattice_tb(spec, source, eps, log)
        d = matched_dps(spec, source, b)
        tbs.append(b)
        starts.append(info)
        dps_m.append(d)
        dist.append(LT.ansatz_distance(b, d.A, d.T))
        pairs.append(launched_pair(spec, source, b, eps))
        say(f"travelling-breathers: lattice TB from eps = {eps:g}: T = {b.T:.10g} (ansatz {info['T_hop']:.6g}), "
            f"eps_b = {b.eps:.6g}, residual {b.residual:.2g}, {b.iterations} iterations, distance to DpS "
            f"{dist[-1]['distance']:.3g}")
    ver = [verdict(b, spec.stability_threshold, LATTICE_TRIVIAL) for b in tbs]
    eps_b = np.array([b.eps for b in tbs]) / math.sqrt(spec.norm)
    distance = np.array([x["distance"] for x in dist])
    fit, cov = np.polyfit(np.log(eps_b), np.log(distance), 1, cov=True)
    # the continuation in c from the first TB
    first = tbs[0]
    steps = np.asarray(spec.lattice_steps, float)
    cs = first.c * (1.0 + steps)
    # steps halved down to a tenth of the grid's (the amplitude moves some 30 times faster than c along the family)
    least = 0.1 * float(np.min(np.diff(steps))) if steps.size > 1 else 0.001
    down, _ = LT.continue_family(first, cs[steps < 0][::-1], spec.newton_tol, min_step=least, log=log)
    up, _ = LT.continue_family(first, cs[steps > 0], spec.newton_tol, min_step=least, log=log)
    family = down[::-1] + [first] + up
    fver = [verdict(b, spec.stability_threshold, LATTICE_TRIVIAL) for b in family]
    run = LT.direct_run(first, spec.lattice_periods)
    N = first.z.size // 2
    c_f = np.array([b.c for b in family])
    groups = {
        "/lattice": ({"period": 1.0 / c_f, "eps": [b.eps / math.sqrt(spec.norm) for b in family],
                      "energy": [b.energy for b in family], "residual": [b.residual for b in family],
                      "tail": [M.tail_amplitude(b.envelope) for b in family],
                      "trivial_defect": [v[0] for v in fver], "growth_rate": [v[1] for v in fver],
                      "unstable": [int(v[2]) for v in fver],
                      "reciprocal_defect": [LB.multiplier_checks(b.multipliers)["reciprocal"] for b in family],
                      "smallest_singular": [b.smallest_singular for b in family]},
                     {"c_lattice": c_f}),
        "/lattice_eps": ({"period": [b.T for b in tbs], "c_tb": [b.c for b in tbs], "eps_tb": eps_b,
                          "ansatz_period": [x["T_hop"] for x in starts],
                          "start_residual": [x["start_residual"] for x in starts],
                          "residual": [b.residual for b in tbs], "iterations": [b.iterations for b in tbs],
                          "energy": [b.energy for b in tbs], "tail": [M.tail_amplitude(b.envelope) for b in tbs],
                          "trivial_defect": [v[0] for v in ver], "growth_rate": [v[1] for v in ver],
                          "unstable": [int(v[2]) for v in ver],
                          "reciprocal_defect": [LB.multiplier_checks(b.multipliers)["reciprocal"] for b in tbs],
                          "smallest_singular": [b.smallest_singular for b in tbs],
                          "dps_c": [d.c for d in dps_m],
                          "resonance": [math.remainder(d.theta + b.T, 2.0 * math.pi) for b, d in zip(tbs, dps_m,
                                                                                                   strict=True)],
                          "ansatz_distance": distance,
                          **{k: [p[k] for p in pairs] for k in ("dps_speed", "exact_speed", "dps_radiation",
                                                                "exact_radiation", "exact_radiation_max",
                                                                "dps_energy_drift", "exact_energy_drift")}},
                         {"eps_lattice": list(spec.lattice_eps)}),
        "/lattice_states": ({"x": np.array([b.z[:N] for b in tbs]), "v": np.array([b.z[N:] for b in tbs]),
                             "mu_re": np.array([b.multipliers.real for b in tbs]),
                             "mu_im": np.array([b.multipliers.imag for b in tbs]),
                             "dps_A_re": np.array([d.A.real for d in dps_m]),
                             "dps_A_im": np.array([d.A.imag for d in dps_m]),
                             "source_A_re": source.A.real, "source_A_im": source.A.imag},
                            {"eps_lattice": list(spec.lattice_eps), "site": np.arange(N), "mode": np.arange(2 * N)}),
    }
    groups["/lattice_motion"] = ({"dps_distance": np.array([p["dps_distance"] for p in pairs]),
                                  "exact_distance": np.array([p["exact_distance"] for p in pairs])},
                                 {"eps_lattice": list(spec.lattice_eps), "s_lattice": pairs[0]["s"]})
    attrs = {"lattice_source_c": source.c,
             "lattice_max_residual": float(max(b.residual for b in tbs + family)),
             "lattice_max_trivial_defect": float(max(v[0] for v in ver + fver)),
             "lattice_max_reciprocal_defect": float(max(LB.multiplier_checks(b.multipliers)["reciprocal"]
                                                        for b in tbs + family)),
             "lattice_n_unstable": int(sum(v[2] for v in ver + fver)),
             "lattice_distance_power": float(fit[0]), "lattice_distance_power_error": float(math.sqrt(cov[0, 0])),
             "lattice_distance_power_expected": spec.alpha - 1.0,
             "lattice_c_reached": f"{c_f[0]:.8g} to {c_f[-1]:.8g} ({len(family)} of {len(cs)} members)",
             "lattice_direct_periods": spec.lattice_periods,
             "lattice_direct_energy_drift": float(np.max(run["energy_drift"])),
             "lattice_direct_max_residual": float(np.max(run["residual"])),
             "lattice_method": "Gauss-Newton on R = S^{-1} Phi_T(z) - z at fixed T with the time-shift phase "
                               "condition; Phi_T by DOP853 with contact events (rtol "
                               f"{LT.RTOL:g}), the Jacobian by the variational equations (rtol {LT.JAC_RTOL:g}); the "
                               "near-symmetry's direction left out of the step (truncated least squares) until the "
                               "residual is what it alone can remove",
             "lattice_cpu_s": _time.process_time() - t0}
    more, more_attrs = lattice_rings_groups(spec, source, tbs, by_step(cs, family), log)
    return groups | more, attrs | more_attrs



def lattice_rings_groups(spec: TravellingBreathers, source: TravellingBreather, tbs: list[LatticeTB],
                         family: list[LatticeTB | None], log: Log | None = None) -> tuple[dict, dict]:
    """The groups /lattice_rings (the TBs at every lattice_eps on the ring of lattice_N and on every ring of
    ``lattice_rings``; the continuation in c on ``lattice_family_rings``) and /lattice_large (TBs at
    ``lattice_large_eps`` on the ring of lattice_N by :func:`LT.newton_core_first`), with their attributes
    (prefixed ``lattice_rings_``, ``lattice_large_``). ``source``: the DpS member whose ansatz started ``tbs`` (the
    TBs at lattice_eps); ``family``: the members of /lattice at the lattice_steps (None where not reached)."""
    from cradle.integrators import lattice_travelling as LT

    t0 = _time.process_time()
    say = log or (lambda *a: None)
    rings = [spec.lattice_N, *spec.lattice_rings]
    steps = np.asarray(spec.lattice_steps, float)
    i0 = int(np.argmin(np.abs(steps)))
    eps_rows: list[list[LatticeTB | None]] = [list(tbs)]
    fam_rows: list[list[LatticeTB | None]] = [list(family)]
    for N in spec.lattice_rings:
        # each member from the same member of the ring before (the first ring: the ring of lattice_N)
        row = [None if p is None else carried(spec, p, N, log) for p in eps_rows[-1]]
        eps_rows.append(row)
        fam: list[LatticeTB | None] = [None] * steps.size
        first = row[0]
        if N in spec.lattice_family_rings and first is not None:
            cs = first.c * (1.0 + steps)
            least = 0.1 * float(np.min(np.diff(steps))) if steps.size > 1 else 0.001
            # the corrector on the core first: the predictor's error would otherwise put a tail on the far sites
            down, _ = LT.continue_family(first, cs[:i0][::-1], spec.newton_tol, min_step=least, log=log,
                                         core_first=True)
            up, _ = LT.continue_family(first, cs[i0 + 1:], spec.newton_tol, min_step=least, log=log, core_first=True)
            fam = by_step(cs, down[::-1] + [first] + up)
        fam_rows.append(fam)
        say(f"travelling-breathers: lattice TBs on the ring of {N}: " + ", ".join(
            "-" if b is None else f"eps {b.eps:.4g} residual {b.residual:.2g}" for b in row)
            + (f"; {sum(b is not None for b in fam)} of {steps.size} members in c" if N in spec.lattice_family_rings
               else ""))
    width = max(rings)
    eps_vals = [[ring_member(b, spec) for b in row] for row in eps_rows]
    fam_vals = [[ring_member(b, spec) for b in row] for row in fam_rows]
    xe, ve = zip(*[_padded(row, width) for row in eps_rows], strict=True)
    xf, vf = zip(*[_padded(row, width) for row in fam_rows], strict=True)
    data = {k: np.array([[m[k] for m in row] for row in eps_vals]) for k in RING_MEMBER}
    data |= {f"{k}_family": np.array([[m[k] for m in row] for row in fam_vals]) for k in RING_MEMBER}
    data |= {"x": np.array(xe), "v": np.array(ve), "x_family": np.array(xf), "v_family": np.array(vf),
             "c_family": np.array([[math.nan if b is None else b.c for b in row] for row in fam_rows])}
    stored = [b for row in eps_rows + fam_rows for b in row if b is not None]
    cpu_rings = _time.process_time() - t0
    large, large_attrs = lattice_large(spec, source, log)
    zeros, zeros_attrs = lattice_zeros(spec, rings, eps_rows, fam_rows, log)
    groups = {"/lattice_rings": (data, {"ring": rings, "eps_lattice": list(spec.lattice_eps),
                                        "c_step": list(steps), "ring_site": np.arange(width)}),
              **large, **zeros}
    attrs = {"lattice_rings_max_residual": float(max(b.residual for b in stored)),
             "lattice_rings_reached": f"{sum(b is not None for row in eps_rows for b in row)} of "
                                      f"{len(rings) * len(tbs)} members at lattice_eps, "
                                      f"{sum(b is not None for row in fam_rows[1:] for b in row)} of "
                                      f"{len(spec.lattice_family_rings) * steps.size} in c beyond the first ring",
             "lattice_rings_method": "each ring's TB from the same member of the ring before, sites at rest added on "
                                     "the far side (the breather centred), Newton at the same T; the continuation in "
                                     "c as on the ring of lattice_N, its corrector on the core's unknowns first",
             "lattice_rings_cpu_s": cpu_rings, **large_attrs, **zeros_attrs}
    return groups, attrs


def lattice_large(spec: TravellingBreathers, source: TravellingBreather, log: Log | None = None) -> tuple[dict, dict]:
    """The group /lattice_large: the exact TBs from the ansatz of the DpS member ``source`` at each
    ``lattice_large_eps`` on the ring of lattice_N, by :func:`LT.newton_core_first` at the period of the closest
    return (:func:`LT.launch_period`); its attributes prefixed ``lattice_large_``. Empty without such eps."""
    from cradle.integrators import lattice_travelling as LT

    if not spec.lattice_large_eps:
        return {}, {}
    t0 = _time.process_time()
    say = log or (lambda *a: None)
    members, extra = [], []
    for eps in spec.lattice_large_eps:
        z, T_hop = LT.ansatz_start(source.A, source.T, spec.alpha, eps)
        T, start_res = LT.launch_period(z, T_hop, spec.alpha)
        b, core_res = LT.newton_core_first(z, T, spec.alpha, tol=spec.newton_tol, max_iter=20, log=log)
        say(f"travelling-breathers: lattice TB at eps = {eps:g} (core first): residual {b.residual:.2g}, "
            f"converged {b.converged}")
        members.append(b)
        extra.append({"ansatz_period": T_hop, "start_residual": start_res, "core_residual": core_res,
                      "converged": int(b.converged)})
    vals = [ring_member(b, spec) for b in members]
    data: dict[str, object] = {k: [m[k] for m in vals] for k in RING_MEMBER}
    data |= {k: [e[k] for e in extra] for k in extra[0]}
    data |= {"x": np.array([b.z[:b.z.size // 2] for b in members]),
             "v": np.array([b.z[b.z.size // 2:] for b in members])}
    attrs = {"lattice_large_max_residual": float(max(b.residual for b in members)),
             "lattice_large_method": "Newton in two stages at the period of the closest return: the core's unknowns "
                                     f"alone (|xi_n| above {LT.CORE:g} of the largest) to a residual of "
                                     f"{LT.CORE_TOL:g}, the far sites at the ansatz's values, then all unknowns",
             "lattice_large_cpu_s": _time.process_time() - t0}
    return {"/lattice_large": (data, {"eps_large": list(spec.lattice_large_eps),
                                      "site": np.arange(spec.lattice_N)})}, attrs
