"""The desk-toy experiments as an analysis: (nc) against the ideal hard-sphere cradle, in SI.

A desk toy (a :class:`cradle.models.physical.Cradle`, default 1 cm steel balls on 10 cm strings) of
``N`` balls in a line, the ``lifted`` balls at the left end pulled out to ``angle_deg`` and released at rest
(:mod:`cradle.models.desk_toy`). Its amplitude in (nc)'s units is enormous (about 3.7e17 for the default at
20 degrees, docs/physical-units.md), where the DpS approximation of a scene is meaningless and cannot be
integrated: hence an analysis, not scenes. For each chain length N and each lifted count:

* the lattice (nc) (free ends, ``dop853_numba`` at ``rtol``; the damping of (ncdamped) when ``damping``
  is given, :mod:`cradle.models.damping`, in (nc)'s units), stored on the grid t_j = 2 pi j / samples over
  ``swings`` swing periods 2 pi;
* the ideal hard-sphere cradle (:mod:`cradle.models.hard_spheres`) at each restitution coefficient e, on
  the same grid (it has no on-site damping: its losses are the collisions' own);
* the measurements of :mod:`cradle.measurements.desk_toy` on each run: the one-out-one-out share f_k at
  t = k pi and how many out-swings it stays >= each threshold, the velocities just after the first cascade
  and the gaps at the first largest swing t = pi (the break-up of the line, Hutzler, Delaney, Weaire &
  MacLeod, Am. J. Phys. 72 (2004) 1508), and each bead's energy averaged over each swing period.

Everything is stored in SI (CF units: m, s, m/s, J): a value of (nc) times the cradle's scale
(:func:`cradle.models.physical.to_si`); the scales are attributes of each group (``X_m``, ``T_s``,
``V_m_per_s``, ``E_J``), so a reader gets (nc)'s values back by dividing.

The (nc) cascade is resolved on a grid of its own (the collisions of a desk toy last about 1e-4 of a swing):
a second run over [0, pi] stored every ``CASCADE_DT`` from the impact at t = pi/2 on
(:func:`cascade_run`), as benchmarks/desk_toy.py does.
"""
from __future__ import annotations

import math
import time as _time
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.protocol import Analysis
from cradle.data.variables import Var
from cradle.models.damping import Damping
from cradle.models.physical import Cradle
from cradle.models.restitution_data import STEEL_ASSUMED
from cradle.specs.declare import declared, param, plain
from cradle.specs.values import RTOL_FLOOR

if TYPE_CHECKING:
    from collections.abc import Iterable

    import xarray as xr
    from numpy.typing import ArrayLike, NDArray

    from cradle.analyses.protocol import Log
    from cradle.integrators.lattice_solver import LatticeSolution
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors

#: the largest chain of this analysis: a desk toy has 5 to 10 balls; a longer chain is a lattice scene
MAX_CHAIN = 100

#: restitution of two steel balls at desk-toy speeds used by default beside e = 1: an ASSUMED value
#: (cradle.models.restitution_data.STEEL_ASSUMED, where its status is said; docs/desk-toy.md)
STEEL_RESTITUTION_ASSUMED = STEEL_ASSUMED.e

#: the (nc) cascade is stored every CASCADE_DT over CASCADE_SPAN after the impact at t = pi/2
CASCADE_DT, CASCADE_SPAN = 1e-5, 0.05

_LIFTED = {"type": "integer", "minimum": 1, "maximum": MAX_CHAIN - 1, "description": "Balls lifted together."}
_CHAIN = {"type": "integer", "minimum": 2, "maximum": MAX_CHAIN, "description": "Balls in the line."}
_E = {"type": "number", "exclusiveMinimum": 0, "maximum": 1, "description": "Restitution coefficient e in (0, 1]."}
_THRESHOLD = {"type": "number", "exclusiveMinimum": 0, "exclusiveMaximum": 1,
              "description": "A threshold of the share f_k, in (0, 1)."}


#: the cradle of a spec that gives none: steel balls (AISI 52100, cradle.models.physical.MATERIALS) of radius 1 cm on
#: 10 cm strings
DEFAULT_CRADLE = Cradle(material="steel", radius=0.01, length=0.1)


def cradle_of(spec: DeskToyRuns) -> Cradle:
    """The spec's cradle, or :data:`DEFAULT_CRADLE` when it gives none."""
    return spec.cradle if spec.cradle is not None else DEFAULT_CRADLE


@declared(doc="The desk-toy experiments (issue 24): N balls, 1, 2 or 3 lifted to an angle and released; the lattice "
              "(nc) at the desk toy's own amplitude against the ideal hard-sphere cradle (restitution e), in SI: "
              "displacements, one-out-one-out shares and holds, the break-up of the line after the first cascade, "
              "energy per bead per swing -> results/desk-toy/desk-toy.nc and results/figures/desk-toy.{pdf,png}.")
class DeskToyRuns:
    cradle: Cradle = param(None, "The spheres and their strings (cradle.models.physical.Cradle; a pendulum length "
                           "is needed). Absent: steel balls of radius 1 cm on 10 cm strings (DEFAULT_CRADLE).")
    angle_deg: float = param(20.0, "Angle of the lifted balls' strings from the vertical (degrees); in (0, 90).",
                             exclusiveMinimum=0, exclusiveMaximum=90)
    lifted: list[int] = param([1, 2, 3], "Lifted counts: the first `lifted` balls are released together (each "
                              "< every chain length).", minItems=1, maxItems=10, items=_LIFTED)
    chains: list[int] = param([5, 10], "Chain lengths N (balls in the line).", minItems=1, maxItems=6, items=_CHAIN,
                              reduced=[5])
    swings: int = param(40, "Swing periods 2 pi (in (nc)'s time t = omega_0 s) of each run: 2 swings out-swings "
                        "k pi of the one-out-one-out measure.", minimum=1, maximum=1000,
                        reduced=6)
    samples: int = param(256, "Stored times per swing period 2 pi.", minimum=16, maximum=4096)
    restitution: list[float] = param(
        [1.0, STEEL_RESTITUTION_ASSUMED],
        "Restitution coefficients e of the hard-sphere runs: e = 1 (the textbook cradle) and 0.95 for steel, an "
        "ASSUMED value (docs/desk-toy.md): no measured steel-on-steel restitution below 1 m/s was checked against "
        "its source (Kuwabara & Kono, Jpn. J. Appl. Phys. 26 (1987) 1230 measured such collisions: take the value "
        "from there or from one's own cradle).", minItems=1, maxItems=6, items=_E)
    rtol: float = param(1e-14, "Relative tolerance of the (nc) runs (dop853_numba; atol = rtol times the "
                        "amplitude).", minimum=RTOL_FLOOR, maximum=1e-6)
    thresholds: list[float] = param([0.9, 0.5], "Thresholds of the one-out-one-out measure: the pattern holds "
                                    "while f_k >= threshold.", minItems=1, maxItems=6, items=_THRESHOLD)
    damping: Damping = param(None, "Damping of the (nc) runs, (ncdamped) in (nc)'s units (cradle.models.damping: "
                             "onsite gamma = rate (1/s) / omega_0, contact eta = Kuwabara-Kono A (s) times "
                             "omega_0); absent: the conservative (nc). The hard-sphere runs lose energy only "
                             "through e.")

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Each form: every lifted count below every chain length, a pendulum cradle, no repeated value."""
        if self.cradle is not None and self.cradle.length is None:
            out.add(where + ["cradle"], "a desk toy needs the pendulum length (a stiff oscillator has no angle)")
        short = min(self.chains)
        for i, k in enumerate(self.lifted):
            if k >= short:
                out.add(where + ["lifted", i], f"must be < every chain length (smallest: {short}): one ball at "
                                               "least stays in the line", k)
        for key in ("chains", "lifted", "restitution", "thresholds"):
            values = getattr(self, key)
            if len(set(values)) != len(values):
                out.add(where + [key], "lists a value twice", values)


# ----------------------------------------------------------------- the runs


def label(n_beads: int, lifted: int) -> str:
    """The group name of one desk toy: ``n5-lifted1``."""
    return f"n{n_beads}-lifted{lifted}"


def parse_label(name: str) -> tuple[int, int]:
    """(n_beads, lifted) of the group name ``n5-lifted1`` (:func:`label`); another name is a ValueError."""
    import re

    m = re.fullmatch(r"n([0-9]+)-lifted([0-9]+)", name)
    if m is None:
        raise ValueError(f"{name!r}: not a desk toy's name (n<balls>-lifted<count>, e.g. n5-lifted1)")
    return int(m.group(1)), int(m.group(2))


def time_grid(swings: int, samples: int) -> np.ndarray:
    """t_j = 2 pi j / samples, j = 0 .. swings samples: the stored times in (nc)'s units."""
    return 2.0 * np.pi * np.arange(swings * samples + 1) / samples


def nc_run(x0: NDArray[np.float64], t: NDArray[np.float64], rtol: float, damping: Damping | None) -> LatticeSolution:
    """(nc) with free ends from (x0, 0) stored at ``t``: dop853_numba at ``rtol`` (atol its default, rtol times
    the amplitude), damped by ``damping`` ((ncdamped)) when given."""
    from cradle.integrators import integrate_lattice

    return integrate_lattice(x0, np.zeros_like(x0), t, alpha=1.5, bc="free", method="dop853_numba", rtol=rtol,
                             damping=damping)


def cascade_run(x0: NDArray[np.float64], rtol: float,
                damping: Damping | None = None) -> tuple[NDArray[np.float64], LatticeSolution]:
    """(t, run) of (nc) over [0, pi] stored every CASCADE_DT over CASCADE_SPAN from the impact at t = pi/2 (and
    100 times elsewhere): resolves the first cascade and ends at the first largest swing t = pi."""
    dense = np.pi / 2 + np.linspace(0.0, CASCADE_SPAN, int(round(CASCADE_SPAN / CASCADE_DT)) + 1)
    t = np.unique(np.concatenate([np.linspace(0.0, np.pi, 101), dense]))
    return t, nc_run(x0, t, rtol, damping)


def _measured(t: NDArray[np.float64], x: ArrayLike, v: ArrayLike, lifted: int,
              thresholds: Iterable[float]) -> dict:
    from cradle.measurements import desk_toy as m

    _, f = m.out_fractions(t, x, v, lifted)
    holds = [m.pattern_hold(t, x, v, lifted, th) for th in thresholds]
    _, E = m.energy_per_swing(t, x, v)
    return {"share": f, "hold_swings": [h.swings for h in holds], "hold_time": [h.t_break for h in holds],
            "energy_per_swing": E}


def desk_toy_runs(spec: DeskToyRuns, n_beads: int, lifted: int) -> dict:
    """The runs and measurements of one desk toy, in (nc)'s units (module docstring): arrays along
    ``model`` = (nc), then the hard spheres at each e of ``spec.restitution``; the scales and checks beside."""
    from cradle.measurements import desk_toy as m
    from cradle.models import desk_toy as dt
    from cradle.models.hard_spheres import hard_sphere_run

    toy = dt.desk_toy(n_beads, lifted, spec.angle_deg, cradle_of(spec))
    x0, v0, s = dt.desk_toy_initial(toy)
    t = time_grid(spec.swings, spec.samples)
    damping = spec.damping if spec.damping is not None and spec.damping.active else None
    run = nc_run(x0, t, spec.rtol, damping)
    tc, crun = cascade_run(x0, spec.rtol, damping)
    _, c_end, ic = m.cascade_end(tc, crun.x)
    _, gaps, _ = m.line_state(tc, crun.x, crun.v, np.pi)
    models = [{"x": run.x, "v": run.v, "energy": run.energy, "dissipated": run.dissipated,
               "cascade_velocity": crun.v[ic] if ic >= 0 else np.full(n_beads, np.nan), "cascade_end": c_end,
               "gap_at_pi": gaps}]
    for e in spec.restitution:
        hs = hard_sphere_run(x0, v0, t, restitution=e)
        # just after the first instant of collisions (t = pi/2: the released balls meet the line), and at t = pi
        first = hard_sphere_run(x0, v0, np.array([np.pi / 2 + 1e-12, np.pi]), restitution=e)
        models.append({"x": hs.x, "v": hs.v, "energy": hs.energy, "dissipated": hs.dissipated,
                       "cascade_velocity": first.v[0],
                       "cascade_end": float(first.collision_t[0]) if first.collision_t.size else math.nan,
                       "gap_at_pi": np.diff(first.x[1])})
    for r in models:
        r.update(_measured(t, r["x"], r["v"], lifted, spec.thresholds))
    return {"t": t, "models": models, "scales": s, "amplitude": float(-x0[0]),
            "collision_fraction": dt.collision_fraction(toy), "energy_drift": float(run.energy_drift),
            "n_steps": int(run.n_steps), "cascade_energy_drift": float(crun.energy_drift)}


# ----------------------------------------------------------------- the stored file

_M = ("model",)
#: the variables of one desk toy's group (``/n5-lifted1``): SI values, (nc)'s divided by the scales in the
#: group's attributes X_m, T_s, V_m_per_s, E_J
DESK_VARIABLES: dict[str, Var] = {
    "model": Var(_M, "model: the lattice (nc), then the hard-sphere cradle at each restitution e",
                 attrs=(("comment", "the names are also in the group attribute model_names"),)),
    "t": Var(("t",), "time since the release", "s"),
    "n": Var(("n",), "ball index, the lifted balls first (bond n joins balls n and n+1)"),
    "bond": Var(("bond",), "bond index n: balls n and n+1"),
    "swing": Var(("swing",), "out-swing k = 1, 2, ...: the largest swing at t = k pi / omega_0"),
    "period": Var(("period",), "swing period k: [2 pi k, 2 pi (k+1)) / omega_0"),
    "threshold": Var(("threshold",), "threshold of the share f_k of the one-out-one-out measure"),
    "restitution": Var(_M, "restitution coefficient e of the hard-sphere model (NaN for (nc))"),
    "x": Var(_M + ("t", "n"), "horizontal displacement of each ball from its rest position", "m"),
    "energy": Var(_M + ("t",), "energy of the cradle: on-site (small-angle pendulum) plus Hertz contact energy "
                  "(ham)", "J"),
    "dissipated": Var(_M + ("t",), "energy dissipated since the release (damping of (nc); collisions with e < 1)",
                      "J", attrs=(("comment", "integrated as its own quantity: energy + dissipated is conserved"),)),
    "swing_time": Var(("swing",), "time k pi / omega_0 of out-swing k", "s"),
    "share": Var(_M + ("swing",), "share f_k of the energy carried by the `lifted` outermost balls (far end for "
                 "k odd, release end for k even) at the stored time nearest k pi"),
    "hold_swings": Var(_M + ("threshold",), "out-swings in a row from the first with f_k >= threshold"),
    "hold_time": Var(_M + ("threshold",), "time of the first out-swing with f_k < threshold", "s",
                     attrs=(("comment", "NaN: the pattern held through the run"),)),
    "period_start": Var(("period",), "start 2 pi k / omega_0 of swing period k", "s"),
    "energy_per_swing": Var(_M + ("period", "n"), "each ball's energy (on-site plus half of each of its bonds' "
                            "Hertz energy) averaged over the swing period", "J"),
    "cascade_end": Var(_M, "end of the first cascade: (nc) the first stored time after the first compression with "
                       "no bond compressed; hard spheres the first instant of collisions", "s"),
    "cascade_velocity": Var(_M + ("n",), "velocity of each ball just after the first cascade", "m/s"),
    "gap_at_pi": Var(_M + ("bond",), "gap x_{n+1} - x_n of each bond at the first largest swing t = pi / omega_0",
                     "m"),
}

#: the stored variables of the `desk-toy` file: one group per desk toy (``/n5-lifted1``); the root holds the spec
VARIABLES = {"/": {}, "/{scene}": DESK_VARIABLES}


def model_names(spec: DeskToyRuns) -> list[str]:
    """The names along ``model``: (nc) (damped when the spec has damping), then each hard-sphere cradle."""
    damped = spec.damping is not None and spec.damping.active
    return ["(nc) damped" if damped else "(nc)"] + [f"hard spheres e = {e:g}" for e in spec.restitution]


def _group(spec: DeskToyRuns, r: dict, lifted: int) -> tuple[dict, dict, dict]:
    from cradle.models.physical import to_si

    s = r["scales"]
    ms = r["models"]
    t = r["t"]
    K = ms[0]["share"].size
    P = ms[0]["energy_per_swing"].shape[0]

    def stack(key: str) -> NDArray[np.float64]:
        return np.stack([np.asarray(mm[key], dtype=float) for mm in ms])

    data = {
        "restitution": np.array([np.nan, *spec.restitution]),
        "x": to_si(stack("x"), "displacement", s),
        "energy": to_si(stack("energy"), "energy", s),
        "dissipated": to_si(stack("dissipated"), "energy", s),
        "swing_time": to_si(np.pi * np.arange(1, K + 1), "time", s),
        "share": stack("share"),
        "hold_swings": stack("hold_swings"),
        "hold_time": to_si(stack("hold_time"), "time", s),
        "period_start": to_si(2.0 * np.pi * np.arange(P), "time", s),
        "energy_per_swing": to_si(stack("energy_per_swing"), "energy", s),
        "cascade_end": to_si(stack("cascade_end"), "time", s),
        "cascade_velocity": to_si(stack("cascade_velocity"), "velocity", s),
        "gap_at_pi": to_si(stack("gap_at_pi"), "displacement", s),
    }
    N = ms[0]["x"].shape[1]
    coords = {"model": model_names(spec), "t": to_si(t, "time", s), "n": np.arange(N), "bond": np.arange(N - 1),
              "swing": np.arange(1, K + 1), "period": np.arange(P), "threshold": np.asarray(spec.thresholds, float)}
    attrs = {"n_beads": N, "lifted": lifted, "model_names": ", ".join(model_names(spec)),
             "X_m": s.X, "T_s": s.T, "V_m_per_s": s.V, "E_J": s.E, "mass_kg": s.m, "omega0_rad_per_s": s.omega0,
             "amplitude_nc": r["amplitude"], "amplitude_m": to_si(r["amplitude"], "displacement", s),
             "collision_fraction": r["collision_fraction"], "nc_energy_drift": r["energy_drift"],
             "nc_cascade_energy_drift": r["cascade_energy_drift"], "nc_steps": r["n_steps"]}
    return data, coords, attrs


def compute(spec: DeskToyRuns, inputs: dict | None = None, log: Log | None = None) -> xr.DataTree:
    """The `desk-toy` analysis as a tree: one group per (chain length, lifted count) (:data:`VARIABLES`); it
    reads no file (``inputs`` is empty)."""
    from cradle.data.io import make_tree

    say = log or (lambda *a: None)
    t0 = _time.perf_counter()
    groups: dict = {"/": ({}, {})}
    variables: dict = {"/": {}}
    group_attrs, names = {}, []
    for N in spec.chains:
        for k in spec.lifted:
            r = desk_toy_runs(spec, N, k)
            data, coords, attrs = _group(spec, r, k)
            path = f"/{label(N, k)}"
            groups[path], variables[path], group_attrs[path] = (data, coords), DESK_VARIABLES, attrs
            names.append(label(N, k))
            holds = ", ".join(f"{m}: {int(h[0])}" for m, h in zip(model_names(spec), data["hold_swings"],
                                                                 strict=True))
            say(f"desk-toy: {label(N, k)}: holds (f >= {spec.thresholds[0]:g}) {holds}; (nc) drift "
                f"{r['energy_drift']:.2g}, {r['n_steps']} steps")
    c = cradle_of(spec)
    damped = spec.damping is not None and spec.damping.active
    attrs = {
        "desk_toys": ", ".join(names),
        "model_names": ", ".join(model_names(spec)),
        "cradle": f"{c.material} balls of radius {c.radius:g} m on strings of {c.length:g} m (g = {c.g:g} m/s^2)",
        "angle_deg": spec.angle_deg,
        "nc_integrator": f"dop853_numba, rtol = {spec.rtol:g}, atol = rtol * amplitude, free ends",
        "damping": (f"(ncdamped) onsite gamma = {spec.damping.onsite:g}, contact eta = {spec.damping.contact:g} "
                    "((nc) units)" if damped else "none"),
        "restitution_status": f"e = {STEEL_RESTITUTION_ASSUMED:g} is an assumed value for steel (docs/desk-toy.md), "
                              "not a measured one",
        "pendulum": "(nc)'s on-site force is the small-angle pendulum: the released balls meet the line at "
                    "L sin(theta) omega_0, not sqrt(2 g L (1 - cos theta))",
        "wall_time_s": _time.perf_counter() - t0,
    }
    tree = make_tree(groups, variables, attrs=attrs, params=plain(spec),
                     title="The desk-toy experiments: (nc) against the hard-sphere cradle, in SI")
    for path, a in group_attrs.items():
        tree[path].attrs = a
    return tree

ANALYSIS = Analysis(
    name="desk-toy", spec=DeskToyRuns, compute=compute, variables=VARIABLES,
    title="The desk-toy experiments: (nc) at a desk toy's amplitude against the hard-sphere cradle, in SI")

