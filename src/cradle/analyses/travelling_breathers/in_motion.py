"""DpS travelling breathers in motion (issue 37, item 3): the member at ``motion_speed`` launched in the lattice (nc)
through (ansatz) at each ``motion_eps``, against the same profile run in DpS: distance travelled, speed loss,
radiation (group /motion).
"""
from __future__ import annotations

import time as _time
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:

    from cradle.analyses.protocol import Log
    from cradle.analyses.travelling_breathers import TravellingBreathers
    from cradle.integrators.dps_travelling import TravellingBreather


#: half-width (sites) of the centroid that gives a breather's position: the DpS core decays doubly exponentially,
#: so its weight beyond it is below rounding of the weight's sum and radiation near the core barely moves it
MOTION_CORE = 4
#: DOP853's relative tolerance in the rerun that checks the lattice's speed against the integrator
MOTION_CHECK_RTOL = 1e-11


def motion(spec: TravellingBreathers, b: TravellingBreather, log: Log) -> tuple[dict, dict]:
    """The member ``b`` launched on a ring of ``motion_ring`` sites (:mod:`cradle.models.tb_launch`): in (dfnls)
    (integrate_dps at the family's rtol), and in (nc) through (ansatz) at each eps of ``motion_eps`` (integrate_lattice,
    srkn6c, the pipeline's exact method), both over ``motion_sites`` periods T of tau; positions, distances,
    velocities and radiation by :mod:`cradle.measurements.breather_motion` (lattice: energy density; DpS: norm
    density). Returns the ``/motion`` group and its attributes (prefixed ``motion_``)."""
    from cradle.integrators import integrate_dps, integrate_lattice
    from cradle.measurements import breather_motion as BM
    from cradle.measurements.continuum import fit_power
    from cradle.models import dps_travelling as M, tb_launch

    t0 = _time.process_time()
    al, S, per = spec.alpha, spec.motion_sites, spec.motion_samples
    s = np.linspace(0.0, float(S), S * per + 1)
    half = s.size // 2
    # DpS: the same start on the same ring; after k periods it should be the start shifted by k sites
    A0 = tb_launch.embedded(b.A, spec.motion_ring)
    run = integrate_dps(A0, s * b.T, alpha=al, rtol=spec.rtol)
    w = np.abs(run.A) ** 2
    p_dps = BM.track(w, MOTION_CORE)
    k = np.arange(S + 1)
    at_k = run.A[k * per]
    shift_res = max(float(np.max(np.abs(at_k[j] - np.exp(1j * j * b.theta) * M.shift(A0, int(j))))) for j in k)
    dps_rad = BM.radiation(w, p_dps, spec.motion_window)
    attrs: dict = {
        "motion_c": b.c, "motion_ring": spec.motion_ring, "motion_core": MOTION_CORE,
        "motion_window": spec.motion_window,
        "motion_dps_speed_error": abs(BM.velocity(s, p_dps) - 1.0),
        "motion_dps_position_error": float(np.max(np.abs(p_dps[k * per] - p_dps[0] - k))),
        "motion_dps_shift_residual": shift_res / float(np.max(np.abs(A0))),
        "motion_dps_norm_drift": float(run.max_l2_drift),
        "motion_dps_radiation_max": float(np.max(dps_rad)),
    }
    rows: dict[str, list] = {key: [] for key in ("speed_ratio", "speed_early", "speed_late", "radiation_end",
                                                 "energy_drift", "distance", "radiation")}
    for eps in spec.motion_eps:
        ini = tb_launch.launch(b.A, eps, al, spec.motion_ring)
        sol = integrate_lattice(ini.x0, ini.v0, s * b.T / eps ** (al - 1.0), alpha=al)
        e = BM.energy_density(sol.x, sol.v, al)
        p = BM.track(e, MOTION_CORE)
        rad = BM.radiation(e, p, spec.motion_window)
        # velocities against s = tau / T: in units of the DpS TB's c eps^(alpha-1)
        rows["speed_ratio"].append(BM.velocity(s, p))
        rows["speed_early"].append(BM.velocity(s[:half + 1], p[:half + 1]))
        rows["speed_late"].append(BM.velocity(s[half:], p[half:]))
        rows["radiation_end"].append(float(rad[-1]))
        rows["energy_drift"].append(float(sol.energy_drift))
        rows["distance"].append(p - p[0])
        rows["radiation"].append(rad)
        log(f"travelling-breathers: c = {b.c:.4g} in (nc) at eps = {eps:g}: {p[-1] - p[0]:.4f} sites while DpS "
            f"travels {S}, speed ratio {rows['speed_ratio'][-1]:.6f} (halves {rows['speed_early'][-1]:.6f}, "
            f"{rows['speed_late'][-1]:.6f}), radiation {rad[-1]:.3g}, energy drift {sol.energy_drift:.2g}")
    ratio = np.asarray(rows["speed_ratio"])
    # the integrator's share: the largest eps rerun by the adaptive DOP853 (another method, its own error control)
    eps0 = spec.motion_eps[0]
    ini = tb_launch.launch(b.A, eps0, al, spec.motion_ring)
    ref = integrate_lattice(ini.x0, ini.v0, s * b.T / eps0 ** (al - 1.0), alpha=al, method="dop853_numba",
                            rtol=MOTION_CHECK_RTOL)
    ref_ratio = BM.velocity(s, BM.track(BM.energy_density(ref.x, ref.v, al), MOTION_CORE))
    attrs.update({"motion_check_method": f"dop853_numba, rtol {MOTION_CHECK_RTOL:g}, at eps = {eps0:g}",
                  "motion_check_speed_ratio": ref_ratio,
                  "motion_check_speed_difference": abs(ref_ratio - float(ratio[0]))})
    deficit = 1.0 - ratio
    if np.all(deficit > 0):
        # (ansatz) leaves out terms of relative order eps^(alpha-1): the deficit's first correction is of that power
        f = fit_power(spec.motion_eps, deficit, correction=al - 1.0)
        attrs.update({"motion_order": f.power, "motion_order_uncertainty": f.uncertainty,
                      "motion_order_constant": f.K, "motion_order_correction": f.k})
    else:
        attrs.update({"motion_order": np.nan, "motion_order_uncertainty": np.nan,
                      "motion_order_constant": np.nan, "motion_order_correction": np.nan})
    loss = 1.0 - np.asarray(rows["speed_late"]) / np.asarray(rows["speed_early"])
    attrs.update({
        "motion_order_expected": al - 1.0,
        "motion_order_fit": "ln(1 - speed_ratio) = p ln eps + ln K + k eps^(alpha-1) over every eps (least squares); "
                            "uncertainty the larger of the standard error and the change when the smallest or the "
                            "largest eps is left out",
        "motion_max_energy_drift": float(max(rows["energy_drift"])),
        "motion_speed_loss_max": float(np.max(np.abs(loss))),
        "motion_exact_tb": "the exact TBs of (nc) launched the same way beside the DpS member (its own ring and eps): "
                           "/lattice_eps (dps_speed, exact_speed, *_radiation), with the key lattice (the full form)",
        "motion_cpu_s": _time.process_time() - t0,
    })
    data = {"speed_ratio": ratio, "speed_early": rows["speed_early"], "speed_late": rows["speed_late"],
            "deficit": deficit, "radiation_end": rows["radiation_end"], "energy_drift": rows["energy_drift"],
            "distance": np.array(rows["distance"]), "radiation": np.array(rows["radiation"]),
            "dps_distance": p_dps - p_dps[0], "dps_radiation": dps_rad}
    return {"/motion": (data, {"eps": list(spec.motion_eps), "s": s})}, attrs
