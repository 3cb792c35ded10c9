"""Desk-toy measurements (cradle.measurements.desk_toy) against exact answers: the ideal hard-sphere cradle,
and two beads of (nc), whose centre of mass and relative motion decouple exactly.

Two beads of (nc): s = (x0 + x1)/2 obeys s'' + s = 0 and r = x1 - x0 obeys r'' + r = 2 (-r)_+^(3/2), each on
its own. Released from x0 = -A, s = -(A/2) cos t for ever; r = A cos t reaches contact at t = pi/2 with speed
A, spends a time tau compressed (the half-oscillation in the well r^2/2 + (4/5) (-r)_+^(5/2), by quadrature)
and leaves with speed A: the run is known in closed form. After the first contact the far ball carries the
share (1 + cos tau)/2 of the energy.

(nc) is scale-free up to a time/amplitude scaling: x = A y gives y'' + y = A^(1/2) (contact force in y), so a
desk toy's A ~ 3.7e17 differs from a moderate A only by the ratio of the collision time to the swing period,
t_c / 2 pi ~ A^(-1/5) (0.02 at A = 1e6, 1.2e-4 for the desk toy): the tests run moderate amplitudes, where
the adaptive integrator takes a few hundred steps per period.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from cradle.integrators import integrate_lattice
from cradle.measurements import desk_toy as m
from cradle.models.hard_spheres import hard_sphere_run
from cradle.models.lattice import hamiltonian


def contact_time(A: float) -> float:
    """tau = 2 int_0^c_max dc / sqrt(A^2 - c^2 - (8/5) c^(5/2)) (c = -r, energy of the relative motion)."""
    def g(c):
        return A * A - c * c - 1.6 * c**2.5
    c_max = brentq(g, 0.0, A, xtol=1e-15 * A, rtol=1e-15)
    # c = c_max (1 - u^2) takes the inverse square root out of the end point
    return 2.0 * quad(lambda u: 2.0 * c_max * u / math.sqrt(max(g(c_max * (1.0 - u * u)), 1e-300)), 0.0, 1.0,
                      epsabs=0.0, epsrel=1e-13, limit=200)[0]


def two_beads_exact(A: float, t: np.ndarray):
    """(x, v, free) of two beads of (nc) released from (-A, 0) at rest; ``free``: the times out of contact,
    where x and v hold (in contact they are not computed)."""
    tau = contact_time(A)
    s, ds = -0.5 * A * np.cos(t), 0.5 * A * np.sin(t)
    j = np.floor((t - math.pi / 2) / (math.pi + tau))          # contacts start at pi/2 + j (pi + tau)
    exit_ = math.pi / 2 + j * (math.pi + tau) + tau
    free = (t < math.pi / 2) | (t >= exit_)
    r = np.where(t < math.pi / 2, A * np.cos(t), A * np.sin(t - exit_))
    dr = np.where(t < math.pi / 2, -A * np.sin(t), A * np.cos(t - exit_))
    return np.stack([s - r / 2, s + r / 2], axis=1), np.stack([ds - dr / 2, ds + dr / 2], axis=1), free


def nc_run(x0, t):
    return integrate_lattice(x0, np.zeros_like(x0), t, alpha=1.5, bc="free", method="dop853_numba", rtol=1e-12)


def exact_fractions(A: float, times: np.ndarray):
    xe, ve, free = two_beads_exact(A, times)
    e = 0.5 * (xe**2 + ve**2)
    return np.where(np.arange(1, times.size + 1) % 2 == 1, e[:, 1], e[:, 0]) / (A * A / 2), free


@pytest.mark.parametrize("A", [1e2, 1e4, 1e8])
def test_two_beads_of_nc_share_the_energy_as_the_exact_solution(A):
    t = np.linspace(0.0, 6 * math.pi, 1201)
    run = nc_run(np.array([-A, 0.0]), t)
    times, f = m.out_fractions(t, run.x, run.v, 1)
    exact, free = exact_fractions(A, times)
    assert free[0] and f[0] == pytest.approx((1 + math.cos(contact_time(A))) / 2, abs=1e-9)
    np.testing.assert_allclose(f[free], exact[free], atol=1e-8)


def test_two_beads_hold_one_out_one_out_as_long_as_the_exact_solution():
    A = 1e8   # tau = 0.061: at t = k pi, k <= 24, the beads are apart
    t = np.linspace(0.0, 24 * math.pi, 4801)
    run = nc_run(np.array([-A, 0.0]), t)
    exact, free = exact_fractions(A, np.pi * np.arange(1, 25))
    assert np.all(free)
    for threshold in (0.9, 0.5):
        hold = m.pattern_hold(t, run.x, run.v, 1, threshold)
        below = np.flatnonzero(exact < threshold)
        assert (hold.swings, hold.measured) == (below[0] if below.size else 24, 24)
        assert hold.t_break == (math.pi * (below[0] + 1) if below.size else pytest.approx(math.nan, nan_ok=True))


def test_the_ideal_desk_toy_holds_one_out_one_out_for_ever():
    A = 1e6
    x0 = np.zeros(5)
    x0[0] = -A
    t = (np.arange(40 * 64 + 1) + 0.5) * (2 * math.pi / 64)       # 40 periods, no sample on a collision
    r = hard_sphere_run(x0, np.zeros(5), t, restitution=1.0)
    times, f = m.out_fractions(t, r.x, r.v, 1)
    assert times.size == 80 and np.all(np.abs(f - 1.0) < 1e-15)
    for threshold in (0.9, 0.5):
        hold = m.pattern_hold(t, r.x, r.v, 1, threshold)
        assert (hold.swings, hold.measured) == (80, 80) and math.isnan(hold.t_break)
    # each end ball carries the whole energy half of each period, the middle balls none
    starts, E = m.energy_per_swing(t, r.x, r.v)
    assert starts.size == 40
    np.testing.assert_allclose(E / (A * A / 2), np.tile([0.5, 0, 0, 0, 0.5], (40, 1)), atol=1e-14)


@pytest.mark.parametrize("e", [0.95, 0.5])
def test_a_gap_opened_by_a_hard_sphere_collision_grows_as_e_a_sin(e):
    A = 2.0
    t = np.linspace(0.0, 3.0, 301)
    r = hard_sphere_run(np.array([-A, 0.0]), np.zeros(2), t, restitution=e)
    at, gaps, v = m.line_state(t, r.x, r.v, math.pi / 2 + 1.0)
    assert gaps[0] == pytest.approx(e * A * math.sin(at - math.pi / 2), rel=1e-14)
    assert v[1] - v[0] == pytest.approx(e * A * math.cos(at - math.pi / 2), rel=1e-14)
    assert math.isnan(m.cascade_end(t, r.x)[1])   # no compression: hard spheres' contacts take no time


@pytest.mark.parametrize("e", [1.0, 0.8, 0.3])
def test_two_hard_spheres_share_the_energy_as_the_collision_law_says(e):
    # after the collision at pi/2 the velocities are A ((1-e)/2, (1+e)/2): the far ball's share of what is left
    # is (1+e)^2 / (2 (1 + e^2)) at every later out-swing of it, k = 1, 3, ... until the next collision
    t = np.linspace(0.0, 1.2 * math.pi, 121)
    r = hard_sphere_run(np.array([-3.0, 0.0]), np.zeros(2), t, restitution=e)
    _, f = m.out_fractions(t, r.x, r.v, 1)
    assert f[0] == pytest.approx((1 + e) ** 2 / (2 * (1 + e * e)), rel=1e-14)


def test_nc_line_breaks_up_and_its_gaps_then_open_harmonically():
    # five beads at a moderate amplitude: after the first cascade every bond is open and each gap is harmonic
    # (all beads share the on-site frequency) until the next contact
    A = 1e6
    x0 = np.zeros(5)
    x0[0] = -A
    t = np.linspace(0.0, 2 * math.pi, 8001)
    run = nc_run(x0, t)
    t_start, t_end, i = m.cascade_end(t, run.x)
    assert t_start == pytest.approx(math.pi / 2, abs=2 * (t[1] - t[0]))
    assert math.pi / 2 < t_end < math.pi
    d_e, w_e = np.diff(run.x[i]), np.diff(run.v[i])
    at, gaps, _ = m.line_state(t, run.x, run.v, math.pi)
    assert np.all(np.diff(run.x[i:np.searchsorted(t, at) + 1], axis=1) >= 0.0)   # no contact in between
    np.testing.assert_allclose(gaps, d_e * math.cos(at - t_end) + w_e * math.sin(at - t_end), rtol=0, atol=1e-9 * A)
    assert np.all(gaps[1:] > 0.0)   # the line has broken up (bond 0: the released ball, left behind)


def test_energy_per_bead_per_swing_sums_to_the_conserved_energy():
    A = 1e6
    x0 = np.zeros(5)
    x0[:2] = -A
    t = np.linspace(0.0, 4 * math.pi, 4001)
    run = nc_run(x0, t)
    starts, E = m.energy_per_swing(t, run.x, run.v)
    assert starts.size == 2
    np.testing.assert_allclose(E.sum(axis=1), hamiltonian(x0, np.zeros(5), 1.5, "free"),
                               rtol=10 * max(run.energy_drift, 1e-12))


def test_bead_energies_sum_to_the_hamiltonian():
    rng = np.random.default_rng(3)
    x, v = rng.normal(size=(7, 6)), rng.normal(size=(7, 6))
    np.testing.assert_allclose(m.bead_energies(x, v).sum(axis=1), hamiltonian(x, v, 1.5, "free"), rtol=1e-14)


def test_bad_arguments_are_one_line():
    t, x = np.linspace(0, 7, 8), np.zeros((8, 3))
    with pytest.raises(ValueError, match="threshold = 1.5"):
        m.pattern_hold(t, x, x, 1, 1.5)
    with pytest.raises(ValueError, match="lifted = 3"):
        m.out_fractions(t, x, x, 3)
