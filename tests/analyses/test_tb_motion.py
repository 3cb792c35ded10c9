"""travelling-breathers, TBs in motion (issue 37, item 3): a DpS travelling breather launched in (nc) through
(ansatz), checked from mathematics.

One TB on a ring of 16 (the first member Newton finds from the pushed static breather), launched on a ring of 34:

* in (dfnls) on its own ring it moves one site per T: its position after k periods is k sites on, to the bound
  that its measured shift-map residual gives the centroid;
* in (nc) the energy is conserved far below the radiation measured (what is measured is no integration error);
* as eps -> 0 the lattice's velocity tends to the DpS TB's c eps^(alpha-1) with the order alpha - 1 that the
  terms (ansatz) leaves out give (relative order eps^(alpha-1)), within the fit's uncertainty.
"""
from __future__ import annotations

import numpy as np
import pytest

from cradle.analyses import travelling_breathers as tb
from cradle.analyses.travelling_breathers import dps_family, in_motion
from cradle.integrators import integrate_dps, integrate_lattice
from cradle.measurements import breather_motion as BM
from cradle.models import dps_travelling as M, lattice, tb_launch
from cradle.specs.declare import from_plain
from cradle.specs.values import Errors

ALPHA = 1.5


@pytest.fixture(scope="module")
def member():
    """The TB Newton finds from the static site breather pushed by kappa = 0.15 (c ~ 0.08), ring of 16."""
    from cradle.integrators import dps_travelling as DT

    phi, _ = dps_family.static_profiles(16, ALPHA, 1.0)["site"]
    A, T, theta = DT.start(phi, 0.15, ALPHA)
    b = DT.newton(A, T, theta, ALPHA, 1.0, tol=1e-11)
    assert b.converged
    return b


def _spec(**over):
    plain = {"N": 16, "check_N": [18], "check_rtol": [1e-12], "speeds": [0.06, 0.08, 0.1], "direct_speed": 0.08,
             "motion_speed": 0.08, "motion_eps": [0.01, 0.003, 0.001, 3e-4], "motion_sites": 12, "motion_ring": 34,
             "motion_samples": 8, **over}
    return from_plain(tb.TravellingBreathers, plain)


@pytest.fixture(scope="module")
def moved(member):
    spec = _spec()
    groups, attrs = in_motion.motion(spec, member, lambda *a: None)
    return spec, groups["/motion"][0], attrs


def test_embedded_puts_the_centre_at_n_over_2_and_is_a_roll_on_its_own_ring(member):
    A = tb_launch.embedded(member.A, 40)
    assert abs(M.centre(A[:16]) - 8) < 0.5 and np.all(A[16:] == 0)
    own = tb_launch.embedded(member.A, 16)
    k = int(np.argmax(np.abs(own))) - int(np.argmax(np.abs(member.A)))
    assert np.array_equal(own, np.roll(member.A, k))


def test_the_dps_tb_moves_one_site_per_period_to_its_residual(member):
    """On its own ring, A(kT) = e^{ik theta} S^k A(0) + dA with max|dA| = r_k max|A| (measured). The centroid over
    2 c + 1 sites moves by at most sum |n - p| |dw_n| / sum w <= 2c (2c + 1) 2 max|A| max|dA| / sum w."""
    per, S = 8, 6
    A0 = tb_launch.embedded(member.A, member.A.size)
    run = integrate_dps(A0, np.linspace(0, S * member.T, S * per + 1), alpha=ALPHA, rtol=1e-13)
    k = np.arange(S + 1)
    r = max(float(np.max(np.abs(run.A[j * per] - np.exp(1j * j * member.theta) * M.shift(A0, int(j))))) for j in k)
    assert r < 1e-8 * np.max(np.abs(A0))
    w = np.abs(run.A) ** 2
    p = BM.track(w, in_motion.MOTION_CORE)
    c = in_motion.MOTION_CORE
    bound = 2 * c * (2 * c + 1) * 2 * np.max(np.abs(A0)) * r / np.min(np.sum(w, axis=1)) * 1.01
    assert np.max(np.abs(p[k * per] - p[0] - k)) <= bound


def test_the_lattice_run_conserves_energy_far_below_the_radiation(member, moved):
    spec, data, attrs = moved
    drift = np.asarray(data["energy_drift"])
    assert np.all(drift < 1e-3 * np.min(data["radiation_end"]))
    # the stored drift is the integrator's; recomputed from the energy density at the last sample, too
    eps = spec.motion_eps[-1]
    ini = tb_launch.launch(member.A, eps, ALPHA, spec.motion_ring)
    sol = integrate_lattice(ini.x0, ini.v0, np.array([0.0, 3 * member.T / eps ** (ALPHA - 1)]), alpha=ALPHA)
    H0 = float(lattice.hamiltonian(ini.x0, ini.v0, ALPHA))
    assert abs(float(np.sum(BM.energy_density(sol.x[-1], sol.v[-1], ALPHA))) - H0) <= sol.energy_drift * H0 * 1.01


def test_the_speed_is_the_lattices_not_the_integrators(moved):
    """The largest eps rerun by DOP853 (another method, its own error control) gives the same speed to far below the
    deficit measured."""
    spec, data, attrs = moved
    assert float(attrs["motion_check_speed_difference"]) < 1e-3 * float(np.min(data["deficit"]))


def test_the_lattice_speed_tends_to_the_dps_one_with_order_alpha_minus_one(moved):
    spec, data, attrs = moved
    deficit = np.asarray(data["deficit"])
    assert np.all(deficit > 0) and np.all(np.diff(deficit) < 0)   # eps decreasing: the deficit shrinks
    p, u = float(attrs["motion_order"]), float(attrs["motion_order_uncertainty"])
    assert abs(p - (ALPHA - 1.0)) <= 3 * u
    assert u < 0.05     # an order that is measured, not a bound that says nothing


def test_the_dps_run_on_the_long_ring_travels_its_sites(member, moved):
    """The same start in (dfnls) on the long ring (the tail beyond the TB's own ring cut off) is after k periods the
    start shifted by k sites to the stored shift residual r, and its position k sites on to the centroid's bound
    for that r (as above, the norm sum w = 1); the norm is kept."""
    spec, data, attrs = moved
    c, amax = in_motion.MOTION_CORE, float(np.max(np.abs(member.A)))
    r = float(attrs["motion_dps_shift_residual"]) * amax
    assert r < 1e-5 * amax
    assert float(attrs["motion_dps_position_error"]) <= 2 * c * (2 * c + 1) * 2 * amax * r * 1.01
    assert float(data["dps_distance"][-1]) == pytest.approx(spec.motion_sites, abs=float(
        attrs["motion_dps_position_error"]) * 1.01)
    assert float(attrs["motion_dps_norm_drift"]) < 1e-10


def test_motion_keys_are_checked_in_one_line_each():
    spec = _spec(motion_speed=0.07, motion_eps=[0.01, 0.02, 0.001, 3e-4], motion_ring=20)
    out = Errors()
    spec.check(["beyond", "travelling-breathers"], None, out)
    for key in ("motion_speed", "motion_eps", "motion_ring"):
        assert sum(line.startswith(f"config error: beyond.travelling-breathers.{key} = ") for line in out.lines) == 1
