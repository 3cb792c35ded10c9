"""Theorem 1 measured: the exact periodic travelling waves of (nc) with V = V0 against DpS.

The waves themselves, solutions of the advance-delay equation (ad) by a sine-series Newton, are
:mod:`cradle.models.waves` (:func:`~cradle.models.waves.solve`, :func:`~cradle.models.waves.branch`).
Here: their frequencies against the DpS relation (wleadingorder)/(freq), the relative correction
and its slope in a (estim1), the profile correction v_a against its leading term (va) K_h P_h
N0(sin) by quadrature of (ph)-(kh), the decay of the sine coefficients, the convergence in the
number of modes, the q = pi binary oscillation of (inteq) whose period is a quadrature, and the
paper's travelling-wave scenes (their amplitude, wavenumber, alpha and time span read from their
initial-data files); :func:`compute` stores them as a tree of netCDF groups (:data:`VARIABLES`).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.protocol import Analysis, scene_reads
from cradle.data.variables import Var
from cradle.models import dps
from cradle.models.waves import Wave, branch, dV0, solve, wave_max
from cradle.scenes.spec import Travelling
from cradle.specs.declare import declared, param, plain
from cradle.specs.values import angle_expr, angle_or_none, parse_angle, show

if TYPE_CHECKING:
    from collections.abc import Callable

    import xarray as xr
    from numpy.typing import ArrayLike, NDArray

    from cradle.analyses.protocol import Log
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors


@declared(doc="Exact periodic travelling waves of (nc) with V = V0 by a sine-series Newton solver of (ad), against "
              "(wleadingorder) -> results/theorem1/theorem1.nc and results/figures/theorem1.{pdf,png}.")
class Theorem1:
    alpha: list[float] = param([1.5, 2.0, 3.0], "Hertz exponents alpha of V0 to solve for (each > 1).", minItems=1,
                               maxItems=6, items={"$ref": "#/$defs/alpha", "maximum": 10})
    q: list[float | str] = param(["pi/5", "pi/2", "4pi/5", "pi"], "Wavenumbers q of the travelling waves, in (0, pi] "
                                 "(numbers or 'pi/5'-style strings); include pi for the (inteq) check.", minItems=1,
                                 maxItems=8, items={"$ref": "#/$defs/angle"})
    a_min: float = param(1e-8, "Smallest amplitude a (first sine coefficient of u, ansatzu).", exclusiveMinimum=0,
                         minimum=1e-12, maximum=1.0)
    a_max: float = param(1.0, "Largest amplitude a; must exceed a_min.", exclusiveMinimum=0, maximum=100.0)
    n_amplitudes: int = param(31, "Number of amplitudes, log-spaced from a_min to a_max.", minimum=3, maximum=200)
    modes: int = param(128, "Number J of sine modes of u (sin(j xi), j = 1..J).", minimum=8, maximum=512)
    grid_log2: int = param(15, "log2 of the number M of grid points on which N(u) is sampled (aliasing error ~ "
                           "M^-(alpha+1)); M must exceed 8 J.", minimum=10, maximum=18)
    slope_eps_max: float = param(0.01, "The slope of the relative frequency correction is fitted where 1e-7 <= "
                                 "a^(alpha-1) <= slope_eps_max.", exclusiveMinimum=0, maximum=1.0)
    convergence_a: float = param(0.1, "Amplitude a of the convergence study in the number of modes.",
                                 exclusiveMinimum=0, maximum=100.0)
    convergence_modes: list[int] = param([16, 32, 64, 128], "Mode counts J of the convergence study (the reference "
                                         "is twice the largest).", minItems=2, maxItems=8,
                                         items={"description": "A number of sine modes.", "type": "integer",
                                                "minimum": 4, "maximum": 256})
    n_xi: int = param(129, "Number of samples of xi in [0, 2 pi] for the profiles v_a and K_h P_h N0(sin) (va).",
                      minimum=9, maximum=2001)
    scenes: list[str] = param([], "Travelling-wave scenes (names under scenes:, initial.kind travelling) whose "
                              "amplitude and time span, read from their results/initial/<scene>.nc, give exact vs "
                              "DpS frequency and the phase drift.", maxItems=10, items={"$ref": "#/$defs/name"})

    @property
    def wavenumbers(self) -> list[float]:
        """The wavenumbers q in radians."""
        return [parse_angle(q) for q in self.q]

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """q in (0, pi], a_max > a_min, a grid fine enough for the modes (2^grid_log2 >= 8 x
        max(modes, 2 x max(convergence_modes))), and every named scene that exists a travelling wave.
        A name that is no scene is reported with every analysis's reads (cradle.pipeline.config.checks)."""
        for i, q in enumerate(self.q):
            x = angle_or_none(q)
            if x is not None and not 0.0 < x <= math.pi + 1e-12:
                out.add(where + ["q", i], "must be in (0, pi]", q)
        if not self.a_max > self.a_min:
            out.add(where + ["a_max"], f"must exceed a_min = {show(self.a_min)}", self.a_max)
        if 2 ** self.grid_log2 < 8 * max(self.modes, 2 * max(self.convergence_modes)):
            out.add(where + ["grid_log2"], "2^grid_log2 must be >= 8 x max(modes, 2 x max(convergence_modes))",
                    self.grid_log2)
        for i, name in enumerate(self.scenes):
            sc = context.scenes.get(name)
            if sc is not None and not isinstance(sc.initial, Travelling):
                out.add(where + ["scenes", i], "not a travelling-wave scene", name)


_AQ = ("alpha", "q")
_AQA = ("alpha", "q", "a")
_SCENE = ("scene",)
_ALPHA = Var(("alpha",), "Hertz exponent alpha of the exact travelling waves")
_Q = Var(("q",), "wavenumber q of the travelling wave", "rad")

#: the stored variables of the `theorem1` file, per netCDF group: "/waves" the exact waves of (ad)
#: on the grid (alpha, q, a); "/profiles" the profile correction v_a against xi; "/convergence" the
#: checks in the number of sine modes; "/scenes" the paper's travelling-wave scenes
VARIABLES = {
    "/": {},
    "/waves": {
        "alpha": _ALPHA, "q": _Q,
        "a": Var(("a",), "amplitude a: first sine coefficient of u (ansatzu)"),
        "omega": Var(_AQA, "frequency omega_a of the exact travelling wave of (ad)"),
        "omega_dps": Var(_AQA, "DpS frequency (wleadingorder) without o(): omega_tw of (freq)"),
        "lambda": Var(_AQA, "lambda = (omega_a^2 - 1) / a^(alpha-1) (adcentral)"),
        "rel_correction": Var(_AQA, "relative correction (omega_a - omega_DpS)/(omega_DpS - 1)"),
        "residual": Var(_AQA, "max residual of the discrete (ad), scale-free units"),
        "newton_iterations": Var(_AQA, "Newton iterations"),
        "profile_error": Var(_AQA, "max_xi |v_a - K_h P_h N0(sin)|: remainder R_a of (va)"),
        "u_max": Var(_AQA, "max_xi u(xi) of the exact wave"),
        "correction_slope": Var(_AQ, "log-log slope of the relative frequency correction in a"),
        "omega_binary": Var(("alpha", "a"), "q = pi: 2 pi / period of (inteq) at amplitude max u, by quadrature"),
    },
    "/profiles": {
        "alpha": _ALPHA, "q": _Q,
        "xi": Var(("xi",), "moving-frame coordinate xi = q n - omega t", "rad"),
        "v_small": Var(_AQ + ("xi",), "profile correction v_a(xi) at the smallest amplitude"),
        "v_large": Var(_AQ + ("xi",), "profile correction v_a(xi) at the largest amplitude"),
        "va_leading": Var(_AQ + ("xi",), "leading term K_h P_h N0(sin) of v_a (va), by quadrature"),
    },
    "/convergence": {
        "alpha": _ALPHA, "q": _Q,
        "modes": Var(("modes",), "number J of sine modes of the discretisation"),
        "omega_error": Var(_AQ + ("modes",), "|omega_J - omega_ref| against twice the largest J"),
        "profile_error": Var(_AQ + ("modes",), "max_xi |v_J - v_ref| against twice the largest J"),
        "decay_rate": Var(_AQ, "exponent s of the algebraic decay |v_j| ~ j^-s"),
    },
    "/scenes": {
        "scene": Var(_SCENE, "name of a travelling-wave scene of config.yaml"),
        "a": Var(_SCENE, "amplitude a of the scene (from its omega_tw by (freq))"),
        "q": Var(_SCENE, "wavenumber q of the scene", "rad"),
        "alpha": Var(_SCENE, "Hertz exponent of the scene"),
        "t_end": Var(_SCENE, "time span of the scene"),
        "omega": Var(_SCENE, "exact travelling-wave frequency omega_a at the scene's amplitude"),
        "omega_dps": Var(_SCENE, "DpS frequency omega_tw (freq) at the scene's amplitude"),
        "drift": Var(_SCENE, "phase drift |omega_a - omega_tw| t over the scene's time span", "rad"),
        "residual": Var(_SCENE, "max residual of the discrete (ad) at the scene's amplitude"),
    },
}

# ----------------------------------------------------------------- leading orders of Theorem 1

# the slope of the relative correction is fitted where eps = a^(alpha-1) >= EPS_FIT_MIN: below, the
# correction (~ eps) sinks into the round-off of lambda (~ 1e-13)
EPS_FIT_MIN = 1e-7


def relative_correction(lam: ArrayLike, a: ArrayLike, q: ArrayLike, alpha: ArrayLike) -> NDArray[np.float64]:
    """(omega_a - omega_DpS) / (omega_DpS - 1) from lambda without cancellation.

    omega_a - 1 = eps lambda / (1 + s), s = sqrt(1 + eps lambda); omega_DpS - 1 = eps lambda0 / 2, so the
    ratio minus one is [2 (lambda - lambda0) - lambda0 eps lambda / (1 + s)] / (lambda0 (1 + s)).
    """
    lam, a = np.asarray(lam, dtype=float), np.asarray(a, dtype=float)
    eps = a ** (np.asarray(alpha, dtype=float) - 1.0)
    lam0 = 4.0 / np.vectorize(dps.tau0)(alpha) * np.abs(np.sin(np.asarray(q) / 2.0)) ** (np.asarray(alpha) + 1.0)
    s1 = 1.0 + np.sqrt(1.0 + eps * lam)
    return (2.0 * (lam - lam0) - lam0 * eps * lam / s1) / (lam0 * s1)


def omega_dps(a: ArrayLike, q: float, alpha: float) -> NDArray[np.float64]:
    """(wleadingorder) without the o(): 1 + (2/tau0) a^(alpha-1) |sin(q/2)|^(alpha+1) (= (freq))."""
    return 1.0 + 2.0 / dps.tau0(alpha) * np.asarray(a, dtype=float) ** (alpha - 1.0) * abs(np.sin(q / 2.0)) ** (
        alpha + 1.0)


def lambda0(q: float, alpha: float) -> float:
    """lambda at a -> 0: omega^2 - 1 ~ a^(alpha-1) lambda0 = 2 (omega_DpS - 1)."""
    return 4.0 / dps.tau0(alpha) * abs(np.sin(q / 2.0)) ** (alpha + 1.0)


def N0(xi: ArrayLike, q: float, alpha: float) -> NDArray[np.float64]:
    """N0(sin)(xi) = V0'(sin(xi+q) - sin xi) - V0'(sin xi - sin(xi-q)) (the bracket of (va))."""
    xi = np.asarray(xi, dtype=float)
    return dV0(np.sin(xi + q) - np.sin(xi), alpha) - dV0(np.sin(xi) - np.sin(xi - q), alpha)


def _breaks(q: float) -> list[float]:
    """Where the contacts of N0(sin) open or close in [0, 2 pi] (zeros of the elongations)."""
    # sin(xi+q) - sin(xi) = 2 cos(xi + q/2) sin(q/2) = 0 at xi = pi/2 - q/2 + k pi; likewise for d-.
    pts = [(np.pi / 2 - q / 2 + k * np.pi) % (2 * np.pi) for k in range(2)]
    pts += [(np.pi / 2 + q / 2 + k * np.pi) % (2 * np.pi) for k in range(2)]
    return sorted(pts)


def va_leading(xi: ArrayLike, q: float, alpha: float) -> NDArray[np.float64]:
    """K_h P_h N0(sin) of (va), with the operators (ph) and (kh), by adaptive quadrature."""
    from scipy.integrate import quad  # here: scipy.integrate takes 0.5 s to import, and the Snakefile imports us

    f = lambda s: float(N0(s, q, alpha))  # noqa: E731
    br = _breaks(q)

    def integral(g: Callable[[float], float], lo: float, hi: float) -> float:
        pts = [p for p in br if lo < p < hi]
        edges = [lo] + pts + [hi]
        return sum(quad(g, x0, x1, epsabs=1e-13, epsrel=1e-11, limit=400)[0]
                   for x0, x1 in zip(edges[:-1], edges[1:], strict=True))

    import warnings

    warnings.filterwarnings("ignore", message=".*roundoff error.*")
    zeta = 2.0 / np.pi * integral(lambda s: np.sin(s) * f(s), 0.0, np.pi)
    Ph = lambda s: f(s) - np.sin(s) * zeta  # noqa: E731
    kcoef = 1.0 / np.pi * integral(lambda s: (s - np.pi) * np.cos(s) * Ph(s), 0.0, np.pi)
    xi = np.atleast_1d(np.asarray(xi, dtype=float))
    out = np.empty_like(xi)
    for i, x in enumerate(xi):
        conv = integral(lambda s, x=x: np.sin(x - s) * Ph(s), 0.0, x) if x > 0 else 0.0  # type: ignore[misc]
        out[i] = np.sin(x) * kcoef + conv
    return out


# ----------------------------------------------------------------- q = pi: binary oscillations (inteq)

def binary_period(A: float, alpha: float) -> float:
    """Period of a'' = -a - 2^alpha a |a|^(alpha-1) (inteq) at amplitude max|a| = A, by quadrature.

    T = 4 int_0^{pi/2} A cos(th) dth / sqrt(A^2 cos^2 th + 2^(alpha+1) A^(alpha+1) (1 - sin^(alpha+1) th)/(alpha+1)),
    the substitution a = A sin(th) removing the turning-point singularity.
    """
    from scipy.integrate import quad

    k = 2.0**alpha

    def g(th: float) -> float:
        c, s = np.cos(th), np.sin(th)
        # (1 - s^(alpha+1)) / c^2 evaluated stably near th = pi/2
        one_minus = -np.expm1((alpha + 1.0) * np.log(s)) if s > 0 else 1.0
        ratio = one_minus / (c * c) if c > 1e-6 else (alpha + 1.0) / 2.0
        return 1.0 / np.sqrt(1.0 + 2.0 * k * A ** (alpha - 1.0) * ratio / (alpha + 1.0))

    val, _ = quad(g, 0.0, np.pi / 2.0, epsabs=0.0, epsrel=1e-13, limit=200)
    return 4.0 * val


def binary_frequency(A: float, alpha: float) -> float:
    """omega = 2 pi / period of the binary oscillation of amplitude A (inteq)."""
    return 2.0 * np.pi / binary_period(A, alpha)


def decay_rate(v: np.ndarray, j_min: int = 8) -> float:
    """Algebraic decay exponent s of |v_j| ~ j^-s from the upper envelope of |v_j|, j >= j_min."""
    v = np.abs(np.asarray(v, dtype=float))
    J = v.size
    j = np.arange(1, J + 1)
    # envelope: max over the tail beyond j (monotone), sampled on a log grid
    env = np.maximum.accumulate(v[::-1])[::-1]
    sel = (j >= j_min) & (j <= J // 2) & (env > 0)
    if sel.sum() < 3:
        return float("nan")
    idx = np.unique(np.round(np.geomspace(j[sel][0], j[sel][-1], 20)).astype(int)) - 1
    slope = np.polyfit(np.log(j[idx]), np.log(env[idx]), 1)[0]
    return float(-slope)


def log_slope(x: NDArray[np.float64], y: NDArray[np.float64]) -> float:
    """Least-squares slope of log|y| against log x."""
    x, y = np.asarray(x, dtype=float), np.abs(np.asarray(y, dtype=float))
    ok = (x > 0) & (y > 0) & np.isfinite(y)
    return float(np.polyfit(np.log(x[ok]), np.log(y[ok]), 1)[0])


# ----------------------------------------------------------------- the pipeline stage

def _sample_v(w: Wave, xi: ArrayLike) -> np.ndarray:
    j = np.arange(1, w.modes + 1)
    return np.sin(np.multiply.outer(np.asarray(xi, dtype=float), j)) @ w.v


def compute(spec: Theorem1, inputs: dict, log: Log | None = None) -> xr.DataTree:
    """The `theorem1` analysis as a tree of groups (see module docstring and :data:`VARIABLES`).

    The grid: alpha, q, n_amplitudes amplitudes log-spaced in [a_min, a_max], ``modes`` sine modes
    on M = 2^grid_log2 points; the slope is fitted where EPS_FIT_MIN <= a^(alpha-1) <= slope_eps_max;
    the convergence study at convergence_a; profiles on n_xi samples. Each scene of ``spec.scenes``
    (``inputs["<scene>/initial"]``, its initial data) gives its a, q, alpha and t_end, where exact and
    DpS frequencies are set side by side.
    """
    import time

    from cradle.data.io import make_tree

    t_start = time.perf_counter()
    say = log or (lambda *a: None)
    alphas = list(spec.alpha)
    qs = spec.wavenumbers
    amps = np.geomspace(spec.a_min, spec.a_max, spec.n_amplitudes)
    J, M = spec.modes, 2**spec.grid_log2
    conv_modes = sorted(spec.convergence_modes)
    J_ref = 2 * conv_modes[-1]
    xi = np.linspace(0.0, 2.0 * np.pi, spec.n_xi)
    shape = (len(alphas), len(qs), amps.size)
    om, om_dps, lam, res, prof_err, umax, iters = (np.full(shape, np.nan) for _ in range(7))
    slope, decay = np.full(shape[:2], np.nan), np.full(shape[:2], np.nan)
    v_small, v_large, v_lead = (np.full(shape[:2] + (xi.size,), np.nan) for _ in range(3))
    conv_om, conv_prof = (np.full(shape[:2] + (len(conv_modes),), np.nan) for _ in range(2))
    pi_quad = np.full((len(alphas), amps.size), np.nan)
    for ia, al in enumerate(alphas):
        for iq, q in enumerate(qs):
            ws = branch(amps, q, al, modes=J, M=M)
            lead = va_leading(xi, q, al)
            v_lead[ia, iq] = lead
            for k, w in enumerate(ws):
                om[ia, iq, k], lam[ia, iq, k], res[ia, iq, k] = w.omega, w.lam, w.residual
                iters[ia, iq, k] = w.iterations
                om_dps[ia, iq, k] = omega_dps(w.a, q, al)
                prof_err[ia, iq, k] = np.max(np.abs(_sample_v(w, xi) - lead))
                umax[ia, iq, k] = wave_max(w)
                if abs(abs(q) - np.pi) < 1e-12:
                    pi_quad[ia, k] = binary_frequency(umax[ia, iq, k], al)
            v_small[ia, iq], v_large[ia, iq] = _sample_v(ws[0], xi), _sample_v(ws[-1], xi)
            rel = relative_correction(lam[ia, iq], amps, q, al)
            eps = amps ** (al - 1.0)
            sel_fit = (eps <= spec.slope_eps_max) & (eps >= EPS_FIT_MIN)
            if sel_fit.sum() >= 2:
                slope[ia, iq] = log_slope(amps[sel_fit], rel[sel_fit])
            # convergence in the number of modes at one amplitude, against 2 x the largest count
            a_c = spec.convergence_a
            ref = solve(a_c, q, al, modes=J_ref, M=M, guess=solve(a_c, q, al, modes=conv_modes[-1], M=M))
            decay[ia, iq] = decay_rate(ref.v)
            xs = np.linspace(0.0, 2.0 * np.pi, 4 * J_ref + 1)
            v_ref = _sample_v(ref, xs)
            for im, Jm in enumerate(conv_modes):
                w = solve(a_c, q, al, modes=Jm, M=M, guess=ref)
                conv_om[ia, iq, im] = abs(w.omega - ref.omega)
                conv_prof[ia, iq, im] = np.max(np.abs(_sample_v(w, xs) - v_ref))
            say(f"theorem1: alpha={al} q={q:.6g}: omega(a_max)={om[ia, iq, -1]:.10g}, slope={slope[ia, iq]:.4f}, "
                f"decay j^-{decay[ia, iq]:.3f}")
    rel_corr = relative_correction(lam, amps, np.asarray(qs)[:, None], np.asarray(alphas)[:, None, None])
    # the paper's travelling-wave scenes: exact vs DpS frequency and the phase drift over the run
    # (the amplitude as the scene's initial data has it: given, or (freq) inverted from its omega_tw)
    scenes = list(spec.scenes)
    sc = {k: np.full(len(scenes), np.nan) for k in ("a", "q", "alpha", "om", "omd", "t", "drift", "res")}
    for i, name in enumerate(scenes):
        scene_attrs = inputs[f"{name}/initial"].attrs
        al, q, a = float(scene_attrs["alpha"]), float(scene_attrs["q"]), float(scene_attrs["a"])
        path = np.geomspace(min(1e-3, a), a, 12)
        w = branch(path, q, al, modes=J, M=M)[-1]
        sc["a"][i], sc["q"][i], sc["alpha"][i], sc["t"][i] = a, q, al, float(scene_attrs["t_end"])
        sc["om"][i], sc["omd"][i], sc["res"][i] = w.omega, omega_dps(a, q, al), w.residual
        sc["drift"][i] = abs(sc["om"][i] - sc["omd"][i]) * sc["t"][i]
        say(f"theorem1: scene {name}: a={a:.6g} omega={w.omega:.10g} omega_DpS={sc['omd'][i]:.10g} "
            f"drift={sc['drift'][i]:.4g} rad over t={sc['t'][i]}")
    alpha_q = {"alpha": alphas, "q": qs}
    groups = {
        "/waves": ({"omega": om, "omega_dps": om_dps, "lambda": lam, "rel_correction": rel_corr, "residual": res,
                    "newton_iterations": iters, "profile_error": prof_err, "u_max": umax,
                    "correction_slope": slope, "omega_binary": pi_quad}, {**alpha_q, "a": amps}),
        "/profiles": ({"v_small": v_small, "v_large": v_large, "va_leading": v_lead}, {**alpha_q, "xi": xi}),
        "/convergence": ({"omega_error": conv_om, "profile_error": conv_prof, "decay_rate": decay},
                         {**alpha_q, "modes": conv_modes}),
        "/scenes": ({"a": sc["a"], "q": sc["q"], "alpha": sc["alpha"], "t_end": sc["t"], "omega": sc["om"],
                     "omega_dps": sc["omd"], "drift": sc["drift"], "residual": sc["res"]},
                    {"scene": np.array(scenes, dtype=object)}),
    }
    attrs = {
        "q_expr": ", ".join(angle_expr(x) for x in spec.q), "modes": J, "grid_points": M,
        "reference_modes": J_ref, "convergence_a": spec.convergence_a,
        "slope_eps_max": spec.slope_eps_max, "slope_eps_min": EPS_FIT_MIN,
        "solver": "sine-series Galerkin/collocation of (ad) with c_1 = a (ansatzu), omega^2 = 1 + a^(alpha-1) "
                  "lambda; Newton with analytic Jacobian, continuation in a",
        "expected_correction_slope": "alpha - 1 (estim1, V = V0)",
        "expected_decay_rate": "alpha + 3 (N(u) is C^1 with |d|^alpha singularities where contacts open)",
        "max_residual": float(np.nanmax(res)),
        "wall_time_s": time.perf_counter() - t_start,
    }
    if np.any(np.isfinite(pi_quad)):
        iq = [i for i, q in enumerate(qs) if abs(abs(q) - np.pi) < 1e-12][0]
        attrs["pi_max_relative_error"] = float(np.nanmax(np.abs(om[:, iq, :] / pi_quad - 1.0)))
    return make_tree(groups, VARIABLES, attrs=attrs, params=plain(spec),
                     title="Theorem 1 measured: exact travelling waves of (nc) with V = V0 against the DpS "
                              "dispersion relation (wleadingorder)")


def reads(spec: Theorem1) -> dict:
    """The initial data of every travelling-wave scene named (their a, q, alpha and t_end)."""
    return scene_reads(spec.scenes, parts=("initial",))


ANALYSIS = Analysis(
    name="theorem1", spec=Theorem1, compute=compute, reads=reads, variables=VARIABLES,
    title="Theorem 1 measured: exact travelling waves of (ad) against (wleadingorder)")
