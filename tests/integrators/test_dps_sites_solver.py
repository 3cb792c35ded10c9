"""integrate_dps(..., sites=...): (dpsimperfect) through kind 5 of the numba DOP853 (and scipy's DOP853) against
(dfnls), exact rotations and plane waves, and its two invariants on a disordered, precompressed ring."""
from __future__ import annotations

import numpy as np
import pytest

from cradle.integrators import integrate_dps
from cradle.models import dps_sites as S
from cradle.models.dps import plane_wave, tau0


@pytest.mark.parametrize("bc", ["periodic", "free"])
def test_homogeneous_sites_are_today_s_dps(bc):
    rng = np.random.default_rng(0)
    A0 = rng.normal(size=10) + 1j * rng.normal(size=10)
    tau = np.linspace(0.0, 2.0, 5)
    ref = integrate_dps(A0, tau, alpha=1.5, bc=bc, rtol=1e-12)
    got = integrate_dps(A0, tau, alpha=1.5, bc=bc, rtol=1e-12, sites=S.homogeneous(10))
    assert got.sites is not None and ref.sites is None
    assert np.max(np.abs(got.A - ref.A)) < 1e-12 * np.max(np.abs(A0))


def test_isolated_sites_turn_at_their_own_frequency():
    """A gap larger than every swing (delta~ < -2 |A_{n+1} - A_n|): no contact, each bead rotates at
    delta_n + (3/2) beta~_n |A_n|^2 exactly."""
    rng = np.random.default_rng(5)
    N = 6
    A0 = 0.5 * np.exp(2j * np.pi * rng.uniform(size=N))
    sites = S.dps_sites(rng.uniform(0.8, 1.2, N), 1.0 + 0.05 * rng.normal(size=N), np.ones(N), alpha=1.5, eps=0.01,
                        beta=rng.uniform(-1, 1, N), delta0=-0.01 * 2.5)   # delta~ = -2.5 < -2 max|D| = -2
    tau = np.linspace(0.0, 5.0, 6)
    sol = integrate_dps(A0, tau, alpha=1.5, rtol=1e-12, sites=sites)
    rot = sites.detuning + 1.5 * sites.beta * np.abs(A0) ** 2
    exact = A0 * np.exp(1j * rot * tau[:, None])
    assert np.max(np.abs(sol.A - exact)) < 1e-10


@pytest.mark.parametrize("delta", [0.0, 0.8, 3.0])
def test_uniformly_detuned_plane_wave(delta):
    """A_n = R e^{i (Omega tau - q n)} e^{i delta tau}, Omega = |sin(q/2)| g(2 R |sin(q/2)|; delta~) / (tau0 R):
    (ds) at delta~ = 0, 2 kappa~ sin^2(q/2) for delta~ >> R (the linear band of the precompressed chain)."""
    N, q, R, det = 16, 2 * np.pi * 3 / 16, 0.6, 0.37
    s = abs(np.sin(q / 2))
    sites = S.DpsSites(np.full(N, det), np.ones(N), np.ones(N), np.zeros(N), np.full(N, delta))
    g, _ = S.coupling(2 * R * s, delta, 1.5)
    Om = s * float(g) / (tau0(1.5) * R)
    n = np.arange(N)
    tau = np.linspace(0.0, 4.0, 5)
    sol = integrate_dps(R * np.exp(-1j * q * n), tau, alpha=1.5, rtol=1e-12, sites=sites)
    exact = R * np.exp(1j * (Om * tau[:, None] - q * n)) * np.exp(1j * det * tau[:, None])
    assert np.max(np.abs(sol.A - exact)) < 1e-9
    if delta == 0.0:
        np.testing.assert_allclose(sol.A, plane_wave(n, tau[:, None], R, q, 0.0, 1.5)
                                   * np.exp(1j * det * tau[:, None]), atol=1e-9)


@pytest.mark.parametrize("method", ["dop853_numba", "dop853"])
def test_disordered_precompressed_ring_conserves_its_invariants(method):
    rng = np.random.default_rng(9)
    N = 12
    sites = S.dps_sites(rng.uniform(0.8, 1.25, N), 1.0 + 0.02 * rng.normal(size=N), rng.uniform(0.6, 1.4, N),
                        alpha=1.5, eps=0.01, beta=0.5, delta0=0.008)   # delta~_n ~ 0.8: contacts open and close
    A0 = rng.normal(size=N) + 1j * rng.normal(size=N)
    sol = integrate_dps(A0, np.linspace(0.0, 3.0, 4), alpha=1.5, rtol=1e-12, method=method, sites=sites)
    assert sol.max_l2_drift < 1e-10
    assert sol.max_energy_drift < 1e-8
    assert sol.l2 is not None and sol.energy is not None
    assert sol.l2[-1] == pytest.approx(S.l2_weighted(sol.A[-1], sites), rel=1e-13)
    assert sol.energy[-1] == pytest.approx(S.hamiltonian(sol.A[-1], 1.5, sites), rel=1e-11)
    # the run moved: the invariants are not trivially constant
    assert np.max(np.abs(sol.A[-1] - A0)) > 0.1


def test_imperfect_lattice_follows_dpsimperfect_at_order_eps_alpha():
    """The consistency law of (ansatz): sup_{t <= T eps^(1-alpha)} max_n |x_n - x_n^app| = O(eps^alpha) for the
    imperfect lattice (ncimperfect) (detuned, disordered masses and stiffnesses, precompressed) against
    (dpsimperfect) with coefficients fixed in slow units; (dfnls) without the imperfections misses them at O(eps)."""
    from cradle.integrators import integrate_lattice
    from cradle.measurements.damped_validity import sup_error
    from cradle.models.inhomogeneity import Inhomogeneity
    from cradle.models.lattice_terms import Terms
    from cradle.models.precompression import Precompression

    alpha, N = 1.5, 8
    n = np.arange(N)
    A0 = (1.0 + 0.3 * np.cos(2 * np.pi * n / N)) * np.exp(-1j * np.pi / 4 * n) / 1.3
    rng = np.random.default_rng(4)
    det, mass, k = 0.3 * rng.normal(size=N), 1.0 + 0.1 * rng.normal(size=N), 1.0 + 0.2 * rng.normal(size=N)
    errors, plain = [], []
    for eps in (0.008, 0.002):
        omega = 1.0 + det * eps ** (alpha - 1)
        sites = S.dps_sites(mass, omega, k, alpha=alpha, eps=eps, delta0=eps)
        terms = Terms(inhomogeneity=Inhomogeneity(omega=tuple(omega), mass=tuple(mass), stiffness=tuple(k)),
                      precompression=Precompression(delta0=eps))
        x0 = 2 * eps * A0.real
        v0 = 2 * eps * (1j * A0 + eps ** (alpha - 1) * S.rhs(A0, alpha, sites)).real
        t = np.linspace(0.0, eps ** (1 - alpha), int(np.ceil(eps ** (1 - alpha) / 0.05)) + 1)
        lat = integrate_lattice(x0, v0, t, alpha=alpha, method="dop853_numba", rtol=1e-11, terms=terms)
        tau = eps ** (alpha - 1) * t
        errors.append(sup_error(t, lat.x, integrate_dps(A0, tau, alpha=alpha, rtol=1e-11, sites=sites).A, eps,
                                alpha, [1.0])["abs_error"][0])
        plain.append(sup_error(t, lat.x, integrate_dps(A0, tau, alpha=alpha, rtol=1e-11).A, eps, alpha,
                               [1.0])["abs_error"][0])
    power = np.log(errors[0] / errors[1]) / np.log(4.0)
    assert 1.3 < power < 1.7, (errors, power)
    assert min(p / e for p, e in zip(plain, errors, strict=True)) > 3.0, (plain, errors)
