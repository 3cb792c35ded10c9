"""The paper's numerical statements against ours: the analysis ``paper-checks`` (the claims table),
results/paper-checks/paper-checks.nc, written out as results/paper-checks/paper-checks.{csv,md} by
:mod:`cradle.figures.paper_checks`.

One row per statement: label or equation, quantity, the paper's value, ours,
verdict, and how ours is measured. Every "ours" is computed here from the
pipeline's netCDF outputs (the initial data, runs and metrics of every scene and
the homoclinic solutions, read by name) or, for closed forms, from cradle's
functions, never typed in. Verdicts:

* ``agrees``: within the precision the paper prints (one unit of its last
  digit, which also covers the paper's truncations such as a ~ 2.11 for
  2.118), or inside the bound it states, or the same yes/no;
* ``disagrees``: outside it;
* ``not comparable``: ours could not be measured (e.g. no merging within the run).

Thresholds that turn a measurement into yes/no are module constants,
documented where they are defined.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.checks_localised import (
    breather_frequencies,
    half_period,
    merging,
    radiation,
)
from cradle.analyses.claims_table import (
    COLUMNS,
    HARMONIC_PRESENT,
    Results,
    Row,
    _fmt,
    agrees_printed,
    explained,
    printed_tol,
    printed_unit,
)
from cradle.analyses.protocol import Analysis, Read, scene_reads
from cradle.data.variables import Var
from cradle.measurements import compare, sidebands
from cradle.models import dps, stationary
from cradle.specs.declare import declared, param, plain

if TYPE_CHECKING:
    from collections.abc import Callable, Iterable

    import xarray as xr
    from numpy.typing import NDArray

    from cradle.analyses.protocol import Log
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors

#: the files of a scene the table may read
SCENE_PARTS = ("initial", "exact", "dps", "metrics")
_ALL = {"type": "string", "const": "all", "description": "Every entry of that config section."}

#: A run is modulationally unstable at time t when its largest sideband
#: (sidebands.sideband_ratio, harmonics excluded) reaches this fraction of the
#: carrier. Stable runs stay at a few percent (DpS at q = pi/2: 0.04), unstable
#: ones exceed 1 (carrier destroyed).
UNSTABLE_RATIO = 0.5
#: A harmonic is "present" when its height is at least HARMONIC_PRESENT of the carrier and it is a coherent
#: peak: its bin stands at least this factor above the median of the 5 bins on
#: each side (sidebands.harmonic_over_band). In a band of unstable modes with random phases |x_hat_k| is
#: Rayleigh distributed, P(|x_hat| > r median) = 2^(-r^2): r = 3 keeps a band bin at one of the two mirror
#: harmonics from passing for a harmonic with probability < 0.4 %.
PEAK_OVER_BAND = 3.0
#: Two waves are "out of phase" when their phase difference at k = q exceeds this.
OUT_OF_PHASE = np.pi / 2
#: A phase shift is "small" below this.
SMALL_SHIFT = np.pi / 4


@declared(doc="The paper's numerical statements against ours (the claims table), from the outputs of the scenes "
              "and homoclinic solutions named here, then the cited papers' statements the analyses named here store "
              "(their claims groups) -> results/paper-checks/paper-checks.nc and "
              "results/paper-checks/paper-checks.{csv,md}; a group of rows that reads an entry not named is left out.")
class PaperChecks:
    scenes: list[str] | str = param("all", "The scenes whose initial data, runs and metrics the table reads (names "
                                    "under scenes:), or all: every scene of the config.",
                                    anyOf=[_ALL, {"type": "array", "items": {"$ref": "#/$defs/name"}}])
    homoclinic: list[str] | str = param("all", "The homoclinic solutions the table reads (names under homoclinic:), "
                                        "or all: every one of the config.",
                                        anyOf=[_ALL, {"type": "array", "items": {"$ref": "#/$defs/name"}}])
    analyses: list[str] | str = param("all", "The analyses beyond the paper whose rows (the cited papers' statements "
                                      "against theirs) the table collects from the output of the form all builds: "
                                      "names under beyond: whose module declares a claims group, or all: every one "
                                      "that does.", anyOf=[{**_ALL, "description": "Every analysis that declares a "
                                                            "claims group."},
                                                           {"type": "array", "items": {"$ref": "#/$defs/name"}}])

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Each analysis named declares a claims group."""
        if isinstance(self.analyses, str):
            return
        every = claiming_analyses()
        for i, name in enumerate(self.analyses):
            if name not in every:
                out.add(where + ["analyses", i], f"no analysis of that name declares claims rows (those that do: "
                        f"{', '.join(every)})", name)


def claiming_analyses() -> list[str]:
    """The analyses that declare a claims group (``claims`` of their :class:`~cradle.analyses.protocol.Analysis`),
    in the registry's order."""
    from cradle.analyses.registry import ANALYSES

    return [a.name for a in ANALYSES.values() if a.claims]


def collected(spec: PaperChecks) -> list[str]:
    """The analyses whose claims rows the table collects: those the spec names, or every one that declares some."""
    return claiming_analyses() if isinstance(spec.analyses, str) else list(spec.analyses)


def reads(spec: PaperChecks) -> dict[str, Read]:
    """The initial data, both runs and the metrics of every scene of the spec (``<scene>/<part>``), every
    homoclinic solution (``homoclinic/<name>``), and the output of every analysis whose claims it collects
    (``analysis/<name>``)."""
    return {**scene_reads(spec.scenes, SCENE_PARTS),
            **{f"homoclinic/{name}": Read.of("homoclinic", name=name) for name in spec.homoclinic},
            **{f"analysis/{name}": Read.of("analysis", analysis=name) for name in collected(spec)}}


# ------------------------------------------------------------------ the rows

def closed_forms() -> list[Row]:
    t0 = dps.tau0(1.5)
    near_one = dps.tau0(1.0 + 1e-9)
    return [
        Row("(tau0)", "tau0 at alpha = 3/2", "1.545", _fmt(t0, 7), agrees_printed("1.545", t0),
            "5 Gamma(1/4)^2 / (24 sqrt(pi)) via log-Gamma (cradle.models.dps.tau0)", printed_tol("1.545")),
        Row("(tau0)", "limit of tau0 as alpha -> 1+", "2", _fmt(near_one, 10), agrees_printed("2", near_one),
            "tau0(1 + 1e-9)", printed_tol("2")),
    ]


def amplitudes(res: Results, scenes: dict) -> list[Row]:
    rows = []
    for scene, paper in scenes.items():
        ini = res.initial(scene)
        a = float(ini.attrs["a"])
        rows.append(Row("(freq)", f"a for q = {ini.attrs['q_expr']}, omega_tw = {float(ini.attrs['omega_tw']):g} "
                        f"(scene {scene})", paper, _fmt(a, 5), agrees_printed(paper, a),
                        "(freq) inverted for a, written in results/initial/<scene>.nc", printed_tol(paper)))
    return rows


def eps_fft106(res: Results, scene: str = "fft106") -> list[Row]:
    eps = float(res.initial(scene).attrs["eps"])
    return [Row("fft106", "eps = a/2 for q = 4pi/5, omega_tw = 1.1", "3.8e-3", _fmt(eps, 4),
                agrees_printed("3.8e-3", eps), "(freq), eps = a/2 with R = 1 (attribute eps)",
                printed_tol("3.8e-3"))]


def relative_error(res: Results, scene: str = "tw-weak", bound: float = 0.05) -> list[Row]:
    m = res.metrics(scene)
    E_end, E_max = float(m["E"].values[-1]), float(m["E"].max())
    t_end = float(m["t"].values[-1])
    how = "E(t) = max_n |x^app_n - x_n| / a on the stored grid (results/metrics/<scene>.nc)"
    return [Row("plot4-5", f"E(t) at t = {t_end:g}", f"< {bound:g}", _fmt(E_end),
                "agrees" if E_end < bound else "disagrees", how, f"the paper's bound < {bound:g}"),
            Row("plot4-5", f"max of E(t) on [0, {t_end:g}]", f"< {bound:g} (text: at the final time)",
                _fmt(E_max), "agrees" if E_max < bound else "disagrees", how, f"the paper's bound < {bound:g}")]


def energy_errors(res: Results, scenes: Iterable[str], bound: float = 3.5e-4) -> list[Row]:
    rows = []
    for scene in scenes:
        ex = res.sim(scene, "exact")
        drift = float(ex.attrs["energy_drift"])
        rows.append(Row("section 4", f"relative energy error of the exact run, scene {scene}", f"< {bound:g}",
                        _fmt(drift, 3), "agrees" if drift < bound else "disagrees",
                        f"max over every step of |H(t)-H(0)|/H(0), {ex.attrs['integrator']}, dt = {ex.attrs['dt']}",
                        f"the paper's bound < {bound:g}"))
    return rows


def _ratio(res: Results, scene: str, model: str, t: float) -> float:
    m = res.metrics(scene)
    q = float(res.sim(scene, "exact").attrs["q"])
    spec = m[f"spectrum_{model}"].sel(t=t, method="nearest")
    return float(sidebands.sideband_ratio(m["k"].values, spec.values, q))


def instability(res: Results, cases: Iterable[tuple[str, str, float, dict[str, str]]]) -> list[Row]:
    """cases: (label, scene, t, {model: paper yes/no})."""
    rows = []
    for label, scene, t, expected in cases:
        q_expr = res.initial(scene).attrs["q_expr"]
        for model, paper in expected.items():
            r = _ratio(res, scene, model, t)
            unstable = r >= UNSTABLE_RATIO
            rows.append(Row(label, f"{model} run unstable by t = {t:g} (q = {q_expr})", paper,
                            f"{_fmt(unstable)} (sideband/carrier = {r:.3g})",
                            "agrees" if (paper == "yes") == unstable else "disagrees",
                            f"sideband_ratio >= {UNSTABLE_RATIO} (max |x_hat_k| off +-q and harmonics, "
                            "over the carrier)", f"yes/no: unstable if sideband/carrier >= {UNSTABLE_RATIO}"))
    return rows


def harmonics_present(res: Results, label: str, scene: str, t: float, which: str,
                      expected: dict[str, str]) -> list[Row]:
    """Whether the lattice harmonic ``which`` (key of sidebands.harmonics) is present: a coherent peak of
    at least HARMONIC_PRESENT of the carrier standing PEAK_OVER_BAND above the local band level (a bin of
    a broad band of unstable modes is not a harmonic)."""
    rows = []
    q = float(res.sim(scene, "exact").attrs["q"])
    m = res.metrics(scene)
    k = m["k"].values
    for model, paper in expected.items():
        spec = m[f"spectrum_{model}"].sel(t=t, method="nearest").values
        h = sidebands.harmonic_height(k, spec, q, which)
        peak = sidebands.harmonic_over_band(k, spec, q, which)
        present = h >= HARMONIC_PRESENT and peak >= PEAK_OVER_BAND
        rows.append(Row(label, f"harmonic k = +-{which} in the {model} spectrum at t = {t:g}", paper,
                        f"{_fmt(present)} (height/carrier = {h:.2g}, over the local band x{peak:.2g})",
                        "agrees" if (paper == "yes") == present else "disagrees",
                        "|x_hat| at the harmonic's bin over |x_hat_q|, and over the median of the 5 bins on each "
                        "side (sidebands.harmonic_over_band), the larger mirror",
                        f"yes/no: present if height >= {HARMONIC_PRESENT} of the carrier and >= "
                        f"{PEAK_OVER_BAND:g} x the local band"))
    return rows


def _phase_at_q(x: NDArray[np.float64], q: float) -> float:
    n = np.arange(x.shape[-1])
    return np.angle(np.sum(x * np.exp(-1j * q * n)))


def _phase_gap(x1: NDArray[np.float64], x2: NDArray[np.float64], q: float) -> float:
    d = _phase_at_q(x1, q) - _phase_at_q(x2, q)
    return abs((d + np.pi) % (2 * np.pi) - np.pi)


def phase_shifts(res: Results, scene: str, small_t: float, out_t: float) -> list[Row]:
    ex, ap = res.sim(scene, "exact"), res.sim(scene, "dps")
    q = float(ex.attrs["q"])
    rows = []
    for t, paper, want_small in ((small_t, "small shift", True), (out_t, "out of phase", False)):
        gap = _phase_gap(ex["x"].sel(t=t, method="nearest").values, ap["x"].sel(t=t, method="nearest").values, q)
        ok = gap < SMALL_SHIFT if want_small else gap > OUT_OF_PHASE
        rows.append(Row("plot2-3", f"exact vs approximate profile at t = {t:g} (scene {scene})", paper,
                        f"phase gap {gap:.3g} rad", "agrees" if ok else "disagrees",
                        "difference of the phases of the k = q Fourier component; small < pi/4, "
                        "out of phase > pi/2", "small: gap < pi/4; out of phase: gap > pi/2"))
    return rows


def linear_wave_phase(res: Results, scene: str, t0: float) -> list[Row]:
    ex = res.sim(scene, "exact")
    q, a = float(ex.attrs["q"]), float(ex.attrs["a"])
    x = ex["x"].sel(t=t0, method="nearest")
    lin = compare.linear_wave(np.arange(x.size), np.array([float(x["t"])]), a, q)[0]
    gap = _phase_gap(x.values, lin, q)
    return [Row("plotcomplin", f"exact vs linear wave a cos(qn - t) at t0 = {t0:g}", "approximately out of phase",
                f"phase gap {gap:.3g} rad", "agrees" if gap > OUT_OF_PHASE else "disagrees",
                "phase of the k = q Fourier component; out of phase > pi/2", "out of phase: gap > pi/2")]


def super_exponential(res: Results, name: str = "site") -> list[Row]:
    ds = res.homoclinic(name)
    a = np.abs(ds["a"].values)
    c = int(np.argmax(a))
    ratios = a[c + 2:c + 9] / a[c + 1:c + 8]
    decreasing = bool(np.all(np.diff(ratios) < 0))
    L = ds["log10_abs_a"].values[c:c + ds.sizes["n"] // 2 + 1]
    law = float(L[-1] / L[-2])
    alpha = float(ds.attrs["alpha"])
    return [Row("bcsc", "super-exponential decay of the site-centred homoclinic", "yes",
                f"{_fmt(decreasing)} (|a_(n+1)/a_n| = {', '.join(f'{r:.1e}' for r in ratios[:5])}, ...)",
                "agrees" if decreasing else "disagrees",
                "successive ratios |a_(n+1)/a_n| away from the centre keep decreasing (exponential: constant)",
                "yes/no: every successive ratio smaller"),
            Row("bcsc", "decay law ln|a_(n+1)| / ln|a_n| -> alpha in the tail (from (dpsstn))",
                f"(not in the paper; law: {alpha:g})",
                f"{law:.10g} at |a_n| ~ 1e{L[-1]:.0f}", "agrees" if abs(law - alpha) < 1e-6 else "disagrees",
                "tail continued far below machine precision by (dpsstn) in log variables (log10_abs_a)",
                "|law - alpha| < 1e-6")]


def periodic_orbits(alpha: float = 1.5) -> list[Row]:
    rows = []
    for name, period in (("period2", 2), ("period3", 3), ("period4", 4)):
        U = stationary.explicit_periodic_orbits(alpha)[name]
        err = float(np.max(np.abs(stationary.orbit(U[0], period, alpha)[-1] - U[0])))
        rows.append(Row("traj2", f"explicit {name.replace('period', 'period-')} orbit of the caption is an orbit of G",
                        "yes", f"yes (|G^{period}(U_0) - U_0| = {err:.1e})" if err < 1e-12 else f"no ({err:.1e})",
                        "agrees" if err < 1e-12 else "disagrees", "iterate G from the caption's closed form",
                        "|G^p(U_0) - U_0| < 1e-12"))
    return rows


# ------------------------------------------------------------------ assembly

#: where the docs explain a claim's verdict ("<page>.md#<anchor>" under docs/), declared beside the claim
#: in :func:`_groups`; a claim that can disagree names one
FFTSEUIL = "analyses.md#claims-fftseuil"
HARMONICS = "analyses.md#claims-harmonics"
LOC1_MERGING = "loc1-readings.md#merging-times"

def _groups(res: Results, scenes: Iterable[str]) -> list[tuple[tuple[str, ...], Callable[[], list[Row]]]]:
    """(names the group reads, thunk) for every group of rows, in table order."""
    return [
        ((), closed_forms),
        (("tw-weak", "tw-moderate", "tw-strong"),
         lambda: amplitudes(res, {"tw-weak": "2e-2", "tw-moderate": "2.11", "tw-strong": "52.9"})),
        (("fft106",), lambda: eps_fft106(res)),
        (("tw-weak",), lambda: relative_error(res)),
        (("tw-moderate",), lambda: phase_shifts(res, "tw-moderate", 64.95, 570.95)),
        (("tw-weak",), lambda: linear_wave_phase(res, "tw-weak", 333.7)),
        (("fft106",), lambda: harmonics_present(res, "fft106", "fft106", 106.7, "2(q-pi)",
                                                {"exact": "yes", "dps": "no"})),
        (("fftseuil-52", "fftseuil-51", "fftseuil-50", "fft344"), lambda: explained(FFTSEUIL, instability(res, [
            ("fftseuil", "fftseuil-52", 913.7, {"exact": "yes", "dps": "yes"}),
            ("fftseuil", "fftseuil-51", 913.7, {"exact": "no", "dps": "yes"}),
            ("fftseuil", "fftseuil-50", 913.7, {"exact": "no", "dps": "no"}),
            ("fft344", "fft344", 913.7, {"exact": "yes", "dps": "yes"}),
        ]))),
        (("fftseuil-50",), lambda: explained(HARMONICS, harmonics_present(
            res, "fftseuil", "fftseuil-50", 913.7, "2(q-pi)", {"exact": "yes", "dps": "no"}))),
        (("fft344",), lambda: explained(HARMONICS, harmonics_present(res, "fft344", "fft344", 344.95, "2(q-pi)",
                                                                     {"exact": "yes", "dps": "no"})
                                        + harmonics_present(res, "fft344", "fft344", 344.95, "3q-2pi",
                                                            {"exact": "yes", "dps": "no"}))),
        (("breather-small", "breather-large"),
         lambda: breather_frequencies(res, [("breather-small", "9.7e-3", "1.1"), ("breather-large", "0.34", "1.6")])),
        (("breather-small",), lambda: half_period(res, "breather-small", site=26)),
        (("breather-large",), lambda: radiation(res, "breather-large", 293.2, core=25.5)),
        (("loc1-pair",), lambda: explained(LOC1_MERGING, merging(res, "loc1-pair"))),
        (("site",), lambda: super_exponential(res, "site")),
        ((), periodic_orbits),
        ((), lambda: energy_errors(res, sorted(scenes))),
    ]


def rows(spec: PaperChecks, inputs: dict) -> list[Row]:
    """Every row whose inputs the spec names, computed from the Datasets ``inputs`` (:func:`reads`); a
    group of rows that reads an entry the spec does not name is left out. Then the rows of the analyses it
    collects (:func:`analysis_rows`), after the paper's."""
    res = Results(inputs)
    present = set(spec.scenes) | set(spec.homoclinic)
    out = []
    for group, thunk in _groups(res, spec.scenes):
        if all(n in present for n in group):
            out += thunk()
    for name in collected(spec):
        out += analysis_rows(name, inputs[f"analysis/{name}"])
    return out


def analysis_rows(name: str, tree: xr.DataTree) -> list[Row]:
    """The rows of analysis ``name``'s claims group in its output ``tree``, as the table shows them: a qualitative
    one says so in its tolerance cell, and each names the analysis in its ``measured`` cell."""
    from cradle.analyses.claims_table import read_group
    from cradle.analyses.registry import ANALYSES

    out = read_group(tree[ANALYSES[name].claims].to_dataset())
    for r in out:
        if r.qualitative:
            r.tolerance = f"qualitative: {r.tolerance}" if r.tolerance else "qualitative"
        r.measured = f"{r.measured} (analysis {name})"
    return out


#: the stored variables of the `paper-checks` file: one row per statement, every column text
VARIABLES = {"/": {
    "row": Var(("row",), "index of a statement of the paper, in table order"),
    "label": Var(("row",), "figure label or equation of the paper the statement is in"),
    "quantity": Var(("row",), "what is compared"),
    "paper": Var(("row",), "the paper's value or claim, as printed"),
    "ours": Var(("row",), "our value, computed from the pipeline's outputs"),
    "tolerance": Var(("row",), "the tolerance the verdict is judged with"),
    "verdict": Var(("row",), "agrees, disagrees or not comparable"),
    "measured": Var(("row",), "how our value is measured"),
    "explained_in": Var(("row",), "the paragraph of the docs explaining the verdict, <page>.md#<anchor> under docs/"),
}}


def compute(spec: PaperChecks, inputs: dict, log: Log | None = None) -> xr.Dataset:
    """The claims table as a Dataset, one row per statement (:data:`COLUMNS`, text), the verdict counts as
    attributes."""
    from cradle.data.io import make_dataset

    table = rows(spec, inputs)
    counts = {v: sum(r.verdict == v for r in table) for v in ("agrees", "disagrees", "not comparable")}
    counts["qualitative"] = sum(r.qualitative for r in table)
    if log:
        log(f"paper-checks: {len(table)} statements: " + ", ".join(f"{n} {v}" for v, n in counts.items()))
    data = {c: np.array([getattr(r, c) for r in table], dtype=object) for c in COLUMNS}
    attrs = {f"n_{v.replace(' ', '_')}": n for v, n in counts.items()}
    return make_dataset(data, coords={"row": np.arange(len(table))}, attrs=attrs, params=plain(spec),
                        variables=VARIABLES["/"], title="The paper's numerical statements against ours")


ANALYSIS = Analysis(
    name="paper-checks", spec=PaperChecks, compute=compute, reads=reads, variables=VARIABLES, tables=("csv", "md"),
    title="The paper's claims against ours")


__all__ = [
    "ANALYSIS",
    "COLUMNS",
    "HARMONIC_PRESENT",
    "PaperChecks",
    "Results",
    "Row",
    "agrees_printed",
    "compute",
    "explained",
    "printed_tol",
    "printed_unit",
    "reads",
    "rows",
]
