"""The solitary wave of the Hertz chain, and the pulse of a desk toy's first impact measured against it.

During the first impact of a desk toy the pendulum force is negligible (the collisions last about 1e-4 of a
swing) and the line of balls is a Hertz chain. This analysis

* computes the exact solitary wave of the Hertz chain without on-site potential (:mod:`cradle.models.solitary`:
  Petviashvili's iteration on the advance-delay equation (sw)) at each speed of ``speeds``, independently: its
  strain, force and velocity amplitudes against the speed (the exponent 1/5 of the speed in the velocity
  amplitude, exact by homogeneity, fitted), the residual of (sw) in its differential form, and the profile;
* continues its tail in real space (:func:`cradle.models.solitary.tail`) to ``tail_stop`` sites: log(-log R)
  against xi and its local slope against log(3/2), the doubly exponential decay of English & Pego (2005);
* compares it with Nesterenko's long-wave solitary wave (speed constants in the strain and in the velocity
  amplitude, widths);
* launches the computed wave into the lattice integrator (the Hertz chain with the on-site slot's absent unit,
  :func:`cradle.integrators.lattice_adaptive.run_dop853_hertz_chain`) for ``launch_time`` and compares the
  strain with the translated profile: the wave's residual as a solution of the chain;
* runs the first impact of the desk toy (:mod:`cradle.models.desk_toy`: ``cradle``, one ball lifted to
  ``angle_deg``) for each chain length of ``chains``, twice: the Hertz chain alone from the impact (the struck
  line at rest, the released ball at the line with (nc)'s impact speed) and (nc) itself from the release
  (:func:`cradle.integrators.integrate_lattice`, small-angle pendulum); and measures the pulse on each bead
  (:mod:`cradle.measurements.pulse`): arrival time, peak velocity, local speed and width, in SI, against the
  exact solitary wave and Nesterenko's at the same peak velocity, and the relative difference of the two models.

The chain's length unit is the sphere diameter D = 2R (touching spheres), its time unit that of (nc)
(1/omega_0): a speed of c sites per unit time is c D omega_0 m/s, a velocity v of (nc) is v X omega_0 m/s.
"""
from __future__ import annotations

import math
import time as _time
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.protocol import Analysis
from cradle.data.variables import Var
from cradle.models.physical import Cradle
from cradle.specs.declare import declared, param, plain
from cradle.specs.values import RTOL_FLOOR

if TYPE_CHECKING:
    import xarray as xr
    from numpy.typing import NDArray

    from cradle.analyses.protocol import Log
    from cradle.models.physical import Scales
    from cradle.models.solitary import SolitaryWave as Wave
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors

#: the cradle of a spec that gives none: that of the desk-toy analysis (1 cm AISI 52100 balls, 10 cm strings)
DEFAULT_CRADLE = Cradle(material="steel", radius=0.01, length=0.1)

_SPEED = {"type": "number", "exclusiveMinimum": 0, "minimum": 1e-3, "maximum": 1e3,
          "description": "A speed c of the solitary wave (sites per unit time)."}
_CHAIN = {"type": "integer", "minimum": 3, "maximum": 200, "description": "Balls in the line."}

#: the line's velocity is stored for the figure at every STORE_EVERY-th sample
STORE_EVERY = 4

#: the velocity amplitudes (m/s) at which the speed law is tabulated in SI: a slow push to a hard knock
LAW_VELOCITIES = np.geomspace(1e-3, 10.0, 41)


@declared(doc="The solitary wave of the Hertz chain (issue 38): exact by Petviashvili's iteration of (sw), its "
              "speed against amplitude, residual, doubly exponential tail, against Nesterenko's long-wave wave; "
              "the pulse of a desk toy's first impact in SI against it -> results/solitary-wave/solitary-wave.nc "
              "and results/figures/solitary-wave.{pdf,png}.")
class SolitaryWaveRuns:
    speeds: list[float] = param([0.25, 0.5, 1.0, 2.0, 4.0], "Speeds c at which the wave is solved, each on its "
                                "own (the speed exponent is fitted over them); 1 must be one of them (the "
                                "profile, tail and comparisons are those of c = 1).", minItems=2, maxItems=12,
                                items=_SPEED, reduced=[0.5, 1.0, 2.0])
    length: float = param(40.0, "Length of the periodic box of the iteration (sites).", minimum=16, maximum=400)
    points: int = param(64, "Grid points per site (an integer: the shifts by one site are exact).", minimum=8,
                        maximum=1024, reduced=32)
    tail_stop: float = param(30.0, "The tail is continued in real space up to this xi (sites).", minimum=8,
                             maximum=100, reduced=16.0)
    launch_time: float = param(16.0, "Time (units of the chain, c = 1) over which the computed wave is integrated "
                               "in the lattice; an integer number of grid steps (sites over points).",
                               exclusiveMinimum=0, maximum=1000, reduced=4.0)
    cradle: Cradle = param(None, "The spheres and their strings (cradle.models.physical.Cradle, a pendulum "
                           "length). Absent: steel balls of radius 1 cm on 10 cm strings (DEFAULT_CRADLE).")
    angle_deg: float = param(20.0, "Angle of the released ball's string from the vertical (degrees).",
                             exclusiveMinimum=0, exclusiveMaximum=90)
    chains: list[int] = param([5, 30], "Chain lengths N of the first impact (one ball lifted): the desk toy's "
                              "and a line long enough for the pulse to settle.", minItems=1, maxItems=6,
                              items=_CHAIN, reduced=[5, 20])
    samples: int = param(4000, "Stored times over the window of each impact run (the pulse crosses the line "
                         "and three more sites).", minimum=200, maximum=100000, reduced=2000)
    rtol: float = param(1e-13, "Relative tolerance of the lattice runs (dop853_numba; atol = rtol times the "
                        "largest displacement or the release amplitude).", minimum=RTOL_FLOOR, maximum=1e-6)

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Each form: c = 1 among the speeds, no speed twice, a launch time on the grid, a pendulum cradle."""
        if 1.0 not in self.speeds:
            out.add(where + ["speeds"], "must include 1 (the profile, tail and comparisons are those of c = 1)",
                    self.speeds)
        for key in ("speeds", "chains"):
            values = getattr(self, key)
            if len(set(values)) != len(values):
                out.add(where + [key], "lists a value twice", values)
        steps = self.launch_time * self.points
        if abs(steps - round(steps)) > 1e-9 * max(1.0, steps):
            out.add(where + ["launch_time"], f"must be a whole number of grid steps 1/points = 1/{self.points}",
                    self.launch_time)
        if self.cradle is not None and self.cradle.length is None:
            out.add(where + ["cradle"], "a desk toy needs the pendulum length (a stiff oscillator has no angle)")


def cradle_of(spec: SolitaryWaveRuns) -> Cradle:
    """The spec's cradle, or :data:`DEFAULT_CRADLE`."""
    return spec.cradle if spec.cradle is not None else DEFAULT_CRADLE


# ----------------------------------------------------------------- the exact wave


def _at_sites(w: Wave, f: NDArray[np.float64], offsets: NDArray[np.float64]) -> NDArray[np.float64]:
    """f at xi = ``offsets`` (multiples of the grid step), 0 off the box."""
    h = float(w.xi[1] - w.xi[0])
    i0 = int(np.searchsorted(w.xi, 0.0))
    idx = (i0 + np.round(np.asarray(offsets) / h)).astype(int)
    out = np.zeros(idx.size)
    ok = (idx >= 0) & (idx < w.xi.size)
    out[ok] = f[idx[ok]]
    return out


def launch(w: Wave, t_end: float, rtol: float, N: int | None = None) -> dict:
    """The wave ``w`` laid on a free chain (its peak a third along, its strain on the bonds, its velocity on the
    beads, the beads ahead at rest) and integrated by the Hertz chain without on-site term to ``t_end``: the
    largest error of the bond strains and bead velocities against the translated wave, relative to R_m, v_m."""
    from cradle.integrators.lattice_adaptive import run_dop853_hertz_chain

    N = N or int(math.ceil(w.c * t_end)) + 24
    n0 = 10
    n = np.arange(N)
    strain = _at_sites(w, w.strain, (n - n0).astype(float))
    strain[-1] = 0.0                                  # the free end has no bond N-1
    x0 = np.cumsum(strain[::-1])[::-1]                # x_n = sum_{j >= n} c_j: the beads ahead at rest at 0
    v0 = _at_sites(w, w.velocity, (n - n0).astype(float))
    X, V, _, drift, steps, _, _ = run_dop853_hertz_chain(x0, v0, np.array([0.0, t_end]), rtol,
                                                         rtol * float(np.max(x0)), 1.5, False)
    shift = (n - n0 - w.c * t_end).astype(np.float64)
    c_end = X[-1, :-1] - X[-1, 1:]
    return {"strain_error": float(np.max(np.abs(c_end - _at_sites(w, w.strain, shift[:-1]))) / w.strain_max),
            "velocity_error": float(np.max(np.abs(V[-1] - _at_sites(w, w.velocity, shift))) / w.velocity_max),
            "energy_drift": drift, "steps": steps, "N": N}


def waves(spec: SolitaryWaveRuns) -> dict:
    """The waves at every speed of ``spec``, the fitted exponent, the tail, the launch and Nesterenko's numbers."""
    from cradle.models import solitary as S

    ws = [S.solve(c, spec.length, spec.points) for c in spec.speeds]
    w = ws[list(spec.speeds).index(1.0)]
    vm = np.array([x.velocity_max for x in ws])
    slope = float(np.polyfit(np.log(vm), np.log(np.asarray(spec.speeds)), 1)[0])
    xt, logR = S.tail(w, spec.tail_stop)
    return {"waves": ws, "wave": w, "exponent": slope, "tail_xi": xt, "tail_log_strain": logR,
            "launch": launch(w, spec.launch_time, spec.rtol)}


def tail_slopes(xi: NDArray[np.float64], log_strain: NDArray[np.float64],
                c: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(measured, predicted) slopes of log y over one site, y = -log R: log(y(xi + 1) / y(xi)), and the tail's
    asymptotic law y(xi + 1) = p y + 2 log(p log(p) y) + 2 log c (Laplace's method on the integral form near
    s = xi, where R^(3/2) decays at the rate p log(p) y), NaN where xi + 1 is beyond the tail."""
    from cradle.models.solitary import P

    y = -log_strain
    h = float(xi[1] - xi[0])
    m = int(round(1.0 / h))
    meas = np.full(y.size, np.nan)
    meas[:-m] = np.log(y[m:] / y[:-m])
    with np.errstate(invalid="ignore", divide="ignore"):
        pred = np.log(P + (2.0 * np.log(P * math.log(P) * y) + 2.0 * math.log(c)) / y)
    return meas, pred


# ----------------------------------------------------------------- the desk toy's first impact


def impact_runs(spec: SolitaryWaveRuns, N: int, w: Wave) -> dict:
    """The first impact of the desk toy of N balls (one lifted): the Hertz chain from the impact and (nc) from the
    release on the same window after the impact, and the pulse measured on both, in (nc)'s units."""
    from cradle.integrators import integrate_lattice
    from cradle.integrators.lattice_adaptive import run_dop853_hertz_chain
    from cradle.measurements import pulse
    from cradle.models import solitary as S
    from cradle.models.desk_toy import desk_toy, desk_toy_initial

    x0, v0, s = desk_toy_initial(desk_toy(N, 1, spec.angle_deg, cradle_of(spec)))
    A = float(-x0[0])
    # (nc)'s linear pendulum brings the released ball to the line at t = pi/2 with speed A: the window covers the
    # line and three more sites at the speed of the wave of peak velocity A (faster than the pulse it makes)
    span = (N + 3) / float(S.speed_for_velocity(w, A))
    t = span * np.arange(spec.samples + 1) / spec.samples
    xs, vs = np.zeros(N), np.zeros(N)
    vs[0] = A
    X, V, _, drift, steps, _, _ = run_dop853_hertz_chain(xs, vs, t, spec.rtol, spec.rtol * A, 1.5, False)
    nc = integrate_lattice(x0, v0, np.concatenate(([0.0], 0.5 * np.pi + t)), alpha=1.5, bc="free",
                           method="dop853_numba", rtol=spec.rtol)
    tn, vn = pulse.peaks(t, V)
    tn_nc, vn_nc = pulse.peaks(t, nc.v[1:])
    speeds = pulse.local_speeds(tn)
    return {"t": t, "v": V, "scales": s, "amplitude": A, "t_peak": tn, "v_peak": vn, "speed": speeds,
            "width": pulse.widths(t, V, speeds), "v_peak_nc": vn_nc, "t_peak_nc": tn_nc,
            "drift": drift, "nc_drift": float(nc.energy_drift), "steps": steps}


# ----------------------------------------------------------------- the stored file

_C = ("c",)
_B = ("bead",)
#: the stored variables, per group: "/wave" the exact wave at c = 1 and Nesterenko's at its amplitude (the chain's
#: units: sites, unit masses and Hertz constant: dimensionless); "/speeds" the family against c; "/law" its speed
#: against v_m in the cradle, SI; "/tail" the
#: continued tail; "/nesterenko" the comparison table (string coordinate); "/impact/n<N>" the desk toy's first
#: impact of N balls, in SI
VARIABLES = {
    "/": {},
    "/wave": {
        "xi": Var(("xi",), "moving-frame coordinate xi = n - c t (sites)"),
        "strain": Var(("xi",), "bond compression R(xi) of the exact solitary wave of (sw) at c = 1"),
        "velocity": Var(("xi",), "particle velocity v(xi) = c^-1 int_{xi-1}^{xi} R^(3/2) of the exact wave at c = 1"),
        "strain_nesterenko": Var(("xi",), "Nesterenko's long-wave profile R_m cos^4(sqrt(2/5) xi) at the exact "
                                 "wave's R_m (compact: zero for |xi| > (pi/2) sqrt(5/2))"),
    },
    "/speeds": {
        "c": Var(_C, "speed c of the solitary wave (sites per unit time)"),
        "strain_max": Var(_C, "strain amplitude R_m"),
        "velocity_max": Var(_C, "particle-velocity amplitude v_m"),
        "force_max": Var(_C, "force amplitude R_m^(3/2)"),
        "residual": Var(_C, "max |c^2 R'' - (f(R(xi+1)) - 2 f(R) + f(R(xi-1)))| / max f, f = R^(3/2)"),
        "increment": Var(_C, "last relative increment of Petviashvili's iteration"),
        "iterations": Var(_C, "iterations of Petviashvili's iteration"),
        "speed_nesterenko": Var(_C, "Nesterenko's speed (16/25)^(1/5) v_m^(1/5) at the same v_m"),
    },
    "/law": {
        "v_m": Var(("v_m",), "particle-velocity amplitude of the solitary wave in the cradle", "m/s"),
        "speed_exact": Var(("v_m",), "speed of the exact solitary wave in the cradle: c D omega_0 at v_m / (X "
                           "omega_0) in the chain's units", "m/s"),
        "speed_nesterenko": Var(("v_m",), "Nesterenko's speed in the cradle at the same v_m", "m/s"),
    },
    "/tail": {
        "xi_tail": Var(("xi_tail",), "xi on the continued right tail (sites)"),
        "log_strain": Var(("xi_tail",), "natural log of R(xi), continued in real space"),
        "slope": Var(("xi_tail",), "measured log(y(xi+1)/y(xi)), y = -log R",
                     attrs=(("comment", "log(3/2) for a doubly exponential decay R ~ exp(-C (3/2)^xi)"),)),
        "slope_predicted": Var(("xi_tail",), "log(3/2 + (2 log(p log(p) y) + 2 log c)/y): the tail's asymptotic "
                               "law"),
    },
    "/nesterenko": {
        "quantity": Var(("quantity",), "compared quantity"),
        "exact": Var(("quantity",), "value for the exact solitary wave of (sw)"),
        "nesterenko": Var(("quantity",), "value of Nesterenko's long-wave solitary wave"),
    },
    "/impact": {},
    "/impact/{scene}": {
        "bead": Var(_B, "ball index, the released ball 0"),
        "t": Var(("t",), "time since the impact", "s"),
        "t_stored": Var(("t_stored",), "time since the impact of the stored velocities", "s"),
        "v": Var(("t_stored", "bead"), "velocity of each ball, Hertz chain without on-site term", "m/s"),
        "t_peak": Var(_B, "time of each ball's largest velocity (parabolic refinement)", "s"),
        "v_peak": Var(_B, "each ball's largest velocity", "m/s"),
        "speed": Var(_B, "local pulse speed 2 D / (t_{n+1} - t_{n-1})", "m/s"),
        "speed_exact": Var(_B, "speed of the exact solitary wave whose peak velocity is v_peak", "m/s"),
        "speed_nesterenko": Var(_B, "Nesterenko's speed at v_peak", "m/s"),
        "width": Var(_B, "pulse width: full width at half maximum of v_n(t) times the local speed", "m"),
        "nc_difference": Var(_B, "relative difference of v_peak between (nc) (small-angle pendulum) and the Hertz "
                             "chain alone"),
    },
}


def _impact_group(r: dict, w: Wave, D: float) -> tuple[dict, dict, dict]:
    from cradle.models import solitary as S
    from cradle.models.physical import to_si

    s: Scales = r["scales"]
    per = D / s.T                                    # m/s per site per unit time
    N = r["v"].shape[1]
    stored = slice(None, None, STORE_EVERY)
    data = {"v": to_si(r["v"][stored], "velocity", s), "t_peak": to_si(r["t_peak"], "time", s),
            "v_peak": to_si(r["v_peak"], "velocity", s), "speed": r["speed"] * per,
            "speed_exact": np.asarray(S.speed_for_velocity(w, r["v_peak"])) * per,
            "speed_nesterenko": np.asarray(S.nesterenko_speed_v(r["v_peak"])) * per,
            "width": r["width"] * D, "nc_difference": r["v_peak_nc"] / r["v_peak"] - 1.0}
    coords = {"bead": np.arange(N), "t": to_si(r["t"], "time", s), "t_stored": to_si(r["t"][stored], "time", s)}
    settled = N // 2   # the middle ball: furthest from the impact's transient and from the free end
    attrs = {"n_beads": N, "impact_speed_m_per_s": to_si(r["amplitude"], "velocity", s),
             "diameter_m": D, "hertz_drift": r["drift"], "nc_drift": r["nc_drift"], "hertz_steps": r["steps"],
             "settled_bead": settled,
             "settled_speed_m_per_s": float(data["speed"][settled]),
             "settled_speed_exact_m_per_s": float(data["speed_exact"][settled]),
             "settled_width_m": float(data["width"][settled]),
             "max_nc_difference": float(np.nanmax(np.abs(data["nc_difference"][: N - 1])))}
    return data, coords, attrs


def compute(spec: SolitaryWaveRuns, inputs: dict | None = None, log: Log | None = None) -> xr.DataTree:
    """The `solitary-wave` analysis as a tree of groups (:data:`VARIABLES`); it reads no file."""
    from cradle.data.io import make_tree
    from cradle.models import solitary as S
    from cradle.models.physical import scales

    say = log or (lambda *a: None)
    t0 = _time.perf_counter()
    r = waves(spec)
    w = r["wave"]
    ws = r["waves"]
    cr = cradle_of(spec)
    s = scales(cr)
    D = 2.0 * cr.radius
    vm = np.array([x.velocity_max for x in ws])
    meas, pred = tail_slopes(r["tail_xi"], r["tail_log_strain"], w.c)
    vel_fwhm, strain_fwhm = S.fwhm(w.xi, w.velocity), S.fwhm(w.xi, w.strain)
    nest_profile = S.nesterenko_profile(w.xi, w.strain_max)
    table = {
        "speed constant c / v_m^(1/5)": (w.c / w.velocity_max**0.2, (16.0 / 25.0) ** 0.2),
        "speed constant c / R_m^(1/4)": (w.c / w.strain_max**0.25, 2.0 / math.sqrt(5.0)),
        "v_m / (c R_m)": (w.velocity_max / (w.c * w.strain_max), 1.0),
        "strain FWHM (sites)": (strain_fwhm, S.fwhm(w.xi, nest_profile)),
        "velocity FWHM (sites)": (vel_fwhm, S.fwhm(w.xi, nest_profile)),
        "width where R > 1e-3 R_m (sites)": (_support(w.xi, w.strain, 1e-3),
                                              _support(w.xi, nest_profile, 1e-3)),
    }
    say(f"solitary-wave: c = 1: R_m = {w.strain_max:.12g}, v_m = {w.velocity_max:.12g}; exponent "
        f"{r['exponent']:.12f}; residual {S.residual(w):.2g}; launch error {r['launch']['strain_error']:.2g}")
    groups: dict = {
        "/": ({}, {}),
        "/wave": ({"strain": w.strain, "velocity": w.velocity, "strain_nesterenko": nest_profile}, {"xi": w.xi}),
        "/speeds": ({"strain_max": [x.strain_max for x in ws], "velocity_max": vm,
                     "force_max": [x.force_max for x in ws], "residual": [S.residual(x) for x in ws],
                     "increment": [x.increment for x in ws], "iterations": [x.iterations for x in ws],
                     "speed_nesterenko": S.nesterenko_speed_v(vm)}, {"c": list(spec.speeds)}),
        "/law": ({"speed_exact": np.asarray(S.speed_for_velocity(w, LAW_VELOCITIES / s.V)) * D / s.T,
                  "speed_nesterenko": np.asarray(S.nesterenko_speed_v(LAW_VELOCITIES / s.V)) * D / s.T},
                 {"v_m": LAW_VELOCITIES}),
        "/tail": ({"log_strain": r["tail_log_strain"], "slope": meas, "slope_predicted": pred},
                  {"xi_tail": r["tail_xi"]}),
        "/nesterenko": ({"exact": [v[0] for v in table.values()], "nesterenko": [v[1] for v in table.values()]},
                        {"quantity": np.array(list(table), dtype=object)}),
        "/impact": ({}, {}),
    }
    variables = {k: v for k, v in VARIABLES.items() if "{" not in k}
    group_attrs = {}
    for N in spec.chains:
        ir = impact_runs(spec, N, w)
        data, coords, attrs = _impact_group(ir, w, D)
        path = f"/impact/n{N}"
        groups[path], variables[path], group_attrs[path] = (data, coords), VARIABLES["/impact/{scene}"], attrs
        say(f"solitary-wave: impact n{N}: settled speed {attrs['settled_speed_m_per_s']:.6g} m/s against "
            f"{attrs['settled_speed_exact_m_per_s']:.6g} m/s (exact wave at its v_peak); (nc) - Hertz "
            f"{attrs['max_nc_difference']:.2g}")
    far = r["tail_xi"] <= r["tail_xi"][-1] - 1.0
    attrs = {
        "impacts": ", ".join(f"n{N}" for N in spec.chains),
        "cradle": f"{cr.material} balls of radius {cr.radius:g} m on strings of {cr.length:g} m (g = {cr.g:g} m/s^2)",
        "angle_deg": spec.angle_deg,
        "speed_exponent": r["exponent"], "speed_exponent_expected": 0.2,
        "speed_constant_si": w.c / w.velocity_max**0.2 * D / s.T / s.V**0.2,
        "speed_constant_si_units": "m^(4/5) s^(-4/5): speed = speed_constant_si v_m^(1/5), v_m in m/s",
        "residual_max": float(max(S.residual(x) for x in ws)),
        "launch_strain_error": r["launch"]["strain_error"], "launch_velocity_error": r["launch"]["velocity_error"],
        "launch_time": spec.launch_time, "launch_energy_drift": r["launch"]["energy_drift"],
        "nesterenko_total_width_sites": S.NESTERENKO_WIDTH, "tail_start": S.tail_start(w),
        "tail_slope_far": float(meas[far][-1]), "tail_slope_expected": math.log(1.5),
        "solver": f"Petviashvili's iteration of R = c^-2 Lambda * R^(3/2), gamma = 3, periodic box of "
                  f"{spec.length:g} sites, {spec.points} points per site; tail marched in real space on log R",
        "hertz_chain": "the lattice system of (ncimperfect) with touching homogeneous beads and the on-site slot's "
                       "absent unit (integrators/terms/onsite_none.py): W = 0, no on-site force",
        "nesterenko_source": "V. F. Nesterenko, J. Appl. Mech. Tech. Phys. 24 (1983) 733; Dynamics of Heterogeneous "
                             "Materials (Springer, 2001), section 1.3",
        "tail_source": "J. M. English and R. L. Pego, Proc. Amer. Math. Soc. 133 (2005); K. Ahnert and A. Pikovsky, "
                       "Phys. Rev. E 79 (2009) 026209",
        "wall_time_s": _time.perf_counter() - t0,
    }
    tree = make_tree(groups, variables, attrs=attrs, params=plain(spec),
                     title="The solitary wave of the Hertz chain and the pulse of a desk toy's first impact")
    for path, a in group_attrs.items():
        tree[path].attrs = a
    return tree


def _support(xi: NDArray[np.float64], y: NDArray[np.float64], fraction: float) -> float:
    """The length of xi where y >= fraction max y (sites)."""
    h = float(xi[1] - xi[0])
    return float(np.count_nonzero(y >= fraction * np.max(y)) * h)


ANALYSIS = Analysis(
    name="solitary-wave", spec=SolitaryWaveRuns, compute=compute, variables=VARIABLES,
    title="The solitary wave of the Hertz chain and the pulse of a desk toy's first impact")
