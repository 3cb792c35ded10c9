"""The DpS TBs' verdicts in the limit N -> infinity from fine scans (group /robustness_limit).

Issue 37, "verdicts robust to the discretisation": on a ring the family's verdict at a given c flips with N because
the instabilities come in narrow windows of c whose places move with N. Each member's neighbourhood is scanned in
fine steps of c on rings of growing N; the limit verdict is read from how the neighbourhood's growth rates change
with N (:data:`LIMIT_RULE`); a window resolved as a Krein collision (:func:`bubble_scan`).
"""
from __future__ import annotations

import math
import time as _time
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.travelling_breathers.dps_family import TRIVIAL, first_member, verdict
from cradle.analyses.travelling_breathers.verdict_checks import tail_mi_rate, tail_wave
from cradle.measurements import floquet_modes as FM
from cradle.models.multipliers import split_trivial

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from cradle.analyses.protocol import Log
    from cradle.analyses.travelling_breathers import TravellingBreathers
    from cradle.integrators.dps_travelling import TravellingBreather


#: limit verdicts per member (/robustness_limit/verdict): the codes of every limit rule, MODE_RULE's among them
LIMIT_STABLE, LIMIT_UNSTABLE, LIMIT_UNDECIDED = FM.STABLE, FM.UNSTABLE, FM.UNDECIDED
#: consecutive grid points the fine scan may fail to reach before it stops in that direction
LIMIT_MISSES = 4
#: a failed continuation step is halved down to this fraction of c
LIMIT_MIN_STEP = 1e-4
#: a Newton iterate whose max |A| exceeds this many times sqrt(norm) has left the family (a TB's max |A| is below
#: sqrt(norm)): the scan stops that attempt rather than integrate ever stiffer states
LIMIT_RUNAWAY = 3.0
LIMIT_RULE = ("for each member c and ring N, the fine grid c +- limit_halfwidth gives the median growth rate "
              "g_N(c): the typical TB near c, which windows covering less than half of the neighbourhood cannot "
              "set; the typical TB is unstable on that ring when g_N exceeds the stability threshold. The limit "
              "verdict is the typical TB's verdict when the two largest rings that reach the neighbourhood agree "
              "on it, undecided when they differ. The exponents k of g_N and of the largest rate G_N against N "
              "(least-squares slopes of -ln g against ln N where above the threshold) are reported, not used: "
              "they do not settle on these rings")


def limit_grid(c: NDArray[np.float64], step: float, halfwidth: float) -> NDArray[np.float64]:
    """The fine grid: every step from the slowest member minus ``halfwidth`` to the fastest plus it (rounded to
    1e-9), so that the scan walks in steps of ``step`` only (a longer jump of the predictor sends Newton far
    off) and the windows are counted over the whole range."""
    m = int(math.floor(halfwidth / step + 1e-9))
    n = int(round((float(c[-1]) - float(c[0])) / step)) + 2 * m
    grid = float(c[0]) - m * step + step * np.arange(n + 1)
    return np.round(grid[grid > 0], 9)


def limit_scan(spec: TravellingBreathers, N: int, grid: NDArray[np.float64],
               log: Log | None = None) -> list[TravellingBreather | None]:
    """The TBs on the ring of N at the velocities ``grid`` (None where not reached): from the pushed static breather
    (as :func:`family`), continued up and down the grid point by point, a failed step halved down to
    :data:`LIMIT_MIN_STEP` of c; a point not reached is skipped (the next is tried from the last member reached)
    and the scan stops in that direction after :data:`LIMIT_MISSES` misses in a row (the family ends, turns or
    breaks at a resonance of the ring there)."""
    from cradle.integrators import dps_travelling as DT

    first = first_member(spec, N, spec.rtol)
    out: list[TravellingBreather | None] = [None] * grid.size
    if not first.converged:
        if log:
            log(f"travelling-breathers: limit scan, ring of {N}: no TB from the pushed breather (residual "
                f"{first.residual:.3g}); the ring is left out")
        return out

    from cradle.integrators.continuation import continue_in_c

    cap = LIMIT_RUNAWAY * math.sqrt(spec.norm)

    def correct(cur: TravellingBreather, c2: float) -> TravellingBreather:
        A_g, th_g = cur.predict(1.0 / c2)
        return DT.newton(A_g, 1.0 / c2, th_g, spec.alpha, spec.norm, cur.A, spec.newton_tol, max_iter=8,
                         rtol=spec.rtol, max_amplitude=cap)

    def walk(order: NDArray[np.int64]) -> None:
        cur, misses = first, 0
        for i in order:
            fam, _ = continue_in_c(cur, [grid[i]], correct, LIMIT_MIN_STEP, lambda *a: None, "limit scan",
                                   lambda b: "")
            if not fam:
                misses += 1
                if misses >= LIMIT_MISSES:
                    return
                continue
            cur, misses, out[i] = fam[0], 0, fam[0]

    idx = np.arange(grid.size)
    walk(idx[grid >= first.c])
    walk(idx[grid < first.c][::-1])
    if log:
        log(f"travelling-breathers: limit scan, ring of {N}: {sum(b is not None for b in out)} of {grid.size} "
            f"velocities reached")
    return out


def limit_rule(rings: NDArray[np.float64], typical: NDArray[np.float64], threshold: float) -> tuple[int, float]:
    """(verdict, k) of :data:`LIMIT_RULE` for one member: ``typical`` its median growth rate on each ring (NaN: not
    reached there, left out); k the slope of -ln typical against ln N over the rings where it exceeds the
    threshold (NaN with fewer than two)."""
    ok = np.isfinite(typical)
    n, g = rings[ok], typical[ok]
    above = g > threshold
    k = float(-np.polyfit(np.log(n[above]), np.log(g[above]), 1)[0]) if np.sum(above) >= 2 else np.nan
    if n.size < 2:
        return LIMIT_UNDECIDED, k
    last = above[np.argsort(n)[-2:]]
    if last[0] != last[1]:
        return LIMIT_UNDECIDED, k
    return (LIMIT_UNSTABLE if last[1] else LIMIT_STABLE), k


def limit_member(b: TravellingBreather, threshold: float) -> dict[str, float]:
    """One scanned TB: growth rate, verdict, theta, tail, the tail's MI rate, the multipliers' quartet and Krein
    measures (:mod:`cradle.measurements.floquet_bubbles`), how the unstable multiplier leaves the circle (its
    argument: pi through -1, 0 through +1, else a quartet) and where the mode of the largest non-trivial multiplier
    lives (:mod:`cradle.measurements.floquet_modes`: participation ratio over N, core fraction under the first and
    the last of its core definitions)."""
    from cradle.measurements import floquet_bubbles as FB
    from cradle.models import dps_travelling as M

    assert b.monodromy is not None
    _, rate, unstable, _ = verdict(b, threshold)
    mu, sigma, W = FB.krein_modes(b.monodromy)
    _, k = split_trivial(mu, TRIVIAL)
    top = mu[k[int(np.argmax(np.abs(mu[k])))]]
    q, R = tail_wave(b.A)
    mode = FM.mode_measures(b.monodromy, b.A, b.T, TRIVIAL, (FM.CORE_DEFINITIONS[0], FM.CORE_DEFINITIONS[-1]),
                            eig=(mu, W))
    return {"growth": rate, "unstable": float(unstable), "theta": math.remainder(b.theta, 2 * math.pi),
            "tail": M.tail_amplitude(b.A), "tail_mi": tail_mi_rate(q, R, b.alpha),
            "krein_gap": FB.krein_gap(mu, sigma, TRIVIAL), "quartet_defect": FB.quartet_defect(mu),
            "top_arg": float(np.angle(top)) if unstable else np.nan, "mode_share": mode["participation_share"],
            "mode_core": mode["core_fraction_0"], "mode_core_norm": mode["core_fraction_1"]}


def bubble_scan(spec: TravellingBreathers, b: TravellingBreather, cs: NDArray[np.float64], angle: float,
                width: float) -> dict[str, NDArray[np.float64]]:
    """One window resolved: the TBs continued from ``b`` over the velocities ``cs`` (in order; steps halved down to
    :data:`LIMIT_MIN_STEP` of c), at each the largest ln |mu| of the non-trivial multipliers, the argument of that
    multiplier and the splitting of the pair of opposite Krein signature within ``width`` of ``angle``
    (:func:`cradle.measurements.floquet_bubbles.pair_splitting`; NaN inside the bubble, where the pair is a
    quartet off the circle). Returns arrays c, log_modulus, top_arg, splitting, period (NaN where not reached)."""
    from cradle.integrators import dps_travelling as DT
    from cradle.measurements import floquet_bubbles as FB

    fam, _ = DT.continue_family(b, cs, spec.newton_tol, spec.rtol, min_step=LIMIT_MIN_STEP)
    out = {k: np.full(cs.size, np.nan) for k in ("log_modulus", "top_arg", "splitting", "period")}
    byc = {round(m.c, 12): m for m in fam}
    for i, x in enumerate(cs):
        m = byc.get(round(float(x), 12))
        if m is None or m.monodromy is None:
            continue
        mu, sigma = FB.krein_signatures(m.monodromy)
        _, k = split_trivial(mu, TRIVIAL)
        top = mu[k[int(np.argmax(np.abs(mu[k])))]]
        out["log_modulus"][i] = float(np.log(np.abs(top)))
        out["top_arg"][i] = float(np.angle(top))
        out["splitting"][i] = FB.pair_splitting(mu, sigma, angle, width)
        out["period"][i] = m.T
    return {"c": np.asarray(cs, float), **out}


LIMIT_FINE = ("growth", "unstable", "theta", "tail", "tail_mi", "krein_gap", "quartet_defect", "top_arg",
              "mode_share", "mode_core", "mode_core_norm")


def robustness_limit(spec: TravellingBreathers, c: NDArray[np.float64], log: Log | None = None) -> tuple[dict, dict]:
    """The group /robustness_limit and its attributes: every ring of ``limit_N`` scanned over the fine grid around
    the members ``c`` (:func:`limit_scan`, :func:`limit_member` per point), per member and ring the unstable
    fraction, the median and the largest growth rate of its neighbourhood, and per member the limit verdict with
    its exponent (:func:`limit_rule`)."""
    t0 = _time.process_time()
    grid = limit_grid(c, spec.limit_step, spec.limit_halfwidth)
    rings = np.array(spec.limit_N, float)
    fine = {k: np.full((rings.size, grid.size), np.nan) for k in LIMIT_FINE}
    for i, N in enumerate(spec.limit_N):
        for j, b in enumerate(limit_scan(spec, N, grid, log)):
            if b is not None:
                for k, v in limit_member(b, spec.stability_threshold).items():
                    fine[k][i, j] = v
    near = np.abs(grid[None, :] - c[:, None]) <= spec.limit_halfwidth + 1e-9      # (c, fine)
    frac, typical, largest, reached = (np.full((rings.size, c.size), np.nan) for _ in range(4))
    for i in range(rings.size):
        for j in range(c.size):
            g = fine["growth"][i, near[j]]
            g = g[np.isfinite(g)]
            reached[i, j] = g.size / max(int(np.sum(near[j])), 1)
            if g.size:
                frac[i, j] = float(np.mean(g > spec.stability_threshold))
                typical[i, j] = float(np.median(g))
                largest[i, j] = float(np.max(g))
    rule = [limit_rule(rings, typical[:, j], spec.stability_threshold) for j in range(c.size)]
    env = [limit_rule(rings, largest[:, j], spec.stability_threshold)[1] for j in range(c.size)]
    # the windows' ring-by-ring census over the whole fine grid: how many, how wide, how fast
    from cradle.measurements import floquet_bubbles as FB

    census: dict[str, list[float]] = {"count": [], "mean_width": [], "largest": [], "fraction": []}
    for i in range(rings.size):
        ok = np.isfinite(fine["growth"][i])
        w = FB.windows(grid[ok], fine["unstable"][i][ok] == 1)
        census["count"].append(len(w))
        census["mean_width"].append(float(np.mean([b - a + spec.limit_step for a, b in w])) if w else 0.0)
        census["largest"].append(float(np.nanmax(fine["growth"][i])) if np.any(ok) else np.nan)
        census["fraction"].append(float(np.mean(fine["unstable"][i][ok] == 1)) if np.any(ok) else np.nan)
    verdicts = np.array([v for v, _ in rule], int)
    data = {"growth_rate": fine["growth"], "unstable": np.where(np.isnan(fine["unstable"]), -1,
                                                                fine["unstable"]).astype(int),
            "theta": fine["theta"], "tail": fine["tail"], "tail_mi_rate": fine["tail_mi"],
            "krein_gap": fine["krein_gap"], "quartet_defect": fine["quartet_defect"], "top_arg": fine["top_arg"],
            "mode_participation": fine["mode_share"], "mode_core_fraction": fine["mode_core"],
            "mode_core_fraction_norm": fine["mode_core_norm"], "unstable_fraction": frac.T,
            "typical_growth": typical.T, "largest_growth": largest.T,
            "reached": reached.T, "decay": [k for _, k in rule], "envelope_decay": env, "verdict": verdicts,
            "windows": census["count"], "window_width": census["mean_width"],
            "ring_largest_growth": census["largest"], "ring_unstable_fraction": census["fraction"]}
    attrs = {"limit_rule": LIMIT_RULE, "limit_rings": ", ".join(str(n) for n in spec.limit_N),
             "limit_step": spec.limit_step, "limit_halfwidth": spec.limit_halfwidth,
             **{f"limit_{name}_c": ", ".join(f"{x:g}" for x in c[verdicts == v]) or "none"
                for name, v in (("stable", LIMIT_STABLE), ("unstable", LIMIT_UNSTABLE),
                                ("undecided", LIMIT_UNDECIDED))},
             "limit_max_quartet_defect": (float(np.nanmax(fine["quartet_defect"]))
                                          if np.any(np.isfinite(fine["quartet_defect"])) else np.nan),
             "limit_cpu_s": _time.process_time() - t0}
    return {"/robustness_limit": (data, {"limit_ring": rings.astype(int), "c_fine": grid})}, attrs
