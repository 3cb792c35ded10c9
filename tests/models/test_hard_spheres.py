"""The ideal hard-sphere cradle (cradle.models.hard_spheres): exact exchanges, the energy a collision takes,
the textbook desk toy, exact harmonic flight between collisions, energy never gained."""
from __future__ import annotations

import math

import numpy as np
import pytest

from cradle.models.hard_spheres import closing_times, hard_sphere_run


def test_two_equal_balls_exchange_velocities_exactly():
    # two free balls (no time for the on-site force: they touch at t = 0) meeting head on
    x0 = np.array([0.0, 0.0])
    v0 = np.array([0.3, -0.7])
    r = hard_sphere_run(x0, v0, [0.0, 1e-3], restitution=1.0)
    assert r.collision_t.tolist() == [0.0]
    assert r.v[0].tolist() == [-0.7, 0.3]
    assert (r.approach[0], r.separation[0]) == (1.0, 1.0)


@pytest.mark.parametrize("e", [1.0, 0.95, 0.6, 0.1])
def test_energy_lost_in_one_binary_collision(e):
    # ball 0 released from -1 hits ball 1 at rest at t = pi/2 with speed 1, then the gap reopens for a time pi
    x0, v0 = np.array([-1.0, 0.0]), np.zeros(2)
    t = np.array([1.0, 2.0, 3.0])
    r = hard_sphere_run(x0, v0, t, restitution=e)
    assert r.collision_t.size == 1 and r.collision_t[0] == pytest.approx(math.pi / 2, abs=1e-15)
    w = r.approach[0]
    assert w == pytest.approx(1.0, rel=1e-15)
    lost = (1 - e**2) * 0.5 * w**2 / 2          # (1 - e^2) mu v_rel^2 / 2, mu = 1/2
    assert r.energy[0] - r.energy[1] == pytest.approx(lost, rel=1e-13, abs=4e-16)   # H = 1/2: a few ulps
    assert r.dissipated[1] == pytest.approx(lost, rel=1e-13, abs=1e-16)
    assert r.separation[0] == pytest.approx(e * w, rel=1e-15)
    # momentum kept: after the collision at pi/2 the velocities are ((1-e)/2, (1+e)/2), rotated freely
    after = np.array([(1 - e) / 2, (1 + e) / 2])
    np.testing.assert_allclose(r.v[1], after * math.cos(2.0 - math.pi / 2), rtol=1e-14)


@pytest.mark.parametrize("lifted", [1, 2, 3])
def test_the_desk_toy_ends_each_cascade_with_lifted_balls_out_at_the_original_speed(lifted):
    A = 3.667e17   # a desk toy's amplitude in (nc) (docs/physical-units.md): the rules do not depend on it
    x0 = np.zeros(5)
    x0[:lifted] = -A
    t = np.array([math.pi / 2 + 1e-9, math.pi, 3 * math.pi / 2 + 1e-9, 2 * math.pi])
    r = hard_sphere_run(x0, np.zeros(5), t, restitution=1.0)
    after = r.v[0] / math.cos(1e-9)
    expected = np.zeros(5)
    expected[5 - lifted:] = A
    np.testing.assert_allclose(after, expected, rtol=1e-15, atol=0.0)
    # at the largest swing the out balls are at +A, the others exactly at rest where they hung
    np.testing.assert_allclose(r.x[1], expected, rtol=1e-15, atol=0.0)
    assert np.all(r.v[1, : 5 - lifted] == 0.0)
    # and back: the released balls are out again at t = 2 pi, at -A
    np.testing.assert_allclose(r.x[3], -(expected[::-1]), rtol=1e-14, atol=1e-14 * A)
    assert np.all(r.energy == r.energy[0])


def test_between_collisions_each_ball_follows_the_exact_harmonic_solution():
    x0 = np.array([-2.0, -0.5, 0.0, 1.5])
    v0 = np.array([0.4, 0.1, -0.3, 0.2])
    t = np.linspace(0.0, 12.0, 241)
    r = hard_sphere_run(x0, v0, t, restitution=0.8)
    bounds = np.concatenate([[0.0], np.unique(r.collision_t), [np.inf]])
    for a, b in zip(bounds[:-1], bounds[1:], strict=True):
        inside = np.flatnonzero((t >= a) & (t < b))
        if inside.size < 2:
            continue
        i0 = inside[0]
        dt = t[inside] - t[i0]
        x_ref = r.x[i0] * np.cos(dt)[:, None] + r.v[i0] * np.sin(dt)[:, None]
        v_ref = r.v[i0] * np.cos(dt)[:, None] - r.x[i0] * np.sin(dt)[:, None]
        np.testing.assert_allclose(r.x[inside], x_ref, rtol=0, atol=1e-13)
        np.testing.assert_allclose(r.v[inside], v_ref, rtol=0, atol=1e-13)
    assert r.collision_t.size > 3
    assert np.all(np.diff(r.x, axis=1) >= -1e-13)   # balls never overlap


@pytest.mark.parametrize("e", [1.0, 0.95, 0.5])
def test_energy_never_increases_and_energy_plus_dissipated_is_conserved(e):
    x0 = np.zeros(6)
    x0[:2] = -1.0
    x0[5] = 0.3
    t = np.linspace(0.0, 20.0, 401)
    r = hard_sphere_run(x0, np.zeros(6), t, restitution=e)
    assert np.all(np.diff(r.energy) <= 1e-15 * r.energy[0])
    np.testing.assert_allclose(r.energy + r.dissipated, r.energy[0], rtol=1e-14)
    if e < 1.0:
        assert r.energy[-1] < r.energy[0]


def test_the_gap_closing_times_are_those_of_harmonic_gaps():
    # an open gap d = 1 closing at rate w = -1: d(t) = cos t - sin t closes at pi/4
    tau = closing_times(np.array([0.0, 1.0]), np.array([1.0, 0.0]))
    assert tau[0] == pytest.approx(math.pi / 4, rel=1e-15)
    # touching and separating: it closes again after pi; touching, moving together: never
    assert closing_times(np.array([0.0, 0.0]), np.array([0.0, 1.0]))[0] == pytest.approx(math.pi, rel=1e-15)
    assert closing_times(np.array([0.5, 0.5]), np.array([0.2, 0.2]))[0] == math.inf


@pytest.mark.parametrize("bad, match", [({"restitution": 0.0}, "restitution = 0.0"),
                                        ({"restitution": 1.5}, "restitution = 1.5")])
def test_bad_restitution_is_one_line(bad, match):
    with pytest.raises(ValueError, match=match):
        hard_sphere_run([-1.0, 0.0], [0.0, 0.0], [1.0], **bad)


def test_overlapping_balls_are_refused():
    with pytest.raises(ValueError, match="gaps"):
        hard_sphere_run([0.0, -1.0], [0.0, 0.0], [1.0])


@pytest.mark.parametrize("e", [1.0, 0.9, 0.5])
def test_a_cascade_keeps_momentum_and_ends_with_no_touching_pair_approaching(e):
    # two touching balls at speed 1 strike three at rest, all at x = 0: the cascade is at t = 0 (the state stored
    # at t = 0 is the one after it), where the on-site force has had no time to act
    v0 = np.array([1.0, 1.0, 0.0, 0.0, 0.0])
    r = hard_sphere_run(np.zeros(5), v0, [0.0], restitution=e)
    v = r.v[0]
    assert v.sum() == pytest.approx(2.0, rel=1e-14)
    assert np.all(np.diff(v) >= -1e-14)
    assert 0.5 * (v0 @ v0) - 0.5 * (v @ v) == pytest.approx(r.dissipated[0], rel=1e-12, abs=1e-15)
    if e == 1.0:
        assert v.tolist() == [0.0, 0.0, 0.0, 1.0, 1.0]
