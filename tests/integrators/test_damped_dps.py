"""integrate_dps with dissipation (dpsdamped): exact reductions and closed forms, the balance laws along a run,
and the undamped path unchanged."""
import numpy as np
import pytest

from cradle.integrators import integrate_dps
from cradle.models import dps, dps_damped as DD

ALPHA = 1.5
N = 12
n = np.arange(N)
#: a modulated wave: every bond active, amplitudes of order one
A0 = (1.0 + 0.3 * np.cos(2 * np.pi * n / N)) * np.exp(-1j * np.pi / 3 * n)


@pytest.mark.parametrize("eta, method", [(0.0, "dop853"), (0.4, "dop853"), (0.4, "dop853_numba")])
def test_onsite_damping_is_the_undamped_run_in_a_rescaled_time(eta, method):
    # A(tau) = e^{-gamma tau/2} B(s(tau)), B the run without gamma (dfnls for eta = 0), s of onsite_reduction
    gamma = 0.8
    tau = np.linspace(0.0, 6.0, 13)
    damped = integrate_dps(A0, tau, alpha=ALPHA, method=method, rtol=1e-12,
                           damping=DD.DpsDamping(gamma=gamma, eta=eta))
    decay, s = DD.onsite_reduction(tau, gamma, ALPHA)
    assert s[-1] < 2.0 / ((ALPHA - 1) * gamma)
    B = integrate_dps(A0, s, alpha=ALPHA, method=method, rtol=1e-12,
                      damping=None if eta == 0.0 else DD.DpsDamping(eta=eta))
    assert np.max(np.abs(damped.A - decay[:, None] * B.A)) < 1e-9 * np.max(np.abs(A0))
    assert np.max(np.abs(damped.A[-1])) < 0.2 * np.max(np.abs(A0))   # the damping acted


def test_contact_damping_of_a_plane_wave_closed_form():
    # A_n = R e^{i phi} e^{-iqn}: R' = -Im(kappa) Om R^alpha, phi' = Re(kappa) Om R^(alpha-1), Om tau0 = 2^alpha
    # |sin(q/2)|^(alpha+1) (ds), so R^(1-alpha) = 1 + (alpha-1) Im(kappa) Om tau, phi = Re/Im kappa log(...)/(alpha-1)
    eta, q = 0.5, 4 * np.pi / 5
    Nw = 10
    tau = np.linspace(0.0, 5.0, 11)
    sol = integrate_dps(np.exp(-1j * q * np.arange(Nw)), tau, alpha=ALPHA, rtol=1e-12,
                        damping=DD.DpsDamping(eta=eta))
    kap = DD.contact_factor(eta, ALPHA)
    Om = dps.plane_wave_frequency(1.0, q, ALPHA)
    w = 1.0 + (ALPHA - 1) * kap.imag * Om * tau
    exact = w[:, None] ** (-1 / (ALPHA - 1)) * np.exp(1j * (kap.real / kap.imag * np.log(w)[:, None] / (ALPHA - 1)
                                                           - q * np.arange(Nw)))
    assert np.max(np.abs(sol.A - exact)) < 1e-10
    assert abs(sol.A[-1, 0]) < 0.5


@pytest.mark.parametrize("method", ["dop853_numba", "dop853", "rk45"])
def test_balance_laws_along_a_run(method):
    # the dissipated amounts integrated with the run against the change of l2 and H, and against an independent
    # quadrature of the rates of (dpsdamped) along the output; P = sum A_n decays exactly as e^{-gamma tau/2}
    damping = DD.DpsDamping(gamma=0.3, eta=0.2)
    tau = np.linspace(0.0, 4.0, 401)
    sol = integrate_dps(A0, tau, alpha=ALPHA, method=method, rtol=1e-11, damping=damping)
    assert sol.max_l2_drift < 1e-8 and sol.max_energy_drift < 1e-8 and np.max(sol.P_drift) < 1e-8
    l2 = dps.l2_norm_squared(sol.A)
    H = dps.hamiltonian(sol.A, ALPHA)
    assert np.max(np.abs(l2 - sol.l2)) < 1e-13 * l2[0]
    assert np.max(np.abs(H - sol.energy)) < 1e-13 * abs(H[0])
    assert np.all(np.diff(sol.l2) < 0) and np.all(np.diff(sol.energy) > 0)
    h = tau[1] - tau[0]

    def simpson(f):
        return h / 3 * (f[0] + 4 * f[1:-1:2].sum() + 2 * f[2:-1:2].sum() + f[-1])

    lost_l2 = -simpson(DD.l2_rate(sol.A, ALPHA, damping))
    gained_H = simpson(DD.energy_rate(sol.A, ALPHA, damping))
    assert lost_l2 == pytest.approx(l2[0] - l2[-1], rel=1e-8)
    assert gained_H == pytest.approx(H[-1] - H[0], rel=1e-8)
    assert sol.l2_dissipated[-1] == pytest.approx(lost_l2, rel=1e-8)
    assert sol.damping == damping and sol.method == method


@pytest.mark.parametrize("method", ["dop853_numba", "dop853"])
def test_damping_off_is_the_undamped_run_bitwise(method):
    tau = np.linspace(0.0, 3.0, 7)
    plain = integrate_dps(A0, tau, alpha=ALPHA, method=method)
    for off in (None, DD.DpsDamping()):
        sol = integrate_dps(A0, tau, alpha=ALPHA, method=method, damping=off)
        assert np.array_equal(sol.A, plain.A) and np.array_equal(sol.l2_drift, plain.l2_drift)
        assert sol.n_steps == plain.n_steps and sol.l2 is None and sol.damping is None


def test_bad_damping_is_refused_in_one_line():
    with pytest.raises(ValueError, match="damping.gamma = -1"):
        integrate_dps(A0, [0.0, 1.0], alpha=ALPHA, damping=DD.DpsDamping(gamma=-1.0))
    from cradle.models.damping import Damping

    with pytest.raises(ValueError, match="DpsDamping"):
        integrate_dps(A0, [0.0, 1.0], alpha=ALPHA, damping=Damping(onsite=0.1))
