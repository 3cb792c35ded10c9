"""The sup error of the damped DpS (dpsdamped) against the damped lattice (ncdamped), as dps-validity defines it:
the measurement on known data, and on a small reference lattice run (scipy's DOP853 on the numpy forces of
cradle.models.damping; the compiled damped lattice integrators are another module's)."""
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from cradle.integrators import integrate_dps
from cradle.measurements.compare import approximate_displacement
from cradle.measurements.damped_validity import sup_error
from cradle.models import damping as D, dps_damped as DD

ALPHA = 1.5


def test_sup_error_reads_the_running_sup_at_the_marks():
    eps, N = 0.04, 5
    t = np.linspace(0.0, 10.0, 1001)
    A = np.exp(-0.1 * eps ** (ALPHA - 1) * t)[:, None] * np.exp(1j * np.arange(N))[None, :]
    bump = 1e-4 * np.exp(-((t - 3.0) ** 2))   # the error peaks at t = 3 on bead 2
    x = approximate_displacement(A, t, eps)
    x[:, 2] += bump
    T = np.array([2.0, 1.0]) * eps ** (ALPHA - 1) * np.array([2.0, 5.0])   # t = 4 and t = 5, given unsorted
    m = sup_error(t, x, A, eps, ALPHA, T, v=np.real(2j * eps * A * np.exp(1j * t)[:, None]))
    assert np.allclose(m["t_mark"], [4.0, 5.0], rtol=1e-14)
    assert m["abs_error"] == pytest.approx([bump[300], bump[300]], rel=1e-10)   # x - x_app: rounding of x ~ 0.08
    assert np.array_equal(m["rel_error"], m["abs_error"] / (2 * eps))
    assert m["envelope_error"][0] == pytest.approx(np.max(bump[:401] / (2 * eps * np.abs(A[:401, 0]))), rel=1e-10)
    assert np.all(m["velocity_abs_error"] <= 4 * np.spacing(2 * eps))   # v given as the leading order: rounding
    early = sup_error(t, x, A, eps, ALPHA, [1.0 * eps ** (ALPHA - 1)])   # t = 1: before the bump
    assert early["abs_error"][0] == pytest.approx(bump[100], rel=1e-10)
    with pytest.raises(ValueError, match="ends at t"):
        sup_error(t, x, A, eps, ALPHA, [20.0])


def _lattice(x0, v0, t, damping):
    """(x, v) of (ncdamped) at t: scipy DOP853 on cradle.models.damping.acceleration (periodic ring)."""
    N = x0.size

    def f(_t, y):
        return np.concatenate([y[N:], D.acceleration(y[:N], y[N:], ALPHA, damping)])

    r = solve_ivp(f, (0.0, t[-1]), np.concatenate([x0, v0]), method="DOP853", t_eval=t, rtol=1e-10,
                  atol=1e-12 * np.max(np.abs(x0)))
    assert r.success
    return r.y[:N].T, r.y[N:].T


def test_damped_dps_describes_the_damped_lattice_to_order_eps_alpha():
    # gamma~ = 2 (gamma = 2 eps^(alpha-1)), eta = 0.1: at T = 1/2 the wave has lost 1 - e^{-1/2} of its amplitude;
    # the damped DpS error is O(eps^alpha) (consistency of (ansatz), docs/damped-dps.md), the undamped one O(eps)
    N = 16
    n = np.arange(N)
    A0 = (1.0 + 0.3 * np.cos(2 * np.pi * n / N)) * np.exp(-1j * np.pi / 4 * n)
    A0 /= np.max(np.abs(A0))
    errors, eps_list = [], [0.01, 0.0025]
    for eps in eps_list:
        lattice_damping = D.Damping(onsite=2.0 * eps ** (ALPHA - 1), contact=0.1)
        slow = DD.slow_damping(lattice_damping, eps, ALPHA)
        x0, v0 = DD.lattice_state(A0, eps, ALPHA, slow)
        t_end = 0.5 * eps ** (1 - ALPHA)
        t = np.linspace(0.0, t_end, int(np.ceil(t_end / 0.05)) + 1)   # the sup on samples every 0.05
        x, v = _lattice(x0, v0, t, lattice_damping)
        damped = sup_error(t, x, integrate_dps(A0, eps ** (ALPHA - 1) * t, alpha=ALPHA, rtol=1e-11, damping=slow).A,
                           eps, ALPHA, [0.5])
        undamped = sup_error(t, x, integrate_dps(A0, eps ** (ALPHA - 1) * t, alpha=ALPHA, rtol=1e-11).A,
                             eps, ALPHA, [0.5])
        # the damping is seen: without it the DpS misses the lost amplitude, an error O(eps), eps^(1-alpha)
        # (>= 10) times the O(eps^alpha) of the damped DpS
        assert damped["abs_error"][0] < eps ** (ALPHA - 1) * undamped["abs_error"][0]
        errors.append(damped["abs_error"][0])
    # the power of eps between the two: alpha, up to the next order's relative eps^(alpha-1) (<= 0.1: a shift of
    # the local exponent by about log(1.1)/log(4) = 0.07)
    p = np.log(errors[0] / errors[1]) / np.log(eps_list[0] / eps_list[1])
    assert abs(p - ALPHA) < 0.1
