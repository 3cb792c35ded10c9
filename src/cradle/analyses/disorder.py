"""What survives disorder: waves, modulational instability and breathers against on-site detuning (issue 25).

On-site disorder (ncimperfect): omega_n = 1 + sigma z_n, z_n drawn by ``Inhomogeneity(sigma, seed)``
(:func:`cradle.models.inhomogeneity.sites`; for one seed the pattern z_n is the same at every sigma, so a seed's
results against sigma are one realisation scaled). Both models run from the same data:

* the lattice: ``integrate_lattice(..., terms=Terms(inhomogeneity=...), method="dop853_numba")`` (sigma = 0:
  today's (nc) path, ``terms=None``);
* the DpS with site coefficients (dpsimperfect) (:mod:`cradle.models.dps_sites`): the detuning delta_n =
  (omega_n - 1) eps^(1-alpha), integrated in tau = eps^(alpha-1) t (sigma = 0: (dfnls)).

The amplitude axis is the frequency shift Delta = omega - 1 of the wave or breather at that amplitude (``shifts``):
a wave of (freq) with omega_tw = 1 + Delta, an exact breather of (nc) (:mod:`cradle.integrators.lattice_breathers`)
with omega_b = 1 + Delta. Every run lasts ``slow_periods`` slow periods T_s = 2 pi / Delta, so that (dfnls), which
is invariant under A -> l A, tau -> l^(1-alpha) tau, sees the same problem at every Delta up to the ratio
sigma / Delta: the DpS results depend on sigma / Delta alone (same seed), and the prediction is a crossover at
sigma ~ Delta, where the detuning competes with the amplitude-dependent frequency shift.

Families (4 per disorder realisation), each with a survival measure S (1: as in the homogeneous chain):

* ``wave``: the travelling wave of plot4-5 / tw-weak ((ansatzapprox), q = 2 pi wave_mode / N, pi/5 by default).
  Coherence against the homogeneous run from the same data: the fidelity F(t) = |<A, A_hom>| / (|A| |A_hom|)
  (:func:`cradle.measurements.disorder.fidelity`) and the carrier share P(t) = |A_hat_{-q}|^2 / sum |A_hat|^2.
  Definitions reported: the coherence times t_F (F first < 1/2, and < 1/e) and t_P (P first < 1/2), in slow
  periods (NaN: not reached within the run); their distances v_g t (beads, v_g = d omega_tw / dq = Delta
  (alpha+1)/2 cot(q/2) at fixed a, the envelope's group velocity of (freq)); the correlation length xi = N sum_k
  P_k^2 and the participation ratio at the end (means over the last tenth of the run). S = F at the end. Beside
  them the wave's own sensitivity: 1 - F at the end of a homogeneous run from x_n(0) (1 + 1e-6 z_n) (a lattice
  wave of large amplitude amplifies any perturbation, disorder or not).
* ``mi``: fft106's setting, the wave at q = 2 pi mi_mode / N (4 pi/5) perturbed as in (perturb) by Gaussian
  noise of sd ``mi_noise`` (seed: the disorder seed + NOISE_SEED_OFFSET, recorded), smaller than fft106's 0.05 so
  that the sidebands of the homogeneous ring grow over more than a decade; the growth of the dominant sideband pair
  measured as mi-growth does (:func:`cradle.analyses.mi_growth.measure`): the rate per unit t over Delta with the
  linear DpS rate beside it, whether the growth is exponential (mi-growth's test), and the break-up time t_b (the
  largest pair first at 0.2 of the carrier), in slow periods. Disorder seeds the sidebands itself (the wave is no
  solution of the disordered ring) and dephases the carrier, so the break-up comes earlier: S = t_b / t_b(sigma =
  0) of the same noise seed (t_b = the run's length when the pair never saturates).
* ``kicked``: the bond-centred exact breather at omega_b = 1 + Delta given the phase-gradient kick of (dfnls),
  A_n(0) = (x_n^b / 2) e^{i kick (n - c)} (c the bond centre; the lattice state from (ansatz),
  :func:`cradle.models.initial.lattice_state`). The breathers analysis kicks along the Floquet pinning mode,
  which does not exist where the bond breather of the ring is unstable (its stability exchanges); the phase kick
  is defined at every Delta and is the same for both models. Travel: the displacement of the energy centre over
  the run (beads), its velocity over Delta. S = travel / homogeneous travel.
* ``static``: the same breather unkicked. Its frequency: 1 + the mean rate of the phase of its core (the beads
  within ``window`` of its centre), :func:`cradle.measurements.disorder.overlap_frequency` (robust when the energy
  moves between the core's beads, where one bead's phase jumps), against the homogeneous one, over Delta, beside
  the first-order shift sum_n w_n (omega_n - 1) / sum_n w_n, w_n = x_n(0)^2
  (:func:`cradle.measurements.disorder.detuning_shift`); stability as retention: the share of the energy within
  ``window`` beads of the initial centre at the end (a Floquet analysis would need the disordered breather itself,
  which no continuation here computes). S = retention.

Crossover: for each family, model, Delta and seed, sigma* where S first falls below ``level`` (log-linear between
grid values, :func:`cradle.measurements.disorder.crossover`), then its statistics over seeds (mean, std,
quartiles, and how many seeds cross below or above the grid), and sigma* / Delta (the prediction: of order 1).

The full form is split into batch jobs, one per family and Delta (``split``); the reduced form runs in one job.
"""
from __future__ import annotations

import math
import re
import time
from typing import TYPE_CHECKING, Any

import numpy as np

from cradle.analyses.protocol import Analysis, Batches
from cradle.data.variables import MODEL, MODELS, Var
from cradle.measurements import disorder as md
from cradle.specs.declare import declared, param, plain

if TYPE_CHECKING:
    import xarray as xr
    from numpy.typing import ArrayLike, NDArray

    from cradle.analyses.protocol import Log
    from cradle.integrators.lattice_breathers import Breather
    from cradle.models.inhomogeneity import Inhomogeneity, Sites
    from cradle.models.initial import InitialData
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors

#: Hertz's exponent of (vhertz) for spheres
ALPHA = 1.5
FAMILIES = ("wave", "mi", "kicked", "static")
#: the noise of (perturb) of the mi family is drawn with seed + NOISE_SEED_OFFSET: independent of the disorder draw
#: of the same seed (the same seed would give rho = the same normal numbers as z_n)
NOISE_SEED_OFFSET = 1_000_003
#: the longest sampling step: the phase of A_n must turn by less than pi between samples for the frequency of
#: the static breather, (Delta + 5 sigma) MAX_DT < pi for every allowed Delta and sigma
MAX_DT = 0.5
#: share of the run (its end) over which end values are averaged
END_SHARE = 0.1
#: points of the stored fidelity series per run, on a grid in slow periods
SERIES_POINTS = 121
#: relative size of the perturbation of the wave's control run (its own sensitivity, without disorder)
CONTROL = 1e-6
LEVELS = (0.5, math.exp(-1.0))

_SIGMA = {"type": "number", "minimum": 0, "maximum": 0.2, "description": "A disorder strength sigma (std of "
          "omega_n - 1); <= 0.2 so that no normal draw on a ring of <= 256 beads reaches omega_n <= 0 in practice "
          "(5 sigma)."}
_SHIFT = {"type": "number", "exclusiveMinimum": 0, "maximum": 0.5, "description": "A frequency shift Delta = omega "
          "- 1 of the wave or breather (> 0)."}


@declared(doc="What survives on-site disorder omega_n = 1 + sigma z_n (issue 25): a travelling wave's coherence "
              "(plot4-5's wave), the modulational instability (fft106's setting), a kicked breather's travel and a "
              "static breather's frequency and retention, lattice (ncimperfect) and DpS (dpsimperfect), over seeds; "
              "the crossover sigma* against the frequency shift Delta -> results/disorder/disorder.nc and "
              "results/figures/disorder.{pdf,png}.")
class Disorder:
    N: int = param(40, "Ring size of every run (plot4-5: 50 with q = pi/5; 40 keeps q = pi/5 and 4 pi/5 on the "
                   "grid).", minimum=8, maximum=256)
    sigmas: list[float] = param([0.0, 0.003, 0.01, 0.03, 0.06, 0.1, 0.2], "Disorder strengths sigma (std of "
                                "omega_n - 1), increasing; 0 is the homogeneous reference.", minItems=2,
                                maxItems=24, items=_SIGMA,
                                reduced=[0.0, 0.01, 0.03, 0.1])
    distribution: str = param("normal", "Law of z_n (cradle.models.inhomogeneity): normal or uniform.",
                              enum=["normal", "uniform"])
    shifts: list[float] = param([0.01, 0.03, 0.1, 0.3], "Frequency shifts Delta = omega - 1 of the waves and "
                                "breathers (the amplitude axis), increasing.", minItems=1, maxItems=12, items=_SHIFT,
                                reduced=[0.1, 0.3])
    seeds: int = param(8, "Disorder draws per sigma: seeds first_seed, first_seed + 1, ...", minimum=1, maximum=64,
                       reduced=2)
    first_seed: int = param(1, "First seed of np.random.default_rng for the draws.", minimum=0, maximum=2**31)
    slow_periods: float = param(6.0, "Run length in slow periods T_s = 2 pi / Delta (the same for every Delta: "
                                "the DpS runs then differ by sigma / Delta only).", minimum=1, maximum=50,
                                reduced=6.0)
    samples: int = param(64, "Stored samples per slow period (more where 2 pi / Delta / samples > 0.5).",
                         minimum=16, maximum=1024)
    wave_mode: int = param(4, "k of the coherent wave's q = 2 pi k / N (4 on N = 40: q = pi/5, plot4-5).",
                           minimum=1, maximum=128)
    mi_mode: int = param(16, "k of the unstable wave's q = 2 pi k / N (16 on N = 40: q = 4 pi/5, fft106).",
                         minimum=1, maximum=128)
    mi_noise: float = param(0.02, "sd of the Gaussian noise of (perturb) on the unstable wave (fft106: 0.05; "
                            "smaller here: on a ring of 40 beads 0.05 leaves the sidebands less than a decade to "
                            "grow).",
                            exclusiveMinimum=0, maximum=0.5)
    kick: float = param(0.4, "Phase gradient of the kicked breather, rad per bead.", exclusiveMinimum=0, maximum=1.5)
    window: float = param(5.0, "Beads from a breather's centre within which its energy counts as retained.",
                          exclusiveMinimum=0, maximum=64)
    level: float = param(0.5, "A survival measure below this marks the crossover sigma*.", exclusiveMinimum=0,
                         exclusiveMaximum=1)
    rtol: float = param(1e-9, "Relative tolerance of every lattice and DpS run (dop853_numba).", minimum=1e-13,
                        maximum=1e-6)
    split: bool = param(True, "One batch job per family and Delta (the full form on several cores).",
                        reduced=False)

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Each form: the modes fit the ring below the zone edge; sigmas and shifts increasing, 0 among sigmas."""
        for key in ("wave_mode", "mi_mode"):
            if not 2 * getattr(self, key) < self.N:
                out.add(where + [key], f"must be below N / 2 (N = {self.N}; q < pi)", getattr(self, key))
        for key in ("sigmas", "shifts"):
            v = getattr(self, key)
            if any(b <= a for a, b in zip(v, v[1:], strict=False)):
                out.add(where + [key], "must be strictly increasing", v)
        if self.sigmas[0] != 0.0:
            out.add(where + ["sigmas"], "must start with 0 (the homogeneous reference of every survival measure)",
                    self.sigmas)


# ----------------------------------------------------------------- one run of each model


def seeds_of(spec: Disorder) -> list[int]:
    """The disorder seeds: first_seed, first_seed + 1, ..."""
    return [spec.first_seed + i for i in range(spec.seeds)]


def time_grid(spec: Disorder, shift: float) -> np.ndarray:
    """0 .. slow_periods T_s with ``samples`` per T_s (more if the step would exceed MAX_DT)."""
    Ts = 2.0 * np.pi / shift
    per = max(spec.samples, int(math.ceil(Ts / MAX_DT)))
    return Ts / per * np.arange(int(round(spec.slow_periods * per)) + 1)


def _sites(spec: Disorder, sigma: float, seed: int) -> tuple[Inhomogeneity, Sites]:
    from cradle.models.inhomogeneity import Inhomogeneity, sites

    inh = Inhomogeneity(sigma=sigma, distribution=spec.distribution, seed=seed)
    return inh, sites(inh, spec.N)


def run_models(spec: Disorder, init: InitialData, t: NDArray[np.float64], sigma: float, seed: int) -> dict[str, Any]:
    """Both models from ``init`` (x0, v0, A0, eps) on ``t`` at (sigma, seed): {"exact": (A, x, v), "dps": (A,
    None, None), "omega": omega_n, "drift": lattice energy drift, "l2": DpS l2 drift}; A the (ansatz) amplitude."""
    from cradle.analyses.mi_growth import lattice_amplitude
    from cradle.integrators import integrate_dps, integrate_lattice
    from cradle.models.dps_sites import dps_sites
    from cradle.models.lattice_terms import Terms

    eps = float(init.eps)
    tau = eps ** (ALPHA - 1.0) * t
    if sigma > 0.0:
        inh, s = _sites(spec, sigma, seed)
        lat = integrate_lattice(init.x0, init.v0, t, alpha=ALPHA, method="dop853_numba", rtol=spec.rtol,
                                terms=Terms(inhomogeneity=inh))
        ds = integrate_dps(init.A0, tau, alpha=ALPHA, rtol=spec.rtol,
                           sites=dps_sites(s.mass, s.omega, s.stiffness, alpha=ALPHA, eps=eps))
        omega = s.omega
    else:
        lat = integrate_lattice(init.x0, init.v0, t, alpha=ALPHA, method="dop853_numba", rtol=spec.rtol)
        ds = integrate_dps(init.A0, tau, alpha=ALPHA, rtol=spec.rtol)
        omega = np.ones(spec.N)
    x, v = np.asarray(lat.x), np.asarray(lat.v)
    return {"exact": (lattice_amplitude(x, v, t, eps), x, v), "dps": (np.asarray(ds.A), None, None),
            "omega": omega, "drift": float(lat.energy_drift), "l2": float(ds.max_l2_drift)}


def _end(t: NDArray[np.float64], y: ArrayLike) -> float:
    """Mean of y over the last END_SHARE of the run."""
    return float(np.mean(np.asarray(y)[t >= t[-1] * (1.0 - END_SHARE) - 1e-12]))


# ----------------------------------------------------------------- the families


def initial_data(spec: Disorder, family: str, shift: float, seed: int = 0,
                 breather: Breather | None = None) -> InitialData:
    """The InitialData of a family at Delta (the mi family's noise from ``seed``; the breather families from the
    exact breather ``breather``)."""
    from cradle.models import initial

    q = 2.0 * np.pi * (spec.wave_mode if family == "wave" else spec.mi_mode) / spec.N
    if family == "wave":
        return initial.travelling_wave(spec.N, q, ALPHA, omega_tw=1.0 + shift)
    if family == "mi":
        return initial.travelling_wave(spec.N, q, ALPHA, omega_tw=1.0 + shift, noise_kind="gaussian",
                                       noise_amplitude=spec.mi_noise, seed=seed + NOISE_SEED_OFFSET)
    x_b = np.asarray(breather.x0, dtype=float)  # type: ignore[union-attr]  # a breather family's
    A0 = 0.5 * x_b.astype(complex)
    if family == "kicked":
        A0 = A0 * np.exp(1j * spec.kick * (np.arange(spec.N) - bond_centre(spec.N)))
        x0, v0 = initial.lattice_state(A0, 1.0, ALPHA)
    else:
        x0, v0 = x_b, np.zeros_like(x_b)
    return initial.InitialData(A0=A0, eps=1.0, x0=x0, v0=v0, info={"omega_b": breather.omega})  # type: ignore[union-attr]


def bond_centre(N: int) -> float:
    """Centre of the bond-centred breather of :func:`exact_breather`: the bond (N/2, N/2 + 1)."""
    return N // 2 + 0.5


def exact_breather(spec: Disorder, shift: float) -> Breather:
    """The bond-centred exact breather of (nc) on the ring at omega_b = 1 + Delta (Newton from the DpS breather,
    :func:`cradle.integrators.lattice_breathers.continue_family`)."""
    from cradle.analyses.breathers import _profile
    from cradle.integrators import lattice_breathers as lb

    a = _profile(spec.N, "bond", ALPHA, "periodic")
    fam, _ = lb.continue_family(a, [1.0 + shift], ALPHA, "periodic", "bond", spec.N // 2, tol=1e-11)
    if not fam:
        raise RuntimeError(f"disorder: no exact bond breather at omega_b = {1.0 + shift:g} on N = {spec.N}")
    return fam[0]


#: the measured quantities of each family, per model, sigma and seed (the survival measure first)
MEASURES: dict[str, dict[str, str]] = {
    "wave": {
        "survival": "fidelity F with the homogeneous run, mean over the last tenth of the run",
        "coherence_time_half": "first time F < 1/2, in slow periods 2 pi / Delta (NaN: not within the run)",
        "coherence_time_e": "first time F < 1/e, in slow periods (NaN: not within the run)",
        "carrier_time_half": "first time the carrier share |A_hat_{-q}|^2 / sum |A_hat|^2 < 1/2, in slow periods",
        "coherence_distance_half": "v_g times the first time F < 1/2, beads (v_g = d omega_tw/dq at fixed a)",
        "carrier_end": "carrier share at the end (mean over the last tenth)",
        "correlation_length": "xi = N sum_k P_k^2 at the end (mean over the last tenth), beads",
        "participation": "(sum |A_n|^2)^2 / (N sum |A_n|^4) at the end (mean over the last tenth)",
    },
    "mi": {
        "survival": "break-up time (saturation_time, the run's length if none) over the homogeneous one of the "
                    "same noise seed",
        "rate": "fitted growth rate of the dominant sideband pair per unit t, over Delta",
        "exponential": "1: an exponential phase was found (mi-growth's test), 0: not",
        "saturation_time": "first time the largest sideband pair reaches 0.2 of the carrier, slow periods",
        "p_star": "wavenumber of the dominant sideband pair (rad)",
    },
    "kicked": {
        "survival": "travel of the energy centre over the homogeneous travel",
        "travel": "displacement of the energy centre over the run, beads",
        "velocity": "velocity of the energy centre (second half of the run), beads per unit t, over Delta",
        "retention": "share of the energy within `window` beads of the final centre at the end",
    },
    "static": {
        "survival": "share of the energy within `window` beads of the initial centre (mean over the last tenth)",
        "frequency_shift": "breather frequency minus the homogeneous one, over Delta",
        "frequency_shift_predicted": "first-order shift sum w_n (omega_n - 1) / sum w_n, w_n = x_n(0)^2, over "
                                     "Delta",
        "centre_drift": "|displacement| of the energy centre over the run, beads",
    },
}


def _density(model: str, run: dict, omega: NDArray[np.float64]) -> np.ndarray:
    A, x, v = run[model]
    if model == "exact":
        return md.site_energy(x, v, ALPHA, omega)
    return np.abs(A) ** 2


def measure_family(spec: Disorder, family: str, shift: float, t: NDArray[np.float64], run: dict, ref: dict | None,
                   init: InitialData) -> dict:
    """The quantities of :data:`MEASURES` of one run pair, per model: {model: {name: value}}; ``ref`` the same
    family's homogeneous run pair (its measures under ``"measures"``, its runs under the models)."""
    Ts = 2.0 * np.pi / shift
    N = spec.N
    out: dict[str, dict[str, float]] = {}
    for model in MODELS:
        A = run[model][0]
        r: dict[str, float] = {}
        if family == "wave":
            k_q = spec.wave_mode
            q = 2.0 * np.pi * k_q / N
            F = md.fidelity(A, ref[model][0]) if ref is not None else np.ones(t.size)
            P = md.carrier_fraction(A, -k_q)
            vg = shift * (ALPHA + 1.0) / 2.0 / math.tan(q / 2.0)
            tF = md.first_below(t, F, LEVELS[0])
            r.update(survival=_end(t, F), coherence_time_half=tF / Ts, coherence_time_e=md.first_below(t, F, LEVELS[1])
                     / Ts, carrier_time_half=md.first_below(t, P, 0.5) / Ts, coherence_distance_half=vg * tF,
                     carrier_end=_end(t, P), correlation_length=_end(t, md.correlation_length(A)),
                     participation=_end(t, md.participation(A)))
            r["_series"] = F   # type: ignore[assignment]
        elif family == "mi":
            from cradle.analyses import mi_growth as mg

            S = mg.pair_spectrum(A, spec.mi_mode)
            m = mg.measure(t, S, mg.harmonic_indices(spec.mi_mode, N))
            rate = m["rate"] / shift
            r.update(rate=rate, exponential=float(m["exponential"]), saturation_time=m["t_b"] / Ts if m["saturated"]
                     else float("nan"), p_star=2.0 * np.pi * m["m_star"] / N)
            t_b = m["t_b"] / Ts if m["saturated"] else spec.slow_periods   # never saturated: at least the run
            base = ref["measures"][model]["_breakup"] if ref is not None else t_b
            r["survival"], r["_breakup"] = t_b / base, t_b
        else:
            e = _density(model, run, run["omega"])
            path, dist, vel = md.travel(t, e)
            if family == "kicked":
                base = ref["measures"][model]["travel"] if ref is not None else dist
                r.update(survival=dist / base, travel=dist, velocity=vel / shift,
                         retention=float(md.retention(e[-1], path[-1], spec.window)))
            else:
                near = md.ring_distance(N, bond_centre(N)) <= spec.window
                w = 1.0 + md.overlap_frequency(t, A[:, near])
                base = ref["measures"][model]["_omega"] if ref is not None else w
                pred = md.detuning_shift(np.asarray(init.x0) ** 2, run["omega"] - 1.0)
                ret = md.retention(e, bond_centre(N), spec.window)
                r.update(survival=_end(t, ret), frequency_shift=(w - base) / shift,
                         frequency_shift_predicted=pred / shift, centre_drift=abs(dist), _omega=w)
        out[model] = r
    return out


def run_case(spec: Disorder, family: str, shift: float, t: NDArray[np.float64], sigma: float, seed: int,
             breather: Breather | None, ref: dict | None) -> tuple[dict[str, Any], dict]:
    """One case of a batch (:func:`family_batch`): the run pair of ``family`` at (Delta, sigma, seed) on ``t`` from
    its initial data (``breather`` the batch's exact breather, None for the waves) and its measures against
    ``ref``, the homogeneous run pair (ignored at sigma = 0): (run, {model: {name: value}})."""
    init = initial_data(spec, family, shift, seed, breather)
    run = run_models(spec, init, t, sigma, seed)
    return run, measure_family(spec, family, shift, t, run, ref if sigma > 0 else None, init)


def family_batch(spec: Disorder, family: str, shift: float, log: Log | None = None) -> dict[str, Any]:
    """Every run of one family at one Delta: arrays (model, sigma, seed) of each measure, the fidelity series
    (model, sigma, seed, s) of the wave, and the drifts."""
    say = log or (lambda *a: None)
    t0 = time.perf_counter()
    t = time_grid(spec, shift)
    seeds = seeds_of(spec)
    sig = list(spec.sigmas)
    names = list(MEASURES[family])
    arr = {k: np.full((len(MODELS), len(sig), len(seeds)), np.nan) for k in names}
    s_grid = np.linspace(0.0, spec.slow_periods, SERIES_POINTS)
    series = np.full((len(MODELS), len(sig), len(seeds), SERIES_POINTS), np.nan)
    drift, l2 = np.full((len(sig), len(seeds)), np.nan), np.full((len(sig), len(seeds)), np.nan)
    b = exact_breather(spec, shift) if family in ("kicked", "static") else None
    Ts = 2.0 * np.pi / shift
    ref0 = None   # the homogeneous run pair of the deterministic families: the same for every seed
    for j, seed in enumerate(seeds):
        ref = None
        for i, sigma in enumerate(sig):
            if sigma == 0.0 and ref0 is not None:
                for k in names:
                    arr[k][:, i, j] = arr[k][:, i, 0]
                series[:, i, j] = series[:, i, 0]
                drift[i, j], l2[i, j] = drift[i, 0], l2[i, 0]
                ref = ref0
                continue
            run, res = run_case(spec, family, shift, t, sigma, seed, b, ref)
            if sigma == 0.0:
                ref = dict(run, measures=res)
                if family != "mi":   # the mi family's noise depends on the seed
                    ref0 = ref
            for m, model in enumerate(MODELS):
                for k in names:
                    arr[k][m, i, j] = res[model][k]
                if family == "wave":
                    series[m, i, j] = np.interp(s_grid, t / Ts, res[model]["_series"])
            drift[i, j], l2[i, j] = run["drift"], run["l2"]
    control = np.full(len(MODELS), np.nan)
    if family == "wave" and ref0 is not None:
        # the homogeneous wave's own sensitivity: the same run from x_n(0) (1 + CONTROL z_n), z_n ~ N(0, 1) of seed
        # first_seed; 1 - F at the end tells how much of a lost fidelity the wave's own dynamics would amplify
        init = initial_data(spec, "wave", shift)
        z = np.random.default_rng(spec.first_seed).standard_normal(spec.N)
        init.x0 = init.x0 * (1.0 + CONTROL * z)
        init.A0 = init.A0 * (1.0 + CONTROL * z)
        ctl = run_models(spec, init, t, 0.0, spec.first_seed)
        control[:] = [1.0 - _end(t, md.fidelity(ctl[m][0], ref0[m][0])) for m in MODELS]
    say(f"disorder: {family} Delta = {shift:g}: {time.perf_counter() - t0:.1f} s; survival (lattice, seed mean) "
        + " ".join(f"{s:g}:{np.nanmean(arr['survival'][0, i]):.2f}" for i, s in enumerate(sig)))
    return {"measures": arr, "series": series, "drift": drift, "l2": l2, "control": control,
            "wall": time.perf_counter() - t0,
            "omega_b": float(b.omega) if b is not None else float("nan")}


# ----------------------------------------------------------------- the stored file

_CELL = ("model", "shift", "sigma", "seed")
_XO = ("family", "model", "shift")
_COORDS = {
    "model": MODEL,
    "sigma": Var(("sigma",), "disorder strength sigma: standard deviation of omega_n - 1"),
    "shift": Var(("shift",), "frequency shift Delta = omega - 1 of the wave or breather (the amplitude axis)"),
    "seed": Var(("seed",), "seed of np.random.default_rng of the disorder draw z_n (omega_n = 1 + sigma z_n)",
                attrs=(("comment", "the mi family's noise of (perturb) has seed + noise_seed_offset"),)),
    "stat": Var(("stat",), "statistic over seeds: mean, std (ddof 1), q25, median, q75, count of finite values"),
    "family": Var(("family",), "family of initial data: wave, mi, kicked, static"),
    "s": Var(("s",), "time in slow periods 2 pi / Delta"),
}


def _family_vars(family: str, dims: tuple[str, ...]) -> dict[str, Var]:
    out = {k: Var(dims, doc) for k, doc in MEASURES[family].items()}
    out["energy_drift"] = Var(dims[1:-1] + ("seed",) if "shift" in dims else ("sigma", "seed"),
                              "relative energy drift of the lattice run (integrator error)")
    out["dps_l2_drift"] = Var(out["energy_drift"].dims, "relative l2 drift of the DpS run (integrator error)")
    if family == "wave":
        out["fidelity"] = Var(dims + ("s",), "fidelity F(t) = |<A, A_hom>| / (|A| |A_hom|) against time in slow "
                              "periods")
        out["control_infidelity"] = Var(dims[:-2] if "shift" in dims else ("model",),
                                        "1 - F at the end of the homogeneous run from x_n(0) (1 + 1e-6 z_n): the "
                                        "wave's own sensitivity, without disorder")
    return out


#: the stored variables of the `disorder` file: the coordinates at the root, one group per family (each measure
#: along model, shift, sigma, seed) and "/crossover" (sigma* per seed and its statistics)
VARIABLES: dict[str, dict[str, Var]] = {
    "/": {**_COORDS,
          "omega_b": Var(("shift",), "frequency of the exact bond breather of the kicked and static families"),
          "theory_growth_rate": Var(("shift",), "max over p of the linear DpS growth rate of the mi wave, per unit t, "
                                "over Delta")},
    **{f"/{f}": _family_vars(f, _CELL) for f in FAMILIES},
    "/crossover": {
        "sigma_star": Var(_XO + ("seed",), "sigma where the family's survival first falls below `level`",
                          attrs=(("comment", "NaN: censored, see censoring"),)),
        "censoring": Var(_XO + ("seed",), "0: crossing inside the grid; -1: below at the smallest sigma > 0; "
                         "+1: never below"),
        "sigma_star_stats": Var(_XO + ("stat",), "statistics over seeds of sigma* (crossings inside the grid)"),
        "ratio_stats": Var(_XO + ("stat",), "statistics over seeds of sigma* / Delta (prediction: of order 1)"),
        "n_below": Var(_XO, "seeds already below `level` at the smallest sigma > 0"),
        "n_above": Var(_XO, "seeds never below `level`"),
        "sigma_star_of_mean": Var(_XO, "sigma where the seed-mean survival first falls below `level`"),
        "survival_stats": Var(_XO + ("sigma", "stat"), "statistics over seeds of the survival measure"),
    },
}

#: a batch file: one family at one Delta (the shift dimension dropped)
BATCH_VARIABLES: dict[str, dict[str, Var]] = {f: {**_COORDS, **_family_vars(f, ("model", "sigma", "seed"))}
                                              for f in FAMILIES}


def batch_dataset(spec: Disorder, family: str, shift: float, log: Log | None = None) -> xr.Dataset:
    """One batch (family, Delta) as a Dataset of :data:`BATCH_VARIABLES`."""
    from cradle.data.io import make_dataset

    r = family_batch(spec, family, shift, log)
    data = dict(r["measures"], energy_drift=r["drift"], dps_l2_drift=r["l2"])
    if family == "wave":
        data["fidelity"], data["control_infidelity"] = r["series"], r["control"]
    coords = {"model": np.array(MODELS, dtype=object), "sigma": np.asarray(spec.sigmas, float),
              "seed": np.asarray(seeds_of(spec)), "s": np.linspace(0.0, spec.slow_periods, SERIES_POINTS)}
    return make_dataset(data, coords, attrs={"family": family, "shift": shift, "omega_b": r["omega_b"],
                                             "wall_time_s": r["wall"]},
                        params=plain(spec), variables=BATCH_VARIABLES[family],
                        title=f"disorder batch: {family} at Delta = {shift:g}")


_KEY = re.compile(r"(wave|mi|kicked|static)-(\d+)")


def batch_keys(spec: Disorder) -> list[str]:
    """``<family>-<i>`` for every family and index i of ``shifts`` when ``split``; none otherwise (the analysis
    job runs everything)."""
    return [f"{f}-{i}" for f in FAMILIES for i in range(len(spec.shifts))] if spec.split else []


def run_batch(spec: Disorder, key: str, inputs: dict, log: Log | None = None) -> xr.Dataset:
    """The batch ``key`` of :func:`batch_keys` (it reads no file)."""
    found = _KEY.fullmatch(key)
    if found is None or key not in batch_keys(spec):
        raise ValueError(f"disorder: no batch {key!r} in this form (batches: {', '.join(batch_keys(spec)) or 'none'})")
    return batch_dataset(spec, found.group(1), float(spec.shifts[int(found.group(2))]), log)


def crossovers(spec: Disorder, survival: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The /crossover group from each family's survival (model, shift, sigma, seed)."""
    sig = np.asarray(spec.sigmas, float)
    shifts = np.asarray(spec.shifts, float)
    F, M, D, S = len(FAMILIES), len(MODELS), shifts.size, spec.seeds
    star, cens = np.full((F, M, D, S), np.nan), np.zeros((F, M, D, S), dtype=np.int8)
    of_mean = np.full((F, M, D), np.nan)
    surv = np.full((F, M, D, sig.size, len(md.STATISTICS)), np.nan)
    for f, fam in enumerate(FAMILIES):
        y = survival[fam]
        surv[f] = md.seed_statistics(y, axis=-1)
        for m in range(M):
            for d in range(D):
                for s in range(S):
                    star[f, m, d, s], cens[f, m, d, s] = md.crossover(sig, y[m, d, :, s], spec.level)
                of_mean[f, m, d] = md.crossover(sig, np.nanmean(y[m, d], axis=-1), spec.level)[0]
    return {"sigma_star": star, "censoring": cens, "sigma_star_stats": md.seed_statistics(star),
            "ratio_stats": md.seed_statistics(star / shifts[None, None, :, None]),
            "n_below": np.sum(cens == -1, axis=-1), "n_above": np.sum(cens == 1, axis=-1),
            "sigma_star_of_mean": of_mean, "survival_stats": surv}


def compute(spec: Disorder, inputs: dict | None = None, log: Log | None = None) -> xr.DataTree:
    """The `disorder` analysis as a tree (:data:`VARIABLES`): the batches gathered (``inputs["batch/<key>"]``)
    or, without batches, every family and Delta run here."""
    from cradle.analyses import mi_growth as mg
    from cradle.data.io import make_tree
    from cradle.models import dps

    t0 = time.perf_counter()
    inputs = inputs or {}
    keys = batch_keys(spec)
    shifts = list(spec.shifts)
    groups: dict[str, tuple[dict, dict]] = {}
    survival: dict[str, np.ndarray] = {}
    omega_b = np.full(len(shifts), np.nan)
    walls = 0.0
    for fam in FAMILIES:
        parts = []
        for i, shift in enumerate(shifts):
            key = f"{fam}-{i}"
            ds = inputs[f"batch/{key}"] if keys else batch_dataset(spec, fam, float(shift), log)
            parts.append(ds)
            walls += float(ds.attrs["wall_time_s"])
            if fam in ("kicked", "static"):
                omega_b[i] = float(ds.attrs["omega_b"])
        data = {}
        for name, var in VARIABLES[f"/{fam}"].items():
            axis = var.dims.index("shift")
            data[name] = np.stack([np.asarray(p[name].values, dtype=float) for p in parts], axis=axis)
        groups[f"/{fam}"] = (data, {})
        survival[fam] = data["survival"]
    groups["/crossover"] = (crossovers(spec, survival), {})
    q_mi = 2.0 * np.pi * spec.mi_mode / spec.N
    theory = []
    for shift in shifts:   # the linear DpS rate of the mi wave at omega_tw = 1 + Delta, R = 1, eps = a / 2
        a = dps.amplitude_from_omega(1.0 + shift, q_mi, ALPHA)
        theory.append(float(np.max(mg.theory_rates(q_mi, spec.N, ALPHA, a / 2.0)[1])) / shift)
    groups["/"] = ({"omega_b": omega_b, "theory_growth_rate": np.asarray(theory)},
                   {"model": np.array(MODELS, dtype=object), "sigma": np.asarray(spec.sigmas, float),
                    "shift": np.asarray(shifts, float), "seed": np.asarray(seeds_of(spec)),
                    "stat": np.array(md.STATISTICS, dtype=object), "family": np.array(FAMILIES, dtype=object),
                    "s": np.linspace(0.0, spec.slow_periods, SERIES_POINTS)})
    attrs = {
        "alpha": ALPHA, "N": spec.N, "distribution": spec.distribution, "level": spec.level,
        "wave": f"(ansatzapprox) q = 2 pi {spec.wave_mode} / {spec.N}, omega_tw = 1 + Delta (plot4-5's wave)",
        "mi": f"(ansatzapprox) q = 2 pi {spec.mi_mode} / {spec.N}, omega_tw = 1 + Delta, Gaussian noise of (perturb) "
              f"sd {spec.mi_noise:g} (fft106's setting)",
        "breather": f"exact bond-centred breather of (nc) at omega_b = 1 + Delta; kicked: phase gradient "
                    f"{spec.kick:g} rad per bead; retention window {spec.window:g} beads",
        "noise_seed_offset": NOISE_SEED_OFFSET,
        "run_length": f"{spec.slow_periods:g} slow periods 2 pi / Delta; samples every min(2 pi / Delta / "
                      f"{spec.samples}, ~{MAX_DT:g})",
        "integrators": f"lattice dop853_numba (terms=Terms(inhomogeneity) for sigma > 0), DpS dop853_numba "
                       f"(sites=dps_sites(...) for sigma > 0), rtol = {spec.rtol:g}",
        "max_energy_drift": float(np.nanmax([np.nanmax(groups[f"/{f}"][0]["energy_drift"]) for f in FAMILIES])),
        "batch_wall_time_s_total": walls,
        "wall_time_s": time.perf_counter() - t0,
    }
    return make_tree(groups, VARIABLES, attrs=attrs, params=plain(spec),
                     title="What survives on-site disorder: wave coherence, modulational instability, breather "
                           "travel and frequency, lattice (ncimperfect) and DpS (dpsimperfect)")


ANALYSIS = Analysis(
    name="disorder", spec=Disorder, compute=compute, variables=VARIABLES,
    batches=Batches(keys=batch_keys, run=run_batch),
    title="What survives on-site disorder: waves, modulational instability and breathers, lattice and DpS")
