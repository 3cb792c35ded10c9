"""`breather-interactions`: the collision statistics the paper's conclusion asks for ("compare their
collision properties in both models, a problem which requires a statistical treatment due to its
sensitiveness to relative phases and breather positions").

Two breathers of the DpS family (:mod:`cradle.models.pairs`, omega_sw ~ 1.1 at amplitude 0.01) on a
ring, started from (ansatzapproxst2) at tau = 0 of (breatherdps), run in (nc) and in (dfnls)/(ansatz)
(:mod:`cradle.analyses.pair_runs`) and classified by :mod:`cradle.measurements.interactions`, over

* the profile pair (site-site, bond-bond, site-bond) and the centre spacing,
* the relative phase theta on the carrier: ``n_theta`` values in [0, 2 pi), refined by bisection
  between neighbours whose outcome differs (``refine`` levels); theta other than 0, pi gives
  the copies the ansatz velocities of (ansatzapproxst2) (a complex A_n(0)),
* the amplitude ratio and the overall amplitude, one at a time (at ``amplitude_thetas``, 0 and pi),
* ``n_seeds`` noise seeds per case: A_n(0) += noise * amplitude / 2 * xi_n, xi_n ~ N(0, 1) from
  numpy's default_rng((seed_base, seed)) (bitwise reproducible).

A batch is one (profile pair, spacing) with all its thetas, amplitudes and seeds; they are dealt round
robin to ``chunks`` jobs (:data:`ANALYSIS`'s batches, keys ``0``, ``1``, ...; the full form), or run in the
analysis job itself when ``chunks`` is 1 (the reduced form). Config: ``beyond: breather-interactions:``
(:class:`BreatherInteractions`, the reduced form's keys under ``reduced``).
Output: a tree (:data:`VARIABLES`): ``/cases`` (every run: parameters and, per model, outcome,
merging period (final single breather) and first coalescence, separation and drift velocities, norm moved
to the larger breather) and ``/maps``
(per profile pair, spacing and base theta, the share of seeds that merge and the modal outcome in
each model, and how often the two models agree).
"""
from __future__ import annotations

import time
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.protocol import Analysis, Batches
from cradle.data.variables import Var
from cradle.specs.declare import declared, param, plain
from cradle.specs.values import SEED_MAX

if TYPE_CHECKING:
    from collections.abc import Iterable

    import xarray as xr
    from numpy.typing import ArrayLike, NDArray

    from cradle.analyses.protocol import Log
    from cradle.models.initial import InitialData
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors

MODELS = ("exact", "dps")
PAIRS = {"site-site": ("site", "site"), "bond-bond": ("bond", "bond"), "site-bond": ("site", "bond")}
#: per-case result fields (per model)
FIELDS = ("outcome", "merge_period", "first_coalescence", "separation_velocity", "drift_velocity", "norm_transfer")


# ----------------------------------------------------------------- spec

_PAIRS = {"type": "string", "enum": ["site-site", "bond-bond", "site-bond"]}
_SPACING = {"type": "integer", "minimum": 1, "maximum": 24}
_THETA = {"type": "number", "minimum": 0, "exclusiveMaximum": 6.283185307179586}


@declared(doc="Collisions of two breathers of the DpS family (omega_sw ~ 1.1) on a ring, exact (nc) against DpS "
              "(dfnls), over profile pair, spacing, relative phase, amplitude ratio, amplitude and noise seeds "
              "-> results/breather-interactions/full/breather-interactions.nc (target breather_interactions_full) "
              "and results/breather-interactions/full/breather-interactions.{pdf,png}; the reduced form "
              "(`reduced`) is built by all.")
class BreatherInteractions:
    N: int = param(50, "Ring size (periodic).", minimum=16, maximum=400)
    alpha: float = param(1.5, "Hertz exponent alpha of V0 (> 1).", ref="alpha", maximum=10)
    amplitude: float = param(0.01, "Peak |x_n(0)| of the first copy alone in the theta sweep (omega_sw ~ 1.1).",
                             exclusiveMinimum=0, maximum=0.1)
    pairs: list[str] = param(["site-site", "bond-bond", "site-bond"], "Profile pairs of the two copies of (dpsstn) "
                             "solutions.", minItems=1, maxItems=3, items=_PAIRS,
                             reduced=["site-site"])
    spacings: list[int] = param([4, 5, 6, 7, 8], "Centre spacings (site-bond: each + 1/2), the interacting range "
                                "of docs/loc1-readings.md.", minItems=1, maxItems=24, items=_SPACING,
                                reduced=[4, 6, 8])
    n_theta: int = param(24, "Number of base phases theta = 2 pi j / n_theta of the second copy on the carrier.",
                         minimum=1, maximum=96,
                         reduced=2)
    refine: int = param(1, "Bisection levels between neighbouring base thetas whose outcome (exact, modal over seeds) "
                        "differs.", minimum=0, maximum=4,
                        reduced=0)
    n_seeds: int = param(8, "Noise seeds per case.", minimum=1, maximum=64,
                         reduced=2)
    noise: float = param(0.01, "Noise on A_n(0), relative to the amplitude (Gaussian, sd noise * amplitude / 2).",
                         minimum=0, maximum=1)
    seed_base: int = param(20261122, "First entry of the seed sequence (seed_base, seed) of numpy's default_rng; in "
                           "[0, 2^62].", minimum=0, maximum=SEED_MAX)
    periods: float = param(600.0, "Run length in breather periods 2 pi / omega_sw (the paper: up to 600).",
                           exclusiveMinimum=0, maximum=5000,
                           reduced=150.0)
    ratios: list[float] = param([0.8, 1.0, 1.25], "Amplitude ratios (second copy / first) of the amplitude sweep, at "
                                "the base amplitude.", minItems=1, maxItems=8,
                                items={"type": "number", "exclusiveMinimum": 0, "maximum": 10},
                                reduced=[1.0])
    amplitudes: list[float] = param([0.005, 0.01, 0.02], "Overall amplitudes of the amplitude sweep, at ratio 1.",
                                    minItems=1, maxItems=8,
                                    items={"type": "number", "exclusiveMinimum": 0, "maximum": 0.1},
                                    reduced=[0.01])
    amplitude_thetas: list[float] = param([0.0, 3.141592653589793], "Phases (radians) of the amplitude sweep.",
                                          minItems=1, maxItems=8, items=_THETA)
    chunks: int = param(4, "Jobs the full sweep is split into (round robin over (pair, spacing)); 1: the sweep runs "
                        "in the analysis job itself.", minimum=1, maximum=64,
                        reduced=1)

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Spacings distinct; the pair must fit the ring."""
        sp = self.spacings
        if len(set(map(str, sp))) != len(sp):
            out.add(where + ["spacings"], "must be distinct", sp)
        if any(s + 10 > self.N for s in sp):
            out.add(where + ["spacings"], f"must leave room for both breathers: spacing + 10 <= N = {self.N}", sp)


def spacings_of(pair: str, spacings: Iterable[int]) -> list[float]:
    """The centre spacings of a profile pair: the integers ``spacings`` (site-site, bond-bond), each
    + 1/2 for site-bond (a site and a bond midpoint are half a site apart)."""
    return [float(s) + (0.5 if pair == "site-bond" else 0.0) for s in spacings]


def batches(spec: BreatherInteractions) -> list[tuple[str, float]]:
    """Every (profile pair, spacing) of the sweep, in a fixed order."""
    return [(p, s) for p in spec.pairs for s in spacings_of(p, spec.spacings)]


def chunk_batches(spec: BreatherInteractions, chunk: int) -> list[tuple[str, float]]:
    """The batches of job ``chunk`` (round robin over ``spec.chunks`` jobs)."""
    return batches(spec)[chunk::spec.chunks]


def initial(spec: BreatherInteractions, pair: str, spacing: float, theta: float, ratio: float, amplitude: float,
            seed: int) -> InitialData:
    """Initial data of one case: the pair (:func:`cradle.models.pairs.two_breathers`) plus the noise."""
    from cradle.models import pairs
    from cradle.models.initial import InitialData, lattice_state

    N, alpha = spec.N, spec.alpha
    prof = PAIRS[pair]
    c = pairs.symmetric_centres(N, prof, spacing)
    d = pairs.two_breathers(N, alpha, profiles=prof, centres=c, amplitudes=(amplitude, ratio * amplitude),
                            theta=theta)
    if spec.noise > 0:
        xi = np.random.default_rng((spec.seed_base, int(seed))).standard_normal(N)
        A0 = d.A0 + 0.5 * spec.noise * amplitude * xi
        x0, v0 = lattice_state(A0, 1.0, alpha, "periodic")
        d = InitialData(A0=A0, eps=1.0, x0=x0, v0=v0, info=d.info)
    return d


def run_case(spec: BreatherInteractions, pair: str, spacing: float, theta: float, ratio: float, amplitude: float,
             seed: int) -> dict:
    """One case in both models -> {f"{field}_{model}": value}."""
    from cradle.analyses import pair_runs

    d = initial(spec, pair, spacing, theta, ratio, amplitude, seed)
    T = 2 * np.pi / d.info["omega_sw"]
    res = pair_runs.run_pair(d, spec.periods * T, spec.alpha)
    out = {}
    for m in MODELS:
        oc = res[m]["outcome"]
        out.update({f"outcome_{m}": oc.code, f"merge_period_{m}": oc.merge_period,
                    f"first_coalescence_{m}": oc.first_coalescence,
                    f"separation_velocity_{m}": oc.separation_velocity, f"drift_velocity_{m}": oc.drift_velocity,
                    f"norm_transfer_{m}": res[m]["norm_share_end"] - res[m]["norm_share_0"]})
    return out


def _theta_grid(spec: BreatherInteractions) -> NDArray[np.float64]:
    return 2 * np.pi * np.arange(spec.n_theta) / spec.n_theta


def _modal(codes: ArrayLike) -> int:
    return int(np.bincount(np.asarray(codes, dtype=int), minlength=5).argmax())


def run_batch(spec: BreatherInteractions, pair: str, spacing: float, log: Log | None = None) -> list[dict]:
    """Every case of one (pair, spacing): the theta grid at ratio 1 and the base amplitude, refined where the
    modal outcome (over seeds, exact model) changes between neighbours; then the ratios (at the base
    amplitude) and the amplitudes (at ratio 1) at ``amplitude_thetas``. Returns one dict per case."""
    say = log or (lambda *a: None)
    seeds = range(spec.n_seeds)
    A, rows = spec.amplitude, []

    def cases(theta: float, ratio: float, amp: float, kind: int) -> list[dict]:
        got = []
        for s in seeds:
            r = {"pair": pair, "spacing": spacing, "theta": float(theta), "ratio": float(ratio),
                 "amplitude": float(amp), "seed": int(s), "sweep": kind}
            r.update(run_case(spec, pair, spacing, theta, ratio, amp, s))
            got.append(r)
        return got

    t0 = time.perf_counter()
    grid = {float(th): cases(th, 1.0, A, 0) for th in _theta_grid(spec)}
    for _level in range(spec.refine):
        ths = sorted(grid)
        for i, a in enumerate(ths):
            b = ths[(i + 1) % len(ths)]
            b_up = b + (2 * np.pi if i == len(ths) - 1 else 0.0)
            if _modal([r["outcome_exact"] for r in grid[a]]) != _modal([r["outcome_exact"] for r in grid[b]]):
                mid = float(0.5 * (a + b_up) % (2 * np.pi))
                if mid not in grid:
                    grid[mid] = cases(mid, 1.0, A, 1)
    for rs in grid.values():
        rows += rs
    # one parameter at a time: the ratios at the base amplitude, the amplitudes at ratio 1 (the base case
    # itself is in the theta grid when its theta is)
    combos = [(r, A) for r in spec.ratios] + [(1.0, a) for a in spec.amplitudes]
    for th in spec.amplitude_thetas:
        for ratio, amp in dict.fromkeys(combos):
            if ratio == 1.0 and amp == A and any(abs(th - t) < 1e-12 for t in grid):
                continue
            rows += cases(th, ratio, amp, 2)
    say(f"{pair} spacing {spacing:g}: {len(rows)} cases in {time.perf_counter() - t0:.1f} s")
    return rows


# ----------------------------------------------------------------- the tables

_CASE = {
    "case": Var(("case",), "case number"),
    "pair": Var(("case",), "profile pair of the two copies (site-site, bond-bond, site-bond)"),
    "spacing": Var(("case",), "distance of the two centres", "1",
                   attrs=(("comment", "sites; a bond-centred copy sits on a bond midpoint"),)),
    "theta": Var(("case",), "phase of the second copy relative to the first on the (-1)^n carrier", "rad"),
    "ratio": Var(("case",), "amplitude of the second copy over the first"),
    "amplitude": Var(("case",), "peak |x_n(0)| of the first copy alone"),
    "seed": Var(("case",), "noise seed: A_n(0) += noise amplitude / 2 xi_n, xi ~ default_rng((seed_base, seed))"),
    "sweep": Var(("case",), "which sweep the case belongs to",
                 attrs=(("flag_values", (0, 1, 2)), ("flag_meanings", "theta_grid theta_refined amplitude_ratio"))),
}
for _m, _model in (("exact", "exact (nc)"), ("dps", "DpS (dfnls)/(ansatz)")):
    _CASE.update({
        f"outcome_{_m}": Var(("case",), f"interaction outcome, {_model}",
                             attrs=(("flag_values", (0, 1, 2, 3, 4)),
                                    ("flag_meanings", "merge bound repel transmit none"))),
        f"merge_period_{_m}": Var(("case",), f"merging time in breather periods, {_model} (NaN: no merge)",
                                  attrs=(("comment", "first period of the final single breather"),)),
        f"first_coalescence_{_m}": Var(("case",), f"first coalescence in breather periods, {_model} (NaN: none)",
                                       attrs=(("comment", "first period of the first single state, which a "
                                                          "breathing bound pair may leave again"),)),
        f"separation_velocity_{_m}": Var(("case",), f"separation velocity of a repelled pair, {_model} "
                                                     "(sites per breather period; NaN: not repelled)"),
        f"drift_velocity_{_m}": Var(("case",), f"drift velocity of the merged breather, {_model} "
                                                "(sites per breather period; NaN: no merge)"),
        f"norm_transfer_{_m}": Var(("case",), f"share of the norm held near the largest breather at the end "
                                               f"minus at the start, {_model}",
                                   attrs=(("comment", ("norm density |A_n|^2 (DpS), (x_n^2 + v_n^2)/4 (lattice); "
                                                      "sites within 3 of the largest hump")),)),
    })
_CASE["merge_ratio"] = Var(("case",), "merging time exact over DpS (NaN unless both merge)")

_MAPS = {
    "pair": Var(("pair",), "profile pair"),
    "spacing": Var(("spacing",), "index of the spacing of the sweep's list (site-bond: + 1/2)"),
    "theta": Var(("theta",), "base theta of the grid", "rad"),
}
for _m, _model in (("exact", "exact (nc)"), ("dps", "DpS")):
    _MAPS.update({
        f"merge_share_{_m}": Var(("pair", "spacing", "theta"), f"share of the seeds that merge, {_model}"),
        f"modal_outcome_{_m}": Var(("pair", "spacing", "theta"), f"most frequent outcome over seeds, {_model}",
                                   attrs=(("flag_values", (0.0, 1.0, 2.0, 3.0, 4.0)),
                                          ("flag_meanings", "merge bound repel transmit none"))),
        f"median_merge_period_{_m}": Var(("pair", "spacing", "theta"),
                                         f"median merging period over the seeds that merge, {_model}"),
    })
_MAPS["agreement"] = Var(("pair", "spacing", "theta"), "share of the seeds whose outcome is the same in both models")

VARIABLES = {"/": {}, "/cases": _CASE, "/maps": _MAPS}


def case_table(rows: list[dict]) -> dict:
    """Columns of the /cases group from case dicts (pairs as strings)."""
    cols = {k: np.array([r[k] for r in rows]) for k in rows[0]} if rows else {}
    for k in ("sweep", "outcome_exact", "outcome_dps", "seed"):    # integer flags, as their flag_values
        if k in cols:
            cols[k] = cols[k].astype(np.int64)
    if rows:
        me, md = cols["merge_period_exact"], cols["merge_period_dps"]
        with np.errstate(invalid="ignore", divide="ignore"):
            cols["merge_ratio"] = np.where(np.isfinite(me) & np.isfinite(md) & (md > 0), me / md, np.nan)
    return cols


def maps(cols: dict, spec: BreatherInteractions) -> tuple[dict, dict]:
    """Per (pair, spacing, base theta): merge share, modal outcome, median merging period, agreement."""
    pairs = list(spec.pairs)
    nsp = len(spec.spacings)
    ths = _theta_grid(spec)
    shape = (len(pairs), nsp, ths.size)
    out = {f"{k}_{m}": np.full(shape, np.nan) for k in ("merge_share", "modal_outcome", "median_merge_period")
           for m in MODELS}
    out["agreement"] = np.full(shape, np.nan)
    base = cols["sweep"] == 0
    for i, p in enumerate(pairs):
        for j, s in enumerate(spacings_of(p, spec.spacings)):
            for k, th in enumerate(ths):
                sel = base & (cols["pair"] == p) & (cols["spacing"] == s) & np.isclose(cols["theta"], th)
                if not sel.any():
                    continue
                for m in MODELS:
                    oc = cols[f"outcome_{m}"][sel]
                    out[f"merge_share_{m}"][i, j, k] = np.mean(oc == 0)
                    out[f"modal_outcome_{m}"][i, j, k] = _modal(oc)
                    mp = cols[f"merge_period_{m}"][sel]
                    mp = mp[np.isfinite(mp)]
                    out[f"median_merge_period_{m}"][i, j, k] = np.median(mp) if mp.size else np.nan
                out["agreement"][i, j, k] = np.mean(cols["outcome_exact"][sel] == cols["outcome_dps"][sel])
    return out, {"pair": np.array(pairs), "spacing": np.arange(nsp), "theta": ths}


def tree(rows: list[dict], spec: BreatherInteractions, wall: float) -> xr.DataTree:
    from cradle.data.io import make_tree

    cols = case_table(rows)
    mp, coords = maps(cols, spec)
    agree = float(np.mean(cols["outcome_exact"] == cols["outcome_dps"]))
    attrs = {"n_cases": len(rows), "outcome_agreement": agree, "wall_time_s": wall,
             "outcomes": "merge bound repel transmit none"}
    case_coords = {"case": np.arange(len(rows))}
    return make_tree({"/cases": (dict(cols), case_coords),
                      "/maps": (mp, coords)}, variables=VARIABLES, attrs=attrs, params=plain(spec),
                     title="breather-interactions: two DpS-family breathers, exact (nc) against DpS (dfnls)")


def batch(spec: BreatherInteractions, chunk: int, log: Log | None = None) -> list[dict]:
    """Every case of job ``chunk``."""
    rows = []
    for pair, spacing in chunk_batches(spec, chunk):
        rows += run_batch(spec, pair, spacing, log)
    return rows


def batch_dataset(spec: BreatherInteractions, chunk: int, log: Log | None = None) -> xr.Dataset:
    """The /cases table of one batch job as a netCDF Dataset."""
    from cradle.data.io import make_dataset

    t0 = time.perf_counter()
    rows = batch(spec, chunk, log)
    cols = case_table(rows)
    return make_dataset(cols, coords={"case": np.arange(len(rows))}, attrs={"chunk": chunk, "n_cases": len(rows),
                                                                            "wall_time_s": time.perf_counter() - t0},
                        params=plain(spec), variables=_CASE, title=f"breather-interactions batch {chunk}")


def _rows_of(ds: xr.Dataset) -> list[dict]:
    """The case dicts of one batch file (merge_ratio is recomputed from them)."""
    return [{k: (str(ds[k].values[i]) if ds[k].dtype.kind in "USO" else ds[k].values[i].item())
             for k in _CASE if k in ds and k not in ("merge_ratio", "case")} for i in range(ds.sizes["case"])]


# ----------------------------------------------------------------- the protocol

def batch_keys(spec: BreatherInteractions) -> list[str]:
    """The batch jobs of a form, ``0`` ... ``chunks - 1``: none when ``chunks`` is 1 (the reduced form's
    tiny sweep runs in the analysis job itself)."""
    return [str(c) for c in range(spec.chunks)] if spec.chunks > 1 else []


def run_batch_job(spec: BreatherInteractions, key: str, inputs: dict, log: Log | None = None) -> xr.Dataset:
    """Batch ``key`` of :func:`batch_keys` (it reads no file)."""
    if key not in batch_keys(spec):
        raise ValueError(f"breather-interactions: no batch {key!r} in this form "
                         f"(batches: {', '.join(batch_keys(spec)) or 'none'})")
    return batch_dataset(spec, int(key), log)


def compute(spec: BreatherInteractions, inputs: dict, log: Log | None = None) -> xr.DataTree:
    """The analysis of one form: its batches gathered (``inputs["batch/<key>"]``), or, without batches,
    the sweep run here. The cases are in one order whatever the split: by pair, spacing, sweep, theta,
    ratio, amplitude and seed."""
    t0 = time.perf_counter()
    keys = batch_keys(spec)
    if keys:
        rows = [row for key in keys for row in _rows_of(inputs[f"batch/{key}"])]
    else:
        rows = batch(spec, 0, log)
    rows.sort(key=lambda r: (r["pair"], r["spacing"], r["sweep"], r["theta"], r["ratio"], r["amplitude"], r["seed"]))
    return tree(rows, spec, time.perf_counter() - t0)


ANALYSIS = Analysis(
    name="breather-interactions", spec=BreatherInteractions, compute=compute, variables=VARIABLES,
    batches=Batches(keys=batch_keys, run=run_batch_job),
    title="Collisions of two breathers, exact (nc) against DpS (dfnls): outcome statistics (loc1)")
