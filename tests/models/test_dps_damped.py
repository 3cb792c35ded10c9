"""The damped DpS equation (dpsdamped): the averaged damping terms of (ncdamped) against a quadrature over one
fast period of the lattice forces, the closed form of the clipped contact factor, the balance laws."""
import numpy as np
import pytest
from scipy.integrate import quad

from cradle.integrators import dps_damped_solver
from cradle.integrators.systems import dps as SD
from cradle.models import damping as D, dps, dps_damped as DD


def _harmonic_of_damping(A, eps, alpha, damping):
    """(1/2pi) int_0^{2pi} [acceleration of (ncdamped) + x] e^{-it} dt on x = eps (A e^{it} + c.c.),
    v = eps (i A e^{it} + c.c.) (periodic ring), by quad between the kinks of every bond force."""
    N = A.size
    D_ = np.roll(A, -1) - A
    theta = np.angle(D_)
    u_clip = np.arctan2(1.0, damping.contact) if damping.contact > 0 else np.pi / 2
    # bond n is in contact for u = t + theta_n - pi in (-pi/2, pi/2), clipped from u_clip on
    kinks = np.concatenate([np.pi - theta + u for u in (-np.pi / 2, np.pi / 2, u_clip)]) % (2 * np.pi)
    edges = np.unique(np.concatenate([[0.0, 2 * np.pi], kinks]))

    def force(t):
        z = A * np.exp(1j * t)
        x, v = 2 * eps * z.real, 2 * eps * (1j * z).real
        return D.acceleration(x, v, alpha, damping) + x

    out = np.zeros(N, dtype=complex)
    for n in range(N):
        for part, fn in ((1.0, np.cos), (-1j, np.sin)):
            tot = sum(quad(lambda t, n=n, fn=fn: force(t)[n] * fn(t), a, b, epsabs=1e-15, epsrel=1e-13, limit=200)[0]
                      for a, b in zip(edges[:-1], edges[1:], strict=True))
            out[n] += part * tot / (2 * np.pi)
    return out


@pytest.mark.parametrize("alpha, gamma, eta", [(1.5, 0.0, 0.4), (1.5, 0.3, 0.0), (2.0, 0.1, 1.5), (3.0, 0.2, 0.05)])
def test_averaged_damping_terms_against_quadrature_over_a_fast_period(alpha, gamma, eta):
    # the first harmonic of the forces of (ncdamped) on the ansatz is exactly (homogeneity of degree alpha)
    # eps^alpha 2^(alpha-1) c_alpha kappa L_n - i gamma eps A_n: the right-hand side of (calculapp) with damping
    rng = np.random.default_rng(7)
    A = rng.normal(size=5) + 1j * rng.normal(size=5)
    eps = 0.01
    got = _harmonic_of_damping(A, eps, alpha, D.Damping(onsite=gamma, contact=eta))
    kappa = DD.contact_factor(eta, alpha)
    expected = eps**alpha * 2 ** (alpha - 1) * dps.c_alpha(alpha) * kappa * dps.p_laplacian(A, alpha) \
        - 1j * gamma * eps * A
    assert np.max(np.abs(got - expected)) < 1e-10 * np.max(np.abs(expected))


@pytest.mark.parametrize("alpha", [1.1, 1.5, 2.0, 3.0])
def test_contact_factor_small_eta_expansion(alpha):
    # the clipping enters at relative order eta^alpha: Im kappa = eta/alpha - eta^(alpha+1)/(alpha (alpha+1) W),
    # Re kappa = 1 + eta^(alpha+2)/((alpha+1)(alpha+2) W), W = pi c_alpha, each up to a relative O(eta^2) = 1e-4
    # (eta = 1e-2 keeps Re kappa - 1 >= 4e-12, far above the rounding of 1)
    eta = 1e-2
    W = np.pi * dps.c_alpha(alpha)
    kappa = DD.contact_factor(eta, alpha)
    assert kappa.imag - eta / alpha == pytest.approx(-eta ** (alpha + 1) / (alpha * (alpha + 1) * W), rel=1e-3, abs=0)
    assert kappa.real - 1.0 == pytest.approx(eta ** (alpha + 2) / ((alpha + 1) * (alpha + 2) * W), rel=1e-3, abs=0)
    assert DD.contact_factor(0.0, alpha) == 1.0
    assert DD.contact_factor_unclipped(eta, alpha) == complex(1.0, eta / alpha)


def test_contact_factor_refuses_negative_eta():
    with pytest.raises(ValueError, match="eta"):
        DD.contact_factor(-0.1, 1.5)


@pytest.mark.parametrize("bc", ["periodic", "free"])
def test_kernel_is_the_reference_and_the_balance_laws_hold_pointwise(bc):
    alpha = 1.5
    damping = DD.DpsDamping(gamma=0.7, eta=0.3)
    rng = np.random.default_rng(3)
    A = rng.normal(size=9) + 1j * rng.normal(size=9)
    ref = DD.rhs(A, alpha, damping, bc)
    t0 = dps.tau0(alpha)
    y = np.concatenate([A.view(np.float64), [0.0, 0.0]])
    dy = np.empty_like(y)
    SD.dps_rhs(dps_damped_solver.system(damping, alpha, 0.5 / t0, bc == "periodic"), y, dy)
    assert np.max(np.abs(dy[:-2].view(np.complex128) - ref)) < 1e-14 * np.max(np.abs(ref))
    # d/dtau sum |A|^2 = 2 Re sum conj(A) A'
    l2_dot = 2 * np.sum((np.conj(A) * ref).real)
    assert DD.l2_rate(A, alpha, damping, bc) == pytest.approx(l2_dot, rel=1e-13)
    assert -dy[-2] == pytest.approx(l2_dot, rel=1e-13)
    # d/dtau H by the chain rule on the bonds: dS/dtau = (alpha+1) Re sum |D|^(alpha-1) conj(D) D'
    Dn, Dn_dot = dps.differences(A, bc), dps.differences(ref, bc)
    S_dot = (alpha + 1) * np.sum((np.abs(Dn) ** (alpha - 1) * np.conj(Dn) * Dn_dot).real)
    H_dot = -S_dot / ((alpha + 1) * t0)
    assert DD.energy_rate(A, alpha, damping, bc) == pytest.approx(H_dot, rel=1e-12)
    assert dy[-1] == pytest.approx(-S_dot, rel=1e-12)
    assert l2_dot < 0 < H_dot


def test_slow_damping_scales_gamma_not_eta():
    d = DD.slow_damping(D.Damping(onsite=0.01, contact=0.2), 1e-4, 1.5)
    assert d.gamma == pytest.approx(0.01 * 1e-4 ** -0.5, rel=1e-15) and d.eta == 0.2
    with pytest.raises(ValueError, match="eps"):
        DD.slow_damping(D.Damping(), 0.0, 1.5)
