"""Spectral stability of the exact travelling waves of (nc) against the DpS modulational instability.

The Bloch-Floquet modes (bloch) of the waves of :mod:`cradle.models.waves`, Hill's method for
them and the brute-force checks on a ring are :mod:`cradle.analyses.bloch`. Here: the lattice
growth rate g(p) of each sideband p against the DpS rate of (ansatz3) converted to lattice time
(:func:`dps_growth`, R = a/2), over (q, p) at the amplitude omega_tw fixes by (freq); the lattice
threshold (:func:`threshold`) against the amplitude, tending to the DpS q_c = pi/2; the small-
amplitude limit; and :func:`compute`, which stores them as a tree of netCDF groups (:data:`VARIABLES`).
Its spec is :class:`cradle.analyses.floquet_spec.Floquet` (config ``beyond: floquet:``, a reduced form for
``all``); it reads no file.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.bloch import (
    NOISE_FLOOR,
    Hill,
    direct_growth,
    match_distance,
    multipliers,
    ring_exponents_hill,
    ring_monodromy,
    wave_for,
)
from cradle.analyses.floquet_spec import Floquet, Numerics
from cradle.analyses.protocol import Analysis
from cradle.data.variables import Var
from cradle.models import dps
from cradle.specs.declare import plain
from cradle.specs.values import angle_expr, parse_angle

if TYPE_CHECKING:
    import xarray as xr
    from numpy.typing import ArrayLike, NDArray

    from cradle.analyses.protocol import Log


def dps_growth(q: ArrayLike, p: ArrayLike, alpha: float, a: float) -> NDArray[np.float64]:
    """The DpS growth rate of sideband p in lattice time: modulational.growth_rate with R = a / 2."""
    from cradle.analyses.mi_diagram import growth_rate

    return growth_rate(q, p, alpha, R=0.5 * a)


def dps_max_growth(q: float, alpha: float, a: float) -> tuple[float, float]:
    """(max_p DpS growth in lattice time, argmax |p|)."""
    from cradle.analyses.mi_diagram import max_over_p

    g, p = max_over_p(q, alpha)
    return g / dps.tau0(alpha) * (0.5 * a) ** (alpha - 1.0), p


# ----------------------------------------------------------------- thresholds

def _hill_at(q: float, alpha: float, omega_tw: float, num: Numerics) -> Hill:
    w = wave_for(q, alpha, omega_tw=omega_tw, modes=num.wave_modes, grid_log2=num.wave_grid_log2)
    return Hill(w, L=num.hill_modes, M=2 ** num.grid_log2)


def threshold(alpha: float, omega_tw: float, q_lo: float, q_hi: float, num: Numerics, n_scan: int = 16,
              n_p: int = 61, floor: float = NOISE_FLOOR, tol: float = 2e-6) -> tuple[float, float, float, int]:
    """Smallest q in [q_lo, q_hi] where the exact wave (a from (freq) at omega_tw) has an unstable Bloch mode.

    Scan n_scan points for the first q with max_p signed > floor (p in (0, pi], refined between grid
    points), then bisect to |dq| < tol. Returns (q_c, dq, p of the first unstable mode, n_waves solved);
    (nan, nan, nan, n) if the scan finds no transition (stable throughout or unstable at q_lo).
    """
    qs = np.linspace(q_lo, q_hi, n_scan)
    prev, count = None, 0
    for q in qs:
        s, _ = _hill_at(q, alpha, omega_tw, num).max_signed(n_p, floor)
        count += 1
        if s > floor:
            if prev is None:
                return float("nan"), float("nan"), float("nan"), count
            lo, hi = prev, q
            break
        prev = q
    else:
        return float("nan"), float("nan"), float("nan"), count
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        s, _ = _hill_at(mid, alpha, omega_tw, num).max_signed(n_p, floor)
        count += 1
        if s > floor:
            hi = mid
        else:
            lo = mid
    _, p_first = _hill_at(hi, alpha, omega_tw, num).max_signed(n_p, floor)
    return float(0.5 * (lo + hi)), float(0.5 * (hi - lo)), float(p_first), count + 1


# ----------------------------------------------------------------- the pipeline stage

_Q = Var(("q",), "wavenumber q of the exact travelling wave", "rad")
_P = Var(("p",), "Bloch wavenumber p of the perturbation (DpS sideband p)", "rad")
_GROWTH = Var(("q", "p"), "lattice growth rate g(p): max Re lambda of the central Bloch pair", "1",
              attrs=(("comment", "per unit lattice time t; 0 where stable; p = 0 (trivial pair) set to 0"),))

#: the stored variables of the `floquet` file, per netCDF group (the root holds the attributes):
#: "/sweep" the growth over (q, p) at omega_tw, "/profiles" growth against p at selected q,
#: "/thresholds" the lattice threshold against the amplitude (omega_tw), "/small_amplitude" the
#: check against DpS. Rates are per unit t of (nc); DpS rates in lattice time (R = a/2)
VARIABLES = {
    "/": {},
    "/sweep": {
        "q": _Q, "p": _P,
        "a": Var(("q",), "amplitude a (first sine coefficient of u) from (freq) at omega_tw"),
        "omega": Var(("q",), "frequency omega_a of the exact wave"),
        "growth": _GROWTH,
        "growth_dps": Var(("q", "p"), "DpS growth rate of sideband p in lattice time (R = a/2)"),
        "max_growth": Var(("q",), "max over p of the lattice growth rate"),
        "argmax_p": Var(("q",), "p of the fastest-growing lattice mode (NaN where stable)", "rad"),
        "max_growth_dps": Var(("q",), "max over p of the DpS growth rate in lattice time"),
        "argmax_p_dps": Var(("q",), "p of the fastest-growing DpS sideband (NaN where stable)", "rad"),
        "trivial_defect": Var(("q",), "max |lambda| of the central pair at p = 0 (exactly 0; numerical error)"),
    },
    "/profiles": {
        "q": Var(("q",), "wavenumber q of a growth-against-p profile", "rad"), "p": _P,
        "growth": Var(("q", "p"), "lattice growth rate against p at a selected q"),
        "growth_dps": Var(("q", "p"), "DpS growth rate (lattice time) against p at a selected q"),
        "max_growth": Var(("q",), "max over p of the lattice growth rate at a selected q"),
        "argmax_p": Var(("q",), "p of the fastest-growing lattice mode at a selected q", "rad"),
        "max_growth_fine": Var(("q",), "the same with the finer numerics (convergence check)"),
        "max_growth_dps": Var(("q",), "max over p of the DpS growth rate at a selected q"),
    },
    "/thresholds": {
        "omega_tw": Var(("omega_tw",), "omega_tw of (freq) fixing the amplitude of a threshold search"),
        "q_threshold": Var(("omega_tw",), "lattice instability threshold: smallest unstable q", "rad"),
        "q_threshold_halfwidth": Var(("omega_tw",), "half-width of the final bisection bracket of the threshold",
                                     "rad"),
        "p_threshold": Var(("omega_tw",), "p of the first unstable lattice mode at the threshold", "rad"),
    },
    "/small_amplitude": {
        "q": Var(("q",), "wavenumber q of a small-amplitude check against DpS", "rad"),
        "max_growth": Var(("q",), "max lattice growth rate at the small amplitude"),
        "max_growth_dps": Var(("q",), "max DpS growth rate (lattice time) at the small amplitude"),
        "rel_error": Var(("q",), "lattice / DpS max growth rate - 1 at the small amplitude"),
    },
}


def compute(spec: Floquet, inputs: dict | None = None, log: Log | None = None) -> xr.DataTree:
    """The `floquet` analysis as a tree of groups (:data:`VARIABLES`), from the spec of one form (it reads no
    file: ``inputs`` is empty). Every Hill problem and wave uses ``spec.numerics``, the convergence checks
    ``spec.fine``.
    """
    import time

    from cradle.data.io import make_tree

    t_start = time.perf_counter()
    say = log or (lambda *a: None)
    al, om_tw = spec.alpha, spec.omega_tw
    num, conv = spec.numerics, spec.fine
    n_p = spec.n_p
    qs = np.linspace(parse_angle(spec.q_min), parse_angle(spec.q_max), spec.n_q)
    ps = np.linspace(0.0, np.pi, n_p)
    timings = {}

    # 1. growth over (q, p) at omega_tw, lattice (Hill) and DpS
    t0 = time.perf_counter()
    G, Gd = np.zeros((qs.size, n_p)), np.zeros((qs.size, n_p))
    amp, omg, gmax, pmax, gdmax, pdmax, defect = (np.full(qs.size, np.nan) for _ in range(7))
    for i, q in enumerate(qs):
        H = _hill_at(q, al, om_tw, num)
        amp[i], omg[i] = H.w.a, H.w.omega
        G[i] = H.growth(ps)
        G[i, 0] = 0.0                                    # p = 0: the trivial pair, reported as defect
        defect[i] = H.trivial_defect()
        gmax[i], pmax[i] = H.max_growth(n_p)
        Gd[i] = dps_growth(q, ps, al, H.w.a)
        gdmax[i], pdmax[i] = dps_max_growth(q, al, H.w.a)
        if not gdmax[i] > 0:
            pdmax[i] = np.nan
    timings["sweep"] = time.perf_counter() - t0
    say(f"floquet: sweep of {qs.size} q x {n_p} p in {timings['sweep']:.1f} s; max trivial defect "
        f"{np.max(defect):.2g}")

    # 2. thresholds against the amplitude (omega_tw), and at omega_tw with finer numerics / another floor
    t0 = time.perf_counter()
    om_list = [float(x) for x in spec.threshold_omega_tw]
    qlo, qhi = parse_angle(spec.threshold_q_min), parse_angle(spec.threshold_q_max)
    thr, thr_dq, thr_p = (np.full(len(om_list), np.nan) for _ in range(3))
    for j, om in enumerate(om_list):
        thr[j], thr_dq[j], thr_p[j], nw = threshold(al, om, qlo, qhi, num, n_scan=spec.threshold_n_scan)
        say(f"floquet: omega_tw={om}: lattice threshold q_c = {thr[j]:.8f} = {thr[j] / np.pi:.6f} pi "
            f"(+- {thr_dq[j]:.1g}), first p = {thr_p[j] / np.pi:.4f} pi, {nw} waves")
    j_main = int(np.argmin(np.abs(np.asarray(om_list) - om_tw)))
    if abs(om_list[j_main] - om_tw) > 1e-12:
        raise ValueError(f"config error: beyond.floquet.threshold_omega_tw = {om_list}: must contain omega_tw = "
                         f"{om_tw}")
    q_c, dq_c = thr[j_main], thr_dq[j_main]
    # the same threshold with finer numerics and with a 100 x higher floor, from a bracket around it
    br = (q_c - 0.002 * np.pi, q_c + 0.002 * np.pi)
    q_c_conv = threshold(al, om_tw, *br, conv, n_scan=2)[0]
    q_c_floor = threshold(al, om_tw, *br, num, n_scan=2, floor=1e-5)[0]
    unc = float(dq_c + abs(q_c_conv - q_c) + abs(q_c_floor - q_c))
    timings["thresholds"] = time.perf_counter() - t0
    say(f"floquet: threshold at omega_tw={om_tw}: {q_c / np.pi:.6f} pi; finer numerics {q_c_conv / np.pi:.6f} pi; "
        f"floor 1e-5 {q_c_floor / np.pi:.6f} pi; uncertainty {unc:.2g} rad; DpS pi/2")

    # 2b. the deepest dip of max_p g above the threshold (where the unstable band changes family)
    t0 = time.perf_counter()
    from scipy.optimize import minimize_scalar

    above = np.where(qs > q_c)[0] if np.isfinite(q_c) else np.array([], dtype=int)
    q_dip, g_dip = float("nan"), float("nan")
    inner = [i for i in above if 0 < i < qs.size - 1 and gmax[i] <= gmax[i - 1] and gmax[i] <= gmax[i + 1]]
    if inner:
        i = min(inner, key=lambda i_: gmax[i_])
        res = minimize_scalar(lambda x: _hill_at(x, al, om_tw, num).max_signed(n_p)[0], bounds=(qs[i - 1], qs[i + 1]),
                              method="bounded", options={"xatol": 1e-5})
        q_dip, g_dip = float(res.x), float(res.fun)
        say(f"floquet: deepest dip of the max growth above q_c: {g_dip:.3g} at q = {q_dip / np.pi:.5f} pi")
    timings["dip"] = time.perf_counter() - t0

    # 3. growth against p at selected q, refined maxima, convergence
    t0 = time.perf_counter()
    qsel = [parse_angle(x) for x in spec.q_profiles]
    prof, prof_d = np.zeros((len(qsel), n_p)), np.zeros((len(qsel), n_p))
    pm, pm_p, pm_conv, pm_d, pm_dp = (np.full(len(qsel), np.nan) for _ in range(5))
    for i, q in enumerate(qsel):
        H = _hill_at(q, al, om_tw, num)
        prof[i] = H.growth(ps)
        prof[i, 0] = 0.0
        pm[i], pm_p[i] = H.max_growth(n_p)
        pm_conv[i] = _hill_at(q, al, om_tw, conv).max_growth(n_p)[0]
        prof_d[i] = dps_growth(q, ps, al, H.w.a)
        pm_d[i], pm_dp[i] = dps_max_growth(q, al, H.w.a)
        say(f"floquet: q = {q / np.pi:.4f} pi: lattice max growth {pm[i]:.6g} at p = {pm_p[i] / np.pi:.4f} pi "
            f"(finer numerics {pm_conv[i]:.6g}); DpS {pm_d[i]:.6g} at p = {pm_dp[i] / np.pi:.4f} pi; "
            f"e-folds over t = 913.7: {913.7 * pm[i]:.3g} (DpS {913.7 * pm_d[i]:.3g})")
    timings["profiles"] = time.perf_counter() - t0

    # 4. small amplitude: lattice -> DpS
    t0 = time.perf_counter()
    sq = [parse_angle(x) for x in spec.small_q]
    sm_lat, sm_dps = np.full(len(sq), np.nan), np.full(len(sq), np.nan)
    for i, q in enumerate(sq):
        H = _hill_at(q, al, spec.small_omega_tw, num)
        sm_lat[i] = H.max_growth(n_p)[0]
        sm_dps[i] = dps_max_growth(q, al, H.w.a)[0]
    sm_rel = sm_lat / sm_dps - 1.0
    timings["small_amplitude"] = time.perf_counter() - t0
    say(f"floquet: omega_tw={spec.small_omega_tw}: lattice/DpS max growth - 1 = {np.round(sm_rel, 4)}")

    # 5. brute force on a ring: monodromy vs Bloch reduction; direct simulation
    t0 = time.perf_counter()
    N, k = spec.ring_N, spec.ring_k
    Hr = _hill_at(2 * np.pi * k / N, al, om_tw, num)
    T = 2 * np.pi / Hr.w.omega
    mu = np.linalg.eigvals(ring_monodromy(Hr.w, N))
    mu_h = multipliers(ring_exponents_hill(Hr, N), T)
    ring_dist = match_distance(mu, mu_h)
    ring_rate, ring_rate_h = float(np.max(np.log(np.abs(mu))) / T), float(np.max(np.log(np.abs(mu_h))) / T)
    ring_trivial = float(np.sort(np.abs(mu - 1.0))[1])
    timings["ring"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    Nd, kd = spec.direct_N, spec.direct_k
    wd = wave_for(2 * np.pi * kd / Nd, al, omega_tw=om_tw, modes=num.wave_modes, grid_log2=num.wave_grid_log2)
    d_mode, d_dist, d_rate, _, _ = direct_growth(wd, Nd, growth_factor=spec.direct_growth_factor)
    timings["direct"] = time.perf_counter() - t0
    say(f"floquet: ring N={N} k={k}: |mu_brute - mu_Bloch| <= {ring_dist:.2g}, top rate {ring_rate:.8g} vs "
        f"{ring_rate_h:.8g}, trivial |mu - 1| = {ring_trivial:.2g}; direct run N={Nd} k={kd}: {d_mode:.6g} "
        f"(|delta| fit {d_dist:.6g}) vs Floquet {d_rate:.6g}")

    def at(qv: float) -> float:
        return float(pm[int(np.argmin(np.abs(np.asarray(qsel) - qv)))]) if qsel else float("nan")

    groups = {
        "/sweep": ({"a": amp, "omega": omg, "growth": G, "growth_dps": Gd, "max_growth": gmax,
                    "argmax_p": np.where(gmax > 0, pmax, np.nan), "max_growth_dps": gdmax, "argmax_p_dps": pdmax,
                    "trivial_defect": defect}, {"q": qs, "p": ps}),
        "/profiles": ({"growth": prof, "growth_dps": prof_d, "max_growth": pm,
                       "argmax_p": np.where(pm > 0, pm_p, np.nan), "max_growth_fine": pm_conv,
                       "max_growth_dps": pm_d}, {"q": qsel, "p": ps}),
        "/thresholds": ({"q_threshold": thr, "q_threshold_halfwidth": thr_dq, "p_threshold": thr_p},
                        {"omega_tw": om_list}),
        "/small_amplitude": ({"max_growth": sm_lat, "max_growth_dps": sm_dps, "rel_error": sm_rel}, {"q": sq}),
    }
    wall = time.perf_counter() - t_start
    attrs = {
        "alpha": al, "omega_tw": om_tw,
        "amplitude": "a from (freq) inverted at omega_tw for each q (as the fftseuil scenes); the exact wave of "
                     "(ad) with that first sine coefficient, frequency omega of /sweep",
        "hill_modes": num.hill_modes, "grid_points": 2 ** num.grid_log2, "wave_modes": num.wave_modes,
        "wave_grid_points": 2 ** num.wave_grid_log2,
        "fine_numerics": f"hill_modes={conv.hill_modes}, grid_points=2^{conv.grid_log2}, "
                         f"wave_modes={conv.wave_modes}",
        "noise_floor": NOISE_FLOOR,
        "q_profiles_expr": ", ".join(angle_expr(x) for x in spec.q_profiles),
        "q_threshold_lattice": q_c, "q_threshold_lattice_over_pi": q_c / np.pi,
        "q_threshold_uncertainty": unc, "q_threshold_fine_numerics": q_c_conv, "q_threshold_high_floor": q_c_floor,
        "q_threshold_dps": float(np.pi / 2),
        "q_dip": q_dip, "q_dip_over_pi": q_dip / np.pi, "growth_dip": g_dip,
        "growth_at_pi_over_2": at(np.pi / 2), "growth_at_051pi": at(0.51 * np.pi), "growth_at_052pi": at(0.52 * np.pi),
        "max_profile_fine_change": float(np.nanmax(np.abs(pm_conv - pm))),
        "small_omega_tw": spec.small_omega_tw, "small_max_rel_error": float(np.nanmax(np.abs(sm_rel))),
        "ring_N": N, "ring_k": k, "ring_multiplier_distance": ring_dist, "ring_top_rate_monodromy": ring_rate,
        "ring_top_rate_bloch": ring_rate_h, "ring_trivial_multiplier_distance": ring_trivial,
        "direct_N": Nd, "direct_k": kd, "direct_growth_factor": spec.direct_growth_factor,
        "direct_rate_mode": d_mode, "direct_rate_distance": d_dist, "direct_rate_floquet": d_rate,
        "direct_rel_error": d_mode / d_rate - 1.0,
        "growth_units": "1 / t (lattice time of (nc)); DpS rates converted by growth_rate(q, p, alpha, R = a/2)",
        "method": "Hill's method for the Bloch-Floquet pencil (bloch) in the co-moving frame; central strip "
                  "|Im lambda| < omega/2 = DpS sideband p; brute-force ring monodromy (DOP853) as a check",
        "timings_s": ", ".join(f"{k_}={v:.1f}" for k_, v in timings.items()),
        "wall_time_s": wall,
    }
    say(f"floquet: done in {wall:.1f} s ({attrs['timings_s']})")
    return make_tree(groups, VARIABLES, attrs=attrs, params=plain(spec),
                     title="Spectral (Bloch-Floquet) stability of the exact travelling waves of (nc) against "
                           "the DpS modulational-instability threshold")


ANALYSIS = Analysis(
    name="floquet", spec=Floquet, compute=compute, variables=VARIABLES,
    title="Bloch-Floquet stability of the exact travelling waves against the DpS threshold")
