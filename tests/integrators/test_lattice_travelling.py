"""Exact travelling breathers of (nc) (cradle.integrators.lattice_travelling), checked from mathematics.

The binary oscillation x_n = (-1)^n a(t) of (inteq) is an exact solution of (nc) on an even ring, and since
a(t + P/2) = -a(t) it is also a travelling wave modulo shift, x_n(t + P/2) = x_{n-1}(t), with P its period from the
(inteq) quadrature (theorem1.binary_period): Newton on the shooting map modulo shift at T = P/2 must find it from a
perturbed guess, with the energy of amplitude a0; an independent integrator confirms the shift-map residual; the
monodromy modulo shift is symplectic (multipliers in pairs mu, 1/mu) with the trivial pair at 1 (time shift and
energy); a direct run conserves the energy and stays a travelling wave.

A TB from the DpS ansatz (ring of 16, the c = 0.1 DpS member, eps = 0.005): Newton reaches a shift-map residual below
1e-10, confirmed at another tolerance of the contact-event DOP853; a direct run over several periods conserves the
energy and stays a TB; its multipliers come in the symplectic pairs mu, 1/mu; the compiled variational equations
give the monodromy of scipy's DOP853 over the project's right-hand side.
"""
from __future__ import annotations

import numpy as np
import pytest

from cradle.analyses import theorem1
from cradle.integrators import (
    dps_travelling as DT,
    integrate_lattice,
    lattice_breathers as LB,
    lattice_travelling as LT,
)

ALPHA, A0, N = 1.5, 0.8, 6


@pytest.fixture(scope="module")
def binary():
    T = theorem1.binary_period(A0, ALPHA) / 2.0
    exact = np.concatenate([A0 * (-1.0) ** np.arange(N), np.zeros(N)])
    guess = exact + 1e-3 * A0 * np.random.default_rng(1).standard_normal(2 * N)
    return T, exact, LT.newton(guess, T, ALPHA, reference=exact, tol=1e-12)


def test_unshift_inverts_the_shift():
    z = np.arange(2 * N, dtype=float)
    S = np.concatenate([np.roll(z[:N], 1), np.roll(z[N:], 1)])
    assert np.array_equal(LT.unshift(S), z)


def test_newton_finds_the_binary_oscillation(binary):
    T, exact, b = binary
    assert b.converged
    # the energy (ham) of x = a0 (-1)^n, v = 0: N a0^2/2 on the beads, (2 a0)^(alpha+1)/(alpha+1) on the N/2
    # compressed bonds
    H = N * A0**2 / 2 + (N // 2) * (2 * A0) ** (ALPHA + 1) / (ALPHA + 1)
    assert b.energy == pytest.approx(H, rel=1e-10)
    # the phase condition about the exact state removes the time shift: the state itself is found
    assert np.max(np.abs(b.z - exact)) <= 1e-9 * A0


def test_shift_map_residual_by_another_integrator(binary):
    T, _, b = binary
    run = integrate_lattice(b.z[:N], b.z[N:], [0.0, T], alpha=ALPHA, method="dop853_numba", rtol=1e-13)
    zT = np.concatenate([run.x[-1], run.v[-1]])
    assert LT.relative_residual(b.z, zT) <= 1e-10


def test_multipliers_symplectic_with_the_trivial_pair(binary):
    _, _, b = binary
    checks = LB.multiplier_checks(b.multipliers)
    # the time shift's Jordan block with the energy: two multipliers at 1, split by ~sqrt(rounding)
    assert checks["trivial"] < 1e-5
    assert checks["reciprocal"] < 1e-6
    assert checks["conjugate"] < 1e-8


def test_direct_run_conserves_energy_and_stays_a_travelling_wave(binary):
    _, _, b = binary
    run = LT.direct_run(b, 5)
    assert np.max(run["energy_drift"]) < 1e-11
    assert np.max(run["residual"]) < 1e-9


def test_compiled_monodromy_matches_scipy():
    """The compiled variational equations (systems.lattice_variational) against scipy's DOP853 over the project's
    right-hand side and Jacobian (lattice_breathers.flow): the same flow and monodromy to the tolerances' level."""
    T = theorem1.binary_period(A0, ALPHA) / 2.0
    z = np.concatenate([A0 * (-1.0) ** np.arange(N), np.zeros(N)])
    z = z + 1e-3 * A0 * np.random.default_rng(2).standard_normal(2 * N)
    M, zT = LT.monodromy(z, T, ALPHA, 1e-13)
    x, v, _, Phi = LB.flow(z[:N], z[N:], T, ALPHA, "periodic", np.eye(2 * N), 1e-13)
    assert np.max(np.abs(zT - np.concatenate([x, v]))) < 1e-11
    assert np.max(np.abs(M - LT.unshift(Phi))) < 1e-8 * np.max(np.abs(M))


@pytest.fixture(scope="module")
def from_ansatz():
    from cradle.analyses.travelling_breathers.dps_family import static_profiles

    phi, _ = static_profiles(16, ALPHA, 1.0)["site"]
    A, T, theta = DT.start(phi, 0.15, ALPHA)
    first = DT.newton(A, T, theta, ALPHA, 1.0)
    source = DT.continue_family(first, [0.1])[0][0]
    z, T_hop = LT.ansatz_start(source.A, source.T, ALPHA, 0.005)
    T, _ = LT.launch_period(z, T_hop, ALPHA)
    return LT.newton(z, T, ALPHA, tol=1e-11, max_iter=20)


@pytest.mark.slow
def test_tb_from_the_ansatz_solves_tbnc(from_ansatz):
    b = from_ansatz
    assert b.converged and b.residual <= 1e-10
    # the same state through the contact-event DOP853 at another tolerance (another step sequence)
    assert LT.relative_residual(b.z, LT.flow(b.z, b.T, ALPHA, 1e-13)) <= 1e-10
    # a TB, not the rest state: eps of the ansatz at its amplitude near the start's
    assert b.eps == pytest.approx(0.005, rel=0.05)


@pytest.mark.slow
def test_tb_from_the_ansatz_direct_run(from_ansatz):
    """Three periods run one after the other: the energy kept, and after k periods the start shifted by k sites
    (the residual may grow with k by the integrator's error and the multipliers' departure from the unit circle)."""
    run = LT.direct_run(from_ansatz, 3)
    # each period is some 1e4 steps at rtol 1e-14: the energy may move by 1e-11 a period, not grow faster
    assert np.all(run["energy_drift"][1:] < 1e-11 * run["k"][1:])
    assert np.max(run["residual"]) < 1e-9


@pytest.mark.slow
def test_tb_from_the_ansatz_multipliers_symplectic(from_ansatz):
    checks = LB.multiplier_checks(from_ansatz.multipliers)
    # the monodromy from the variational equations at rtol 1e-13, its multipliers paired to that level
    assert checks["reciprocal"] < 1e-6
    assert checks["conjugate"] < 1e-8
    # four at 1 (time shift and energy; the carrier's phase and the wave action), the others well away
    d = np.sort(np.abs(from_ansatz.multipliers - 1.0))
    assert d[3] < 1e-3 < d[4]
