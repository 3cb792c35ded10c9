"""Growth rates of the modulational instability measured in the scenes' runs, against the linear DpS theory.

For each scene (a travelling wave (ansatzapprox) on a periodic ring, perturbed as
in (perturb)), both models are rerun from the pipeline's own initial data
(results/initial/<scene>.nc) with the scene's own integrators and tolerances,
sampled every ``sample_every`` (the scene files keep snapshots only); the
rerun is checked against results/sim/<scene>/{exact,dps}.nc at their stored
times (``sim_check``).

Measured quantity: the complex amplitude of (ansatz) in both models,

* DpS: A_n(tau) itself, tau = eps^(alpha-1) t;
* lattice: A_n(t) = (x_n - i dx_n/dt) e^{-it} / (2 eps), the same leading-order
  relation x_n = eps (A_n e^{it} + c.c.), dx_n/dt = eps (i A_n e^{it} + c.c.) read backwards,

whose plane wave (ansatz3) A_n = R e^{i(Omega tau - q n)} has its carrier at
the single wavenumber -q. A perturbation beta e^{ipn} + conj(gamma) e^{-ipn} of
the rotating frame (cradle.analyses.mi_diagram) lives at -q + p and -q - p, so the
sideband-pair amplitude

    S_p(t) = sqrt(|A_hat_{-q+p}|^2 + |A_hat_{-q-p}|^2) / |A_hat_{-q}|,   p = 2 pi m / N, m = 1..N/2,

grows like e^{lambda(q, p) tau} = e^{lambda(q, p) eps^(alpha-1) t} in the linear phase, with
lambda(q, p) of :func:`cradle.analyses.mi_diagram.growth_rate` (units 1/tau, R = 1 here). Every rate
below is per unit t of (nc): rate_t = rate_tau eps^(alpha-1). (Unlike the x spectrum, the A
spectrum separates -q + p from q - p, so the growing p is read off without ambiguity.) The
bins where the lattice's harmonics land (p = +-q, +-2q, +-3q, +-4q mod 2 pi: e^{2i theta},
e^{3i theta} terms of x_n) are left out of the choice of p*, in both models.

Window (automatic): E(t) = max_p S_p(t). The window ends at t_b, the first time E reaches
``saturation`` (the end of the linear phase; if it never does, at the maximum of E, and no
exponential growth is claimed); p* is the p of that maximum; the window starts at t_a, the
last time before t_b with S_{p*} <= S_{p*}(t_b) 10^-decades (if S_{p*} never was that low,
at its minimum before t_b, and no exponential growth is claimed). log S_{p*} is fitted by
least squares on [t_a, t_b]; the growth is called exponential when E saturated, the window
spans ``decades`` decades and r^2 >= ``r2_min``. The slope of log S_p over the same window
for every p gives the measured rate-versus-p curve.
"""
from __future__ import annotations

import time
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses import mi_diagram as modulational
from cradle.analyses.protocol import Analysis, scene_reads
from cradle.data.variables import MODEL, MODELS, Var
from cradle.measurements import compare
from cradle.models import dps
from cradle.scenes.spec import Travelling
from cradle.scenes.times import store_times
from cradle.specs.declare import declared, param, plain
from cradle.specs.values import ConfigError

if TYPE_CHECKING:
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors

#: the growth-rate diagram of the mi-growth figure: max_p of the scaled linear DpS rate on THEORY_N_Q
#: wavenumbers q in [0, pi], each a grid search over THEORY_N_P values of p then a bounded refinement
THEORY_N_Q = 361
THEORY_N_P = 1001


@declared(doc="Growth rates of the modulational instability measured in the scenes' own runs (exact lattice and DpS, "
              "rerun from results/initial/<scene>.nc with the scene's integrators, sampled every sample_every), "
              "fitted on the sideband pairs of the |A_hat| spectrum and compared with the linear DpS rate "
              "(cradle.analyses.mi_diagram.growth_rate) -> results/mi-growth/mi-growth.nc and "
              "results/figures/mi-growth.{pdf,png}.")
class MIGrowth:
    scenes: list[str] = param([], "Scenes (names under scenes:, travelling waves on a periodic ring) whose runs are "
                              "measured; the target mi_growth needs at least one.", minItems=0, maxItems=12,
                              items={"$ref": "#/$defs/name"})
    sample_every: float = param(0.5, "Sampling interval in t of the spectra (the scenes store only snapshots, so "
                                "their runs are repeated on this grid).", exclusiveMinimum=0, maximum=10.0)
    saturation: float = param(0.2, "The fit window ends when the largest sideband pair first reaches this fraction "
                              "of the carrier (end of the linear phase).", exclusiveMinimum=0, maximum=1.0)
    decades: float = param(1.0, "The fit window covers the last `decades` decades of growth of the dominant pair "
                           "before the window end (fewer if the run grew less: then no exponential phase is "
                           "claimed).", exclusiveMinimum=0, maximum=4.0)
    r2_min: float = param(0.95, "Smallest coefficient of determination of the log-linear fit for the growth to be "
                          "called exponential.", exclusiveMinimum=0, maximum=1.0)

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Every named scene that exists is a travelling wave on a periodic ring (a name that is no scene is
        reported with every analysis's reads, cradle.pipeline.config.checks)."""
        for i, name in enumerate(self.scenes):
            sc = context.scenes.get(name)
            if sc is not None and not (isinstance(sc.initial, Travelling) and sc.bc == "periodic"):
                out.add(where + ["scenes", i], "must be a travelling-wave scene on a periodic ring (initial.kind "
                                               "travelling, bc periodic)", name)


# ---------------------------------------------------------------- spectra

def lattice_amplitude(x, v, t, eps: float):
    """A_n(t) = (x_n - i v_n) e^{-it} / (2 eps): the (ansatz) amplitude read from a lattice state."""
    t = np.asarray(t, dtype=float)
    return (np.asarray(x) - 1j * np.asarray(v)) * np.exp(-1j * t)[:, None] / (2.0 * eps)


def pair_spectrum(A, k_q: int):
    """S_p(t) for p = 2 pi m / N, m = 0..N//2 (column 0 is NaN): sideband pairs around the carrier -q.

    ``A`` has shape (T, N); q = 2 pi k_q / N. For 2m = N the two sidebands are one bin, counted once.
    """
    A = np.asarray(A)
    N = A.shape[-1]
    Ah = np.fft.fft(A, axis=-1) / N
    c = (-int(k_q)) % N
    m = np.arange(N // 2 + 1)
    plus = np.abs(Ah[:, (c + m) % N]) ** 2
    minus = np.abs(Ah[:, (c - m) % N]) ** 2
    same = (2 * m) % N == 0
    amp = np.sqrt(np.where(same, plus, plus + minus))
    S = amp / np.abs(Ah[:, c])[:, None]
    S[:, 0] = np.nan
    return S


def harmonic_indices(k_q: int, N: int) -> list[int]:
    """m in [0, N/2] of p = +-j q (j = 1..4) mod 2 pi: where the lattice harmonics 2q, 3q sit relative to -q."""
    out = set()
    for j in (1, 2, 3, 4):
        m = (j * int(k_q)) % N
        out.add(min(m, N - m))
    return sorted(out)


# ---------------------------------------------------------------- fits

def fit_log_linear(t, y):
    """Least-squares fit log y = c + rate t: (rate, standard error, r^2)."""
    t = np.asarray(t, dtype=float)
    ly = np.log(np.asarray(y, dtype=float))
    n = t.size
    if n < 3:
        return float("nan"), float("nan"), float("nan")
    A = np.vstack([t, np.ones(n)]).T
    coef, *_ = np.linalg.lstsq(A, ly, rcond=None)
    res = ly - A @ coef
    ss_res = float(res @ res)
    ss_tot = float(np.sum((ly - ly.mean()) ** 2))
    se = np.sqrt(ss_res / (n - 2) / np.sum((t - t.mean()) ** 2))
    r2 = 1.0 - ss_res / ss_tot if ss_tot > 0 else float("nan")
    return float(coef[0]), float(se), float(r2)


def growth_window(t, y, saturation: float, decades: float, envelope=None):
    """(i_a, i_b, saturated, full): the fit window [t[i_a], t[i_b]] of the module docstring.

    ``y`` is the series fitted; ``envelope`` (default ``y``) decides where the window ends.
    """
    y = np.asarray(y, dtype=float)
    E = y if envelope is None else np.asarray(envelope, dtype=float)
    hit = np.flatnonzero(E >= saturation)
    saturated = hit.size > 0
    i_b = int(hit[0]) if saturated else int(np.nanargmax(E))
    low = y[i_b] * 10.0 ** (-decades)
    below = np.flatnonzero(y[: i_b + 1] <= low)
    full = below.size > 0
    i_a = int(below[-1]) if full else int(np.nanargmin(y[: i_b + 1]))
    return i_a, i_b, saturated, full


def measure(t, S, exclude_m=(), saturation: float = 0.2, decades: float = 1.0, r2_min: float = 0.95) -> dict:
    """The growth measurement of the module docstring on a pair spectrum S (T, M) sampled at t."""
    t = np.asarray(t, dtype=float)
    S = np.array(S, dtype=float)
    allowed = np.ones(S.shape[1], dtype=bool)
    allowed[0] = False
    allowed[list(exclude_m)] = False
    Sa = np.where(allowed[None, :], S, -np.inf)
    E = np.max(Sa, axis=1)
    hit = np.flatnonzero(E >= saturation)
    i_end = int(hit[0]) if hit.size else int(np.argmax(E))
    m_star = int(np.argmax(Sa[i_end]))
    y = S[:, m_star]
    i_a, i_b, saturated, full = growth_window(t, y, saturation, decades, envelope=E)
    sl = slice(i_a, i_b + 1)
    rate, se, r2 = fit_log_linear(t[sl], y[sl])
    rate_p = np.full(S.shape[1], np.nan)
    if i_b - i_a >= 2:
        tt = t[sl] - t[sl].mean()
        ly = np.log(S[sl, 1:])
        rate_p[1:] = (tt @ (ly - ly.mean(axis=0))) / (tt @ tt)
    exponential = bool(saturated and full and np.isfinite(r2) and r2 >= r2_min)
    return {"m_star": m_star, "i_a": i_a, "i_b": i_b, "t_a": float(t[i_a]), "t_b": float(t[i_b]), "rate": rate,
            "stderr": se, "r2": r2, "saturated": saturated, "full": full, "exponential": exponential,
            "rate_p": rate_p, "envelope": E, "pair": y}


# ---------------------------------------------------------------- scene runs

def run_scene(spec, init_ds, every: float):
    """Rerun scene ``spec`` (a resolved :class:`cradle.scenes.spec.Scene`) from its initial Dataset:
    (t, {model: A (T, N)}, {model: x (T, N)}, info)."""
    from cradle.integrators import SPLITTING_METHODS, integrate_dps, integrate_lattice

    alpha, bc = spec.alpha, spec.bc
    eps = float(init_ds.attrs["eps"])
    # the grid 0, every, ..., t_end plus the scene's own stored times (to check against its files)
    t = np.asarray(store_times(list(spec.times), every, spec.t_end))
    ex = spec.exact
    accuracy = ({"dt_factor": ex.dt_factor} if ex.method in SPLITTING_METHODS else {"rtol": ex.rtol})
    x0, v0 = init_ds["x0"].values, init_ds["v0"].values
    lat = integrate_lattice(x0, v0, t, alpha=alpha, bc=bc, method=ex.method, **accuracy)
    A0 = init_ds["A0_re"].values + 1j * init_ds["A0_im"].values
    st = spec.dps
    ap = integrate_dps(A0, eps ** (alpha - 1.0) * t, alpha=alpha, bc=bc, method=st.method, rtol=st.rtol)
    A = {"exact": lattice_amplitude(lat.x, lat.v, t, eps), "dps": np.asarray(ap.A)}
    x = {"exact": lat.x, "dps": compare.approximate_displacement(ap.A, t, eps)}
    info = {"exact_integrator": lat.method, "exact_energy_drift": lat.energy_drift,
            "dps_integrator": ap.method, "dps_rtol": ap.rtol, "dps_l2_drift": ap.max_l2_drift,
            "wall_time_s": lat.wall_time_s + ap.wall_time_s}
    return t, A, x, info


def sim_check(t, x, sim_ds, a: float, t_max: float) -> float:
    """max |x - x_sim| / a over the times of ``sim_ds`` up to ``t_max`` (NaN when none is common)."""
    ts = sim_ds["t"].values
    worst = float("nan")
    for j, tj in enumerate(ts):
        if tj > t_max + 1e-9:
            continue
        i = np.flatnonzero(np.abs(t - tj) <= 1e-9)
        if i.size:
            d = float(np.max(np.abs(x[i[0]] - sim_ds["x"].values[j]))) / a
            worst = d if not np.isfinite(worst) else max(worst, d)
    return worst


def theory_rates(q: float, N: int, alpha: float, eps: float):
    """(p, lambda(q, p) eps^(alpha-1)) for p = 2 pi m / N, m = 0..N//2: the linear DpS rate per unit t (R = 1)."""
    p = 2.0 * np.pi * np.arange(N // 2 + 1) / N
    return p, modulational.growth_rate(q, p, alpha, 1.0) * eps ** (alpha - 1.0)


# ---------------------------------------------------------------- the stage

_SC, _SM = ("scene",), ("scene", "model")

#: the stored variables of the `mi-growth` file, per netCDF group: "/" one row per scene and model
#: (the fitted growth rates), "/sidebands" every sideband pair p, "/series" the sideband amplitudes
#: against t, "/theory" the linear DpS diagram. Rates are per unit t of (nc)
VARIABLES = {
    "/": {
        "scene": Var(_SC, "name of a travelling-wave scene of config.yaml"),
        "model": MODEL,
        "q": Var(_SC, "carrier wavenumber q of the scene", "rad"),
        "N": Var(_SC, "number N of beads of the scene"),
        "eps": Var(_SC, "small parameter eps = a/2 of (ansatz); tau = eps^(alpha-1) t"),
        "growth_scale": Var(_SC, "tau0 / eps^(alpha-1): a rate per unit t times this is lambda tau0 R^(1-alpha)"),
        "growth_theory_max": Var(_SC, "max over p of the linear DpS growth rate, per unit t"),
        "growth": Var(_SM, "measured growth rate of the dominant sideband pair, per unit t"),
        "growth_stderr": Var(_SM, "standard error of the fitted growth rate, per unit t"),
        "r2": Var(_SM, "coefficient of determination of the log-linear fit"),
        "growth_theory": Var(_SM, "linear DpS growth rate at the scene's q and the measured p*, per unit t"),
        "p_star": Var(_SM, "|p| of the sideband pair that grows (fit target)", "rad"),
        "window_start": Var(_SM, "start of the fit window in t"),
        "window_end": Var(_SM, "end of the fit window in t"),
        "exponential": Var(_SM, "an exponential growth phase was found",
                           attrs=(("comment", "1: exponential phase found (growth over the window >= decades, "
                                              "r2 >= r2_min), 0: not"),)),
        "sim_check": Var(_SM, "max |x - x_sim| / a against results/sim/<scene>/<model>.nc up to the window end"),
    },
    "/sidebands": {
        "m": Var(("m",), "index m of the perturbation wavenumber p = 2 pi m / N"),
        "p": Var(("scene", "m"), "perturbation wavenumber p = 2 pi m / N (NaN past N/2)", "rad"),
        "growth_theory": Var(("scene", "m"), "linear DpS growth rate lambda(q, p) eps^(alpha-1), per unit t"),
        "growth": Var(("scene", "model", "m"),
                      "slope of log sideband-pair amplitude at p over the fit window, per unit t"),
    },
    "/series": {
        "t": Var(("t",), "dimensionless time t of (nc)"),
        "pair": Var(("scene", "model", "t"),
                    "sideband-pair amplitude at p* over the carrier, |A_hat| spectrum (NaN past t_end)"),
        "envelope": Var(("scene", "model", "t"), "largest sideband-pair amplitude over the carrier"),
    },
    "/theory": {
        "q": Var(("q",), "wavenumber q of the linear DpS growth-rate diagram", "rad"),
        "max_growth": Var(("q",), "max over p of the scaled linear DpS growth rate lambda tau0 R^(1-alpha)"),
    },
}


def compute(spec: MIGrowth, inputs: dict, log=None):
    """The `mi-growth` analysis as a tree of groups (:data:`VARIABLES`), from the initial data and the
    exact and DpS runs of every scene of ``spec.scenes`` (``inputs["<scene>/initial"]``, ...); each scene
    is rerun with the integrators its files were computed with (:func:`cradle.scenes.stored.scene_of`).
    """
    from cradle.data.io import make_tree
    from cradle.scenes.stored import scene_of

    wall0 = time.perf_counter()
    say = log or (lambda *a: None)
    every = spec.sample_every
    names = list(spec.scenes)
    scenes = {n: (scene_of(inputs[f"{n}/initial"]), inputs[f"{n}/initial"],
                  {"exact": inputs[f"{n}/exact"], "dps": inputs[f"{n}/dps"]}) for n in names}
    Ns = [scenes[n][0].N for n in names]
    M = max(Ns) // 2 + 1
    t_end_max = max(scenes[n][0].t_end for n in names)
    tg = np.arange(int(np.floor(t_end_max / every * (1 + 1e-12))) + 1) * every
    S, Mo, T = len(names), len(MODELS), tg.size
    f = {k: np.full((S, Mo), np.nan) for k in ("rate", "stderr", "r2", "theory", "pstar", "ta", "tb", "check")}
    expo = np.zeros((S, Mo), dtype=np.int8)
    rate_p = np.full((S, Mo, M), np.nan)
    pair = np.full((S, Mo, T), np.nan)
    env = np.full((S, Mo, T), np.nan)
    pgrid = np.full((S, M), np.nan)
    theo = np.full((S, M), np.nan)
    qs, eps_s, tmax = np.empty(S), np.empty(S), np.empty(S)
    alphas = set()
    drifts = {}
    for i, name in enumerate(names):
        sc, init_ds, sims = scenes[name]
        alpha, N = sc.alpha, sc.N
        alphas.add(alpha)
        assert isinstance(sc.initial, Travelling)   # mi-growth measures travelling waves (checked in the config)
        q = sc.initial.wavenumber
        k_q = int(round(q * N / (2 * np.pi)))
        eps = float(init_ds.attrs["eps"])
        a = float(init_ds.attrs["a"])
        qs[i], eps_s[i] = q, eps
        p, lam = theory_rates(q, N, alpha, eps)
        pgrid[i, : p.size], theo[i, : p.size] = p, lam
        tmax[i] = float(np.max(lam))
        t, A, x, info = run_scene(sc, init_ds, every)
        drifts[name] = info
        on_grid = np.abs(t / every - np.round(t / every)) <= 1e-9
        excl = harmonic_indices(k_q, N)
        for j, m in enumerate(MODELS):
            Sp = pair_spectrum(A[m], k_q)
            r = measure(t, Sp, excl, spec.saturation, spec.decades, spec.r2_min)
            f["rate"][i, j], f["stderr"][i, j], f["r2"][i, j] = r["rate"], r["stderr"], r["r2"]
            f["pstar"][i, j] = p[r["m_star"]]
            f["theory"][i, j] = lam[r["m_star"]]
            f["ta"][i, j], f["tb"][i, j] = r["t_a"], r["t_b"]
            expo[i, j] = int(r["exponential"])
            rate_p[i, j, : p.size] = r["rate_p"]
            ng = np.round(t[on_grid] / every).astype(int)
            pair[i, j, ng] = r["pair"][on_grid]
            env[i, j, ng] = r["envelope"][on_grid]
            f["check"][i, j] = sim_check(t, x[m], sims[m], a, r["t_b"])
            say(f"mi-growth {name} ({m}): p* = {p[r['m_star']] / np.pi:.4f} pi, rate {r['rate']:.5g} +- "
                f"{r['stderr']:.2g} per unit t on [{r['t_a']:.1f}, {r['t_b']:.1f}] (r2 {r['r2']:.4f}, "
                f"exponential {r['exponential']}), linear DpS theory {lam[r['m_star']]:.5g} (max {tmax[i]:.5g}); "
                f"rerun vs sim file {f['check'][i, j]:.2e}")
    if len(alphas) != 1:
        raise ValueError(f"mi-growth: scenes with different alpha {sorted(alphas)}: one diagram per alpha")
    alpha = alphas.pop()
    q_theory = np.linspace(0.0, np.pi, THEORY_N_Q)
    max_theory = np.array([modulational.max_over_p(x, alpha, THEORY_N_P)[0] for x in q_theory])
    groups = {
        "/": ({"q": qs, "N": Ns, "eps": eps_s, "growth_scale": dps.tau0(alpha) / eps_s ** (alpha - 1.0),
               "growth_theory_max": tmax, "growth": f["rate"], "growth_stderr": f["stderr"], "r2": f["r2"],
               "growth_theory": f["theory"], "p_star": f["pstar"], "window_start": f["ta"], "window_end": f["tb"],
               "exponential": expo, "sim_check": f["check"]},
              {"scene": np.array(names, dtype=object), "model": np.array(MODELS, dtype=object)}),
        "/sidebands": ({"p": pgrid, "growth_theory": theo, "growth": rate_p}, {"m": np.arange(M)}),
        "/series": ({"pair": pair, "envelope": env}, {"t": tg}),
        "/theory": ({"max_growth": max_theory}, {"q": q_theory}),
    }
    attrs = {"alpha": alpha, "tau0": dps.tau0(alpha),
             "sample_every": every, "saturation": spec.saturation, "decades": spec.decades,
             "r2_min": spec.r2_min,
             "time_units": "every rate is per unit t of (nc); DpS rates lambda (per unit tau of (dfnls)) are "
                           "converted by tau = eps^(alpha-1) t, rate_t = lambda eps^(alpha-1), R = 1",
             "measured_quantity": "S_p = sqrt(|A_hat_{-q+p}|^2 + |A_hat_{-q-p}|^2) / |A_hat_{-q}|; lattice A_n = "
                                  "(x_n - i v_n) e^{-it} / (2 eps)",
             "window": "ends where max_p S_p first reaches saturation; starts `decades` decades of S_{p*} earlier",
             "wall_time_s": time.perf_counter() - wall0}
    for name, info in drifts.items():   # CF attribute names: letters, digits, underscores
        for key, val in info.items():
            attrs[f"scene_{name.replace('-', '_')}_{key}"] = val
    return make_tree(groups, VARIABLES, attrs=attrs, params=plain(spec),
                     title="Modulational-instability growth rates measured in the scenes' runs (exact and DpS) "
                              "against the linear DpS theory")


def reads(spec: MIGrowth) -> dict:
    """The initial data and both runs of every scene measured (at least one)."""
    if not spec.scenes:
        raise ConfigError("config error: beyond.mi-growth.scenes is empty: name at least one scene to measure")
    return scene_reads(spec.scenes)


ANALYSIS = Analysis(
    name="mi-growth", spec=MIGrowth, compute=compute, reads=reads, variables=VARIABLES,
    title="Modulational-instability growth rates measured in the scenes' runs, exact and DpS")
