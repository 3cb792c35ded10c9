"""The damping terms of (ncdamped) (cradle.models.damping): their power is what the energy (ham) loses, it is never
negative, and the contact force never pulls."""
import numpy as np
import pytest

from cradle.models import damping as D, lattice as L


@pytest.mark.parametrize("bc", ["periodic", "free"])
def test_the_energy_decreases_at_the_dissipated_power(bc):
    """dH/dt = sum v_n (x_n'' + x_n) + sum f_n (v_{n+1} - v_n) along (ncdamped) equals -P, on random states
    (compressed, separating and clipped bonds alike)."""
    rng = np.random.default_rng(1)
    d = D.Damping(onsite=0.1, contact=0.7)
    for _ in range(20):
        x, v = rng.normal(size=12) * 0.3, rng.normal(size=12) * 0.3
        a = D.acceleration(x, v, 1.5, d, bc)
        rate = np.roll(v, -1) - v
        if bc == "free":
            rate[-1] = 0.0
        dH = np.sum(v * (a + x)) + np.sum(L.bond_forces(x, 1.5, bc) * rate)
        P = D.dissipated_power(x, v, 1.5, d, bc)
        assert P >= 0.0
        assert dH == pytest.approx(-P, rel=1e-12, abs=1e-15)


def test_the_contact_force_pushes_and_is_clipped_at_zero():
    """g = -max(c^alpha + eta c^(alpha-1) c', 0) on a compressed bond: Kuwabara-Kono while pushing, zero where the
    damping would pull, zero on an open bond."""
    x = np.array([0.0, -0.04, 0.3])        # bond 0 compressed by 0.04, bond 1 open, bond 2 (ring) compressed by 0.3
    for v, expect0 in ((np.array([0.0, -0.1, 0.0]), -(0.04**1.5 + 0.5 * 0.04**0.5 * 0.1)),
                       (np.array([0.0, 1.0, 0.0]), 0.0)):   # separating fast: clipped
        g = D.bond_forces(x, v, 1.5, 0.5, "periodic")
        assert g[0] == pytest.approx(expect0, rel=1e-14, abs=0.0)
        assert g[1] == 0.0 and np.all(g <= 0.0)


def test_no_damping_is_the_conservative_lattice():
    rng = np.random.default_rng(2)
    x, v = rng.normal(size=9), rng.normal(size=9)
    np.testing.assert_array_equal(D.acceleration(x, v, 1.5, D.NONE, "free"), L.acceleration(x, 1.5, "free"))
    assert D.dissipated_power(x, v, 1.5, D.NONE) == 0.0 and not D.NONE.active
