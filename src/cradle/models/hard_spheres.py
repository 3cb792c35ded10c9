"""The ideal cradle of a hard-sphere impact law: (nc)'s pendula with instantaneous binary collisions.

Between collisions each bead is the free linear oscillator of (nc), x_n'' + x_n = 0, moved exactly by the
rotation x(t) = x cos t + v sin t, v(t) = v cos t - x sin t. Beads are points of (nc)'s displacement (at rest
the balls touch: x_n = x_{n+1} = 0); the gap of bond n is d_n = x_{n+1} - x_n >= 0. All beads share one
frequency, so every gap is itself harmonic, d_n(t) = d_n cos t + w_n sin t with w_n = v_{n+1} - v_n, and the
next contact of bond n is found in closed form: after pi - atan2(d_n, w_n) (in (0, pi]) when the gap is open,
now when it is closed and the pair approaches, never when the pair touches and moves together.

A collision is instantaneous, between two equal masses, with the restitution coefficient e (0 < e <= 1), a
constant or a law e(u) of the approach speed u = -w > 0 (a viscoelastic contact's restitution depends on it):
the relative velocity w becomes -e w, the momentum is kept; each ball gets v_n += (1+e) w / 2,
v_{n+1} -= (1+e) w / 2 (with e = 1 the two velocities are swapped, which is exact in floating point). The energy
lost is (1 - e^2) mu w^2 / 2 with mu = 1/2 the reduced mass.

Several contacts at once (the desk toy's line of touching balls) are resolved by the sequential-collision
rule: binary collisions one pair at a time, sweeping the bonds in the direction of travel of the collision
that started the cascade (left to right when its left ball is the faster one), sweep after sweep, until no
touching pair approaches. This is the "independent collision" model that Hutzler, Delaney, Weaire & MacLeod
(Am. J. Phys. 72 (2004) 1508, "Rocking Newton's cradle", section II) contrast with the real cradle, and the
rigid limit whose failure for touching balls Hinch & Saint-Jean (Proc. R. Soc. Lond. A 455 (1999) 3201, "The
fragmentation of a line of balls by an impact") analyse: with e = 1 it gives the textbook answer (k balls in,
k balls out, the others at rest), whatever the elastic law.

Touching is exact. Balls touch when their gap, computed from the stored positions, is <= 0. At a collision the
pair's positions are made equal: the ball that comes in (the faster one, with every ball touching it that
moves with it, bitwise equal positions and velocities) is put where the ball it hits is (a move of the size
of the rounding error of its rotation); balls at rest touching keep x_n = x_{n+1} exactly, and a touching
pair whose relative velocity is within rounding of zero (|w| <= 64 eps max |v|) neither approaches nor
separates: it moves together.

Energy: H = sum_n (v_n^2 + x_n^2)/2 ((ham) without contact energy: hard spheres never overlap); the energy
dissipated by the collisions is summed as its own quantity (H + D = H(0) to rounding).
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

#: relative velocities within this many rounding units of the largest speed count as zero
_ROUNDING = 64.0 * np.finfo(float).eps


@dataclass
class HardSphereRun:
    """Result of :func:`hard_sphere_run`.

    ``t`` (T,) the requested times; ``x``, ``v`` (T, N) the state at each (after the collisions of that
    instant); ``energy`` (T,) H; ``dissipated`` (T,) the energy the collisions took up to each time;
    the collisions in time order: ``collision_t``, ``collision_bond`` (bond n: beads n, n+1),
    ``approach`` (-w > 0 before), ``separation`` (w after, = e times the approach speed), arrays of one
    entry per collision; ``restitution`` e (a constant, or the law e(u) of the approach speed u)."""

    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    energy: np.ndarray
    dissipated: np.ndarray
    collision_t: np.ndarray
    collision_bond: np.ndarray
    approach: np.ndarray
    separation: np.ndarray
    restitution: float | Callable[[float], float]


def rotate(x: NDArray[np.float64], v: NDArray[np.float64],
           dt: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The free motion x'' + x = 0 over a time ``dt``: (x cos dt + v sin dt, v cos dt - x sin dt)."""
    c, s = math.cos(dt), math.sin(dt)
    return x * c + v * s, v * c - x * s


def closing_times(x: NDArray[np.float64], v: NDArray[np.float64]) -> np.ndarray:
    """The time until each bond's gap closes with the pair approaching (inf: never), from the harmonic gap
    d(t) = d cos t + w sin t (module docstring)."""
    d = np.diff(x)
    w = np.diff(v)
    tol = _ROUNDING * float(np.max(np.abs(v))) if v.size else 0.0
    out = np.pi - np.arctan2(np.maximum(d, 0.0), w)
    touching = d <= 0.0
    out[touching & (w < -tol)] = 0.0
    out[touching & (np.abs(w) <= tol)] = np.inf
    out[touching & (w > tol)] = np.pi
    return out


def _collide(v: NDArray[np.float64], n: int, law: float | Callable[[float], float]) -> tuple[float, float, float]:
    """Binary collision of beads n and n+1 (equal masses, restitution e, or e(u) of the approach speed u):
    (approach, separation, energy lost)."""
    w = v[n + 1] - v[n]
    e = law if isinstance(law, float) else _law_value(law, -w)
    if e == 1.0:
        v[n], v[n + 1] = v[n + 1], v[n]
        return -w, -w, 0.0
    before = 0.5 * (v[n] ** 2 + v[n + 1] ** 2)
    j = 0.5 * (1.0 + e) * w
    v[n] += j
    v[n + 1] -= j
    return -w, v[n + 1] - v[n], before - 0.5 * (v[n] ** 2 + v[n + 1] ** 2)


def _snap(x: NDArray[np.float64], v: NDArray[np.float64], n: int) -> None:
    """Put the incoming ball of bond n (the faster), and every ball moving with it, where the hit ball is."""
    N = x.size
    if abs(v[n]) >= abs(v[n + 1]):
        xs, vs, k, step, target = x[n], v[n], n, -1, x[n + 1]
    else:
        xs, vs, k, step, target = x[n + 1], v[n + 1], n + 1, 1, x[n]
    while 0 <= k < N and x[k] == xs and v[k] == vs:
        x[k] = target
        k += step


def _law_value(law: Callable[[float], float], u: float) -> float:
    e = float(law(u))
    if not 0.0 < e <= 1.0:
        raise ValueError(f"restitution law: e({u!r}) = {e!r}: must be in (0, 1] (a restitution coefficient)")
    return e


def _cascade(x: NDArray[np.float64], v: NDArray[np.float64], trigger: int, e: float | Callable[[float], float],
             t: float,
             log: list[tuple[float, int, float, float]], max_sweeps: int) -> float:
    """The sequential-collision rule at one instant (module docstring); returns the energy it dissipated."""
    order = range(x.size - 1) if abs(v[trigger]) >= abs(v[trigger + 1]) else range(x.size - 2, -1, -1)
    _snap(x, v, trigger)
    lost = 0.0
    for _ in range(max_sweeps):
        tol = _ROUNDING * float(np.max(np.abs(v)))
        hit = False
        for n in order:
            if x[n + 1] - x[n] <= 0.0 and v[n + 1] - v[n] < -tol:
                approach, separation, de = _collide(v, n, e)
                log.append((t, n, approach, separation))
                lost += de
                hit = True
        if not hit:
            return lost
    raise RuntimeError(f"hard_sphere_run: the collisions at t = {t!r} did not end in {max_sweeps} sweeps")


def hard_sphere_run(x0: ArrayLike, v0: ArrayLike, t_out: ArrayLike, *,
                    restitution: float | Callable[[float], float] = 1.0,
                    max_collisions: int = 1_000_000) -> HardSphereRun:
    """The ideal hard-sphere cradle from (x0, v0) at t = 0, stored at the times ``t_out`` (module docstring).

    ``x0`` nondecreasing (gaps >= 0: balls never overlap), ``v0`` of the same shape, ``t_out`` increasing,
    >= 0; ``restitution`` e in (0, 1], or a function e(u) of the approach speed u > 0 (in (nc)'s units) with
    values in (0, 1] (checked at each collision). At most ``max_collisions`` collisions (a RuntimeError beyond)."""
    x = np.array(x0, dtype=float)
    v = np.array(v0, dtype=float)
    t_out = np.asarray(t_out, dtype=float)
    if x.ndim != 1 or x.size < 2 or v.shape != x.shape or not (np.all(np.isfinite(x)) and np.all(np.isfinite(v))):
        raise ValueError(f"x0, v0 must be finite arrays of one shape (N,), N >= 2, got {x.shape} and {v.shape}")
    if np.any(np.diff(x) < 0.0):
        raise ValueError(f"x0 = {x!r}: gaps x_(n+1) - x_n must be >= 0 (hard spheres do not overlap)")
    if t_out.ndim != 1 or t_out.size == 0 or t_out[0] < 0.0 or np.any(np.diff(t_out) <= 0.0) or \
            not np.all(np.isfinite(t_out)):
        raise ValueError("t_out must be a nonempty, finite, strictly increasing array of times >= 0")
    e: float | Callable[[float], float]
    if callable(restitution):
        e = restitution
    else:
        if not 0.0 < restitution <= 1.0:
            raise ValueError(f"restitution = {restitution!r}: must be in (0, 1] (a restitution coefficient)")
        e = float(restitution)
    T, N = t_out.size, x.size
    X, V = np.empty((T, N)), np.empty((T, N))
    D = np.empty(T)
    log: list[tuple[float, int, float, float]] = []
    t, lost, k = 0.0, 0.0, 0
    while k < T:
        tau = closing_times(x, v)
        j = int(np.argmin(tau))
        t_next = t + float(tau[j])
        while k < T and t_out[k] < t_next:   # stored before the collisions of t_next
            X[k], V[k] = rotate(x, v, t_out[k] - t)
            D[k] = lost
            k += 1
        if k == T:
            break
        x, v = rotate(x, v, t_next - t)
        t = t_next
        lost += _cascade(x, v, j, e, t, log, max_sweeps=10 * N + 1000)
        if len(log) > max_collisions:
            raise RuntimeError(f"hard_sphere_run: more than max_collisions = {max_collisions} collisions by t = {t!r}")
    energy = 0.5 * np.sum(X**2 + V**2, axis=1)
    cols = np.array(log, dtype=float).reshape(-1, 4)
    return HardSphereRun(t_out, X, V, energy, D, cols[:, 0], cols[:, 1].astype(int), cols[:, 2], cols[:, 3], e)
