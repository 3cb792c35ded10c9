"""The minute as a movie: one desk toy of the `desk-toy-minute` analysis, in real time, slowed down at chosen impacts.

The analysis stores its runs 16 times per swing period (about 25 times a second for 10 cm strings), never during a
contact (a contact lasts about 1e-4 of a swing), and keeps only per-swing samples of the balls. The movie's input is
a run of its own; the analysis's outputs are left as they are:

1. the analysis's run of the desk toy ((ncdamped), :func:`cradle.analyses.desk_toy_minute.minute_run`, the same
   arguments, so the same states) on its stored grid, with the order parameters S and R and the energy on that grid
   (the movie's timeline);
2. the frames between impacts, every 1 / fps seconds of the cradle (real time): each integrated from the stored
   state just before it, so every frame lies on the analysis's trajectory to the integrator's tolerance (one run
   over the minute stored at the frames would step differently and, the rocking of the balls being chaotic,
   drift away from it by the in-phase time);
3. the slow-motion impacts: the first ``first_impacts`` impacts, the impact before the first out-swing whose share
   f_k falls below the analysis's first pattern threshold (the break-up of one-out-one-out, ``break_up``) and the
   impact nearest each of ``moments``. The impact before out-swing k lies between the out-swings k - 1 and k
   (t = (k - 1) pi and k pi in (nc)'s units, both stored): that half swing is integrated from the stored state on a
   uniform grid of t_c / ``per_contact`` (t_c the Hertz contact time at the release speed,
   :func:`cradle.models.desk_toy.collision_time_nc`), and its frames are chosen as in the desk-toy movie
   (:func:`cradle.measurements.slow_motion.impact_windows`, :func:`cradle.measurements.slow_motion.frame_indices`):
   every stored state within ``margin`` t_c of a contact, the spacing growing by ``ramp`` per frame to real time;
4. kept for each frame: the displacements (m), the contact forces (N) of (ncdamped)'s bonds, F = k max(delta^(3/2) +
   eta' delta^(1/2) delta', 0) (eta' the Kuwabara-Kono A, delta the compression), and which slow-motion impact it
   belongs to.

:func:`movie_run` returns the Dataset :mod:`cradle.figures.desk_toy_minute_movie` draws (:data:`VARIABLES`).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from cradle.data.variables import Var
from cradle.specs.declare import declared, param, plain

if TYPE_CHECKING:
    import xarray as xr
    from numpy.typing import NDArray

    from cradle.analyses.desk_toy_minute import DeskToyMinute
    from cradle.models.damping import Damping


@declared(doc="The minute as a movie (target `desk_toy_minute_movies`, in `movies`; "
              "cradle.analyses.desk_toy_minute_movie): one desk toy of the desk-toy-minute analysis's full form "
              "in real time, chosen impacts in slow motion.")
class MinuteMovie:
    toys: list[str] = param(["n5-lifted1"], "Desk toys of the desk-toy-minute full form filmed (n<N>-lifted<k>).",
                            minItems=0, maxItems=8, items={"type": "string", "pattern": "^n[0-9]+-lifted[0-9]+$",
                                                           "description": "A desk toy: n<N>-lifted<k>."})
    contact: int = param(1, "Index of the contact among the analysis's (restitution or kk_constant; the default "
                         "1 is e = 0.98, whose in-phase motion comes within the minute).", minimum=0, maximum=3)
    drag: int = param(0, "Index of the drag rate among the analysis's (0: Stokes' drag, the lower bound).",
                      minimum=0, maximum=3)
    first_impacts: int = param(2, "The first impacts shown in slow motion.", minimum=0, maximum=20)
    break_up: bool = param(True, "Show in slow motion the impact before the first out-swing whose share f_k falls "
                           "below the analysis's first pattern threshold (the end of one-out-one-out).")
    moments: list[float] = param([], "Further times (s): the impact nearest each is shown in slow motion.",
                                 maxItems=8, items={"type": "number", "minimum": 0, "maximum": 600,
                                                    "description": "A time since the release (s)."})
    per_contact: int = param(8, "Stored states per Hertz contact time t_c at the release speed in a slow-motion "
                             "impact.", minimum=2, maximum=32)
    margin: float = param(2.0, "Contact times t_c shown state by state before a contact starts and after it ends.",
                          minimum=0, maximum=50)
    ramp: float = param(1.5, "Growth of the time between frames per frame, from an impact to real time.",
                        exclusiveMinimum=1, maximum=10)


_F = ("frame",)
#: the variables of a minute movie's run (results/movies/desk-toy-minute-<toy>.nc is not written: the rule draws it)
VARIABLES: dict[str, Var] = {
    "frame": Var(_F, "movie frame"),
    "n": Var(("n",), "ball index, the lifted balls first"),
    "bond": Var(("bond",), "bond index n: balls n and n+1"),
    "impact": Var(("impact",), "slow-motion impact"),
    "t_line": Var(("t_line",), "stored time of the analysis's run", "s"),
    "t": Var(_F, "time since the release, at each frame", "s"),
    "x": Var(_F + ("n",), "horizontal displacement of each ball from its rest position", "m"),
    "force": Var(_F + ("bond",), "contact force k max(delta^(3/2) + A delta^(1/2) delta', 0) of each bond", "N"),
    "slow": Var(_F, "index of the slow-motion impact the frame belongs to, -1 in real time"),
    "impact_start": Var(("impact",), "first frame time of the slow-motion impact", "s"),
    "impact_end": Var(("impact",), "last frame time of the slow-motion impact", "s"),
    "impact_label": Var(("impact",), "why the impact is in slow motion"),
    "com_share": Var(("t_line",), "centre-of-mass share S of the swing (cradle.measurements.desk_toy_minute)"),
    "phase_coherence": Var(("t_line",), "phase coherence R of the balls"),
    "energy_share": Var(("t_line",), "energy H(t) / H(0)"),
}


def _states(x0: NDArray[np.float64], v0: NDArray[np.float64], times: NDArray[np.float64], damping: Damping,
            rtol: float, atol: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(x, v) of (ncdamped) from (x0, v0) at ``times`` (>= 0, from the start; (nc)'s units), at the tolerances of
    the run it continues (its atol: rtol times the release amplitude, not the state's own)."""
    from cradle.integrators import integrate_lattice

    if times.size == 1 and times[0] == 0.0:
        return x0[None, :].copy(), v0[None, :].copy()
    grid = times if times[0] == 0.0 else np.concatenate([[0.0], times])
    run = integrate_lattice(x0, v0, grid, alpha=1.5, bc="free", method="dop853_numba", rtol=rtol,
                            atol=atol, damping=damping)
    skip = 0 if times[0] == 0.0 else 1
    return run.x[skip:], run.v[skip:]


def contact_forces(x: NDArray[np.float64], v: NDArray[np.float64], eta: float) -> NDArray[np.float64]:
    """(nc)'s contact force of each bond, max(c^(3/2) + eta c^(1/2) c', 0) where c = x_n - x_(n+1) > 0, else 0
    ((..., N-1), (nc)'s units: times the force scale F for newtons)."""
    c = x[..., :-1] - x[..., 1:]
    cd = v[..., :-1] - v[..., 1:]
    pos = np.maximum(c, 0.0)
    return np.where(c > 0.0, np.maximum(pos**1.5 + eta * np.sqrt(pos) * cd, 0.0), 0.0)


def slow_swings(spec: DeskToyMinute, motion: MinuteMovie, t: NDArray[np.float64], x: NDArray[np.float64],
                v: NDArray[np.float64], lifted: int, T_s: float) -> list[tuple[int, str]]:
    """(k, why) of the out-swings whose preceding impact is shown in slow motion (module docstring), k >= 1 in time
    order, each once."""
    from cradle.measurements import desk_toy as dm

    K = int(np.floor(t[-1] / np.pi + 1e-9))
    picks: dict[int, str] = {}
    for k in range(1, min(motion.first_impacts, K) + 1):
        picks.setdefault(k, "the first impact" if k == 1 else f"impact {k}")
    if motion.break_up:
        _, f = dm.out_fractions(t, x, v, lifted)
        below = np.flatnonzero(f < spec.pattern_thresholds[0])
        if below.size:
            k = int(below[0]) + 1
            picks.setdefault(k, f"the break-up: out-swing {k} is the first whose outermost ball carries < "
                                f"{spec.pattern_thresholds[0]:g} of the energy")
    for m in motion.moments:
        k = min(max(1, round(m / T_s / np.pi + 0.5)), K)
        picks.setdefault(k, f"near {m:g} s")
    return sorted(picks.items())


def movie_run(spec: DeskToyMinute, n_beads: int, lifted: int, motion: MinuteMovie, fps: int) -> xr.Dataset:
    """The movie's run of the desk toy (``n_beads``, ``lifted``) of the `desk-toy-minute` spec ``spec`` (module
    docstring), for a movie of ``fps`` frames per second."""
    from cradle.analyses import desk_toy_minute as dmin
    from cradle.data.io import make_dataset
    from cradle.measurements import desk_toy_minute as mm
    from cradle.measurements.slow_motion import frame_indices, impact_windows, ramp_offsets
    from cradle.models import desk_toy as dt

    contacts, rates = dmin.contacts(spec), dmin.drag_rates(spec)
    if motion.contact >= len(contacts):
        raise ValueError(f"movies.desk_toy_minute.contact = {motion.contact}: must index the analysis's "
                         f"{len(contacts)} contacts")
    if motion.drag >= len(rates):
        raise ValueError(f"movies.desk_toy_minute.drag = {motion.drag}: must index the analysis's {len(rates)} "
                         "drag rates")
    e, A = contacts[motion.contact]
    rate = rates[motion.drag]
    cradle = dmin.cradle_of(spec)
    x0, v0, s = dt.desk_toy_initial(dt.desk_toy(n_beads, lifted, spec.angle_deg, cradle))
    damping = dmin.damping_of(A, rate, s)
    t = dmin.time_grid(spec.duration / s.T, spec.samples)
    run = dmin.minute_run(x0, t, damping, spec.rtol)
    atol = float(run.atol) if run.atol is not None else spec.rtol
    t_c = dt.collision_time_nc(-float(x0[0]))
    h = t_c / motion.per_contact
    sparse = 1.0 / fps / s.T
    reach = float(ramp_offsets(h, sparse, motion.ramp)[-1]) if sparse > h else 0.0
    half = spec.samples // 2          # stored states per half swing: out-swing k is stored state k * half

    frames_t: list[NDArray[np.float64]] = []
    frames_x: list[NDArray[np.float64]] = []
    frames_v: list[NDArray[np.float64]] = []
    frames_slow: list[NDArray[np.int64]] = []
    spans: list[tuple[float, float]] = []
    labels: list[str] = []
    for k, why in slow_swings(spec, motion, t, run.x, run.v, lifted, s.T):
        i0 = (k - 1) * half
        grid = h * np.arange(math.floor((t[k * half] - t[i0]) / h) + 1)
        x, v = _states(run.x[i0], run.v[i0], grid, damping, spec.rtol, atol)
        touching = np.any(x[:, :-1] - x[:, 1:] > 0.0, axis=1)
        if not touching.any():
            continue
        windows = impact_windows(grid, touching, motion.margin * t_c)
        lo, hi = windows[0, 0] - reach, windows[-1, 1] + reach
        idx = frame_indices(grid, windows, sparse, motion.ramp)
        idx = idx[(grid[idx] >= lo) & (grid[idx] <= hi)]
        frames_t.append(t[i0] + grid[idx])
        frames_x.append(x[idx])
        frames_v.append(v[idx])
        frames_slow.append(np.full(idx.size, len(spans), dtype=np.int64))
        spans.append((t[i0] + grid[idx[0]], t[i0] + grid[idx[-1]]))
        labels.append(why)
    # real time elsewhere: one frame every 1 / fps s of the cradle, each from the stored state before it
    real = np.arange(math.floor(t[-1] / sparse) + 1) * sparse
    for a, b in spans:
        real = real[(real < a) | (real > b)]
    start = np.clip(np.searchsorted(t, real, side="right") - 1, 0, t.size - 1)
    for i in np.unique(start):
        times = real[start == i]
        x, v = _states(run.x[i], run.v[i], times - t[i], damping, spec.rtol, atol)
        frames_t.append(times)
        frames_x.append(x)
        frames_v.append(v)
        frames_slow.append(np.full(times.size, -1, dtype=np.int64))
    tf = np.concatenate(frames_t)
    order = np.argsort(tf, kind="stable")
    tf = tf[order]
    xf = np.concatenate(frames_x)[order]
    vf = np.concatenate(frames_v)[order]
    slow = np.concatenate(frames_slow)[order]
    force = contact_forces(xf, vf, damping.contact) * s.F
    R, S = mm.phase_coherence(run.x, run.v), mm.com_share(run.x, run.v)
    attrs = {"scene": f"desk-toy-minute-{dmin.label(n_beads, lifted)}", "n_beads": n_beads, "lifted": lifted,
             "material": cradle.material, "radius_m": cradle.radius, "length_m": cradle.length,
             "angle_deg": spec.angle_deg, "restitution": e, "restitution_speed": spec.restitution_speed,
             "kk_A_s": A, "drag_rate_per_s": rate,
             "drag_source": ("given in drag_rates" if spec.drag_rates is not None else
                             ("Stokes' drag, the lower bound", "quadratic drag, the upper bound")[motion.drag]),
             "fps": fps, "contact_time_s": t_c * s.T, "omega0_rad_per_s": s.omega0,
             "rtol": spec.rtol, "share_thresholds": list(spec.share_thresholds),
             "inphase_time_share_s": [float(mm.settle_time(t, S, th)) * s.T
                                      for th in spec.share_thresholds]}
    return make_dataset(
        {"t": tf * s.T, "x": xf * s.X, "force": force, "slow": slow,
         "impact_start": np.array([a for a, _ in spans]) * s.T, "impact_end": np.array([b for _, b in spans]) * s.T,
         "impact_label": np.array(labels, dtype=str),
         "com_share": S, "phase_coherence": R, "energy_share": run.energy / run.energy[0]},
        coords={"frame": np.arange(tf.size), "n": np.arange(n_beads),
                "bond": np.arange(n_beads - 1), "impact": np.arange(len(spans)), "t_line": t * s.T},
        attrs=attrs, title=f"The minute movie's run of {dmin.label(n_beads, lifted)}: (ncdamped) at each frame, "
                           "real time with chosen impacts in slow motion, in SI",
        params={"desk_toy_minute": plain(spec), "motion": plain(motion), "fps": fps}, variables=VARIABLES)
