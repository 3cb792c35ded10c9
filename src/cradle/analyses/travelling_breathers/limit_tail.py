"""The DpS TBs' verdicts in the limit N -> infinity read from the tail (:data:`TAIL_RULE`) and from the member
itself (:data:`MEMBER_RULE`), on the rings of ``limit_N`` and ``limit_large_N`` (groups /limit_tail, /limit_large).

Issue 37, "verdicts robust to the discretisation", with an input that does not change with N: the tail. A TB on the
infinite lattice carries a tail that never vanishes (James 2018), a plane wave of wavenumber q = theta; the
linearisation about the TB has the tail's own spectrum as its essential spectrum (in the TB's frame shifted by an
imaginary Doppler term only), so a tail that is modulationally unstable makes the TB unstable at the tail's MI rate,
whatever its core does. theta is the same on every ring and tolerance (/limit_tail/theta_spread); whether the plane
wave is modulationally unstable is cos q < 0 for every amplitude (mi_diagram.max_growth_rate). Only the members
whose tail is stable need the extrapolation of their finite-size instabilities in N.
"""
from __future__ import annotations

import math
import time as _time
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.travelling_breathers.fine_scan import (
    LIMIT_STABLE,
    LIMIT_UNDECIDED,
    LIMIT_UNSTABLE,
    limit_grid,
    limit_member,
    limit_scan,
)

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from cradle.analyses.protocol import Log
    from cradle.analyses.travelling_breathers import TravellingBreathers


TAIL_RULE = ("tail MI-unstable (cos theta < 0, closed form: every tail amplitude R > 0 is unstable at a rate "
             "proportional to R^(alpha-1)): unstable in the limit. Tail MI-stable: the largest growth rate over the "
             "member's neighbourhood c +- limit_halfwidth, on the points whose own tail is MI-stable and that every "
             "ring's grid holds, on each ring of limit_N and limit_large_N, fitted as g_inf + b N^-k (its error the "
             "larger of the standard error and g_inf's change when the smallest or the largest ring is left out); "
             "stable when g_inf plus TAIL_RULE_SIGMAS errors is below the stability threshold, unstable when g_inf "
             "less that many errors is above it, undecided otherwise (both are consistent with the fit: a g_inf "
             "merely consistent with 0 is not enough), when the fit is missing (fewer than 4 rings) and when it is "
             "degenerate (k on a bound of its range: its error is then no error of g_inf)")
#: a verdict from the fit needs g_inf this many standard errors on one side of the stability threshold
TAIL_RULE_SIGMAS = 2.0


def tail_mi_unstable(theta: float) -> bool:
    """Whether the tail's plane wave e^{i theta n} is modulationally unstable (cos theta < 0, any amplitude)."""
    return math.cos(theta) < 0.0


def common_points(grids: list[NDArray[np.float64]]) -> NDArray[np.float64]:
    """The velocities every grid holds (rounded to 1e-9, as :func:`limit_grid` rounds)."""
    common = set(np.round(grids[0], 9))
    for g in grids[1:]:
        common &= set(np.round(g, 9))
    return np.array(sorted(common))


def kind_envelope(grid: NDArray[np.float64], growth: NDArray[np.float64], theta: NDArray[np.float64],
                  centre: float, halfwidth: float, unstable_kind: bool, points: NDArray[np.float64]) -> float:
    """The largest growth rate over the grid points within ``halfwidth`` of ``centre`` that are among ``points``
    and whose tail is of the kind ``unstable_kind`` (:func:`tail_mi_unstable`); NaN when none is reached."""
    keep = (np.abs(grid - centre) <= halfwidth + 1e-9) & np.isin(np.round(grid, 9), points) & np.isfinite(growth)
    keep &= np.array([tail_mi_unstable(t) == unstable_kind if np.isfinite(t) else False for t in theta])
    return float(np.max(growth[keep])) if np.any(keep) else np.nan


def tail_rule_verdict(mi_unstable: bool, fit: dict[str, float], threshold: float) -> int:
    """The limit verdict of :data:`TAIL_RULE` from the tail's kind and the fit of the envelope against N
    (:func:`cradle.measurements.floquet_bubbles.fit_limit`)."""
    if mi_unstable:
        return LIMIT_UNSTABLE
    g, err = fit["g_inf"], fit["g_inf_error"]
    if not (np.isfinite(g) and np.isfinite(err)) or fit.get("degenerate", 0.0) == 1.0:
        return LIMIT_UNDECIDED
    if g - TAIL_RULE_SIGMAS * err > threshold:
        return LIMIT_UNSTABLE
    if g + TAIL_RULE_SIGMAS * err < threshold:
        return LIMIT_STABLE
    return LIMIT_UNDECIDED


MEMBER_RULE = ("two questions the envelope of TAIL_RULE mixes: (i) the member itself, its own growth rate at c on "
               "each ring of limit_N and limit_large_N fitted as g_inf + b N^-k and read as TAIL_RULE reads the "
               "envelope, or stable when it is stable on every ring reached, at least 4 of them (member_verdict); "
               "(ii) any TB within c +- limit_halfwidth, the envelope (verdict). A window near c may hold TBs of "
               "another branch of the ring's family (past a fold in c, on a larger tail: /limit_fold), unstable where "
               "the member is not")


def member_verdict(mi_unstable: bool, growth: NDArray[np.float64], fit: dict[str, float], threshold: float) -> int:
    """The limit verdict of the member itself (:data:`MEMBER_RULE`): stable when it is stable on every ring reached
    and at least as many rings as a fit needs are reached (no growth to extrapolate), else the reading of
    :func:`tail_rule_verdict` of its own growth rates' fit."""
    from cradle.measurements import floquet_bubbles as FB

    g = growth[np.isfinite(growth)]
    if not mi_unstable and g.size >= FB.LIMIT_FIT_MIN and np.all(g <= threshold):
        return LIMIT_STABLE
    return tail_rule_verdict(mi_unstable, fit, threshold)


def member_growth(grid: NDArray[np.float64], growth: NDArray[np.float64], c: float) -> float:
    """The growth rate at the grid point c itself (NaN when the grid does not hold c or the scan did not reach it)."""
    hit = np.flatnonzero(np.abs(grid - c) <= 1e-9)
    return float(growth[hit[0]]) if hit.size else np.nan


LARGE_FINE = ("growth", "unstable", "theta", "tail", "tail_mi", "quartet_defect", "mode_share", "mode_core",
              "mode_core_norm")


def mode_rule(kind: NDArray[np.bool_], rings: list[int], growth: NDArray[np.float64], core: NDArray[np.float64],
              threshold: float) -> tuple[dict, dict]:
    """The verdicts of :data:`cradle.measurements.floquet_modes.MODE_RULE` per member (``kind``: its tail is
    MI-unstable, then unstable as :data:`TAIL_RULE` says; ``growth``, ``core``: (member, ring) at c): the group's
    variables (the verdict and the slopes it reads, and the verdict under every threshold and growth reading) and
    the attributes (the rule, the readings as text, and under the key ``mode_reading`` the readings' names: the
    group's coordinate, popped by the caller)."""
    from cradle.measurements import floquet_modes as FM

    def one(j: int, delta: float, resolved: bool) -> tuple[int, dict[str, float]]:
        if kind[j]:
            return LIMIT_UNSTABLE, {}
        return FM.mode_verdict(rings, growth[j], core[j], threshold, delta, resolved)

    main = [one(j, FM.MODE_RULE_THRESHOLDS[0], False) for j in range(kind.size)]
    keys = ("growth_slope", "growth_slope_error", "core_slope", "core_slope_error")
    readings = [(d, r) for r in (False, True) for d in FM.MODE_RULE_THRESHOLDS]
    each = np.array([[one(j, d, r)[0] for d, r in readings] for j in range(kind.size)], int).reshape(kind.size,
                                                                                                    len(readings))
    group = {"mode_verdict": np.array([v for v, _ in main], int),
             **{f"mode_{k}": [i.get(k, np.nan) for _, i in main] for k in keys}, "mode_verdict_readings": each}
    names = [f"delta {d:g}{', resolved' if r else ''}" for d, r in readings]
    letter = {LIMIT_STABLE: "S", LIMIT_UNSTABLE: "U", LIMIT_UNDECIDED: "?"}
    text = "; ".join(f"{name}: " + " ".join(letter[int(v)] for v in each[:, i]) for i, name in enumerate(names))
    return group, {"mode_rule": FM.MODE_RULE, "mode_rule_readings": text,
                   "mode_reading": np.array(names, dtype=object)}


def large_scan(spec: TravellingBreathers, c: NDArray[np.float64], theta: NDArray[np.float64],
               log: Log | None = None) -> tuple[NDArray[np.float64], dict[str, NDArray[np.float64]]]:
    """The rings of ``limit_large_N`` scanned (:func:`limit_scan` at ``limit_large_newton_tol``) over the grid of step
    ``limit_large_step`` around the members whose tail is MI-stable: the grid and, per (ring, point), the
    quantities of :func:`limit_member` named in :data:`LARGE_FINE` (NaN where not reached)."""
    import dataclasses

    stable = np.array([not tail_mi_unstable(t) for t in theta])
    if not spec.limit_large_N or not np.any(stable):
        return np.zeros(0), {k: np.zeros((len(spec.limit_large_N), 0)) for k in LARGE_FINE}
    grid = limit_grid(c[stable], spec.limit_large_step, spec.limit_halfwidth)
    out = {k: np.full((len(spec.limit_large_N), grid.size), np.nan) for k in LARGE_FINE}
    relaxed = dataclasses.replace(spec, newton_tol=spec.limit_large_newton_tol)
    for i, N in enumerate(spec.limit_large_N):
        for j, b in enumerate(limit_scan(relaxed, N, grid, log)):
            if b is not None:
                m = limit_member(b, spec.stability_threshold)
                for k in LARGE_FINE:
                    out[k][i, j] = m[k]
    return grid, out


def tail_rule(spec: TravellingBreathers, c: NDArray[np.float64], theta: NDArray[np.float64], rob: dict,
              limit: tuple[dict, dict], log: Log | None = None) -> tuple[dict, dict]:
    """The groups /limit_tail (per member: the tail's plane wave and its MI in closed form, the envelope of the
    growth rates on every ring, its fit in N and the verdict of :data:`TAIL_RULE`) and /limit_large (the scans of
    :func:`large_scan`), with their attributes (prefixed ``tail_rule_``). ``theta`` the members' theta on the ring
    of N, ``rob`` :func:`robustness`'s arrays, ``limit`` the (data, coords) of /robustness_limit."""
    t0 = _time.process_time()
    grid_large, large = large_scan(spec, c, theta, log)
    groups, attrs = tail_rule_of(spec, c, theta, rob, limit, grid_large, large)
    attrs["tail_rule_cpu_s"] = _time.process_time() - t0
    return groups, attrs


def tail_rule_of(spec: TravellingBreathers, c: NDArray[np.float64], theta: NDArray[np.float64], rob: dict,
                 limit: tuple[dict, dict], grid_large: NDArray[np.float64],
                 large: dict[str, NDArray[np.float64]]) -> tuple[dict, dict]:
    """:func:`tail_rule` from the scans of the larger rings (:func:`large_scan`'s grid and arrays), without its CPU
    attribute: the rule's reading alone (``benchmarks/tb_limit.py --rule`` applies it to stored scans)."""
    from cradle.analyses import mi_diagram
    from cradle.measurements import floquet_bubbles as FB

    data, coords = limit
    grid_small = coords["c_fine"]
    rings = [*spec.limit_N, *spec.limit_large_N]
    points = common_points([grid_small, grid_large] if grid_large.size else [grid_small])
    per_ring = ([(grid_small, data["growth_rate"][i], data["theta"][i]) for i in range(len(spec.limit_N))]
                + [(grid_large, large["growth"][i], large["theta"][i]) for i in range(len(spec.limit_large_N))])
    q = np.array([math.remainder(t, 2 * math.pi) for t in theta])
    kind = np.array([tail_mi_unstable(t) for t in q])
    closed = [mi_diagram.max_growth_rate(float(x), spec.alpha, 1.0) for x in q]
    hw = spec.limit_halfwidth
    # a member whose neighbourhood the larger rings' grid covers is compared on the points every ring holds, any
    # other on the fine grid of limit_N (the larger rings hold none of its points)
    h = spec.limit_large_step
    covered = [grid_large.size > 0 and grid_large[0] - h < x - hw + 1e-9 and grid_large[-1] + h > x + hw - 1e-9
               for x in c]
    envelope = np.array([[kind_envelope(g_, gr, th, float(x), hw, bool(k), points if cov else np.round(grid_small, 9))
                          for g_, gr, th in per_ring] for x, k, cov in zip(c, kind, covered, strict=True)])
    fits = [FB.fit_limit(rings, envelope[j]) for j in range(c.size)]
    verdicts = np.array([tail_rule_verdict(bool(kind[j]), fits[j], spec.stability_threshold)
                         for j in range(c.size)], int)
    def at_member(small: str, larger: str) -> NDArray[np.float64]:
        """(member, ring): the scans' variable ``small`` (limit_N) and ``larger`` (limit_large_N) at each member's c
        (NaN where a scan did not store it: files written before the modes were measured)."""
        rows = ([(grid_small, data[small][i] if small in data else grid_small * np.nan)
                 for i in range(len(spec.limit_N))]
                + [(grid_large, large[larger][i] if larger in large else grid_large * np.nan)
                   for i in range(len(spec.limit_large_N))])
        return np.array([[member_growth(g_, y, float(x)) for g_, y in rows] for x in c])

    # the member itself (question (i) of MEMBER_RULE): its own growth rate at c on each ring, fitted the same way
    at_c = at_member("growth_rate", "growth")
    member_fits = [FB.fit_limit(rings, at_c[j]) for j in range(c.size)]
    member_verdicts = np.array([member_verdict(bool(kind[j]), at_c[j], member_fits[j], spec.stability_threshold)
                                for j in range(c.size)], int)
    # the member's unstable mode (MODE_RULE): its participation ratio over N and core fraction at c on each ring
    modes = {k: at_member(v, w) for k, v, w in (("share", "mode_participation", "mode_share"),
                                                ("core", "mode_core_fraction", "mode_core"),
                                                ("core_norm", "mode_core_fraction_norm", "mode_core_norm"))}
    by_mode, mode_attrs = mode_rule(kind, rings, at_c, modes["core"], spec.stability_threshold)
    # theta on every ring of /robustness and at every tolerance, against the ring of N's: the rule's input
    spread = np.nanmax(np.abs(np.angle(np.exp(1j * (np.vstack([rob["theta_ring"], rob["theta_tol"]])
                                                        - rob["theta_ring"][0])))), axis=0)
    mi_ring = rob["tail_mi_ring"]
    group = {"tail_q": q, "tail_mi_unstable": kind.astype(int), "theta_spread": spread,
             "unit_amplitude_mi_rate": [x[0] for x in closed], "fastest_sideband": [x[1] for x in closed],
             "unstable_band_low": [x[2] for x in closed], "unstable_band_high": [x[3] for x in closed],
             "tail_mi_rate_min": np.nanmin(mi_ring, axis=0), "tail_mi_rate_max": np.nanmax(mi_ring, axis=0),
             "envelope": envelope, **{f"fit_{k}": [f[k] for f in fits] for k in ("g_inf", "g_inf_error", "g_inf_stderr",
                                                                                 "b", "k", "points", "degenerate")},
             "verdict": verdicts, "member_growth": at_c,
             **{f"member_fit_{k}": [f[k] for f in member_fits] for k in ("g_inf", "g_inf_error", "k", "degenerate")},
             "member_verdict": member_verdicts, "member_participation": modes["share"],
             "member_core_fraction": modes["core"], "member_core_fraction_norm": modes["core_norm"], **by_mode}
    reading = mode_attrs.pop("mode_reading")
    groups = {"/limit_tail": (group, {"fit_ring": np.array(rings), "mode_reading": reading})}
    if grid_large.size:
        groups["/limit_large"] = ({"growth_rate": large["growth"], "theta": large["theta"], "tail": large["tail"],
                                   "tail_mi_rate": large["tail_mi"], "quartet_defect": large["quartet_defect"],
                                   "mode_participation": large["mode_share"], "mode_core_fraction": large["mode_core"],
                                   "mode_core_fraction_norm": large["mode_core_norm"],
                                   "unstable": np.where(np.isnan(large["unstable"]), -1,
                                                        large["unstable"]).astype(int)},
                                  {"large_ring": np.array(spec.limit_large_N), "c_large": grid_large})
    attrs = {"tail_rule": TAIL_RULE, "tail_rule_rings": ", ".join(str(n) for n in rings),
             "tail_rule_points": f"{points.size} common velocities, step {float(np.min(np.diff(points))):.3g}"
             if points.size > 1 else f"{points.size}",
             "tail_rule_mi_unstable_c": ", ".join(f"{x:g}" for x in c[kind]) or "none",
             **{f"tail_rule_{name}_c": ", ".join(f"{x:g}" for x in c[verdicts == v]) or "none"
                for name, v in (("stable", LIMIT_STABLE), ("unstable", LIMIT_UNSTABLE),
                                ("undecided", LIMIT_UNDECIDED))},
             "tail_rule_theta_spread_max": float(np.nanmax(spread)), "member_rule": MEMBER_RULE,
             **{f"member_rule_{name}_c": ", ".join(f"{x:g}" for x in c[member_verdicts == v]) or "none"
                for name, v in (("stable", LIMIT_STABLE), ("unstable", LIMIT_UNSTABLE),
                                ("undecided", LIMIT_UNDECIDED))}, **mode_attrs,
             **{f"mode_rule_{name}_c": ", ".join(f"{x:g}" for x in c[by_mode["mode_verdict"] == v]) or "none"
                for name, v in (("stable", LIMIT_STABLE), ("unstable", LIMIT_UNSTABLE),
                                ("undecided", LIMIT_UNDECIDED))}}
    return groups, attrs
