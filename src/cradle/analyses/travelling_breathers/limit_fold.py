"""The window of c near the family's turning points, followed through them (group /limit_fold).

A window in which a real multiplier leaves +1 is no instability of the member itself: natural continuation in c
stops below it (dA/dT grows without bound: a fold), and followed through the fold by pseudo-arclength the family
comes back in c on a branch with a larger tail, where a real pair leaves +1 and returns at the extrema of H(c), as
Xu et al.'s dH/dc criterion says. The scan of fixed c jumps onto that branch.
"""
from __future__ import annotations

import math
import time as _time
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.travelling_breathers.dps_family import REAL, TRIVIAL, first_member, verdict
from cradle.analyses.travelling_breathers.fine_scan import LIMIT_MIN_STEP
from cradle.models.multipliers import split_trivial

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from cradle.analyses.protocol import Log
    from cradle.analyses.travelling_breathers import TravellingBreathers
    from cradle.integrators.dps_travelling import TravellingBreather


#: the step in c of the natural continuation that finds the fold, and the pseudo-arclength step in (A, theta, T)
FOLD_STEP, FOLD_DS = 2e-4, 1e-2
FOLD = ("on each ring of limit_fold_N: the family continued from the first member upwards in c in steps of FOLD_STEP "
        "until the step, halved down to LIMIT_MIN_STEP of c, fails (the family turns), then followed by "
        "pseudo-arclength (steps FOLD_DS in (Re A, Im A, theta, T)) for limit_fold_points members while c stays "
        "within limit_halfwidth of the first member; per member c, H, the growth rate, the growth rate of a real "
        "multiplier above +1 and the tail. Xu et al.'s criterion: a real pair leaves +1 where dH/dc changes sign")


def real_growth(b: TravellingBreather) -> float:
    """ln mu / T of the largest real multiplier mu > 1 among the non-trivial ones (0 when there is none): the growth
    through +1 that the dH/dc criterion is about."""

    mu = b.multipliers
    rest = mu[split_trivial(mu, TRIVIAL)[1]]
    real = rest[(np.abs(rest.imag) <= REAL * np.abs(rest)) & (rest.real > 1.0)]
    return float(np.log(np.max(real.real)) / b.T) if real.size else 0.0


def fold_scan(spec: TravellingBreathers, N: int, log: Log | None = None) -> dict[str, NDArray[np.float64]]:
    """The family on the ring of N through its fold nearest above the first member (:data:`FOLD`): arrays c, H,
    theta, growth, real_growth, tail, residual and the states A (arc, site) along the arclength (first the natural
    continuation's members, then the pseudo-arclength ones), padded to ``limit_fold_points`` plus the natural ones
    with NaN."""
    from cradle.integrators import dps_travelling as DT
    from cradle.models import dps_travelling as M

    first = first_member(spec, N, spec.rtol)
    hw = spec.limit_halfwidth
    grid = np.round(first.c + FOLD_STEP * np.arange(1, int(hw / FOLD_STEP) + 1), 9)
    fam, _ = DT.continue_family(first, grid, spec.limit_large_newton_tol, spec.rtol, min_step=LIMIT_MIN_STEP)
    last = fam[-1] if fam else first
    arc = DT.continue_arclength(last, FOLD_DS, spec.limit_fold_points, (first.c - hw, first.c + hw),
                                spec.limit_large_newton_tol, spec.rtol, log=log)
    members = [first, *fam, *arc[1:]]
    width = spec.limit_fold_points + grid.size + 1
    out = {k: np.full(width, np.nan) for k in ("velocity", "energy", "theta", "growth", "real_growth", "tail",
                                               "residual")}
    out["A_re"], out["A_im"] = np.full((width, N), np.nan), np.full((width, N), np.nan)
    for i, b in enumerate(members):
        out["A_re"][i], out["A_im"][i] = b.A.real, b.A.imag
        out["velocity"][i], out["energy"][i] = b.c, b.energy
        out["theta"][i] = math.remainder(b.theta, 2 * math.pi)
        out["growth"][i] = verdict(b, spec.stability_threshold)[1]
        out["real_growth"][i], out["tail"][i], out["residual"][i] = real_growth(b), M.tail_amplitude(b.A), b.residual
    if log:
        log(f"travelling-breathers: fold scan, ring of {N}: {len(fam)} members by c up to c = {last.c:.6g}, "
            f"{len(arc) - 1} by arclength")
    return out


def fold_turns(c: NDArray[np.float64], H: NDArray[np.float64]) -> tuple[list[float], list[float]]:
    """(folds, extrema): the c where the arclength's c turns (dc changes sign) and where H(c) has an extremum
    along a branch (dH changes sign while c keeps its direction), each the c of the middle member."""
    ok = np.isfinite(c)
    c, H = c[ok], H[ok]
    dc, dH = np.diff(c), np.diff(H)
    folds = [float(c[i + 1]) for i in range(dc.size - 1) if dc[i] * dc[i + 1] < 0]
    extrema = [float(c[i + 1]) for i in range(dc.size - 1) if dc[i] * dc[i + 1] > 0 and dH[i] * dH[i + 1] < 0]
    return folds, extrema


def real_edges(c: NDArray[np.float64], g: NDArray[np.float64], threshold: float) -> list[float]:
    """The c midway between consecutive members along the arclength where the growth through +1 crosses the
    stability threshold (a real pair leaving or returning to +1)."""
    ok = np.isfinite(c)
    c, above = c[ok], g[ok] > threshold
    return [float(0.5 * (c[i] + c[i + 1])) for i in range(c.size - 1) if above[i] != above[i + 1]]


def fold_group(spec: TravellingBreathers, log: Log | None = None) -> tuple[dict, dict]:
    """The group /limit_fold (:func:`fold_scan` on each ring of limit_fold_N) and its attributes: per ring the folds
    in c, the extrema of H(c) and the c where a real pair crosses the threshold through +1."""
    t0 = _time.process_time()
    scans = [fold_scan(spec, N, log) for N in spec.limit_fold_N]
    width, sites = max(s["velocity"].size for s in scans), max(spec.limit_fold_N)
    data = {k: np.array([np.pad(s[k], [(0, width - s[k].shape[0])] + [(0, sites - N)] * (s[k].ndim - 1),
                                constant_values=np.nan) for s, N in zip(scans, spec.limit_fold_N, strict=True)])
            for k in scans[0]}
    attrs: dict = {"fold_rule": FOLD}
    for N, s in zip(spec.limit_fold_N, scans, strict=True):
        folds, extrema = fold_turns(s["velocity"], s["energy"])
        attrs[f"fold_{N}_c_turns"] = ", ".join(f"{x:.7f}" for x in folds) or "none"
        attrs[f"fold_{N}_dH_dc_zero"] = ", ".join(f"{x:.7f}" for x in extrema) or "none"
        attrs[f"fold_{N}_real_edges"] = ", ".join(f"{x:.7f}" for x in real_edges(s["velocity"], s["real_growth"],
                                                                                  spec.stability_threshold)) or "none"
        attrs[f"fold_{N}_largest_real_growth"] = float(np.nanmax(s["real_growth"]))
    attrs["fold_cpu_s"] = _time.process_time() - t0
    return {"/limit_fold": ({k: v for k, v in data.items()},
                            {"fold_ring": np.array(spec.limit_fold_N), "arc": np.arange(width),
                             "fold_site": np.arange(sites)})}, attrs
