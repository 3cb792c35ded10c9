"""A desk toy watched for a minute (issue 38): from the break-up of the line to the balls swinging in phase.

A desk toy (a :class:`cradle.models.physical.Cradle`, default 1 cm steel balls on 10 cm strings) of ``N`` balls,
the ``lifted`` balls at the left end released at rest from ``angle_deg`` (:mod:`cradle.models.desk_toy`), run for
``duration`` seconds of real time as the damped cradle (ncdamped) (:mod:`cradle.models.damping`): Hertz contacts
with Kuwabara-Kono viscoelastic damping, the SI force between two balls k (delta^(3/2) + A delta^(1/2) delta')
(A in seconds; some sources write k delta^(3/2) + (3/2) A' k delta^(1/2) delta', A = (3/2) A'), and linear on-site
damping standing for the drag of air (a rate in 1/s). Integrated by ``dop853_numba`` at ``rtol`` (atol = rtol times
the amplitude), free ends, stored ``samples`` times per swing period 2 pi / omega_0.

The contact constant. Given as ``kk_constant`` (A in seconds: a measured or fitted value plugs in here), or, by
default, from a restitution coefficient e at the impact speed ``restitution_speed`` through the two-ball collision
of (ncdamped) itself (:func:`cradle.models.restitution.scaled_for`: 1 - e = f(A kappa^(2/5) v^(1/5)),
kappa = 2 k / m). No measured e of the balls was at hand (:mod:`cradle.models.restitution_data` holds none):
``restitution`` lists the two values of ``STEEL_ASSUMED.bracket`` around the assumed 0.95 of the desk-toy analysis,
and every run is made under each.

The drag. No source gives a desk toy's linear drag rate: by default the two rates of
:func:`cradle.models.air_drag.bracketing_rates` (Stokes' drag, a lower bound; the quadratic drag at the release
speed, an upper bound), every run made under each; ``drag_rates`` gives others.

For each chain length N, lifted count and (contact, drag) pair: the run of (ncdamped) (its energy H and the
dissipated energy D, integrated as its own quantity: H + D = H(0) to the integrator's tolerance), and the same run
at rtol / 10 (the convergence check: the in-phase times and the energy at the end); for each contact, the
hard-sphere cradle (:mod:`cradle.models.hard_spheres`), without drag, twice: with the constant e the contact has at
``restitution_speed``, and with the contact's own law e(u) of the approach speed (:func:`restitution_law`: the
Kuwabara-Kono e rises as the impact speed falls, 1 - e ~ u^(1/5), so a constant e overstates the losses of the
slow late impacts). Against the second, what differs is the collisions' duration and the many-ball contacts of
(ncdamped) alone. Measured on each (:mod:`cradle.measurements.
desk_toy_minute` and :mod:`cradle.measurements.desk_toy`): the phase coherence R(t) and the centre-of-mass share
S(t) with the time each settles above each of its thresholds, the balls out and each ball's amplitude at every
out-swing k pi / omega_0, and the one-out-one-out share f_k with how long it holds.

Everything is stored in SI (m, s, J) with string coordinates naming the cases; the cradle's scales are attributes of
each group (``X_m``, ``T_s``, ``E_J``), so a reader gets (nc)'s values back by dividing.
"""
from __future__ import annotations

import functools
import time as _time
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.protocol import Analysis
from cradle.data.variables import Var
from cradle.models import restitution as rs
from cradle.models.air_drag import AIR_DENSITY, AIR_VISCOSITY
from cradle.models.physical import Cradle
from cradle.models.restitution_data import STEEL_ASSUMED
from cradle.specs.declare import declared, param, plain
from cradle.specs.values import RTOL_FLOOR

if TYPE_CHECKING:
    from collections.abc import Callable

    import xarray as xr
    from numpy.typing import NDArray

    from cradle.analyses.protocol import Log
    from cradle.integrators.lattice_solver import LatticeSolution
    from cradle.models.damping import Damping
    from cradle.models.physical import Scales
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors

#: the largest chain of this analysis: a desk toy has 3 to 10 balls
MAX_CHAIN = 20
#: the tolerance of the convergence run is rtol / CONVERGENCE_FACTOR
CONVERGENCE_FACTOR = 10.0

#: the cradle of a spec that gives none: steel balls (AISI 52100, cradle.models.physical.MATERIALS) of radius 1 cm on
#: 10 cm strings, as the desk-toy analysis
DEFAULT_CRADLE = Cradle(material="steel", radius=0.01, length=0.1)

_LIFTED = {"type": "integer", "minimum": 1, "maximum": MAX_CHAIN - 1, "description": "Balls lifted together."}
_CHAIN = {"type": "integer", "minimum": 2, "maximum": MAX_CHAIN, "description": "Balls in the line."}
_E = {"type": "number", "exclusiveMinimum": 0, "exclusiveMaximum": 1,
      "description": "Restitution coefficient e in (0, 1) at restitution_speed."}
_A = {"type": "number", "exclusiveMinimum": 0, "maximum": 1e-3,
      "description": "Kuwabara-Kono constant A (s) of the force k (delta^(3/2) + A delta^(1/2) delta')."}
_RATE = {"type": "number", "minimum": 0, "maximum": 10, "description": "A linear drag rate (1/s)."}
_LENGTH = {"type": "number", "minimum": 0.01, "maximum": 10, "description": "A string length L (m)."}
_RADIUS = {"type": "number", "minimum": 1e-3, "maximum": 0.1, "description": "A ball radius R (m)."}
_UNIT = {"type": "number", "exclusiveMinimum": 0, "exclusiveMaximum": 1, "description": "A threshold in (0, 1)."}


@declared(doc="A desk toy watched for a minute (issue 38): N balls, 1, 2 or 3 lifted and released, Hertz contacts "
              "with Kuwabara-Kono damping and linear air drag, each under two bracketing restitutions and two "
              "bracketing drag rates, against the hard-sphere cradle: energy and dissipation, balls out per swing, "
              "time to in-phase motion under two order parameters, convergence in the tolerance -> "
              "results/desk-toy-minute/desk-toy-minute.nc and results/figures/desk-toy-minute.{pdf,png}.")
class DeskToyMinute:
    cradle: Cradle = param(None, "The spheres and their strings (cradle.models.physical.Cradle; a pendulum length "
                           "is needed). Absent: steel balls of radius 1 cm on 10 cm strings (DEFAULT_CRADLE).")
    angle_deg: float = param(20.0, "Angle of the lifted balls' strings from the vertical (degrees); in (0, 90).",
                             exclusiveMinimum=0, exclusiveMaximum=90)
    chains: list[int] = param([3, 5, 7, 10], "Chain lengths N (balls in the line).", minItems=1, maxItems=8,
                              items=_CHAIN, reduced=[5])
    lifted: list[int] = param([1, 2, 3], "Lifted counts: the first `lifted` balls are released together (each "
                              "< the longest chain; a chain runs the counts below its length).", minItems=1,
                              maxItems=6, items=_LIFTED, reduced=[1, 2])
    duration: float = param(60.0, "Real time of each run (s).", exclusiveMinimum=0, maximum=600, reduced=4.0)
    samples: int = param(16, "Stored times per swing period 2 pi / omega_0 (the out-swings k pi / omega_0 among "
                         "them: even).", minimum=8, maximum=256, multipleOf=2)
    restitution: list[float] = param(list(STEEL_ASSUMED.bracket),
                                     "Restitution coefficients e at restitution_speed from which the "
                                     "Kuwabara-Kono constant A is found (cradle.models.restitution.scaled_for): "
                                     "two values bracketing the ASSUMED 0.95 of the desk-toy analysis (no measured "
                                     "value was at hand); ignored when kk_constant is given.", minItems=1,
                                     maxItems=4, items=_E)
    restitution_speed: float = param(STEEL_ASSUMED.v,
                                     "Impact speed (m/s) at which the restitution coefficients hold, and at "
                                     "which the hard spheres' constant e is taken.", exclusiveMinimum=0,
                                     maximum=100)
    kk_constant: list[float] | None = param(None, "Kuwabara-Kono constants A (s) of the force k (delta^(3/2) + "
                                            "A delta^(1/2) delta') (a measured or fitted value); absent: from "
                                            "restitution.", minItems=1, maxItems=4, items=_A)
    drag_rates: list[float] | None = param(None, "Linear on-site damping rates (1/s) standing for the drag of air; "
                                           "absent: Stokes' drag (lower bound) and the quadratic drag at the "
                                           "release speed (upper bound) of cradle.models.air_drag.", minItems=1,
                                           maxItems=4, items=_RATE)
    air_density: float = param(AIR_DENSITY, "Density of air (kg/m^3): ISO 2533:1975 Standard Atmosphere, sea "
                               "level.", exclusiveMinimum=0, maximum=100)
    air_viscosity: float = param(AIR_VISCOSITY, "Dynamic viscosity of air (Pa s): ISO 2533:1975 Standard "
                                 "Atmosphere, sea level (15 C).", exclusiveMinimum=0, maximum=1)
    rtol: float = param(1e-12, "Relative tolerance of the runs (dop853_numba; atol = rtol times the amplitude); "
                        "the convergence run takes rtol / 10.", minimum=RTOL_FLOOR * CONVERGENCE_FACTOR,
                        maximum=1e-6)
    phase_thresholds: list[float] = param([0.99, 0.999], "Thresholds of the phase coherence R: in phase once R "
                                          "stays above.", minItems=1, maxItems=4, items=_UNIT)
    share_thresholds: list[float] = param([0.9, 0.99], "Thresholds of the centre-of-mass share S: in phase once S "
                                          "stays above.", minItems=1, maxItems=4, items=_UNIT)
    pattern_thresholds: list[float] = param([0.9, 0.5], "Thresholds of the one-out-one-out share f_k "
                                            "(cradle.measurements.desk_toy).", minItems=1, maxItems=4, items=_UNIT)
    trend_lengths: list[float] = param([0.05, 0.2], "String lengths L (m) of the trend runs (5 balls, 1 lifted, the "
                                       "first contact's A, Stokes drag), beside the cradle's own.", minItems=0,
                                       maxItems=6, items=_LENGTH, reduced=[])
    trend_radii: list[float] = param([0.005, 0.02], "Ball radii R (m) of the trend runs, beside the cradle's own.",
                                     minItems=0, maxItems=6, items=_RADIUS, reduced=[])
    ensemble: int = param(12, "Members of the ensemble of each (ncdamped) desk toy at the first drag rate: the "
                          "lifted balls' release displacement times 1 + ensemble_spread z, z seeded standard "
                          "normal, one per member (the lift perturbed, the lifted balls still touching); each "
                          "member run at rtol and rtol / 10 (0: none).", minimum=0, maximum=64,
                          reduced=3)
    ensemble_spread: float = param(1e-6, "Relative spread of the ensemble's release displacements: far below any "
                                   "desk toy's precision, far above the integrator's error.", exclusiveMinimum=0,
                                   maximum=1e-2)
    ensemble_seed: int = param(38, "Seed of the ensemble's perturbations (numpy default_rng).", minimum=0)
    separation_band: list[float] = param([100.0, 1e-3], "The growth rate of the separation between a run and its "
                                         "rerun at rtol / 10 is fitted where it grows from the first value times "
                                         "rtol to the second (both relative to the release amplitude): above the "
                                         "integrator's error, below the swing.", minItems=2, maxItems=2,
                                         items={"type": "number", "exclusiveMinimum": 0, "maximum": 1e12,
                                                "description": "A bound of the fitted band."})
    out_fraction: float = param(0.5, "A ball is out at an out-swing when its amplitude is at least this share of "
                                "the largest.", exclusiveMinimum=0, maximum=1)

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Each form: a pendulum cradle, every lifted count below the longest chain, no repeated value."""
        if self.cradle is not None and self.cradle.length is None:
            out.add(where + ["cradle"], "a desk toy needs the pendulum length (a stiff oscillator has no angle)")
        longest = max(self.chains)
        for i, k in enumerate(self.lifted):
            if k >= longest:
                out.add(where + ["lifted", i], f"must be < the longest chain ({longest}): one ball at least stays "
                                               "in the line (a chain of N <= lifted runs without it)", k)
        low, high = self.separation_band
        if not low * self.rtol < high:
            out.add(where + ["separation_band"], f"must have first * rtol < second ({low:g} * {self.rtol:g} >= "
                                                 f"{high:g}): the band is empty", self.separation_band)
        for key in ("chains", "lifted", "restitution", "kk_constant", "drag_rates", "phase_thresholds",
                    "share_thresholds", "pattern_thresholds", "trend_lengths", "trend_radii"):
            values = getattr(self, key)
            if values is not None and len(set(values)) != len(values):
                out.add(where + [key], "lists a value twice", values)


# ----------------------------------------------------------------- the physical constants of a spec


def cradle_of(spec: DeskToyMinute) -> Cradle:
    """The spec's cradle, or :data:`DEFAULT_CRADLE` when it gives none."""
    return spec.cradle if spec.cradle is not None else DEFAULT_CRADLE


def _b(A_seconds: float, speed: float, s: Scales) -> float:
    """b = A kappa^(2/5) v^(1/5) of two equal balls (reduced mass m/2) at impact speed ``speed`` (m/s)."""
    return float(rs.scaled_constant(A_seconds, speed, s.k, s.m / 2.0))


@functools.cache   # a root of an ODE's solution: found once per value
def restitution_of(A_seconds: float, speed: float, s: Scales) -> float:
    """e of the two-ball collision of (ncdamped) at impact speed ``speed`` (m/s) for the Kuwabara-Kono A (s)."""
    return rs.restitution(_b(A_seconds, speed, s))


@functools.cache   # a root of an ODE's solution: found once per value
def kk_of(restitution: float, speed: float, s: Scales) -> float:
    """The Kuwabara-Kono A (s) whose two-ball collision has restitution e at impact speed ``speed`` (m/s)."""
    return rs.scaled_for(restitution) / _b(1.0, speed, s)


#: the scaled Kuwabara-Kono constants b of the tabulated two-ball restitution loss (:func:`restitution_law`)
_B_TABLE = np.logspace(-8.0, 0.0, 65)


@functools.cache
def _loss_table() -> NDArray[np.float64]:
    return np.array([1.0 - rs.restitution(float(b)) for b in _B_TABLE])


def restitution_law(A_seconds: float, s: Scales) -> Callable[[float], float]:
    """e(u) of the two-ball collision of (ncdamped) for the Kuwabara-Kono A (s), u the approach speed in (nc)'s
    units: 1 - e = f(b), b = A kappa^(2/5) (u V)^(1/5), f tabulated by :func:`cradle.models.restitution.
    restitution` on 8 points a decade of b in [1e-8, 1] and interpolated in log-log (f(b) = C1 b + O(b^2)
    below: linear there)."""
    log_b, log_f = np.log(_B_TABLE), np.log(_loss_table())
    scale = _b(A_seconds, s.V, s)
    slope = float(_loss_table()[0] / _B_TABLE[0])

    def law(u: float) -> float:
        b = scale * u**0.2
        if b <= _B_TABLE[0]:
            return 1.0 - slope * b
        return 1.0 - float(np.exp(np.interp(np.log(b), log_b, log_f)))

    return law


def contacts(spec: DeskToyMinute) -> list[tuple[float, float]]:
    """(e at restitution_speed, A in seconds) of every contact of the spec: from kk_constant when given, else from
    restitution."""
    from cradle.models.physical import scales

    s = scales(cradle_of(spec))
    v = spec.restitution_speed
    if spec.kk_constant is not None:
        return [(restitution_of(A, v, s), float(A)) for A in spec.kk_constant]
    return [(float(e), kk_of(e, v, s)) for e in spec.restitution]


def drag_rates(spec: DeskToyMinute) -> list[float]:
    """The linear drag rates (1/s) of the runs: the spec's, or the bracketing pair of cradle.models.air_drag."""
    from cradle.models.air_drag import bracketing_rates

    if spec.drag_rates is not None:
        return [float(r) for r in spec.drag_rates]
    return list(bracketing_rates(cradle_of(spec), spec.angle_deg, spec.air_density, spec.air_viscosity))


def damping_of(A_seconds: float, rate: float, s: Scales) -> Damping:
    """(ncdamped)'s damping in (nc)'s units for the SI contact constant A (s) and drag rate (1/s)."""
    from cradle.models.damping import Damping, contact_eta, onsite_gamma

    return Damping(onsite=onsite_gamma(rate, s.omega0), contact=contact_eta(A_seconds, s.omega0))


# ----------------------------------------------------------------- the runs


def label(n_beads: int, lifted: int) -> str:
    """The group name of one desk toy: ``n5-lifted1``."""
    return f"n{n_beads}-lifted{lifted}"


def time_grid(duration_nc: float, samples: int) -> NDArray[np.float64]:
    """t_j = 2 pi j / samples up to ``duration_nc`` ((nc)'s units): the stored times, every k pi among them."""
    return 2.0 * np.pi * np.arange(int(np.floor(duration_nc * samples / (2.0 * np.pi) + 1e-9)) + 1) / samples


def minute_run(x0: NDArray[np.float64], t: NDArray[np.float64], damping: Damping, rtol: float) -> LatticeSolution:
    """(ncdamped) from the released desk toy x0 (at rest) stored at ``t``: dop853_numba, free ends."""
    from cradle.integrators import integrate_lattice

    return integrate_lattice(x0, np.zeros_like(x0), t, alpha=1.5, bc="free", method="dop853_numba", rtol=rtol,
                             damping=damping)


def measure(spec: DeskToyMinute, t: NDArray[np.float64], x: NDArray[np.float64], v: NDArray[np.float64],
            lifted: int) -> dict:
    """The measurements of one run ((nc)'s units; module docstring)."""
    from cradle.measurements import desk_toy as dm, desk_toy_minute as mm

    R = mm.phase_coherence(x, v)
    S = mm.com_share(x, v)
    idx, _ = mm.swing_indices(t)
    _, f = dm.out_fractions(t, x, v, lifted)
    return {"phase_coherence": R, "com_share": S,
            "inphase_phase": [mm.settle_time(t, R, th) for th in spec.phase_thresholds],
            "inphase_share": [mm.settle_time(t, S, th) for th in spec.share_thresholds],
            "balls_out": mm.balls_out(x[idx], v[idx], spec.out_fraction),
            "amplitude": np.abs(mm.analytic(x[idx], v[idx])), "share": f,
            "hold_swings": [dm.pattern_hold(t, x, v, lifted, th).swings for th in spec.pattern_thresholds]}


def warm_up() -> None:
    """Compile (or load) the damped kernel once, so that the timed runs time the integration alone."""
    from cradle.models.damping import Damping

    minute_run(np.array([-1.0, 0.0]), np.array([0.0, 1.0]), Damping(onsite=1e-3, contact=1e-3), 1e-8)


def _ensemble_keys(spec: DeskToyMinute) -> dict[str, tuple[int, ...]]:
    M, P, S = spec.ensemble, len(spec.phase_thresholds), len(spec.share_thresholds)
    return {"member_phase": (M, 2, P), "member_share": (M, 2, S), "mean_share_time": (2, S)}


def no_ensemble(spec: DeskToyMinute) -> dict:
    """The ensemble's entries of a case without one: NaN."""
    return {k: np.full(shape, np.nan) for k, shape in _ensemble_keys(spec).items()}


def ensemble(spec: DeskToyMinute, x0: NDArray[np.float64], t: NDArray[np.float64], damping: Damping,
             lifted: int) -> dict:
    """The ensemble of one desk toy: ``spec.ensemble`` members, the lifted balls' release displacement times
    1 + ensemble_spread z_m (z_m seeded standard normal, the same for every lifted ball: the lift angle
    perturbed, the lifted balls still touching), each run at rtol and rtol / 10.
    ``member_phase`` (member, tolerance, threshold) and ``member_share``: each member's time to in-phase motion
    under R and S; ``mean_share_time`` (tolerance, threshold): when the ensemble's mean S(t) settles above each
    threshold ((nc)'s units; tolerance 0 is rtol, 1 is rtol / 10)."""
    from cradle.measurements import desk_toy_minute as mm

    out = no_ensemble(spec)
    if spec.ensemble == 0:
        return out
    z = np.random.default_rng(spec.ensemble_seed).standard_normal(spec.ensemble)
    mean_S = np.zeros((2, t.size))
    for m in range(spec.ensemble):
        x = x0.copy()
        x[:lifted] *= 1.0 + spec.ensemble_spread * z[m]
        for k, rtol in enumerate((spec.rtol, spec.rtol / CONVERGENCE_FACTOR)):
            run = minute_run(x, t, damping, rtol)
            R, S = mm.phase_coherence(run.x, run.v), mm.com_share(run.x, run.v)
            out["member_phase"][m, k] = [mm.settle_time(t, R, th) for th in spec.phase_thresholds]
            out["member_share"][m, k] = [mm.settle_time(t, S, th) for th in spec.share_thresholds]
            mean_S[k] += S / spec.ensemble
    out["mean_share_time"] = np.array([[mm.settle_time(t, mean_S[k], th) for th in spec.share_thresholds]
                                       for k in range(2)])
    return out


def desk_toy_minute(spec: DeskToyMinute, n_beads: int, lifted: int) -> dict:
    """The runs and measurements of one desk toy in (nc)'s units: ``cases`` (one dict per case: the (ncdamped)
    runs of every contact and drag, then the hard spheres of every contact), the time grid and the scales."""
    from cradle.measurements import desk_toy_minute as mm
    from cradle.models import desk_toy as dt
    from cradle.models.hard_spheres import hard_sphere_run

    toy = dt.desk_toy(n_beads, lifted, spec.angle_deg, cradle_of(spec))
    x0, v0, s = dt.desk_toy_initial(toy)
    t = time_grid(spec.duration / s.T, spec.samples)
    cases = []
    amp = float(-x0[0])
    low, high = spec.separation_band
    for e, A in contacts(spec):
        for j, rate in enumerate(drag_rates(spec)):
            damping = damping_of(A, rate, s)
            c0 = _time.process_time()
            run = minute_run(x0, t, damping, spec.rtol)
            cpu = _time.process_time() - c0
            tight = minute_run(x0, t, damping, spec.rtol / CONVERGENCE_FACTOR)
            case = {"name": f"nc e={e:g} drag={rate:.3g}/s", "restitution": e, "kk_A": A, "drag": rate,
                    "energy": run.energy, "dissipated": run.dissipated, "steps": int(run.n_steps), "cpu": cpu,
                    "balance": float(np.max(np.abs(run.energy + run.dissipated - run.energy[0])) / run.energy[0])}
            case.update(measure(spec, t, run.x, run.v, lifted))
            m2 = measure(spec, t, tight.x, tight.v, lifted)
            sep = mm.separation(run.x, run.v, tight.x, tight.v)
            case.update({"tight_inphase_phase": m2["inphase_phase"], "tight_inphase_share": m2["inphase_share"],
                         "tight_energy_end": float(tight.energy[-1]), "separation": sep,
                         "separation_rate": mm.growth_rate(t, sep / amp, low * spec.rtol, high)})
            case.update(ensemble(spec, x0, t, damping, lifted) if j == 0 else no_ensemble(spec))
            cases.append(case)
    for (e, A), law in [(c, w) for c in contacts(spec) for w in (c[0], restitution_law(c[1], s))]:
        c0 = _time.process_time()
        hs = hard_sphere_run(x0, v0, t, restitution=law)
        cpu = _time.process_time() - c0
        name = f"hard e={e:g}" if isinstance(law, float) else f"hard e(v) of A={A:.3g}s"
        case = {"name": name, "restitution": e, "kk_A": A, "drag": 0.0, "energy": hs.energy,
                "separation": np.full(t.size, np.nan), "separation_rate": np.nan, **no_ensemble(spec),
                "dissipated": hs.dissipated, "steps": int(hs.collision_t.size), "cpu": cpu,
                "balance": float(np.max(np.abs(hs.energy + hs.dissipated - hs.energy[0])) / hs.energy[0]),
                "tight_inphase_phase": [np.nan] * len(spec.phase_thresholds),
                "tight_inphase_share": [np.nan] * len(spec.share_thresholds), "tight_energy_end": np.nan}
        case.update(measure(spec, t, hs.x, hs.v, lifted))
        cases.append(case)
    return {"t": t, "cases": cases, "scales": s, "amplitude": float(-x0[0])}


def trend_cradles(spec: DeskToyMinute) -> list[tuple[str, Cradle]]:
    """(name, cradle) of the trend runs: the spec's cradle, then each of trend_lengths and trend_radii in its place."""
    import dataclasses

    c = cradle_of(spec)
    out = [(f"L={c.length:g} m, R={c.radius:g} m", c)]
    out += [(f"L={L:g} m, R={c.radius:g} m", dataclasses.replace(c, length=float(L))) for L in spec.trend_lengths]
    out += [(f"L={c.length:g} m, R={R:g} m", dataclasses.replace(c, radius=float(R))) for R in spec.trend_radii]
    return out


def trends(spec: DeskToyMinute) -> dict:
    """Lee & Hong's trends against the string length and the ball radius: the 5-ball cradle, one lifted, the first
    contact's Kuwabara-Kono A (a material constant: the same for every size) and Stokes' drag of each cradle (or the
    first of drag_rates), over ``duration``; its in-phase times, e at the reference speed and final energy share."""
    from cradle.measurements import desk_toy_minute as mm
    from cradle.models import desk_toy as dt
    from cradle.models.air_drag import stokes_rate
    from cradle.models.physical import scales, to_si

    A = contacts(spec)[0][1]
    rows: dict[str, list] = {k: [] for k in ("name", "length", "radius", "restitution", "drag", "phase", "share",
                                             "energy_share")}
    for name, c in trend_cradles(spec):
        s = scales(c)
        rate = float(spec.drag_rates[0]) if spec.drag_rates is not None else stokes_rate(c, spec.air_viscosity)
        x0, _, _ = dt.desk_toy_initial(dt.desk_toy(5, 1, spec.angle_deg, c))
        t = time_grid(spec.duration / s.T, spec.samples)
        run = minute_run(x0, t, damping_of(A, rate, s), spec.rtol)
        R, S = mm.phase_coherence(run.x, run.v), mm.com_share(run.x, run.v)
        rows["name"].append(name)
        rows["length"].append(c.length)
        rows["radius"].append(c.radius)
        rows["restitution"].append(restitution_of(A, spec.restitution_speed, s))
        rows["drag"].append(rate)
        rows["phase"].append([to_si(mm.settle_time(t, R, th), "time", s) for th in spec.phase_thresholds])
        rows["share"].append([to_si(mm.settle_time(t, S, th), "time", s) for th in spec.share_thresholds])
        rows["energy_share"].append(float(run.energy[-1] / run.energy[0]))
    return rows


# ----------------------------------------------------------------- the stored file

_C = ("case",)
#: the variables of one desk toy's group (``/n5-lifted1``), in SI: (nc)'s values times the scales in the group's
#: attributes X_m, T_s, E_J
MINUTE_VARIABLES: dict[str, Var] = {
    "case": Var(_C, "case: (ncdamped) at one contact constant and one drag rate, or the hard-sphere cradle at one "
                "constant restitution or with the contact's law e(approach speed)"),
    "t": Var(("t",), "time since the release", "s"),
    "n": Var(("n",), "ball index, the lifted balls first"),
    "swing": Var(("swing",), "out-swing k = 1, 2, ...: the largest swings of the ideal cradle at t = k pi / omega_0"),
    "phase_threshold": Var(("phase_threshold",), "threshold of the phase coherence R"),
    "share_threshold": Var(("share_threshold",), "threshold of the centre-of-mass share S"),
    "pattern_threshold": Var(("pattern_threshold",), "threshold of the one-out-one-out share f_k"),
    "restitution": Var(_C, "restitution coefficient e of two balls at the reference impact speed",
                       attrs=(("comment", "(ncdamped) and hard spheres e(v): of the Kuwabara-Kono A; hard spheres "
                                          "e: their constant e"),)),
    "kk_A": Var(_C, "Kuwabara-Kono constant A of the contact force k (delta^(3/2) + A delta^(1/2) delta')", "s"),
    "drag_rate": Var(_C, "linear on-site damping rate standing for the drag of air (0: none)", "1/s"),
    "energy": Var(_C + ("t",), "energy of the cradle: on-site (small-angle pendulum) plus Hertz contact energy "
                  "(ham)", "J"),
    "dissipated": Var(_C + ("t",), "energy dissipated since the release (contact and drag damping; collisions "
                      "with e < 1)", "J",
                      attrs=(("comment", "integrated as its own quantity: energy + dissipated is conserved"),)),
    "energy_balance": Var(_C, "max over the run of |energy + dissipated - energy(0)| / energy(0)"),
    "phase_coherence": Var(_C + ("t",), "phase coherence R = |sum_n z_n / |z_n|| / N, z_n = x_n - i v_n / omega_0"),
    "com_share": Var(_C + ("t",), "share S of the on-site energy in the centre-of-mass swing mode"),
    "inphase_time_phase": Var(_C + ("phase_threshold",), "time after which R stays >= the threshold", "s",
                              attrs=(("comment", "NaN: below at the end of the run"),)),
    "inphase_time_share": Var(_C + ("share_threshold",), "time after which S stays >= the threshold", "s",
                              attrs=(("comment", "NaN: below at the end of the run"),)),
    "tight_inphase_time_phase": Var(_C + ("phase_threshold",), "inphase_time_phase of the run at rtol / 10", "s",
                                    attrs=(("comment", "NaN for the hard spheres (event-driven, exact)"),)),
    "tight_inphase_time_share": Var(_C + ("share_threshold",), "inphase_time_share of the run at rtol / 10", "s",
                                    attrs=(("comment", "NaN for the hard spheres (event-driven, exact)"),)),
    "tight_energy_end": Var(_C, "energy at the end of the run at rtol / 10", "J"),
    "separation": Var(_C + ("t",), "distance between the run and its rerun at rtol / 10, sqrt(sum_n (x_n - x'_n)^2 "
                      "+ ((v_n - v'_n) / omega_0)^2)", "m",
                      attrs=(("comment", "NaN for the hard spheres (event-driven, exact)"),)),
    "separation_rate": Var(_C, "exponential growth rate of the separation over separation_band (a Lyapunov "
                           "exponent's estimate)", "1/s", attrs=(("comment", "NaN: not fitted"),)),
    "member": Var(("member",), "ensemble member: the lifted balls' release displacement times 1 + "
                  "ensemble_spread z, z seeded standard normal (the lifted balls still touching)"),
    "tolerance": Var(("tolerance",), "relative tolerance of the ensemble's runs: rtol, then rtol / 10"),
    "member_inphase_time_phase": Var(_C + ("member", "tolerance", "phase_threshold"), "time after which R stays "
                                     ">= the threshold, for each ensemble member", "s",
                                     attrs=(("comment", "NaN: below at the end, or no ensemble for this case (the "
                                                        "ensemble runs at the first drag rate only)"),)),
    "member_inphase_time_share": Var(_C + ("member", "tolerance", "share_threshold"), "time after which S stays "
                                     ">= the threshold, for each ensemble member", "s",
                                     attrs=(("comment", "NaN: below at the end, or no ensemble for this case"),)),
    "ensemble_inphase_time_share": Var(_C + ("tolerance", "share_threshold"), "time after which the ensemble's "
                                       "mean S stays >= the threshold", "s",
                                       attrs=(("comment", "NaN: below at the end, or no ensemble for this case"),)),
    "swing_time": Var(("swing",), "time k pi / omega_0 of out-swing k", "s"),
    "balls_out": Var(_C + ("swing",), "balls whose swing amplitude is at least out_fraction of the largest, at "
                     "out-swing k"),
    "amplitude": Var(_C + ("swing", "n"), "swing amplitude |x_n - i v_n / omega_0| of each ball at out-swing k", "m"),
    "share": Var(_C + ("swing",), "share f_k of the energy carried by the `lifted` outermost balls (far end for k "
                 "odd, release end for k even) at out-swing k"),
    "hold_swings": Var(_C + ("pattern_threshold",), "out-swings in a row from the first with f_k >= threshold"),
    "steps": Var(_C, "integrator steps ((ncdamped)) or collisions (hard spheres) of the run"),
    "cpu_time": Var(_C, "CPU time of the run (after compilation; the convergence run not included)", "s"),
}

_T = ("trend",)
#: the variables of the group ``/trends`` (Lee & Hong's trends against the string length and the ball radius)
TREND_VARIABLES: dict[str, Var] = {
    "trend": Var(_T, "cradle of a trend run: its string length L and ball radius R (5 balls, 1 lifted)"),
    "phase_threshold": MINUTE_VARIABLES["phase_threshold"],
    "share_threshold": MINUTE_VARIABLES["share_threshold"],
    "length": Var(_T, "string length L, pivot to the ball's centre", "m"),
    "radius": Var(_T, "ball radius R", "m"),
    "restitution": Var(_T, "restitution e of two balls at the reference impact speed, for the first contact's "
                       "Kuwabara-Kono A (the same A for every size)"),
    "drag_rate": Var(_T, "linear on-site damping rate (Stokes' drag of the cradle's balls, or the first given)",
                     "1/s"),
    "inphase_time_phase": MINUTE_VARIABLES["inphase_time_phase"],
    "inphase_time_share": MINUTE_VARIABLES["inphase_time_share"],
    "energy_share_end": Var(_T, "energy at the end of the run over the initial energy"),
}

#: the stored variables of the `desk-toy-minute` file: one group per desk toy, and the trends (full form); the root
#: holds the spec
VARIABLES = {"/": {}, "/trends": TREND_VARIABLES, "/{scene}": MINUTE_VARIABLES}


def _group(spec: DeskToyMinute, r: dict, lifted: int) -> tuple[dict, dict, dict]:
    from cradle.models.physical import to_si

    s = r["scales"]
    cs = r["cases"]
    t = r["t"]

    def stack(key: str) -> NDArray[np.float64]:
        return np.stack([np.asarray(c[key], dtype=float) for c in cs])

    K = cs[0]["share"].size
    data = {
        "restitution": stack("restitution"), "kk_A": stack("kk_A"), "drag_rate": stack("drag"),
        "energy": to_si(stack("energy"), "energy", s), "dissipated": to_si(stack("dissipated"), "energy", s),
        "energy_balance": stack("balance"), "phase_coherence": stack("phase_coherence"),
        "com_share": stack("com_share"),
        "inphase_time_phase": to_si(stack("inphase_phase"), "time", s),
        "inphase_time_share": to_si(stack("inphase_share"), "time", s),
        "tight_inphase_time_phase": to_si(stack("tight_inphase_phase"), "time", s),
        "tight_inphase_time_share": to_si(stack("tight_inphase_share"), "time", s),
        "tight_energy_end": to_si(stack("tight_energy_end"), "energy", s),
        "separation": to_si(stack("separation"), "displacement", s),
        "separation_rate": stack("separation_rate") / s.T,
        "member_inphase_time_phase": to_si(stack("member_phase"), "time", s),
        "member_inphase_time_share": to_si(stack("member_share"), "time", s),
        "ensemble_inphase_time_share": to_si(stack("mean_share_time"), "time", s),
        "swing_time": to_si(np.pi * np.arange(1, K + 1), "time", s),
        "balls_out": np.stack([np.asarray(c["balls_out"], dtype=np.int64) for c in cs]),
        "amplitude": to_si(stack("amplitude"), "displacement", s),
        "share": stack("share"),
        "hold_swings": np.stack([np.asarray(c["hold_swings"], dtype=np.int64) for c in cs]),
        "steps": np.array([c["steps"] for c in cs], dtype=np.int64),
        "cpu_time": stack("cpu"),
    }
    N = cs[0]["amplitude"].shape[1]
    coords = {"case": [str(c["name"]) for c in cs], "t": to_si(t, "time", s), "n": np.arange(N),
              "swing": np.arange(1, K + 1), "phase_threshold": np.asarray(spec.phase_thresholds, float),
              "share_threshold": np.asarray(spec.share_thresholds, float),
              "pattern_threshold": np.asarray(spec.pattern_thresholds, float),
              "member": np.arange(spec.ensemble), "tolerance": np.array([spec.rtol, spec.rtol / CONVERGENCE_FACTOR])}
    attrs = {"n_beads": N, "lifted": lifted, "X_m": s.X, "T_s": s.T, "E_J": s.E, "mass_kg": s.m,
             "omega0_rad_per_s": s.omega0, "amplitude_m": to_si(r["amplitude"], "displacement", s),
             "energy0_J": to_si(float(cs[0]["energy"][0]), "energy", s)}
    return data, coords, attrs


def compute(spec: DeskToyMinute, inputs: dict | None = None, log: Log | None = None) -> xr.DataTree:
    """The `desk-toy-minute` analysis as a tree: one group per (chain length, lifted count)
    (:data:`VARIABLES`); it reads no file (``inputs`` is empty)."""
    from cradle.data.io import make_tree

    say = log or (lambda *a: None)
    t0 = _time.perf_counter()
    warm_up()
    groups: dict = {"/": ({}, {})}
    variables: dict = {"/": {}}
    group_attrs, names = {}, []
    for N in spec.chains:
        for k in (k for k in spec.lifted if k < N):
            r = desk_toy_minute(spec, N, k)
            data, coords, attrs = _group(spec, r, k)
            path = f"/{label(N, k)}"
            groups[path], variables[path], group_attrs[path] = (data, coords), MINUTE_VARIABLES, attrs
            names.append(label(N, k))
            first = data["inphase_time_share"][:, 0]
            say(f"desk-toy-minute: {label(N, k)}: in phase (S >= {spec.share_thresholds[0]:g}) after "
                + ", ".join(f"{c}: {v:.3g} s" for c, v in zip(coords["case"], first, strict=True))
                + f"; CPU {float(np.sum(data['cpu_time'])):.2f} s")
    if spec.trend_lengths or spec.trend_radii:
        tr = trends(spec)
        groups["/trends"] = ({
            "length": np.asarray(tr["length"], float), "radius": np.asarray(tr["radius"], float),
            "restitution": np.asarray(tr["restitution"], float), "drag_rate": np.asarray(tr["drag"], float),
            "inphase_time_phase": np.asarray(tr["phase"], float), "inphase_time_share": np.asarray(tr["share"], float),
            "energy_share_end": np.asarray(tr["energy_share"], float)},
            {"trend": [str(n) for n in tr["name"]], "phase_threshold": np.asarray(spec.phase_thresholds, float),
             "share_threshold": np.asarray(spec.share_thresholds, float)})
        variables["/trends"] = TREND_VARIABLES
        say("desk-toy-minute: trends: in phase (S >= " + f"{spec.share_thresholds[0]:g}) after "
            + ", ".join(f"{n}: {v[0]:.3g} s" for n, v in zip(tr["name"], tr["share"], strict=True)))
    c = cradle_of(spec)
    e_A = contacts(spec)
    attrs = {
        "desk_toys": ", ".join(names),
        "cradle": f"{c.material} balls of radius {c.radius:g} m on strings of {c.length:g} m (g = {c.g:g} m/s^2)",
        "angle_deg": spec.angle_deg,
        "duration_s": spec.duration,
        "integrator": f"dop853_numba, rtol = {spec.rtol:g} (convergence run rtol / {CONVERGENCE_FACTOR:g}), "
                      "atol = rtol * amplitude, free ends",
        "contacts": "; ".join(f"e = {e:.4g} at {spec.restitution_speed:g} m/s <-> A = {A:.4g} s" for e, A in e_A),
        "contact_source": ("kk_constant given" if spec.kk_constant is not None else
                           "restitution: ASSUMED values bracketing 0.95 (no measured e at hand)"),
        "drag_rates_per_s": ", ".join(f"{r:.4g}" for r in drag_rates(spec)),
        "drag_source": ("drag_rates given" if spec.drag_rates is not None else
                        "Stokes 6 pi mu R v (lower bound) and quadratic drag with Schiller-Naumann C_d at the release "
                        "speed (upper bound), air of ISO 2533:1975 at sea level (cradle.models.air_drag)"),
        "out_fraction": spec.out_fraction,
        "pendulum": "(nc)'s on-site force is the small-angle pendulum: the released balls meet the line at "
                    "L sin(theta) omega_0, not sqrt(2 g L (1 - cos theta))",
        "wall_time_s": _time.perf_counter() - t0,
    }
    tree = make_tree(groups, variables, attrs=attrs, params=plain(spec),
                     title="A desk toy watched for a minute: break-up, dissipation and in-phase motion, in SI")
    for path, a in group_attrs.items():
        tree[path].attrs = a
    return tree


ANALYSIS = Analysis(
    name="desk-toy-minute", spec=DeskToyMinute, compute=compute, variables=VARIABLES,
    title="A desk toy watched for a minute: (ncdamped) with contact damping and air drag against the hard-sphere "
          "cradle, in SI")
