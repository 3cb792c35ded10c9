"""The desk-toy initial data (cradle.models.desk_toy): the released state in (nc), its refusals, and the
collision time over the swing period."""
from __future__ import annotations

import math

import numpy as np
import pytest

from cradle.models import desk_toy as dt, physical as ph
from cradle.specs.values import ConfigError

STEEL = ph.real_cradle("steel", 0.01, length=0.1)


@pytest.mark.parametrize("lifted", [1, 2, 3])
def test_the_lifted_balls_start_at_l_sin_theta_over_x_on_the_negative_side(lifted):
    x0, v0, s = dt.desk_toy_initial(dt.desk_toy(5, lifted, 20.0, STEEL))
    A = 0.1 * math.sin(math.radians(20.0)) / s.X
    np.testing.assert_allclose(x0[:lifted], -A, rtol=1e-15)
    assert np.all(x0[lifted:] == 0.0) and np.all(v0 == 0.0)
    assert s == ph.scales(STEEL)


@pytest.mark.parametrize("args, key", [((5, 5, 20.0), "lifted = 5"), ((5, 0, 20.0), "lifted = 0"),
                                       ((1, 1, 20.0), "n_beads = 1"), ((5, 1, 95.0), "angle_deg = 95.0"),
                                       ((5, 1, 90.0), "angle_deg = 90.0"), ((5, 1, 0.0), "angle_deg = 0.0"),
                                       ((5000, 1, 20.0), "n_beads = 5000")])
def test_bad_desk_toys_are_one_line_naming_key_and_value(args, key):
    with pytest.raises(ConfigError) as err:
        dt.desk_toy(*args, STEEL)
    assert len(str(err.value).splitlines()) == 1 and key in str(err.value)


def test_a_stiff_oscillator_has_no_angle():
    with pytest.raises(ConfigError, match="pendulum length"):
        dt.desk_toy(5, 1, 20.0, ph.real_cradle("steel", 0.01, omega0=100.0))


def test_the_collision_time_in_nc_is_the_si_one_over_the_time_scale():
    # the released balls meet the line at speed A in (nc), A X omega_0 in SI: one formula, two unit systems
    spec = dt.desk_toy(5, 1, 20.0, STEEL)
    x0, _, s = dt.desk_toy_initial(spec)
    v_si = -x0[0] * s.V
    assert dt.collision_time_nc(-x0[0]) * s.T == pytest.approx(ph.collision_time(STEEL, v_si), rel=1e-12)
    # t_c falls as v^(-1/5), and equivalent_amplitude inverts t_c(A) / (2 pi)
    assert dt.collision_time_nc(32.0) / dt.collision_time_nc(1.0) == pytest.approx(0.5, rel=1e-14)
    assert dt.equivalent_amplitude(dt.collision_fraction(spec)) == pytest.approx(-x0[0], rel=1e-12)
