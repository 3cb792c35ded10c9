"""Statistics of the modulational-instability threshold over noise seeds, ring sizes and both models.

The experiment of figure fftseuil (section 4.2), repeated many times: the
approximate travelling wave (ansatzapprox)-(freq) with omega_tw fixed
(so a = 2 eps follows from q by (freq)), perturbed as in (perturb) with
Gaussian rho_n^(1), rho_n^(2) (sd ``noise_amplitude``, seed per run), on a
periodic ring of N beads with q = 2 pi k / N, integrated to t_end

* by the lattice (nc) (``model = "exact"``, :func:`cradle.integrators.integrate_lattice`),
* by the DpS equation (dfnls) (``model = "dps"``, :func:`cradle.integrators.integrate_dps`
  in the slow time tau = eps^(alpha-1) t of (ansatz), rebuilt as
  x_n^app(t) = eps (A_n e^{it} + c.c.) on the same t grid).

Measure (on the fly, every ``sample_every`` time units; the fields are not kept):
the paper's spatial spectrum |x_hat_k(t)| on Gamma* (:func:`cradle.measurements.compare.spatial_dft`)
and its sideband-to-carrier ratio r(t) (:func:`cradle.measurements.sidebands.sideband_peak`,
``exclude_bins`` bins left out on each side of +-q and of the lattice harmonics
+-2(q - pi), +-(3q - 2 pi); default 0: only those exact bins). A run is
*unstable* when r first reaches ``fraction`` before t_end; its crossing time
(:func:`crossing_time`) is NaN otherwise, with the flag ``crossed = 0``.

Threshold (:func:`threshold`): with f(q) the fraction of unstable seeds, the
estimate is where f crosses 1/2 for the last time going up in q (linear
interpolation between the two grid points around it; every grid q above it
has f >= 1/2). Its interval [q_lo, q_hi] is stated by Wilson 95 % binomial
intervals: q_lo is the largest grid q below the crossing whose interval for
f lies entirely below 1/2, q_hi the smallest grid q above it whose interval
lies entirely above 1/2 (so the interval is never narrower than the grid).
The DpS linear theory puts the threshold at q_c = pi/2 exactly
(:func:`cradle.analyses.mi_diagram.threshold`).

The sweep is split into batches (:data:`ANALYSIS`: one job per ring size N, model and chunk of q,
key ``N<N>-<model>-<chunk>``): :func:`batch` runs one -> Dataset; :func:`aggregate` joins the batches
of a form and adds the thresholds. Config: ``beyond: mi-statistics:`` (:class:`MIStatistics`), the full
sweep at its top level and the smaller one `all` builds under ``reduced``.
"""
from __future__ import annotations

import dataclasses
import re
import time
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses import mi_diagram as modulational
from cradle.analyses.protocol import Analysis, Batches
from cradle.data.variables import MODEL, MODELS, Var
from cradle.measurements import compare, sidebands
from cradle.models import initial
from cradle.scenes.spec import DPS_METHODS, SPLITTINGS
from cradle.scenes.times import store_times
from cradle.specs.declare import NULL, declared, param, plain
from cradle.specs.values import DT_FACTOR_FLOOR, INTEGER_TOL, RTOL_FLOOR, SEED_MAX

if TYPE_CHECKING:
    from collections.abc import Sequence

    import xarray as xr
    from numpy.typing import ArrayLike, NDArray

    from cradle.analyses.protocol import Log
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors

WILSON_Z = 1.959963984540054   # two-sided 95 %


# ---------------------------------------------------------------- spec

@declared(doc="Lattice integrator.")
class MIStatisticsExact:
    method: str = param("srkn6c", "A splitting of cradle.integrators (srkn6c is the fastest at the default "
                        "accuracy).", enum=list(SPLITTINGS))
    dt_factor: float | None = param(NULL, "Step as a fraction of the shortest linear period; null = the method's "
                                    "default.", minimum=DT_FACTOR_FLOOR, maximum=0.5)


@declared(doc="DpS integrator.")
class MIStatisticsDps:
    method: str = param("dop853_numba", "dop853_numba: DOP853 compiled (fastest for these N).", enum=list(DPS_METHODS))
    rtol: float = param(1e-10, "Relative tolerance (atol = rtol max |A_n(0)|), as defaults.dps.rtol.",
                        minimum=RTOL_FLOOR, maximum=0.001)


@declared(doc="Grid of carrier wavenumbers q / pi: count values from start to stop.")
class QGrid:
    start: float = param(0.47, "Smallest q / pi.", exclusiveMinimum=0, maximum=1.0)
    stop: float = param(0.59, "Largest q / pi.", exclusiveMinimum=0, maximum=1.0)
    count: int = param(7, "Number of q values.", minimum=2, maximum=1000)


_N_DOC = "Ring sizes N (even; q N / (2 pi) must be an integer for every q of the grid)."
_N_ITEMS = {"type": "integer", "minimum": 8, "maximum": 4096, "description": "A ring size."}
_Q_DOC = "Grid of carrier wavenumbers q / pi: count values from start to stop."
_SEEDS_DOC = "Noise realisations per (q, N, model)."
_CHUNKS_DOC = "Batches (Snakemake jobs) per (N, model); q values dealt round-robin."


def _check_sweep(N: list[int], g: QGrid, chunks: int, where: Where, out: Errors) -> None:
    """One sweep (the full form's keys, or ``reduced``): start < stop, no more batches than q values, and
    every q of the grid on every ring's wavenumber grid (N even for Gamma*, q N / (2 pi) an integer)."""
    if not g.start < g.stop:
        out.add(where + ["q_over_pi"], "need start < stop", dataclasses.asdict(g))
        return
    count = int(g.count)
    vals = [g.start + i * (g.stop - g.start) / (count - 1) for i in range(count)]
    if chunks > count:
        out.add(where + ["chunks"], f"more batches than q values (count = {count})", chunks)
    for j, n in enumerate(N):
        if n % 2:
            out.add(where + ["N", j], "must be even (Gamma* of the spatial DFT)", n)
            continue
        for x in vals:
            m = x * n / 2.0
            if abs(m - round(m)) > INTEGER_TOL:
                out.add(where + ["q_over_pi"], f"q = {x:.10g} pi gives q N/(2 pi) = {m:.10g} for N = {n}: with "
                                               f"periodic ends it must be an integer (choose start, stop, count "
                                               f"so that the step is a multiple of 2/N)", dataclasses.asdict(g))
                break


@declared(doc="Threshold of the modulational instability over noise seeds, ring sizes N and both models "
              "(cradle.analyses.mi_statistics): the fftseuil experiment repeated; the settings of both forms, the "
              "full sweep's q grid, N, seeds and batching (`snakemake -j2 mi_statistics_full`: "
              "results/mi-statistics/full/mi-statistics.nc and results/mi-statistics/full/mi-statistics.{pdf,png}), "
              "and under `reduced` the small sweep `all` builds.")
class MIStatistics:
    alpha: float = param(1.5, "Hertz exponent alpha of V0 (> 1).", ref="alpha", maximum=10)
    omega_tw: float = param(1.1, "Frequency omega_tw of the travelling wave (freq); a follows from q (the fftseuil "
                            "scenes: 1.1).", exclusiveMinimum=1.0, maximum=3.0)
    noise_kind: str = param("gaussian", "Distribution of rho_n^(1), rho_n^(2) of (perturb) (the fftseuil scenes: "
                            "gaussian).", enum=["gaussian", "uniform"])
    noise_amplitude: float = param(0.05, "Standard deviation (gaussian) or half-width (uniform) of the noise of "
                                   "(perturb) (the fftseuil scenes: 0.05).", exclusiveMinimum=0, maximum=1.0)
    t_end: float = param(913.7, "Final time t of every run (the fftseuil scenes: 913.7).", exclusiveMinimum=0,
                         maximum=100000.0)
    sample_every: float = param(1.0, "The spectrum is measured every sample_every time units (the fields are not "
                                "stored).", exclusiveMinimum=0, maximum=100.0)
    fraction: float = param(0.5, "A run is unstable when its sideband-to-carrier ratio reaches this fraction by "
                            "t_end. Below the DpS threshold the noise alone brings the ratio to ~0.2 by t = 913.7, "
                            "hence 0.5.",
                            exclusiveMinimum=0, maximum=10.0)
    exclude_bins: int = param(0, "Bins left out on each side of +-q and of the lattice harmonics +-2(q-pi), "
                              "+-(3q-2pi) in the sideband ratio (0: only those bins).", minimum=0, maximum=10)
    seed0: int = param(20111000, "Seeds are seed0, seed0+1, ..., seed0+n_seeds-1, the same at every q and N.",
                       minimum=0, maximum=SEED_MAX)
    exact: MIStatisticsExact = param(MIStatisticsExact(), "Lattice integrator.")
    dps: MIStatisticsDps = param(MIStatisticsDps(), "DpS integrator.")
    N: list[int] = param([200, 400], _N_DOC, minItems=1, maxItems=6, items=_N_ITEMS,
                         reduced=[200])
    q_over_pi: QGrid = param(QGrid(start=0.45, stop=0.65, count=21), _Q_DOC,
                             reduced=QGrid())
    n_seeds: int = param(32, _SEEDS_DOC, minimum=1, maximum=1000,
                         reduced=4)
    chunks: int = param(3, _CHUNKS_DOC, minimum=1, maximum=100,
                        reduced=1)

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """The sweep of each form (:func:`_check_sweep`)."""
        _check_sweep(self.N, self.q_over_pi, self.chunks, where, out)


# ---------------------------------------------------------------- measurement

def sample_times(spec: MIStatistics) -> np.ndarray:
    """0, sample_every, ..., t_end: where the sideband ratio of every run is sampled."""
    return np.asarray(store_times(None, spec.sample_every, spec.t_end))


def crossing_time(t: NDArray[np.float64], r: NDArray[np.float64], fraction: float) -> float:
    """First time r(t) >= fraction, interpolated linearly in log r between the two samples around it.

    NaN when r stays below ``fraction`` on the whole series; t[0] when it starts above.
    """
    t = np.asarray(t, dtype=float)
    r = np.asarray(r, dtype=float)
    above = np.flatnonzero(r >= fraction)
    if above.size == 0:
        return float("nan")
    i = int(above[0])
    if i == 0:
        return float(t[0])
    r0, r1 = r[i - 1], r[i]
    if not (r0 > 0 and r1 > r0):
        return float(t[i])
    s = (np.log(fraction) - np.log(r0)) / (np.log(r1) - np.log(r0))
    return float(t[i - 1] + s * (t[i] - t[i - 1]))


def run_ratio(model: str, N: int, k: int, seed: int,
              spec: MIStatistics) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], dict]:
    """One run: (t, r(t), k_peak(t), info) for carrier q = 2 pi k / N, noise seed ``seed``, with the
    settings of ``spec`` (alpha, omega_tw, noise, t_end, sample_every, exclude_bins, exact, dps)."""
    from cradle.integrators import integrate_dps, integrate_lattice

    alpha = spec.alpha
    q = 2.0 * np.pi * k / N
    t = sample_times(spec)
    data = initial.travelling_wave(N, q, alpha, omega_tw=spec.omega_tw, bc="periodic",
                                   noise_kind=spec.noise_kind, noise_amplitude=spec.noise_amplitude,
                                   seed=int(seed))
    if model == "exact":
        ex = spec.exact
        lat = integrate_lattice(data.x0, data.v0, t, alpha=alpha, bc="periodic", method=ex.method,
                                dt_factor=ex.dt_factor)
        x = lat.x
        info = {"drift": lat.energy_drift, "wall": lat.wall_time_s}
    elif model == "dps":
        st = spec.dps
        sol = integrate_dps(data.A0, data.eps ** (alpha - 1.0) * t, alpha=alpha, bc="periodic",
                            method=st.method, rtol=st.rtol)
        x = compare.approximate_displacement(sol.A, t, data.eps)
        info = {"drift": sol.max_l2_drift, "wall": sol.wall_time_s}
    else:
        raise ValueError(f"model must be one of {MODELS}, got {model!r}")
    if not np.all(np.isfinite(x)):
        raise RuntimeError(f"mi-statistics: {model} run N={N} k={k} seed={seed} is not finite")
    kk, xh = compare.spatial_dft(x)
    r, kp = sidebands.sideband_peak(kk, np.abs(xh), q, exclude_bins=spec.exclude_bins)
    info.update({"a": data.info["a"], "eps": data.eps})
    return t, r, kp, info


# ---------------------------------------------------------------- threshold

def wilson_interval(successes: ArrayLike, n: ArrayLike, z: float = WILSON_Z) -> tuple[np.ndarray, np.ndarray]:
    """Wilson score interval (low, high) for a binomial proportion successes / n."""
    s = np.asarray(successes, dtype=float)
    n = np.asarray(n, dtype=float)
    p = s / n
    den = 1.0 + z**2 / n
    centre = (p + z**2 / (2 * n)) / den
    half = z * np.sqrt(p * (1 - p) / n + z**2 / (4 * n**2)) / den
    return centre - half, centre + half


def threshold(q: NDArray[np.float64], unstable: NDArray[np.bool_]) -> dict:
    """Threshold in q from a boolean array ``unstable`` of shape (n_q, n_seeds) (see the module docstring).

    Returns {estimate, low, high, status, n_nonmonotone}: status "ok", "below_grid" (f >= 1/2 at
    every q: estimate NaN, high = q[0]), "above_grid" (f < 1/2 at the largest q: estimate NaN,
    low = q[-1]). ``low``/``high`` are NaN when no grid point is conclusive on that side.
    n_nonmonotone counts grid points below the crossing with f >= 1/2.
    """
    q = np.asarray(q, dtype=float)
    u = np.asarray(unstable, dtype=bool)
    n = u.shape[1]
    hits = u.sum(axis=1)
    f = hits / n
    lo_ci, hi_ci = wilson_interval(hits, n)
    nan = float("nan")
    below = np.flatnonzero(f < 0.5)
    if below.size == 0:
        return {"estimate": nan, "low": nan, "high": float(q[0]), "status": "below_grid", "n_nonmonotone": 0}
    j = int(below[-1])             # last grid point with f < 1/2
    if j == q.size - 1:
        return {"estimate": nan, "low": float(q[-1]), "high": nan, "status": "above_grid",
                "n_nonmonotone": int(np.sum(f[:j] >= 0.5))}
    i = j + 1
    est = q[j] + (0.5 - f[j]) / (f[i] - f[j]) * (q[i] - q[j])
    lows = np.flatnonzero(hi_ci[: j + 1] < 0.5)
    highs = np.flatnonzero(lo_ci[i:] > 0.5)
    low = float(q[lows[-1]]) if lows.size else nan
    high = float(q[i + highs[0]]) if highs.size else nan
    return {"estimate": float(est), "low": low, "high": high, "status": "ok",
            "n_nonmonotone": int(np.sum(f[:j] >= 0.5))}


# ---------------------------------------------------------------- config

def q_indices(spec: MIStatistics, N: int) -> list[int]:
    """The integers k with q = 2 pi k / N for the grid q / pi = start ... stop (count values)."""
    g = spec.q_over_pi
    vals = np.linspace(g.start, g.stop, g.count)
    k = vals * N / 2.0
    return [int(round(x)) for x in k]


def chunk_indices(spec: MIStatistics, N: int, chunk: int) -> list[int]:
    """The k of chunk ``chunk`` (0-based; q values dealt round-robin so the chunks cost about the same)."""
    ks = q_indices(spec, N)
    c = spec.chunks
    if not 0 <= chunk < c:
        raise ValueError(f"chunk must be in [0, {c - 1}], got {chunk}")
    return ks[chunk::c]


def seeds(spec: MIStatistics) -> list[int]:
    """seed0, seed0 + 1, ...: the same noise realisations at every q (common random numbers)."""
    return [spec.seed0 + s for s in range(spec.n_seeds)]


def _attrs(spec: MIStatistics) -> dict:
    g = spec.q_over_pi
    return {"alpha": spec.alpha, "omega_tw": spec.omega_tw,
            "noise": spec.noise_kind, "noise_amplitude": spec.noise_amplitude, "t_end": spec.t_end,
            "sample_every": spec.sample_every, "fraction": spec.fraction,
            "exclude_bins": spec.exclude_bins, "seed0": spec.seed0, "n_seeds": spec.n_seeds,
            "seeds": str(seeds(spec)), "q_over_pi_grid": f"{g.start}..{g.stop} ({g.count} values)",
            "exact_integrator": spec.exact.method,
            "exact_dt_factor": spec.exact.dt_factor if spec.exact.dt_factor is not None
            else "method default (cradle.integrators.DEFAULT_DT_FACTOR)",
            "dps_integrator": spec.dps.method, "dps_rtol": spec.dps.rtol,
            "dps_atol": "rtol * max |A_n(0)|", "boundary": "periodic",
            "initial_data": "travelling wave (ansatzapprox)-(freq), R = 1, phi = 0, perturbed as in (perturb)",
            "ratio": "max |x_hat_k| / |x_hat_{+-q}| over Gamma* without +-q, +-2(q-pi), +-(3q-2pi) "
                     "(+- exclude_bins bins), cradle.measurements.sidebands.sideband_peak",
            "unstable_when": "ratio >= fraction at some sampled t <= t_end",
            "threshold_method": "last upward crossing of 1/2 by the unstable fraction, linear interpolation; "
                                "interval from Wilson 95 % binomial intervals at the grid points",
            "dps_threshold_linear_theory": modulational.threshold(spec.alpha)[0]}


# ---------------------------------------------------------------- stages

_NMQ, _RUN = ("N", "model", "q"), ("N", "model", "q", "seed")

#: the stored variables of the `mi-statistics` file, per netCDF group: "/" the summary per
#: (N, model, q) and the thresholds, "/runs" one row per run (seed) and its sampled ratio
VARIABLES = {
    "/": {
        "N": Var(("N",), "number N of beads on the ring"),
        "model": MODEL,
        "q": Var(("q",), "carrier wavenumber q of the travelling wave", "rad"),
        "k_index": Var(("N", "q"), "integer k with q = 2 pi k / N"),
        "a": Var(("N", "q"), "wave amplitude a from (freq) at omega_tw"),
        "fraction_unstable": Var(_NMQ, "fraction of seeds unstable by t_end"),
        "fraction_low": Var(_NMQ, "Wilson 95 % lower bound of the unstable fraction"),
        "fraction_high": Var(_NMQ, "Wilson 95 % upper bound of the unstable fraction"),
        "median_crossing_time": Var(_NMQ, "median crossing time over unstable seeds"),
        "threshold": Var(("N", "model"), "threshold q: the unstable fraction crosses 1/2", "rad"),
        "threshold_low": Var(("N", "model"), "lower end of the threshold interval (Wilson 95 %)", "rad"),
        "threshold_high": Var(("N", "model"), "upper end of the threshold interval (Wilson 95 %)", "rad"),
    },
    "/runs": {
        "seed": Var(("seed",), "seed of numpy.random.default_rng drawing the noise of (perturb)"),
        "t": Var(("t",), "dimensionless time t of (nc) at which the spectrum is sampled"),
        "ratio": Var(_RUN + ("t",), "sideband-to-carrier ratio of the spatial spectrum |x_hat_k(t)|"),
        "crossing_time": Var(_RUN, "first time t the sideband ratio reaches the fraction (NaN: not by t_end)",
                             attrs=(("comment", "see crossed; fraction in the global attribute `fraction`"),)),
        "crossed": Var(_RUN, "run unstable by t_end (ratio reached fraction)",
                       attrs=(("comment", "1: the ratio reached fraction by t_end, 0: it did not"),)),
        "k_peak": Var(_RUN, "wavenumber k of the largest sideband at the crossing (at the maximum if none)", "rad"),
        "drift": Var(_RUN, "max relative drift of the lattice energy (exact) or of sum |A_n|^2 (dps)"),
    },
}

#: a batch file (one N, model and chunk of q) is flat: the "/runs" table with k_index and a
BATCH_VARIABLES = {**VARIABLES["/"], **VARIABLES["/runs"]}


def batch(spec: MIStatistics, N: int, model: str, chunk: int, log: Log | None = None) -> xr.Dataset:
    """Runs of one (N, model, chunk): every q of the chunk times every seed -> a flat Dataset
    (:data:`BATCH_VARIABLES`: the "/runs" table with k_index and a)."""
    from cradle.data.io import make_dataset

    say = log or (lambda *a: None)
    wall0 = time.perf_counter()
    ks = chunk_indices(spec, N, chunk)
    sd = seeds(spec)
    t = sample_times(spec)
    R = np.full((len(ks), len(sd), t.size), np.nan, dtype=np.float32)
    KP = np.full((len(ks), len(sd)), np.nan)
    TC = np.full((len(ks), len(sd)), np.nan)
    DR = np.full((len(ks), len(sd)), np.nan)
    amp = np.full(len(ks), np.nan)
    for iq, k in enumerate(ks):
        for js, s in enumerate(sd):
            tt, r, kp, info = run_ratio(model, N, k, s, spec)
            R[iq, js] = r
            TC[iq, js] = crossing_time(tt, r, spec.fraction)
            i = int(np.argmax(r >= spec.fraction)) if np.isfinite(TC[iq, js]) else int(np.argmax(r))
            KP[iq, js] = kp[i]
            DR[iq, js] = info["drift"]
            amp[iq] = info["a"]
        say(f"mi-statistics: N={N} {model} q={2 * k / N:.4f} pi: "
            f"{int(np.sum(np.isfinite(TC[iq])))}/{len(sd)} unstable, {time.perf_counter() - wall0:.1f} s")
    q = 2.0 * np.pi * np.asarray(ks) / N
    data = {"ratio": R[None, None], "crossing_time": TC[None, None],
            "crossed": np.isfinite(TC)[None, None].astype(np.int8), "k_peak": KP[None, None],
            "drift": DR[None, None], "k_index": np.asarray(ks)[None, :], "a": amp[None, :]}
    coords = {"N": [N], "model": np.array([model], dtype=object), "q": q, "seed": sd, "t": t}
    attrs = _attrs(spec) | {"chunk": chunk, "wall_time_s": time.perf_counter() - wall0}
    return make_dataset(data, coords=coords, attrs=attrs, params=plain(spec), variables=BATCH_VARIABLES,
                        title=f"mi-statistics batch: N = {N}, {model}, chunk {chunk}")


def aggregate(batches: Sequence[xr.Dataset], spec: MIStatistics) -> xr.DataTree:
    """Join the batches of one variant (any order) and add the thresholds per (N, model): a tree of
    groups (:data:`VARIABLES`), the summary per q at the root and every run in "/runs"."""
    import warnings

    from cradle.data.io import make_tree

    Ns = sorted({int(n) for b in batches for n in b["N"].values})
    models = [m for m in MODELS if any(m in b["model"].values for b in batches)]
    q = np.unique(np.concatenate([b["q"].values for b in batches]))
    qo = np.round(q / np.pi, 9)
    names = ["ratio", "crossing_time", "crossed", "k_peak", "drift"]
    t = batches[0]["t"].values
    sd = batches[0]["seed"].values
    out = {nm: np.full((len(Ns), len(models), q.size, sd.size) + ((t.size,) if nm == "ratio" else ()),
                       np.nan, dtype=np.float32 if nm == "ratio" else float) for nm in names}
    kidx = np.full((len(Ns), q.size), -1, dtype=int)
    amp = np.full((len(Ns), q.size), np.nan)
    filled = np.zeros((len(Ns), len(models), q.size), dtype=bool)
    wall = 0.0
    for b in batches:
        if not (np.array_equal(b["t"].values, t) and np.array_equal(b["seed"].values, sd)):
            raise ValueError("mi-statistics: batches with different sample times or seeds")
        wall += float(b.attrs.get("wall_time_s", 0.0))
        iN = Ns.index(int(b["N"].values[0]))
        im = models.index(str(b["model"].values[0]))
        iq = np.searchsorted(qo, np.round(b["q"].values / np.pi, 9))
        for nm in names:
            out[nm][iN, im, iq] = b[nm].values[0, 0]
        kidx[iN, iq] = b["k_index"].values[0]
        amp[iN, iq] = b["a"].values[0]
        filled[iN, im, iq] = True
    if not filled.all():
        missing = [(Ns[a], models[b_], float(qo[c])) for a, b_, c in zip(*np.nonzero(~filled), strict=True)]
        raise ValueError(f"mi-statistics: no batch for (N, model, q/pi) = {missing[:5]} ...")
    out["crossed"] = out["crossed"].astype(np.int8)
    frac = out["crossed"].mean(axis=-1)
    thr = {key: np.full((len(Ns), len(models)), np.nan) for key in ("estimate", "low", "high")}
    status = {}
    for iN, N in enumerate(Ns):
        for im, m in enumerate(models):
            th = threshold(q, out["crossed"][iN, im].astype(bool))
            for key in thr:
                thr[key][iN, im] = th[key]
            status[f"threshold_status_N{N}_{m}"] = th["status"]
            status[f"threshold_nonmonotone_N{N}_{m}"] = th["n_nonmonotone"]
    lo, hi = wilson_interval(out["crossed"].sum(axis=-1), sd.size)
    with warnings.catch_warnings():   # all-NaN slices (no unstable seed) give NaN, quietly
        warnings.simplefilter("ignore", RuntimeWarning)
        med = np.nanmedian(np.where(out["crossed"] == 1, out["crossing_time"], np.nan), axis=-1)
    groups = {"/": ({"k_index": kidx, "a": amp, "fraction_unstable": frac, "fraction_low": lo, "fraction_high": hi,
                     "median_crossing_time": med, "threshold": thr["estimate"], "threshold_low": thr["low"],
                     "threshold_high": thr["high"]},
                    {"N": Ns, "model": np.array(models, dtype=object), "q": q}),
              "/runs": (out, {"seed": sd, "t": t})}
    attrs = _attrs(spec) | status | {"batch_wall_time_s_total": wall, "n_runs": int(np.prod(frac.shape)) * sd.size}
    return make_tree(groups, VARIABLES, attrs=attrs, params=plain(spec),
                     title="Modulational-instability threshold statistics: lattice (nc) and DpS (dfnls) over "
                           "noise seeds")


# ---------------------------------------------------------------- the protocol

_KEY = re.compile(r"N(\d+)-(exact|dps)-(\d+)")


def batch_keys(spec: MIStatistics) -> list[str]:
    """The batches of one form, ``N<N>-<model>-<chunk>`` (``N200-exact-0``): every ring size, model and
    chunk of q values."""
    return [f"N{N}-{model}-{chunk}" for N in spec.N for model in MODELS for chunk in range(spec.chunks)]


def run_batch(spec: MIStatistics, key: str, inputs: dict, log: Log | None = None) -> xr.Dataset:
    """The batch ``key`` of :func:`batch_keys` (it reads no file)."""
    found = _KEY.fullmatch(key)
    if found is None or key not in batch_keys(spec):
        raise ValueError(f"mi-statistics: no batch {key!r} in this form (batches: {', '.join(batch_keys(spec))})")
    N, model, chunk = found.groups()
    return batch(spec, int(N), model, int(chunk), log=log)


def compute(spec: MIStatistics, inputs: dict, log: Log | None = None) -> xr.DataTree:
    """The `mi-statistics` file of one form from its batches (``inputs["batch/<key>"]``)."""
    return aggregate([inputs[f"batch/{key}"] for key in batch_keys(spec)], spec)


ANALYSIS = Analysis(
    name="mi-statistics", spec=MIStatistics, compute=compute, variables=VARIABLES,
    batches=Batches(keys=batch_keys, run=run_batch),
    title="Modulational-instability threshold over noise seeds: thresholds from every batch")
