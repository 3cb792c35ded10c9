"""Initial data (ansatzapprox)/(perturb) and comparison tools (ansatz), E(t), the DFT on Gamma*."""
import numpy as np
import pytest

from cradle.measurements import compare
from cradle.models import dps, initial


def test_travelling_wave_matches_ansatzapprox():
    q, N = np.pi / 5, 50
    d = initial.travelling_wave(N, q, 1.5, omega_tw=1.1)
    n = np.arange(N)
    a, w = d.info["a"], d.info["omega_tw"]
    # x_n(t) = a cos(q n - omega t): x(0) = a cos(qn), v(0) = a omega sin(qn)
    assert d.x0 == pytest.approx(a * np.cos(q * n), abs=1e-14 * a)
    assert d.v0 == pytest.approx(a * w * np.sin(q * n), abs=1e-13 * a)
    assert d.eps == pytest.approx(a / 2)


def test_noise_is_reproducible_from_seed_and_bounded():
    d1 = initial.travelling_wave(50, np.pi / 5, 1.5, omega_tw=1.01, noise_kind="uniform", noise_amplitude=0.5, seed=7)
    d2 = initial.travelling_wave(50, np.pi / 5, 1.5, omega_tw=1.01, noise_kind="uniform", noise_amplitude=0.5, seed=7)
    d3 = initial.travelling_wave(50, np.pi / 5, 1.5, omega_tw=1.01, noise_kind="uniform", noise_amplitude=0.5, seed=8)
    assert np.array_equal(d1.x0, d2.x0) and np.array_equal(d1.v0, d2.v0)
    assert not np.array_equal(d1.x0, d3.x0)
    assert np.max(np.abs(d1.rho1)) <= 0.5 and np.max(np.abs(d1.rho2)) <= 0.5
    n = np.arange(50)
    # (perturb): A = (1 + rho1) cos(qn) - i (1 + rho2) sin(qn)
    assert d1.A0.real == pytest.approx((1 + d1.rho1) * np.cos(np.pi / 5 * n))


def test_exactly_one_of_a_and_omega():
    with pytest.raises(ValueError, match="exactly one"):
        initial.travelling_wave(50, np.pi / 5, 1.5, a=0.1, omega_tw=1.1)
    with pytest.raises(ValueError, match="exactly one"):
        initial.travelling_wave(50, np.pi / 5, 1.5)


def test_ansatz_rebuilds_plane_wave_as_travelling_wave():
    # eps (A e^{it} + cc) with A from (ansatz3) is a cos(q n - omega_tw t) (ansatzapprox)
    q, alpha, a = 4 * np.pi / 5, 1.5, 0.3
    eps = a / 2
    t = np.linspace(0, 50, 11)
    n = np.arange(30)
    tau = eps ** (alpha - 1) * t
    A = dps.plane_wave(n[None, :], tau[:, None], R=1.0, q=q, phi=0.0, alpha=alpha)
    x_app = compare.approximate_displacement(A, t, eps)
    w = dps.omega_tw(a, q, alpha)
    assert np.max(np.abs(x_app - a * np.cos(q * n[None, :] - w * t[:, None]))) < 1e-13
    assert np.all(compare.relative_error(x_app, x_app, a) == 0)


def test_spatial_dft_on_gamma_star():
    N = 200
    k = compare.gamma_star(N)
    assert k[0] == pytest.approx(2 * np.pi / N * (-N / 2 + 1)) and k[-1] == pytest.approx(np.pi)
    n = np.arange(N)
    q = 4 * np.pi / 5
    _, xh = compare.spatial_dft(np.cos(q * n))
    peaks = np.sort(k[np.argsort(np.abs(xh))[-2:]])
    assert peaks == pytest.approx([-q, q])
    assert np.max(np.abs(xh)) == pytest.approx(N / 2)
    # the definition, term by term, at one k
    j = 17
    assert xh[j] == pytest.approx(np.sum(np.cos(q * n) * np.exp(-1j * n * k[j])), abs=1e-9)


def test_a_kicked_end_bead_swings_alone_as_a_free_pendulum():
    """A free chain's first bead kicked away from the chain (velocity < 0) touches nothing until it swings
    back to x = 0 at t = pi: x_0(t) = v sin t exactly, the other beads at rest (kick of JKC 2013)."""
    from cradle.integrators import integrate_lattice
    from cradle.models.initial import kick

    v = -0.05
    data = kick(8, 1.5, velocity=v, site=0, bc="free")
    assert data.x0.tolist() == [0.0] * 8 and data.v0[0] == v and data.A0[0] == -0.5j * v
    t = np.linspace(0.0, 3.0, 31)
    sol = integrate_lattice(data.x0, data.v0, t, alpha=1.5, bc="free", method="dop853_numba", rtol=1e-12)
    np.testing.assert_allclose(sol.x[:, 0], v * np.sin(t), rtol=0, atol=1e-12 * abs(v))
    assert np.all(sol.x[:, 1:] == 0.0)
