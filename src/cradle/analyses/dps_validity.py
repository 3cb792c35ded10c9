"""How long and how well DpS describes the lattice: the approximation error measured against eps and T.

Well-prepared data: the lattice (nc) starts exactly on the ansatz (ansatz),
x_n(0) = eps (A_n(0) + c.c.) with the velocities of :func:`cradle.models.initial.lattice_state`;
the DpS equation (dfnls) is integrated from the same A_n(0) and x_app is rebuilt by (ansatz)
(:func:`cradle.measurements.compare.approximate_displacement`). Recorded: the sup-norm error

    E_abs(eps, T) = sup_{0 <= t <= T eps^(1-alpha)} max_n |x_n(t) - x_n^app(t)|,   E_rel = E_abs / (2 eps),

for slow times T = tau = eps^(alpha-1) t. Every family is normalised so that max_n |A_n(0)| = 1 and
2 eps is the largest initial displacement (a = 2 eps for the waves of (ansatzapprox)).

Bidegaray-Fesquet, Dumas & James (SIAM J. Math. Anal. 45, 2013) prove the approximation on the
time scale t <= T eps^(1-alpha); we did not find the exact statement of their bound (power of eps)
in the sources available to us, so the reference law here is the consistency order of (ansatz):
the residual of x_app in (nc) is the non-resonant harmonics e^{3it}, e^{5it}, ... of
V0'(eps (...)) = eps^alpha V0'(...), of size eps^alpha, plus eps^(2 alpha - 1) A_tautau; over
t ~ eps^(1-alpha) the Gronwall factor is e^{C T}. Hence E_abs = O(eps^alpha) (E_rel = O(eps^(alpha-1)))
with a constant growing with T. The fitted power of eps is compared with alpha.

Families (:data:`FAMILIES`): the travelling waves (ansatzapprox) q = pi/5 and 4 pi/5 on a ring of
``N_wave`` beads; the bond-centred breather (ansatzapproxst2)/(breatherdps) from the homoclinic
profile of (dpsstn) on ``N_breather`` beads; the modulationally unstable wave q = 4 pi/5 perturbed as
in (perturb) with small uniform noise on ``N_noise`` beads (DpS growth rate: (ansatz3)).

The work is split into batches (:data:`ANALYSIS`: one job per alpha, key ``alpha<k>-<alpha>``; the lattice
runs last T eps^(1-alpha), so the largest alphas cost most and run side by side): :func:`batch` runs every
family at one alpha -> Dataset; :func:`compute` joins the batches of a form and derives the ratios and fits
(``compute(spec)`` with no batches runs them itself, one after another).
"""
from __future__ import annotations

import time
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.protocol import Analysis, Batches
from cradle.data.variables import Var
from cradle.measurements.dps_range import EPS_MEASURED
from cradle.specs.declare import declared, param, plain
from cradle.specs.values import DT_FACTOR_FLOOR, RTOL_FLOOR, SEED_MAX, show

if TYPE_CHECKING:
    import xarray as xr
    from numpy.typing import ArrayLike, NDArray

    from cradle.analyses.protocol import Log
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors

FAMILIES = ("tw-pi5", "tw-4pi5", "breather-bond", "mi-4pi5-noise")
_Q = {"tw-pi5": np.pi / 5.0, "tw-4pi5": 4.0 * np.pi / 5.0, "mi-4pi5-noise": 4.0 * np.pi / 5.0}

# ----------------------------------------------------------------- the spec (config `beyond: dps-validity:`)

_ALPHAS = {"$ref": "#/$defs/alpha", "maximum": 10}
_EPS = {"description": "Smallest eps of one alpha.", "type": "number", "exclusiveMinimum": 0, "maximum": 1}
_TS = {"description": "A slow time T = eps^(alpha-1) t (> 0).", "type": "number", "exclusiveMinimum": 0,
       "maximum": 1000}
_FAMILY = {"description": "A family of well-prepared data.", "type": "string", "enum": list(FAMILIES)}


@declared(doc="How long and how well DpS describes the lattice: sup_{t <= T eps^(1-alpha)} |x - x_app| with x_app "
              "from (ansatz), for well-prepared data (travelling waves q = pi/5, 4 pi/5, a bond-centred breather, "
              "a modulationally unstable wave with small noise) over eps and T, and the fitted power of eps "
              "against the consistency order eps^alpha -> results/dps-validity/dps-validity.nc and "
              "results/figures/dps-validity.{pdf,png}.")
class DpsValidity:
    alpha: list[float] = param([1.1, 1.5, 2.0, 3.0], "Hertz exponents alpha of V0 (each > 1).", minItems=1,
                               maxItems=6, items=_ALPHAS,
                               reduced=[1.5])
    eps_min: list[float] = param([1e-5, 1e-5, 1e-4, 1e-2], "Smallest eps of (ansatz), one per alpha (< eps_max): "
                                 "the lattice runs last T eps^(1-alpha) (alpha = 3: T eps^-2, unreachable at "
                                 "eps = 1e-5), so the range shrinks as alpha grows.", minItems=1, maxItems=6,
                                 items=_EPS,
                                 reduced=[1e-3])
    eps_max: float = param(EPS_MEASURED, "Largest eps (half the largest initial displacement).", exclusiveMinimum=0,
                           maximum=1.0)
    n_eps: int = param(9, "Number of eps, log-spaced from eps_min to eps_max.", minimum=3, maximum=41,
                       reduced=3)
    T: list[float] = param([0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 16.0], "Slow times T = tau: the sup "
                           "over t is taken up to t = T eps^(1-alpha) (one run to the largest T gives them all).",
                           minItems=1, maxItems=12, items=_TS,
                           reduced=[1.0, 2.0])
    families: list[str] = param(list(FAMILIES), "Families of well-prepared data (cradle.analyses.dps_validity."
                                "FAMILIES).", minItems=1, maxItems=4, items=_FAMILY)
    N_wave: int = param(10, "Ring size of the travelling waves (q N / 2 pi an integer for q = pi/5, 4 pi/5).",
                        minimum=10, maximum=1000, multipleOf=10)
    N_breather: int = param(32, "Ring size of the bond-centred breather.", minimum=8, maximum=1000)
    N_noise: int = param(50, "Ring size of the noisy unstable wave (q N / 2 pi an integer for q = 4 pi/5).",
                         minimum=10, maximum=1000, multipleOf=5)
    noise_amplitude: float = param(0.01, "Amplitude of the uniform noise rho of (perturb) of mi-4pi5-noise.",
                                   exclusiveMinimum=0, maximum=0.5)
    seed: int = param(20261122, "Seed of the noise (numpy default_rng); alpha number k uses seed + round(100 "
                      "alpha); in [0, 2^62].", minimum=0, maximum=SEED_MAX)
    sample_every: float = param(0.2, "Lattice-time spacing of the samples of the sup over t.", exclusiveMinimum=0,
                                maximum=1.0)
    dt_factor: float = param(0.01, "srkn6c step as a fraction of the shortest linearised period (the run at the "
                             "smallest eps is repeated with dt / 2).", minimum=DT_FACTOR_FLOOR, maximum=0.05)
    dps_rtol: float = param(1e-11, "Relative tolerance of the DpS runs (dop853_numba).", minimum=RTOL_FLOOR,
                            maximum=1e-6)
    chunk: int = param(20000, "Samples per integration chunk (bounds the memory of the long runs).", minimum=100,
                       maximum=1000000)

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Each form: one eps_min per alpha, each below eps_max (none of them: said at eps_max); the families
        distinct."""
        al, em, hi = self.alpha, self.eps_min, self.eps_max
        if len(al) != len(em):
            out.add(where + ["eps_min"], f"needs one value per alpha ({len(al)}: {show(al)})", em)
        above = [i for i, e in enumerate(em) if not e < hi]
        if above and len(above) == len(em):   # no eps_min below it: eps_max is the value to change
            out.add(where + ["eps_max"], f"must be above every eps_min (eps_min = {show(em)})", hi)
        for i in above if len(above) < len(em) else ():
            out.add(where + ["eps_min", i], f"must be below eps_max = {show(hi)}", em[i])
        if len(set(map(str, self.families))) != len(self.families):
            out.add(where + ["families"], "lists a family twice", self.families)


# ----------------------------------------------------------------- the initial data of a family


def family_amplitude(family: str, alpha: float, spec: DpsValidity) -> tuple[NDArray[np.complex128], int, dict]:
    """(A_n(0) with max_n |A_n(0)| = 1 (noise aside), N, info) of a family (see module docstring)."""
    from cradle.models import initial

    if family in ("tw-pi5", "tw-4pi5"):
        N = spec.N_wave
        return np.exp(-1j * _Q[family] * np.arange(N)), N, {}
    if family == "mi-4pi5-noise":
        N = spec.N_noise
        seed = spec.seed + round(100 * alpha)  # one recorded realisation per alpha
        rho1, rho2 = initial.noise(N, "uniform", spec.noise_amplitude, seed)
        n = np.arange(N)
        q = _Q[family]
        # (perturb): A_n(0) = (1 + rho1_n) cos(q n) - i (1 + rho2_n) sin(q n)
        return (1.0 + rho1) * np.cos(q * n) - 1j * (1.0 + rho2) * np.sin(q * n), N, {"seed": seed}
    if family == "breather-bond":
        from cradle.models import homoclinic_continuation

        N = spec.N_breather
        sol = homoclinic_continuation.solve_kind(N, "bond", alpha, "periodic")
        if not sol.converged:
            raise ValueError(f"dps-validity: bond homoclinic at alpha={alpha} did not converge "
                             f"(residual {sol.residual:.3e})")
        a = np.asarray(sol.a, dtype=float)
        # (breatherdps): A_n = a_n e^{i nu tau} up to scale; the scale is eps (module docstring)
        return (a / np.max(np.abs(a))).astype(complex), N, {"residual": float(sol.residual)}
    raise ValueError(f"unknown dps-validity family {family!r} (known: {', '.join(FAMILIES)})")


def dps_growth(family: str, alpha: float, N: int) -> float:
    """Largest DpS growth rate (per unit tau, R = 1) of the sidebands p = 2 pi k / N of the family's
    plane wave (ansatz3); 0 for the breather (no plane wave) and for the stable q <= pi/2."""
    from cradle.analyses.mi_diagram import growth_rate

    if family not in _Q:
        return 0.0
    p = 2.0 * np.pi * np.arange(N // 2 + 1) / N
    return float(np.max(growth_rate(_Q[family], p, alpha, R=1.0)))


# ----------------------------------------------------------------- one run: the running sup error


def sup_error(A0: ArrayLike, eps: float, alpha: float, T_marks: ArrayLike, *, sample_every: float, dt_factor: float,
              rtol: float, chunk: int = 20000, check: bool = False) -> dict:
    """Running sup_t max_n |x - x_app| of one run on a ring, read at t = T eps^(1-alpha), T in ``T_marks``.

    The lattice (srkn6c with the fixed step dt = dt_factor 2 pi / omega_max of the initial
    compression bound) and the DpS run (dop853_numba, ``rtol``) advance in chunks of ``chunk``
    samples (memory stays bounded over 10^6 periods), each continuing from the last state of the
    previous one (the splitting takes the same steps as one run). ``check``: a second lattice run
    with dt / 2; its max deviation from the first estimates the lattice's own error (x 64/63 for
    the sixth order, ignored: it is a bound to compare with E, not a correction).
    """
    from cradle.integrators import (
        compression_bounds,
        default_dt,
        integrate_dps,
        integrate_lattice,
    )
    from cradle.measurements import compare
    from cradle.models import initial
    from cradle.models.lattice import hamiltonian

    A0 = np.asarray(A0, dtype=complex)
    x, v = initial.lattice_state(A0, eps, alpha)
    H0 = float(hamiltonian(x, v, alpha, "periodic"))
    c_assumed, _ = compression_bounds(x, v, alpha)
    dt = default_dt(c_assumed, alpha, "srkn6c", dt_factor)
    marks = np.sort(np.asarray(T_marks, dtype=float)) * eps ** (1.0 - alpha)
    n_total = int(np.ceil(marks[-1] / sample_every))
    t_grid = np.linspace(0.0, marks[-1], n_total + 1)
    # index of the last sample at or before each mark (the marks are sampled exactly: the last is the end)
    at_mark = np.searchsorted(t_grid, marks * (1.0 + 1e-12), side="right") - 1
    running = np.empty(t_grid.size)
    running_dev = np.zeros(t_grid.size)
    A = A0.copy()
    x2, v2 = x.copy(), v.copy()
    best, dev, drift, drift2, cmax = 0.0, 0.0, 0.0, 0.0, 0.0
    for i0 in range(0, n_total, chunk):
        i1 = min(i0 + chunk, n_total)
        t = t_grid[i0:i1 + 1]
        lat = integrate_lattice(x, v, t, alpha=alpha, method="srkn6c", dt=dt, t0=t[0], energy0=H0)
        sol = integrate_dps(A, eps ** (alpha - 1.0) * (t - t[0]), alpha=alpha, rtol=rtol)
        x_app = compare.approximate_displacement(sol.A, t, eps)
        err = np.max(np.abs(lat.x - x_app), axis=1)
        running[i0:i1 + 1] = np.maximum.accumulate(np.maximum(err, best))
        best = running[i1]
        drift, cmax = max(drift, lat.energy_drift), max(cmax, lat.max_compression)
        if check:
            fine = integrate_lattice(x2, v2, t, alpha=alpha, method="srkn6c", dt=0.5 * dt, t0=t[0], energy0=H0)
            d = np.max(np.abs(fine.x - lat.x), axis=1)
            running_dev[i0:i1 + 1] = np.maximum.accumulate(np.maximum(d, dev))
            dev = running_dev[i1]
            drift2 = max(drift2, fine.energy_drift)
            x2, v2 = fine.x[-1], fine.v[-1]
        x, v, A = lat.x[-1], lat.v[-1], sol.A[-1]
    return {"abs_error": running[at_mark], "dt": dt, "energy_drift": drift, "max_compression": cmax,
            "n_samples": t_grid.size, "t_end": float(t_grid[-1]),
            "halving_deviation": running_dev[at_mark] if check else np.nan,
            "halving_energy_drift": drift2 if check else np.nan}


# ----------------------------------------------------------------- the fits


def power_fit(eps: ArrayLike, err: ArrayLike) -> tuple[float, float, float]:
    """Least squares log E = p log eps + c: (p, standard error of p, c); NaN with < 3 finite points."""
    eps, err = np.asarray(eps, dtype=float), np.asarray(err, dtype=float)
    ok = np.isfinite(err) & (err > 0) & (eps > 0)
    if ok.sum() < 3:
        return float("nan"), float("nan"), float("nan")
    X, Y = np.log(eps[ok]), np.log(err[ok])
    Xm = X - X.mean()
    p = float(np.sum(Xm * (Y - Y.mean())) / np.sum(Xm**2))
    c = float(Y.mean() - p * X.mean())
    res = Y - (p * X + c)
    se = float(np.sqrt(np.sum(res**2) / (ok.sum() - 2) / np.sum(Xm**2)))
    return p, se, c


def local_exponents(eps: ArrayLike, err: ArrayLike) -> NDArray[np.float64]:
    """Slopes of log E between neighbouring eps (length n - 1): where they leave alpha, the law fails."""
    return np.diff(np.log(np.asarray(err, dtype=float))) / np.diff(np.log(np.asarray(eps, dtype=float)))


# ----------------------------------------------------------------- the pipeline stage

_FAM = Var(("family",), "family of initial data (tw-pi5, tw-4pi5, breather-bond, mi-4pi5-noise)")
_ALPHA = Var(("alpha",), "Hertz exponent alpha of V0 (vhertz)")
_T = Var(("T",), "slow time T = tau = eps^(alpha-1) t up to which the error is taken (dfnls)")
_IEPS = Var(("i_eps",), "index of the small parameter eps of (ansatz) in its per-alpha range")
_GRID = ("family", "alpha", "i_eps", "T")
_FIT = ("family", "alpha", "T")
_FA = ("family", "alpha")

_CHAOS = "after an instability has saturated (T >= T_lost) both are O(1): the lattice itself is then chaotic"

#: the stored variables of the `dps-validity` file, per netCDF group: "/errors" the sup-norm errors on
#: (family, alpha, eps, T); "/fits" the fitted powers of eps; "/checks" the integrators' own errors
VARIABLES = {
    "/": {},
    "/errors": {
        "family": _FAM, "alpha": _ALPHA, "i_eps": _IEPS, "T": _T,
        "eps": Var(("alpha", "i_eps"), "small parameter eps of (ansatz): largest initial displacement / 2"),
        "abs_error": Var(_GRID, "sup_{t <= T eps^(1-alpha)} max_n |x_n(t) - x_n^app(t)| (ansatz)"),
        "rel_error": Var(_GRID, "abs_error / (2 eps): the error relative to the amplitude a = 2 eps"),
        "law_ratio": Var(_GRID, "rel_error / eps^(alpha-1): constant where the law E_abs ~ eps^alpha holds"),
        "law_departure": Var(_GRID, "law_ratio / law_ratio at the smallest eps: 1 where C(T) eps^alpha holds",
                             attrs=(("comment", "the law is said to fail outside the departure_band [1/2, 2]"),)),
        "T_lost": Var(("family", "alpha", "i_eps"), "smallest stored T where rel_error >= lost_level "
                      "(NaN: never up to the largest T)"),
        "t_end": Var(("alpha", "i_eps", "T"), "lattice time T eps^(1-alpha) of the sup"),
    },
    "/fits": {
        "family": _FAM,
        "i_pair": Var(("i_pair",), "index of a pair of neighbouring eps (local slopes)"),
        "exponent": Var(_FIT, "fitted power p of eps in abs_error ~ C eps^p, all eps of the range"),
        "exponent_stderr": Var(_FIT, "standard error of the fitted power (least squares in log-log)"),
        "prefactor": Var(_FIT, "C of abs_error ~ C eps^p (all eps)"),
        "exponent_small": Var(_FIT, "fitted power over the smaller half of the eps range (asymptotic regime)"),
        "exponent_small_stderr": Var(_FIT, "standard error of exponent_small"),
        "local_exponent": Var(_FIT + ("i_pair",), "slope of log abs_error between neighbouring eps"),
        "eps_pair": Var(("alpha", "i_pair"), "geometric mean of the two eps of a local slope"),
        "expected_exponent": Var(("alpha",), "power of eps of the consistency order of (ansatz): alpha"),
        "dps_growth_rate": Var(_FA, "largest DpS growth rate (ansatz3) per unit tau over the ring's sidebands",
                               attrs=(("comment", "R = 1; 0 for stable waves and the breather"),)),
    },
    "/checks": {
        "family": _FAM,
        "dt": Var(_FA + ("i_eps",), "fixed step of the srkn6c splitting of the lattice run"),
        "energy_drift": Var(_FA + ("i_eps",), "max relative energy drift of the lattice run (ham)"),
        "halving_deviation": Var(_FIT, "sup_{t <= T eps^(1-alpha)} max_n |x(dt) - x(dt/2)| of the lattice run at "
                                 "the smallest eps"),
        "halving_ratio": Var(_FIT, "halving_deviation / abs_error at the smallest eps, per T",
                             attrs=(("comment", _CHAOS),)),
        "n_samples": Var(_FA + ("i_eps",), "number of samples of the sup over t"),
    },
}


#: the approximation is called lost where the relative error reaches this (|x - x_app| = a / 2)
LOST_LEVEL = 0.5



def eps_grid(spec: DpsValidity, ia: int) -> np.ndarray:
    """The eps of alpha number ``ia``: n_eps log-spaced from eps_min[ia] to eps_max."""
    return np.geomspace(spec.eps_min[ia], spec.eps_max, spec.n_eps)


# ----------------------------------------------------------------- the batches: one job per alpha

#: a batch file (one alpha, every family) is flat: the runs' results on the dims of the tree, alpha of length 1
#: (the fits and ratios are derived from them by :func:`compute`)
BATCH_VARIABLES = {name: VARIABLES[group][name] for group, names in (
    ("/errors", ("family", "alpha", "i_eps", "T", "eps", "abs_error")),
    ("/fits", ("dps_growth_rate",)),
    ("/checks", ("dt", "energy_drift", "halving_deviation", "n_samples"))) for name in names}

def batch_keys(spec: DpsValidity) -> list[str]:
    """The batches of one form, one per alpha: ``alpha<k>-<alpha>`` (``alpha0-1.1``), k its index in
    ``spec.alpha`` (unique even if two alphas are equal)."""
    return [f"alpha{ia}-{float(al):g}" for ia, al in enumerate(spec.alpha)]


def batch(spec: DpsValidity, ia: int, log: Log | None = None) -> xr.Dataset:
    """Every family at alpha number ``ia``: its A_n(0) (:func:`family_amplitude`), its DpS growth rate
    (:func:`dps_growth`) and one :func:`sup_error` run per eps of :func:`eps_grid` (the smallest also with
    dt / 2) -> a flat Dataset (:data:`BATCH_VARIABLES`); attributes: the noise seeds, the wall time."""
    from cradle.data.io import make_dataset

    t_start = time.perf_counter()
    say = log or (lambda *a: None)
    al = float(spec.alpha[ia])
    fams = list(spec.families)
    Ts = np.sort(np.asarray(spec.T, dtype=float))
    eps_all = eps_grid(spec, ia)
    n_eps = spec.n_eps
    E = np.full((len(fams), 1, n_eps, Ts.size), np.nan)
    dts, drifts, nsamp = (np.full((len(fams), 1, n_eps), np.nan) for _ in range(3))
    halving, growth = np.full((len(fams), 1, Ts.size), np.nan), np.zeros((len(fams), 1))
    seeds = {}
    for jf, fam in enumerate(fams):
        A0, N, info = family_amplitude(fam, al, spec)
        if "seed" in info:
            seeds[f"{fam}_alpha{al:g}"] = info["seed"]
        growth[jf, 0] = dps_growth(fam, al, N)
        for ie, eps in enumerate(eps_all):
            r = sup_error(A0, eps, al, Ts, sample_every=spec.sample_every, dt_factor=spec.dt_factor,
                          rtol=spec.dps_rtol, chunk=spec.chunk, check=ie == 0)
            E[jf, 0, ie] = r["abs_error"]
            dts[jf, 0, ie], drifts[jf, 0, ie], nsamp[jf, 0, ie] = r["dt"], r["energy_drift"], r["n_samples"]
            if ie == 0:
                halving[jf, 0] = r["halving_deviation"]
        say(f"dps-validity: {fam} alpha={al:g}: E_rel(T={Ts[-1]:g}) = "
            + " ".join(f"{e:.3g}" for e in E[jf, 0, :, -1] / (2 * eps_all)))
    data = {"eps": eps_all[None, :], "abs_error": E, "dps_growth_rate": growth, "dt": dts, "energy_drift": drifts,
            "halving_deviation": halving, "n_samples": nsamp}
    coords = {"family": list(fams), "alpha": [al], "i_eps": np.arange(n_eps), "T": Ts}
    attrs = {"alpha_index": ia, "family_names": ", ".join(fams),
             "noise_seeds": ", ".join(f"{k}={v}" for k, v in seeds.items()),
             "wall_time_s": time.perf_counter() - t_start}
    return make_dataset(data, coords=coords, attrs=attrs, params=plain(spec), variables=BATCH_VARIABLES,
                        title=f"dps-validity batch: alpha = {al:g} (alpha number {ia}), every family")


def run_batch(spec: DpsValidity, key: str, inputs: dict | None = None, log: Log | None = None) -> xr.Dataset:
    """The batch ``key`` of :func:`batch_keys` (it reads no file)."""
    keys = batch_keys(spec)
    if key not in keys:
        raise ValueError(f"dps-validity: no batch {key!r} in this form (batches: {', '.join(keys)})")
    return batch(spec, keys.index(key), log=log)


def _batches(spec: DpsValidity, inputs: dict, log: Log | None) -> list[xr.Dataset]:
    """The batch of every alpha, in the order of ``spec.alpha``: all from ``inputs`` or, when it holds none,
    run here one after another."""
    keys = batch_keys(spec)
    given = [key for key in keys if f"batch/{key}" in inputs]
    if not given:
        return [run_batch(spec, key, log=log) for key in keys]
    if len(given) < len(keys):
        raise ValueError(f"dps-validity: no batch {', '.join(k for k in keys if k not in given)} among the inputs "
                         f"(given: {', '.join(given)})")
    return [inputs[f"batch/{key}"] for key in keys]


# ----------------------------------------------------------------- the whole form


def compute(spec: DpsValidity, inputs: dict | None = None, log: Log | None = None) -> xr.DataTree:
    """The `dps-validity` analysis as a tree of groups (see module docstring and :data:`VARIABLES`) for
    one form of its spec, from its batches (``inputs["batch/<key>"]``, one per alpha: :func:`batch_keys`).
    Without them (``inputs`` empty or None: ``compute(spec)`` from Python) the batches are run here, one
    after another. The attribute ``wall_time_s`` is the batches' wall times summed plus this aggregation's."""
    parts = _batches(spec, inputs or {}, log)
    t_start = time.perf_counter()   # after the batches: their own wall times are added to it
    alphas = [float(a) for a in spec.alpha]
    fams = list(spec.families)
    Ts = np.sort(np.asarray(spec.T, dtype=float))
    n_eps = spec.n_eps
    E = np.full((len(fams), len(alphas), n_eps, Ts.size), np.nan)
    eps_all = np.array([eps_grid(spec, ia) for ia in range(len(alphas))])
    dts, drifts, nsamp = (np.full((len(fams), len(alphas), n_eps), np.nan) for _ in range(3))
    halving, growth = np.full((len(fams), len(alphas), Ts.size), np.nan), np.zeros((len(fams), len(alphas)))
    batch_seeds, batch_wall = [], 0.0
    for ia, (al, b) in enumerate(zip(alphas, parts, strict=True)):
        # a batch of another spec (other alpha, families, eps or T) would be joined silently
        if not (int(b.attrs["alpha_index"]) == ia and float(b["alpha"].values[0]) == al
                and str(b.attrs["family_names"]) == ", ".join(fams) and np.array_equal(b["T"].values, Ts)
                and np.array_equal(b["eps"].values[0], eps_all[ia])):
            raise ValueError(f"dps-validity: batch {batch_keys(spec)[ia]} was computed for another spec")
        E[:, ia] = b["abs_error"].values[:, 0]
        dts[:, ia], drifts[:, ia], nsamp[:, ia] = (b[nm].values[:, 0] for nm in ("dt", "energy_drift", "n_samples"))
        halving[:, ia], growth[:, ia] = b["halving_deviation"].values[:, 0], b["dps_growth_rate"].values[:, 0]
        batch_seeds.append(dict(item.split("=") for item in str(b.attrs["noise_seeds"]).split(", ") if item))
        batch_wall += float(b.attrs["wall_time_s"])
    seeds = {}   # family-major, the order of the one-job loop
    for fam in fams:
        for al, found in zip(alphas, batch_seeds, strict=True):
            if f"{fam}_alpha{al:g}" in found:
                seeds[f"{fam}_alpha{al:g}"] = found[f"{fam}_alpha{al:g}"]
    runs = {"abs_error": E, "dt": dts, "energy_drift": drifts, "n_samples": nsamp, "halving_deviation": halving,
            "dps_growth_rate": growth, "noise_seeds": seeds}
    return tree_of_runs(spec, runs, t_start, wall_before=batch_wall)


def tree_of_runs(spec: DpsValidity, runs: dict, t_start: float, wall_before: float = 0.0) -> xr.DataTree:
    """The tree of one form (:data:`VARIABLES`) from its runs: ``runs`` holds on (family, alpha, ...) what
    :func:`batch` stores (abs_error, dt, energy_drift, n_samples, halving_deviation, dps_growth_rate) and
    ``noise_seeds`` ({"<family>_alpha<alpha>": seed}); the ratios, fits and attributes are derived here.
    ``wall_time_s`` is ``wall_before`` plus the time since ``t_start`` (a :func:`time.perf_counter`)."""
    from cradle.data.io import make_tree

    alphas = [float(a) for a in spec.alpha]
    fams = list(spec.families)
    Ts = np.sort(np.asarray(spec.T, dtype=float))
    n_eps = spec.n_eps
    eps_all = np.array([eps_grid(spec, ia) for ia in range(len(alphas))])
    t_end = eps_all[:, :, None] ** (1.0 - np.asarray(alphas)[:, None, None]) * Ts
    E, dts, drifts, nsamp = runs["abs_error"], runs["dt"], runs["energy_drift"], runs["n_samples"]
    halving, growth, seeds = runs["halving_deviation"], runs["dps_growth_rate"], runs["noise_seeds"]
    rel = E / (2.0 * eps_all[None, :, :, None])
    law = rel / eps_all[None, :, :, None] ** (np.asarray(alphas)[None, :, None, None] - 1.0)
    departure = law / law[:, :, :1, :]
    lost = rel >= LOST_LEVEL
    T_lost = np.where(lost.any(axis=-1), Ts[np.argmax(lost, axis=-1)], np.nan)
    p, se, c = (np.full((len(fams), len(alphas), Ts.size), np.nan) for _ in range(3))
    ps, pse = (np.full((len(fams), len(alphas), Ts.size), np.nan) for _ in range(2))
    loc = np.full((len(fams), len(alphas), Ts.size, n_eps - 1), np.nan)
    half = slice(0, max(3, (n_eps + 1) // 2))
    for jf in range(len(fams)):
        for ia in range(len(alphas)):
            for k in range(Ts.size):
                p[jf, ia, k], se[jf, ia, k], c[jf, ia, k] = power_fit(eps_all[ia], E[jf, ia, :, k])
                ps[jf, ia, k], pse[jf, ia, k], _ = power_fit(eps_all[ia][half], E[jf, ia, half, k])
                loc[jf, ia, k] = local_exponents(eps_all[ia], E[jf, ia, :, k])
    eps_pair = np.sqrt(eps_all[:, 1:] * eps_all[:, :-1])
    groups = {
        "/errors": ({"eps": eps_all, "abs_error": E, "rel_error": rel, "law_ratio": law,
                     "law_departure": departure, "T_lost": T_lost, "t_end": t_end},
                    {"family": list(fams), "alpha": alphas, "i_eps": np.arange(n_eps), "T": Ts}),
        "/fits": ({"exponent": p, "exponent_stderr": se, "prefactor": np.exp(c), "exponent_small": ps,
                   "exponent_small_stderr": pse, "local_exponent": loc, "eps_pair": eps_pair,
                   "expected_exponent": np.asarray(alphas), "dps_growth_rate": growth},
                  {"family": list(fams), "i_pair": np.arange(n_eps - 1)}),
        "/checks": ({"dt": dts, "energy_drift": drifts, "halving_deviation": halving,
                     "halving_ratio": halving / E[:, :, 0, :], "n_samples": nsamp}, {"family": list(fams)}),
    }
    attrs = {
        "family_names": ", ".join(fams),
        "families": "tw-pi5, tw-4pi5: travelling waves (ansatzapprox) A_n(0) = e^{-i q n}, q = pi/5, 4 pi/5, "
                    f"ring of N_wave = {spec.N_wave}; breather-bond: bond-centred homoclinic of (dpsstn), "
                    f"A_n(0) = a_n / max|a_n|, ring of N_breather = {spec.N_breather}; mi-4pi5-noise: "
                    f"q = 4 pi/5 perturbed as in (perturb), uniform noise of amplitude {spec.noise_amplitude}"
                    f", seed + round(100 alpha) from seed = {spec.seed}, ring of N_noise = "
                    f"{spec.N_noise}",
        "noise_seeds": ", ".join(f"{k}={v}" for k, v in seeds.items()),
        "reference_law": "abs_error = O(eps^alpha) (rel_error = O(eps^(alpha-1))) for t <= T eps^(1-alpha): "
                         "consistency order of (ansatz) (non-resonant harmonics of size eps^alpha, Gronwall "
                         "factor e^{C T}); the exact bound of Bidegaray-Fesquet, Dumas & James, SIAM J. Math. "
                         "Anal. 45 (2013) was not available to us",
        "eps_ranges": "per alpha: eps_min = "
                      + ", ".join(f"{a:g}: {m:g}" for a, m in zip(alphas, spec.eps_min, strict=True))
                      + f"; eps_max = {spec.eps_max:g}. The lattice time T eps^(1-alpha) sets the cost "
                        "(alpha = 3: T eps^-2), hence the larger eps_min at large alpha",
        "lattice_integrator": f"srkn6c, fixed dt = dt_factor 2 pi / omega_max, dt_factor = {spec.dt_factor}",
        "dps_integrator": f"dop853_numba, rtol = {spec.dps_rtol}",
        "sample_every": spec.sample_every,
        "lost_level": LOST_LEVEL,
        "departure_band": "[0.5, 2]",
        "sup_sampling": "the sup over t is taken on samples every sample_every (the error oscillates at "
                        "frequencies 1, 3, ...: the sampled sup is within a few per cent of the true one, the "
                        "same fraction at every eps)",
        "max_halving_ratio": float(np.nanmax(halving / E[:, :, 0, :])),
        "max_halving_ratio_before_lost": float(np.nanmax(np.where(
            np.isnan(T_lost[:, :, :1]) | (Ts[None, None, :] < T_lost[:, :, :1]), halving / E[:, :, 0, :], np.nan))),
        "max_energy_drift": float(np.nanmax(drifts)),
        "wall_time_s": wall_before + time.perf_counter() - t_start,
    }
    return make_tree(groups, VARIABLES, attrs=attrs, params=plain(spec),
                     title="DpS approximation error: sup_{t <= T eps^(1-alpha)} |x - x_app| against eps, T, family "
                           "and alpha")


ANALYSIS = Analysis(
    name="dps-validity", spec=DpsValidity, compute=compute, variables=VARIABLES,
    batches=Batches(keys=batch_keys, run=run_batch),
    title="DpS approximation error: sup over t <= T eps^(1-alpha) of |x - x_app| against eps, T, family, alpha")
