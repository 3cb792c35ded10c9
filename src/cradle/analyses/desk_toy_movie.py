"""The desk-toy movie's own runs: one desk toy of the `desk-toy` analysis stored densely around its impacts, in SI.

The analysis stores (nc) 256 times per swing period, about 160 contact times apart: its runs never show a
contact. The movie's input is a run of its own (the analysis's outputs are left as they are):

1. (nc) of the desk toy (:func:`cradle.analyses.desk_toy.desk_toy_runs`' integrator, tolerance and damping)
   over ``swings`` swing periods 2 pi, stored on the uniform grid t_j = j h, h = t_c / ``per_contact``, t_c the
   Hertz contact time at the release speed (:func:`cradle.models.desk_toy.collision_time_nc`; a later, slower
   impact lasts longer, t_c ~ v^(-1/5));
2. the impact windows (:func:`cradle.measurements.slow_motion.impact_windows`): the stored states with a bond
   compressed, and the collision instants of the hard-sphere cradle drawn beside, widened by ``margin`` t_c;
3. the frames (:func:`cradle.measurements.slow_motion.frame_indices`): every stored state in a window, the
   spacing growing by ``ramp`` per frame away from it, up to 1 / (fps ``slowdown``) seconds between impacts;
4. only the frames' states are kept: (nc)'s displacements and Hertz contact forces F = k delta^(3/2) (the
   cradle's k, :func:`cradle.models.physical.scales`), and the hard-sphere cradle at the same instants
   (:func:`cradle.models.hard_spheres.hard_sphere_run`, exact at any time) with the bonds that collided since
   the previous frame.

:func:`movie_run` returns the Dataset :mod:`cradle.figures.desk_toy_movie` draws (:data:`VARIABLES`).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from cradle.data.variables import Var
from cradle.specs.declare import declared, param, plain

if TYPE_CHECKING:
    import xarray as xr

    from cradle.analyses.desk_toy import DeskToyRuns


@declared(doc="The slow motion of the desk-toy movies (target `desk_toy_movies`; cradle.analyses.desk_toy_movie): "
              "each impact shown state by state, the movie speeding up between impacts.")
class SlowMotion:
    swings: int = param(2, "Swing periods 2 pi / omega_0 shown (two impacts each).", minimum=1, maximum=6)
    per_contact: int = param(8, "Stored states per Hertz contact time t_c at the release speed: the time "
                             "between two frames within an impact is t_c / per_contact.", minimum=2, maximum=32)
    margin: float = param(2.0, "Contact times t_c shown state by state before a contact starts and after it "
                          "ends.", minimum=0, maximum=50)
    ramp: float = param(1.5, "Growth of the time between frames per frame, away from an impact.",
                        exclusiveMinimum=1, maximum=10)
    slowdown: float = param(2.0, "Slow motion between impacts: a second of movie shows 1 / slowdown seconds of "
                            "the cradle.", minimum=0.1, maximum=100)


_T = ("t",)
#: the variables of a desk-toy movie's run (results/movies/desk-toy-<toy>.nc)
VARIABLES: dict[str, Var] = {
    "model": Var(("model",), "model: the lattice (nc), then the hard-sphere cradle"),
    "t": Var(_T, "time since the release, at each frame", "s"),
    "n": Var(("n",), "ball index, the lifted balls first"),
    "bond": Var(("bond",), "bond index n: balls n and n+1"),
    "impact": Var(("impact",), "impact window index"),
    "x": Var(("model", "t", "n"), "horizontal displacement of each ball from its rest position", "m"),
    "force": Var(_T + ("bond",), "Hertz contact force k delta^(3/2) of each bond of (nc), delta its compression",
                 "N"),
    "collided": Var(_T + ("bond",), "1 where the bond of the hard-sphere cradle collided since the previous "
                    "frame, else 0"),
    "window_start": Var(("impact",), "start of the impact window: a contact's start less the margin", "s"),
    "window_end": Var(("impact",), "end of the impact window: a contact's end plus the margin", "s"),
}


def movie_run(spec: DeskToyRuns, n_beads: int, lifted: int, motion: SlowMotion, fps: int,
              hard: int = 0) -> xr.Dataset:
    """The movie's run of the desk toy (``n_beads``, ``lifted``) of the `desk-toy` spec ``spec`` (module
    docstring), with the hard-sphere cradle of restitution ``spec.restitution[hard]``, for a movie of ``fps``
    frames per second."""
    from cradle.analyses.desk_toy import cradle_of, label, nc_run
    from cradle.data.io import make_dataset
    from cradle.measurements.slow_motion import frame_indices, impact_windows
    from cradle.models import desk_toy as dt
    from cradle.models.hard_spheres import hard_sphere_run
    from cradle.models.lattice import bond_elongations

    if not 0 <= hard < len(spec.restitution):
        raise ValueError(f"hard = {hard}: must index spec.restitution (0 .. {len(spec.restitution) - 1})")
    cradle = cradle_of(spec)
    toy = dt.desk_toy(n_beads, lifted, spec.angle_deg, cradle)
    x0, v0, s = dt.desk_toy_initial(toy)
    t_c = dt.collision_time_nc(-float(x0[0]))
    h = t_c / motion.per_contact
    t = h * np.arange(math.ceil(2.0 * np.pi * motion.swings / h) + 1, dtype=np.float64)
    damping = spec.damping if spec.damping is not None and spec.damping.active else None
    run = nc_run(x0, t, spec.rtol, damping)
    e = spec.restitution[hard]
    instants = hard_sphere_run(x0, v0, t[[0, -1]], restitution=e).collision_t
    compressed = np.diff(run.x, axis=1) < 0.0
    windows = impact_windows(t, compressed.any(axis=1), motion.margin * t_c, instants)
    sparse = 1.0 / (fps * motion.slowdown) / s.T
    idx = frame_indices(t, windows, sparse, motion.ramp)
    tf = t[idx]
    hs = hard_sphere_run(x0, v0, tf, restitution=e)
    collided = np.zeros((tf.size, n_beads - 1), dtype=np.int8)
    for when, bond in zip(hs.collision_t, hs.collision_bond, strict=True):
        collided[np.searchsorted(tf, when), bond] = 1
    # Hertz in (nc)'s units is |d|^(3/2) on a compressed bond; times the force scale F = m omega_0^2 X: newtons
    force = np.maximum(-bond_elongations(run.x[idx], "free")[:, :-1], 0.0) ** 1.5 * s.F
    x = np.stack([run.x[idx], hs.x]) * s.X
    names = ["(nc) damped" if damping else "(nc)", f"hard spheres e = {e:g}"]
    attrs = {"scene": f"desk-toy-{label(n_beads, lifted)}", "n_beads": n_beads, "lifted": lifted,
             "material": cradle.material, "radius_m": cradle.radius, "length_m": cradle.length,
             "angle_deg": spec.angle_deg, "restitution": e, "fps": fps, "contact_time_s": t_c * s.T,
             "grid_dt_s": h * s.T, "model_names": ", ".join(names),
             "nc_energy_drift": float(run.energy_drift), "nc_steps": int(run.n_steps)}
    return make_dataset(
        {"x": x, "force": force, "collided": collided, "window_start": windows[:, 0] * s.T,
         "window_end": windows[:, 1] * s.T},
        coords={"model": names, "t": tf * s.T, "n": np.arange(n_beads), "bond": np.arange(n_beads - 1),
                "impact": np.arange(len(windows))},
        attrs=attrs, title=f"The desk-toy movie's run of {label(n_beads, lifted)}: (nc) and the hard-sphere "
                           "cradle at each frame, dense around the impacts, in SI",
        params={"desk_toy": plain(spec), "slow_motion": plain(motion), "fps": fps, "hard": hard},
        variables=VARIABLES)
