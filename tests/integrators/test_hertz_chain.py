"""The Hertz chain without on-site potential (cradle.integrators.lattice_adaptive.run_dop853_hertz_chain: the
on-site slot's absent unit NoOnsite): closed forms of two touching beads and the chain's invariants.

Two equal beads meeting at speed v: Hertz's collision lasts t_c = 2 I delta_max / v (Landau & Lifshitz;
cradle.models.desk_toy.collision_time_nc) and, without an on-site force, exchanges the velocities exactly
(an elastic collision of equal masses); the total momentum is conserved throughout and so is the energy.
"""
from __future__ import annotations

import numpy as np
import pytest

from cradle.integrators.lattice_adaptive import run_dop853_hertz_chain
from cradle.integrators.terms import onsite_none
from cradle.integrators.terms.slots import onsite_energy, onsite_force, position
from cradle.models.desk_toy import collision_time_nc


def test_absent_unit_has_no_force_and_no_energy():
    unit = onsite_none.NoOnsite()
    assert position(unit, 3, 2.5) == (2.5, 1.0)
    assert onsite_force(unit, 2.5, 2.5) == 0.0
    assert onsite_energy(unit, 3, 2.5) == 0.0


@pytest.mark.parametrize("v", [1.0, 1e6])
def test_two_beads_exchange_velocities_after_hertz_time(v):
    tc = collision_time_nc(v)
    t = np.linspace(0.0, 1.5 * tc, 3001)
    X, V, E, drift, *_ = run_dop853_hertz_chain(np.zeros(2), np.array([v, 0.0]), t, 1e-13, 1e-13 * v * tc, 1.5,
                                                False)
    # contact ends when the bond's compression x_0 - x_1 returns to 0: measured between stored times
    c = X[:, 0] - X[:, 1]
    i = int(np.flatnonzero((c[:-1] > 0.0) & (c[1:] <= 0.0))[0])
    t_end = t[i] + c[i] / (c[i] - c[i + 1]) * (t[i + 1] - t[i])
    assert t_end == pytest.approx(tc, rel=1e-6)   # linear interpolation over a step of tc/2000: error ~ 1e-7
    assert V[-1, 0] == pytest.approx(0.0, abs=1e-10 * v)
    assert V[-1, 1] == pytest.approx(v, rel=1e-10)
    assert np.allclose(V.sum(axis=1), v, rtol=1e-12)
    assert drift < 1e-11
    assert np.allclose(E, 0.5 * v**2, rtol=1e-11)
