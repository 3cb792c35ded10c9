"""Rows of the claims table (:mod:`cradle.analyses.paper_checks`) for section 4.3, localised initial conditions:
plot18's breather frequencies, half-period shift and radiation, loc1's merging times."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.claims_table import (
    HARMONIC_PRESENT,
    Results,
    Row,
    _fmt,
    agrees_printed,
    printed_tol,
)
from cradle.measurements import breathers, interactions

if TYPE_CHECKING:
    from collections.abc import Iterable

#: "Around 175 ... twice more": a merging time agrees within 15 % of the paper's ("around"); the DpS to exact
#: ratio agrees within [1.5, 2.5] ("twice more")
MERGE_REL_TOL = 0.15
RATIO_RANGE = (1.5, 2.5)


def breather_frequencies(res: Results, cases: Iterable[tuple]) -> list[Row]:
    rows = []
    for scene, amplitude_text, paper in cases:
        w = float(res.initial(scene).attrs["omega_sw"])
        rows.append(Row("plot18", f"omega_sw of the breather with |x_(N/2+1)(0)| = {amplitude_text}", paper,
                        _fmt(w, 5), agrees_printed(paper, w),
                        "amplitude fixed as the paper quotes it; mu = (amplitude/|a_n|)^(alpha-1), "
                        "omega_sw = 1 + mu/(2^alpha tau0) (ansatzapproxst2)", printed_tol(paper)))
    return rows


def half_period(res: Results, scene: str, site: int, paper: str = "83", t_exact: float = 569.4,
                t_approx: float = 565.95, grid: float = 0.05) -> list[Row]:
    """plot18: periods until exact and approximate are half a period apart.

    The precision "approximately 83" carries: the paper compares its profiles with a time shift
    t_exact - t_approx = 3.45 at t ~ 569 (its figure), i.e. the lag its own runs had there. A lag growing
    as t dw/w reaches half a period pi/w after w/(2 dw) = t/(2 lag) periods: 82.0 (t = 565.95) to 82.5
    (t = 569.4), consistent with its 83; with the times printed on a 0.05 grid (lag 3.45 +- 0.05) the
    figure fixes the number only to 80.9-83.7. That range is the tolerance (one unit of the printed 83,
    +-1, would be tighter than the figure the number comes from); both are stated in the row."""
    ex, ap = res.sim(scene, "exact"), res.sim(scene, "dps")
    w = float(ex.attrs["omega_sw"])
    sh = breathers.half_period_shift(ex["t"].values, ex["x"].values[:, site], ap["x"].values[:, site], w)
    p = sh["half_shift_periods"]
    lag = t_exact - t_approx
    lo, hi = t_approx / (2 * (lag + grid)), t_exact / (2 * (lag - grid))
    verdict = "not comparable" if not np.isfinite(p) else "agrees" if lo <= p <= hi else "disagrees"
    return [Row("plot18", "breather periods until exact and approximate are half a period apart",
                f"approximately {paper} (its figure's lag {lag:.2f} at t ~ {t_exact:g} implies "
                f"{t_approx / (2 * lag):.1f}-{t_exact / (2 * lag):.1f})",
                f"{p:.3g} (omega exact {sh['omega_exact']:.5g}, approx {sh['omega_approx']:.5g}; "
                f"{'inside' if agrees_printed(paper, p) == 'agrees' else 'outside'} +-1 of the printed {paper})",
                verdict,
                f"zero crossings of x_{site}(t), pi / |omega_ex - omega_app| / period",
                f"{lo:.1f}-{hi:.1f}: the range the paper's lag {lag:.2f} +- {grid:g} (times on a {grid:g} grid) "
                f"implies, t / (2 lag)")]


def radiation(res: Results, scene: str, t: float, core: float) -> list[Row]:
    rows = []
    for model, paper in (("exact", "yes"), ("dps", "no")):
        ds = res.sim(scene, model)
        x = ds["x"].sel(t=t, method="nearest").values
        amp = float(np.max(np.abs(ds["x"].values[0])))
        rad = breathers.dispersive_amplitude(x, core) / amp
        emitted = rad >= HARMONIC_PRESENT
        rows.append(Row("plot18", f"dispersive waves around the large breather, {model}, t = {t:g}", paper,
                        f"{_fmt(emitted)} (max |x_n| > 6 sites from the core / amplitude = {rad:.2g})",
                        "agrees" if emitted == (paper == "yes") else "disagrees",
                        f"emitted if the far field reaches {HARMONIC_PRESENT} of the initial amplitude",
                        f"yes/no: far field >= {HARMONIC_PRESENT} of the amplitude"))
    return rows


def merging(res: Results, scene: str, paper_exact: str = "175", paper_dps: str = "350") -> list[Row]:
    """loc1: the outcome of the pair in both models (interactions.classify on max_t |x_n| per period) and
    the merging times beside the paper's ~175 (exact) and "twice more" (DpS), and their ratio, under both
    definitions: the final single breather, then the first coalescence of the two humps."""
    rows, times, first = [], {}, {}
    tol = f"+-{MERGE_REL_TOL:.0%} of the paper's ('around')"
    for model, paper in (("exact", paper_exact), ("dps", paper_dps)):
        ds = res.sim(scene, model)
        T = 2 * np.pi / float(ds.attrs["omega_sw"])
        oc = interactions.classify_run(ds, T)
        first[model] = oc.first_coalescence
        mt = times[model] = oc.merge_period
        total = (float(ds["t"].values[-1]) - float(ds["t"].values[0])) / T
        ours = (f"merge after {mt:.0f} periods" if oc.outcome == "merge"
                else f"{oc.outcome}, no merging within {total:.0f} periods")
        rows.append(Row("loc1", f"merging time of the two breathers, {model}, in breather periods",
                        paper if model == "exact" else f"~{paper} (twice the exact)", ours, _time_verdict(mt, paper),
                        "interactions.classify: first period of the final single breather in max_t |x_n| per "
                        "period (count smoothed over 11 periods, lasting >= 20)", tol))
    rows.append(_ratio_row("merging time DpS / exact", times, "ratio of the two merging times above"))
    # the second definition: the bound pair breathes (its humps approach, overlap and part), so the first
    # period in which they are one hump comes long before the final single breather
    for model, paper in (("exact", paper_exact), ("dps", paper_dps)):
        fc = first[model]
        rows.append(Row("loc1", f"merging time as first coalescence of the two breathers, {model}, in breather periods",
                        paper if model == "exact" else f"~{paper} (twice the exact)",
                        f"first coalescence after {fc:.0f} periods" if np.isfinite(fc) else "no coalescence",
                        _time_verdict(fc, paper),
                        "interactions.classify: first period of the first single state in max_t |x_n| per period "
                        "(count smoothed over 11 periods), however long it lasts", tol))
    rows.append(_ratio_row("first coalescence DpS / exact", first, "ratio of the two first coalescences above"))
    return rows


def _time_verdict(periods: float, paper: str) -> str:
    """A merging time against the paper's "around" value: within :data:`MERGE_REL_TOL` of it."""
    if not np.isfinite(periods):
        return "not comparable"
    return "agrees" if abs(periods - float(paper)) <= MERGE_REL_TOL * float(paper) else "disagrees"


def _ratio_row(quantity: str, times: dict, how: str) -> Row:
    """The DpS / exact ratio of two merging times against the paper's "twice more" (:data:`RATIO_RANGE`)."""
    ratio = times["dps"] / times["exact"] if np.isfinite(times["exact"]) and times["exact"] > 0 else float("nan")
    verdict = ("not comparable" if not np.isfinite(ratio)
               else "agrees" if RATIO_RANGE[0] <= ratio <= RATIO_RANGE[1] else "disagrees")
    return Row("loc1", quantity, "2 ('twice more')", _fmt(ratio, 3), verdict, how,
               f"in [{RATIO_RANGE[0]:g}, {RATIO_RANGE[1]:g}]")
