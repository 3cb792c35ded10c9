"""Where the (nc) TB's tail vanishes (issue 37, item 2: "the parameters where it nearly vanishes"): the signed tail of
a lattice TB (:mod:`cradle.integrators.lattice_tail`) followed along the branch of each of the two members where the
far field is least (the TB at ``lattice_zero_eps``, the continuation's member at ``lattice_zero_step``) on a fine
grid of c, and its zero located by regula falsi (group /lattice_zeros).
"""
from __future__ import annotations

import math
import time as _time
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.travelling_breathers.dps_family import verdict
from cradle.analyses.travelling_breathers.lattice_members import LATTICE_TRIVIAL, by_step, ring_member

if TYPE_CHECKING:

    from cradle.analyses.protocol import Log
    from cradle.analyses.travelling_breathers import TravellingBreathers
    from cradle.integrators.lattice_tail import SignedTail
    from cradle.integrators.lattice_travelling import LatticeTB


#: the regula falsi's iterates at most (from the measured slopes, one to three reach the floor)
ZERO_ITERATIONS = 4
#: the numbers of each grid point and of each located zero in /lattice_zeros
ZERO_POINT = ("c_tb", "period", "eps_tb", "dps_c", "residual", "sigma", "tail", "phase_defect")
#: the located zero's further numbers: its Floquet verdict, the symmetric time's defect, the bracket, the iterates
ZERO_MORE = ("c_error", "symmetry_defect", "trivial_defect", "growth_rate", "unstable", "reciprocal_defect",
             "bracket_low", "bracket_high", "iterations")


def zero_point(b: LatticeTB | None, s: SignedTail | None, spec: TravellingBreathers) -> dict[str, float]:
    """The numbers :data:`ZERO_POINT` of one member and its signed tail (NaN for a member not reached)."""
    m = ring_member(b, spec)
    if b is None or s is None:
        return dict.fromkeys(ZERO_POINT, math.nan)
    return {k: m[k] for k in ZERO_POINT if k in m} | {"c_tb": b.c, "sigma": s.sigma, "phase_defect": s.phase_defect}


def zero_grid(spec: TravellingBreathers, start: LatticeTB,
              log: Log | None) -> list[tuple[LatticeTB, SignedTail] | None]:
    """(member, signed tail) at each c = c1 (1 + s), s of ``lattice_zero_grid``, c1 the velocity of ``start`` (None
    where the continuation stopped): :func:`LT.continue_family` from ``start`` down and up with the plain corrector
    (the grid's steps leave a predictor error far below the far field)."""
    from cradle.integrators import lattice_tail as LTail, lattice_travelling as LT

    grid = np.asarray(spec.lattice_zero_grid, float)
    cs = start.c * (1.0 + grid)
    least = 0.125 * float(np.min(np.diff(grid))) if grid.size > 1 else 1e-4
    down, _ = LT.continue_family(start, cs[grid < 0][::-1], spec.newton_tol, min_step=least, log=log)
    up, _ = LT.continue_family(start, cs[grid > 0], spec.newton_tol, min_step=least, log=log)
    members = by_step(cs, [*down[::-1], start, *up])
    return [None if b is None else (b, LTail.signed_tail(b.z, b.T, b.alpha)) for b in members]


def zero_bracket(points: list[tuple[LatticeTB, SignedTail] | None]) -> int | None:
    """i such that the grid points i and i + 1 bracket a zero of the signed tail: their signs differ, and beyond them
    the tail grows away (|sigma| larger with the same sign at i - 1 or at i + 2) and shrinks on neither side (a ring
    resonance's bracket, where |sigma| grows towards the sign change, is not a zero's; a point beyond with the other
    sign is a resonance or another zero beyond and says nothing); of several, the one with the smallest larger
    |sigma| of the two. None without one."""
    s = [math.nan if p is None else p[1].sigma for p in points]

    def beyond(i: int, j: int) -> int:
        """+1 if point j has point i's sign and a larger |sigma|, -1 if that sign and a smaller one, else 0."""
        if not 0 <= j < len(s) or not math.isfinite(s[j]) or s[i] * s[j] <= 0:
            return 0
        return 1 if abs(s[j]) > abs(s[i]) else -1

    pairs = []
    for i in range(len(s) - 1):
        if not s[i] * s[i + 1] < 0:
            continue
        outer = (beyond(i, i - 1), beyond(i + 1, i + 2))
        if 1 in outer and -1 not in outer:
            pairs.append((max(abs(s[i]), abs(s[i + 1])), i))
    return min(pairs)[1] if pairs else None


def tail_zero(spec: TravellingBreathers, start: LatticeTB, log: Log | None = None) -> dict:
    """The zero of the signed tail on the branch of ``start``: the grid of :func:`zero_grid`, then
    :func:`LTail.locate_zero` in its bracket (:func:`zero_bracket`); located when the iterates reach the floor,
    |sigma| at most newton_tol (the residuals' bound; below it they scatter). Returns the grid's points (``grid``: a
    dict of :data:`ZERO_POINT` lists), the zero's numbers (``zero``: :data:`ZERO_POINT` and :data:`ZERO_MORE`, NaN
    without a zero located), its state ``z`` (None without) and the iterates' (c, sigma) (``trace``)."""
    from cradle.integrators import lattice_breathers as LB, lattice_tail as LTail

    pts = zero_grid(spec, start, log)
    rows = [zero_point(None, None, spec) if p is None else zero_point(p[0], p[1], spec) for p in pts]
    grid = {k: [r[k] for r in rows] for k in ZERO_POINT}
    zero = dict.fromkeys(ZERO_POINT + ZERO_MORE, math.nan)
    i = zero_bracket(pts)
    if i is None:
        return {"grid": grid, "zero": zero, "z": None, "trace": []}
    (a, sa), (b, sb) = pts[i], pts[i + 1]  # type: ignore[misc]
    m, s, trace = LTail.locate_zero(a, b, sa.sigma, sb.sigma, spec.newton_tol, ZERO_ITERATIONS, log)
    if abs(s.sigma) > spec.newton_tol:
        # the iterates did not reach the floor: a flip within the tail's scatter, not a zero that can be seen
        return {"grid": grid, "zero": zero, "z": None, "trace": trace}
    triv, growth, unstable, _ = verdict(m, spec.stability_threshold, LATTICE_TRIVIAL)
    # the place is known to the c over which the bracket's slope moves sigma by what is not resolved
    slope = abs(sb.sigma - sa.sigma) / abs(b.c - a.c)
    zero = zero_point(m, s, spec) | {"c_error": max(abs(s.sigma), m.residual) / slope,
                                      "symmetry_defect": s.symmetry_defect, "trivial_defect": triv,
                                      "growth_rate": growth, "unstable": int(unstable),
                                      "reciprocal_defect": LB.multiplier_checks(m.multipliers)["reciprocal"],
                                      "bracket_low": a.c, "bracket_high": b.c, "iterations": len(trace)}
    return {"grid": grid, "zero": zero, "z": m.z, "trace": trace}


def lattice_zeros(spec: TravellingBreathers, rings: list[int], eps_rows: list[list[LatticeTB | None]],
                  fam_rows: list[list[LatticeTB | None]], log: Log | None = None) -> tuple[dict, dict]:
    """The group /lattice_zeros: on each ring of ``lattice_zero_rings`` (``rings``, ``eps_rows`` and ``fam_rows``
    as :func:`lattice_rings_groups` builds them) the zero of the signed tail on the branch of the TB at
    lattice_zero_eps and on that of the continuation's member at lattice_zero_step (:func:`tail_zero`); its
    attributes prefixed ``lattice_zeros_``. Empty without such rings."""
    if not spec.lattice_zero_rings:
        return {}, {}
    t0 = _time.process_time()
    say = log or (lambda *a: None)
    j_eps = [float(e) for e in spec.lattice_eps].index(float(spec.lattice_zero_eps))
    j_step = [float(s) for s in spec.lattice_steps].index(float(spec.lattice_zero_step))
    found: list[list[dict | None]] = []
    for N in spec.lattice_zero_rings:
        k = rings.index(N)
        row: list[dict | None] = []
        for start in (eps_rows[k][j_eps], fam_rows[k][j_step]):
            f = None if start is None else tail_zero(spec, start, log)
            row.append(f)
            if f is not None:
                zr = f["zero"]
                say(f"travelling-breathers: tail zero on the ring of {N}: c = {zr['c_tb']:.10g}, sigma "
                    f"{zr['sigma']:.2g}, residual {zr['residual']:.2g}")
        found.append(row)
    width = max(spec.lattice_zero_rings)
    n_grid, n_it = len(spec.lattice_zero_grid), ZERO_ITERATIONS
    blank_grid = {k: [math.nan] * n_grid for k in ZERO_POINT}
    blank = dict.fromkeys(ZERO_POINT + ZERO_MORE, math.nan)
    data: dict[str, object] = {
        f"{k}_grid": np.array([[(blank_grid if f is None else f["grid"])[k] for f in row] for row in found])
        for k in ZERO_POINT}
    data |= {k: np.array([[(blank if f is None else f["zero"])[k] for f in row] for row in found])
             for k in ZERO_POINT + ZERO_MORE}
    trace = np.full((len(found), 2, n_it, 2), np.nan)
    xs, vs = np.full((len(found), 2, width), np.nan), np.full((len(found), 2, width), np.nan)
    for i, row in enumerate(found):
        for j, f in enumerate(row):
            if f is None:
                continue
            for q, cs in enumerate(f["trace"]):
                trace[i, j, q] = cs
            if f["z"] is not None:
                n = f["z"].size // 2
                xs[i, j, :n], vs[i, j, :n] = f["z"][:n], f["z"][n:]
    data |= {"c_iterate": trace[..., 0], "sigma_iterate": trace[..., 1], "x": xs, "v": vs}
    located = [f["zero"] for row in found for f in row if f is not None and np.isfinite(f["zero"]["c_tb"])]
    attrs = {"lattice_zeros_located": f"{len(located)} of {2 * len(found)}",
             "lattice_zeros_max_residual": float(max((z["residual"] for z in located), default=math.nan)),
             "lattice_zeros_max_abs_sigma": float(max((abs(z["sigma"]) for z in located), default=math.nan)),
             "lattice_zeros_method": "signed tail sigma = Re(B / xi_n0) |xi_n0| / max|xi| at the TB's symmetric time "
                                     "(cradle.integrators.lattice_tail); the grid by the continuation in c from each "
                                     "minimum's member, the zero by regula falsi (Illinois) in a sign change of the "
                                     "grid away from which |sigma| grows (zero_bracket), at most "
                                     f"{ZERO_ITERATIONS} iterates, stopped and accepted where |sigma| is at most "
                                     "newton_tol (the residual's bound)",
             "lattice_zeros_cpu_s": _time.process_time() - t0}
    coords = {"zero_ring": list(spec.lattice_zero_rings), "minimum": [0, 1],
              "zero_step": list(spec.lattice_zero_grid), "iterate": np.arange(n_it), "zero_site": np.arange(width)}
    return {"/lattice_zeros": (data, coords)}, attrs
