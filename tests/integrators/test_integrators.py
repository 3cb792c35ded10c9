"""Tests of cradle.integrators: splittings and scipy baselines for (nc)/(meca), DOP853 for (dfnls).

Exact references: the q = 0 in-phase oscillation (no contact, pure rotation),
the binary oscillation x_n = (-1)^n a(t) of (inteq), the two-bead chain
(reduced to one scalar ODE), and the plane waves (ansatz3)/(ds) of (dfnls).
"""
from __future__ import annotations

import time
from itertools import pairwise

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from cradle.integrators import (
    CORRECTED_METHODS,
    DEFAULT_DT_FACTOR,
    _kernels as K,
    _onset_impulse as OI,
    compression_bounds,
    integrate_dps,
    integrate_lattice,
    omega_max,
)
from cradle.integrators._coefficients import SPLITTINGS
from cradle.integrators.systems import dps as SD
from cradle.models import dps as D, lattice as L
from cradle.models.dps import amplitude_from_omega

ORDERS = {"strang": 2, "srkn4": 4, "srkn6": 6}


def wave(N, q, a, omega):
    """Travelling wave (ansatzapprox) at t = 0: x_n = a cos(qn), v_n = a omega sin(qn)."""
    n = np.arange(N)
    return a * np.cos(q * n), a * omega * np.sin(q * n)


def smooth_state(seed=1, N=8, amp=0.5):
    rng = np.random.default_rng(seed)
    return amp * rng.uniform(-1, 1, N), amp * rng.uniform(-1, 1, N)


@pytest.fixture(scope="module")
def tw11():
    """N = 50, q = pi/5, omega_tw = 1.1 (a = 2.118) travelling wave (figure plot6-7)."""
    q = np.pi / 5
    a = amplitude_from_omega(1.1, q, 1.5)
    return wave(50, q, a, 1.1) + (a,)


# ---------------------------------------------------------------- coefficients

@pytest.mark.parametrize("method", list(SPLITTINGS))
def test_coefficients_consistent_and_symmetric(method):
    a, b, order = SPLITTINGS[method]
    assert order == ORDERS[method]
    assert b.size == a.size + 1
    assert abs(a.sum() - 1.0) < 1e-14
    assert abs(b.sum() - 1.0) < 1e-14
    np.testing.assert_array_equal(a, a[::-1])
    np.testing.assert_array_equal(b, b[::-1])


def test_kernels_match_reference_formulas():
    """Force, energy (ham) and the Jacobian agree with cradle.models.lattice / finite differences."""
    rng = np.random.default_rng(3)
    x, v = rng.standard_normal(7), rng.standard_normal(7)
    for bc in ("periodic", "free"):
        for alpha in (1.5, 2.3):
            mode = K.mode_flag("hertz", alpha)
            per = bc == "periodic"
            f, F = np.empty(7), np.empty(7)
            K.forces(x, f, F, alpha, mode, per)
            np.testing.assert_allclose(f, L.bond_forces(x, alpha, bc), rtol=1e-14, atol=1e-15)
            np.testing.assert_allclose(F - x, L.acceleration(x, alpha, bc), rtol=1e-13, atol=1e-14)
            H, _ = K.lattice_energy(x, v, alpha, mode, per)
            assert H == pytest.approx(L.hamiltonian(x, v, alpha, bc), rel=1e-14)
            y = np.concatenate((x, v))
            J = np.empty((14, 14))
            K.lattice_jac(y, J, alpha, mode, per)
            eps = 1e-7
            Jfd = np.empty_like(J)
            for k in range(14):
                yp, ym = y.copy(), y.copy()
                yp[k] += eps
                ym[k] -= eps
                dp, dm = np.empty(14), np.empty(14)
                K.lattice_rhs(yp, dp, f, F, alpha, mode, per)
                K.lattice_rhs(ym, dm, f, F, alpha, mode, per)
                Jfd[:, k] = (dp - dm) / (2 * eps)
            np.testing.assert_allclose(J, Jfd, atol=1e-6)


# ---------------------------------------------------------------- exact solutions

def test_q0_in_phase_wave_is_exact():
    """x_n = a cos t: no bond is ever compressed, so srkn6 reduces to exact rotations."""
    N, a = 8, 0.3
    t = np.linspace(0.0, 100.0, 11)
    s = integrate_lattice(np.full(N, a), np.zeros(N), t, alpha=1.5, method="srkn6")
    err_x = np.abs(s.x - a * np.cos(t)[:, None]).max()
    err_v = np.abs(s.v + a * np.sin(t)[:, None]).max()
    print(f"q=0: max error x {err_x:.2e}, v {err_v:.2e} over {s.n_steps} steps")
    assert err_x < 1e-11 * a and err_v < 1e-11 * a
    assert s.max_compression == 0.0
    assert s.energy_drift < 1e-10


@pytest.mark.parametrize("alpha, tol", [(1.5, 1e-8), (2.0, 5e-10)])
def test_binary_oscillation_inteq(alpha, tol):
    """x_n = (-1)^n a(t), a'' + a + 2^alpha a|a|^(alpha-1) = 0 (inteq), N even, periodic."""
    N, a0, T = 8, 0.5, 20.0
    t = np.linspace(0.0, T, 41)
    ref = solve_ivp(lambda _t, y: [y[1], -y[0] - 2.0**alpha * y[0] * abs(y[0]) ** (alpha - 1.0)],
                    (0.0, T), [a0, 0.0], t_eval=t, method="DOP853", rtol=1e-12, atol=1e-14)
    sign = (-1.0) ** np.arange(N)
    s = integrate_lattice(a0 * sign, np.zeros(N), t, alpha=alpha, method="srkn6")
    err = max(np.abs(s.x - ref.y[0][:, None] * sign).max(), np.abs(s.v - ref.y[1][:, None] * sign).max())
    print(f"(inteq) alpha={alpha}: srkn6 default max error {err:.2e} (a0 = {a0})")
    assert err < tol * a0
    assert s.max_compression == pytest.approx(2 * a0, rel=1e-12)
    d = integrate_lattice(a0 * sign, np.zeros(N), t, alpha=alpha, method="dop853", rtol=1e-12)
    assert np.abs(d.x - ref.y[0][:, None] * sign).max() < tol * a0


def test_two_bead_free_chain_and_rerun():
    """N = 2, free ends: s = x0 + x1 is harmonic, r = x1 - x0 solves r'' + r = 2 max(-r, 0)^alpha.

    The beads start at rest positions with opposite velocities, so the initial
    compression is 0 and the assumed c = A0 = 1 is exceeded: the driver reruns.
    """
    alpha = 1.5
    t = np.linspace(0.0, 10.0, 21)
    s = integrate_lattice([0.0, 0.0], [1.0, -1.0], t, alpha=alpha, bc="free")
    ref = solve_ivp(lambda _t, y: [y[1], -y[0] + 2.0 * max(-y[0], 0.0) ** alpha], (0.0, 10.0), [0.0, -2.0],
                    t_eval=t, method="DOP853", rtol=1e-12, atol=1e-14)
    err = np.abs((s.x[:, 1] - s.x[:, 0]) - ref.y[0]).max()
    print(f"N=2 free: error {err:.2e}, max compression {s.max_compression:.4f}, "
          f"c_assumed {s.c_assumed:.4f}, reruns {s.n_reruns}")
    assert err < 1e-8
    assert np.abs(s.x.sum(axis=1)).max() < 1e-14
    assert s.n_reruns >= 1 and s.c_assumed >= s.max_compression
    assert s.energy_drift < 1e-8


def test_free_ends_conserve_energy(tw11):
    x0, v0, a = tw11
    s = integrate_lattice(x0, v0, np.linspace(0, 50, 6), alpha=1.5, bc="free")
    H = L.hamiltonian(s.x, s.v, 1.5, "free")
    np.testing.assert_allclose(s.energy, H, rtol=1e-13)
    print(f"free ends: energy drift {s.energy_drift:.2e}")
    assert s.energy_drift < 1e-8
    assert np.abs(H - H[0]).max() / H[0] < 1e-8


# ---------------------------------------------------------------- orders

def _observed_order(x0, v0, T, alpha, potential, method, dts, ref):
    errs = []
    for dt in dts:
        s = integrate_lattice(x0, v0, [0.0, T], alpha=alpha, method=method, dt=dt, potential=potential)
        errs.append(max(np.abs(s.x[-1] - ref.x[-1]).max(), np.abs(s.v[-1] - ref.v[-1]).max()))
    return np.polyfit(np.log(dts), np.log(errs), 1)[0], errs


SMOOTH_DTS = {"strang": [0.04, 0.02, 0.01, 0.005], "srkn4": [0.2, 0.1, 0.05, 0.025],
              "srkn6": [0.4, 0.3, 0.2, 0.15, 0.1]}


@pytest.mark.parametrize("method", list(SPLITTINGS))
def test_convergence_order_smooth_meca(method):
    """(meca) with U = |d|^4/4 (alpha = 3, kappa = 1): observed orders 2, 4, 6."""
    x0, v0 = smooth_state()
    ref = integrate_lattice(x0, v0, [0.0, 5.0], alpha=3.0, potential="smooth", method="dop853",
                            rtol=1e-13, atol=1e-15)
    p, errs = _observed_order(x0, v0, 5.0, 3.0, "smooth", method, SMOOTH_DTS[method], ref)
    print(f"(meca) alpha=3 {method}: observed order {p:.2f}, errors {np.array(errs)}")
    assert abs(p - ORDERS[method]) < 0.3


@pytest.mark.parametrize("method", list(SPLITTINGS))
def test_energy_error_smooth_scales_and_stays_bounded(method):
    """Symplectic: the energy error ~ dt^order and does not grow secularly (t = 100 vs 1000)."""
    x0, v0 = smooth_state()
    dts = {"strang": [0.02, 0.01], "srkn4": [0.1, 0.075, 0.05], "srkn6": [0.2, 0.15, 0.1]}[method]
    drifts = []
    for dt in dts:
        s100 = integrate_lattice(x0, v0, [0.0, 100.0], alpha=3.0, potential="smooth", method=method, dt=dt)
        s1000 = integrate_lattice(x0, v0, [0.0, 1000.0], alpha=3.0, potential="smooth", method=method, dt=dt)
        assert s1000.energy_drift < 3 * s100.energy_drift
        drifts.append(s1000.energy_drift)
    p = np.polyfit(np.log(dts), np.log(drifts), 1)[0]
    print(f"(meca) {method}: energy-error order {p:.2f}, drifts {drifts}")
    assert p > ORDERS[method] - 0.5


def test_convergence_order_hertz():
    """Hertz (vhertz) alpha = 3/2: the force is only C^{1,1/2} at contact onset, so the
    observed order is capped near alpha + 1 = 2.5 whatever the nominal order."""
    N, q = 16, 2 * np.pi * 3 / 16
    x0, v0 = wave(N, q, 0.5, 1.1)
    ref = integrate_lattice(x0, v0, [0.0, 10.0], alpha=1.5, method="srkn6", dt=0.0005)
    orders = {}
    for method, dts in {"srkn6": [0.2, 0.1, 0.05, 0.025], "strang": [0.04, 0.02, 0.01, 0.005]}.items():
        orders[method], _ = _observed_order(x0, v0, 10.0, 1.5, "hertz", method, dts, ref)
    print(f"Hertz alpha=1.5 observed orders: {orders}")
    assert orders["srkn6"] > 1.5
    assert abs(orders["strang"] - 2.0) < 0.3


# ---------------------------------------------------------------- contact-onset correction (srkn6c, srkn4c)

def _contact_phase(u, alpha, tau):
    """Two-bead free chain, r = x1 - x0: r'' + r = 2 max(-r, 0)^alpha from the onset r = 0, r' = -u."""
    sol = solve_ivp(lambda _t, y: [y[1], -y[0] + 2.0 * max(-y[0], 0.0) ** alpha], (0.0, tau), [0.0, -u],
                    method="DOP853", rtol=1e-13, atol=1e-18)
    return sol.y[:, -1]


@pytest.mark.parametrize("theta", [0.3, 0.7])
def test_onset_step_local_error(theta):
    """One step across a contact onset at theta h: local error O(h^2.5) plain, O(h^5) corrected.

    Before the onset the two beads fly freely (harmonic, exact), so the state at
    the start of the step and the exact state at its end are known to 1e-15.
    """
    alpha, u = 1.5, 1.0
    hs = np.array([0.2, 0.1, 0.05, 0.025])
    orders = {}
    for method in ("srkn6", "srkn6c", "srkn4c"):
        errs = []
        for h in hs:
            r0, w0 = u * np.sin(theta * h), -u * np.cos(theta * h)
            s = integrate_lattice([-r0 / 2, r0 / 2], [-w0 / 2, w0 / 2], [0.0, h], alpha=alpha, bc="free",
                                  method=method, dt=h)
            r, w = _contact_phase(u, alpha, (1.0 - theta) * h)
            errs.append(max(abs(s.x[-1, 1] - s.x[-1, 0] - r), abs(s.v[-1, 1] - s.v[-1, 0] - w)))
        orders[method] = np.polyfit(np.log(hs), np.log(errs), 1)[0]
    print(f"onset at theta={theta}: local error orders {orders}")
    assert abs(orders["srkn6"] - 2.5) < 0.2
    assert orders["srkn6c"] > 4.7 and orders["srkn4c"] > 4.7


def _impulse_integrand(s, k, h, p):
    """k(h (1 - s)) f(d~(s)), f(d) = -(-d)^1.5 in contact: the impulse's integrand at s = tau / h."""
    return k(h * (1 - s)) * -(-p(s)) ** 1.5


def _stretched_left(u, k, h, p, lo, mid):
    """The integrand on [lo, mid] at s = lo + (mid - lo) u^2, times ds/du."""
    return _impulse_integrand(lo + (mid - lo) * u * u, k, h, p) * 2 * (mid - lo) * u


def _stretched_right(u, k, h, p, hi, mid):
    """The integrand on [mid, hi] at s = hi - (hi - mid) u^2, times -ds/du."""
    return _impulse_integrand(hi - (hi - mid) * u * u, k, h, p) * 2 * (hi - mid) * u


def test_exact_impulse_against_quadrature():
    """The integral of (sin(h - tau), cos(h - tau)) f(d~(tau)) over one step: across one onset to
    ~1e-12 relative, over a contact that begins and ends within the step to ~1e-10."""
    from scipy.integrate import quad

    out = np.empty(2)
    for d0, w0, d1, w1, h, rtol in [(0.01, -0.3, -0.02, -0.35, 0.1, 1e-11), (-0.004, 0.2, 0.01, 0.1, 0.07, 1e-12),
                                    (0.003, -0.1, 0.002, 0.1, 0.2, 1e-9)]:
        p = np.polynomial.Polynomial(OI.hermite(d0, w0, d1, w1, h))
        roots = sorted(r.real for r in p.roots() if abs(r.imag) < 1e-12 and 0 < r.real < 1)
        ref = np.zeros(2)
        cuts = [0.0, *roots, 1.0]
        for lo, hi in pairwise(cuts):
            if p(0.5 * (lo + hi)) >= 0.0:
                continue
            mid = 0.5 * (lo + hi)
            for i, k in enumerate((np.sin, np.cos)):  # s = root +- L u^2 near each root: smooth integrands
                left = quad(_stretched_left, 0, 1, args=(k, h, p, lo, mid), epsabs=0, epsrel=1e-13)
                right = quad(_stretched_right, 0, 1, args=(k, h, p, hi, mid), epsabs=0, epsrel=1e-13)
                ref[i] += h * (left[0] + right[0])
        nroots = OI.exact_impulse(d0, w0, d1, w1, h, 1.5, 0, out)
        assert nroots == len(roots)
        np.testing.assert_allclose(out, ref, rtol=rtol)


def test_sincos_polynomial():
    x = np.linspace(-2.0, 2.0, 401)
    got = np.array([OI._sincos(v) for v in x])
    np.testing.assert_allclose(got[:, 0], np.sin(x), rtol=0, atol=5e-15)
    np.testing.assert_allclose(got[:, 1], np.cos(x), rtol=0, atol=5e-15)


def test_convergence_order_hertz_corrected():
    """Hertz alpha = 3/2, N = 16 travelling wave to t = 10: with the onset correction the
    observed global order is ~5 (srkn6c) and ~4 (srkn4c), against 2.5 uncorrected; the
    reference (srkn6c, dt = 5e-4) agrees with plain srkn6 at dt = 2.5e-4 to ~1e-11."""
    N, q = 16, 2 * np.pi * 3 / 16
    x0, v0 = wave(N, q, 0.5, 1.1)
    ref = integrate_lattice(x0, v0, [0.0, 10.0], alpha=1.5, method="srkn6c", dt=0.0005)
    plain = integrate_lattice(x0, v0, [0.0, 10.0], alpha=1.5, method="srkn6", dt=0.00025)
    assert np.abs(plain.x[-1] - ref.x[-1]).max() < 1e-10
    dts = [0.2, 0.1, 0.05, 0.025]
    orders = {m: _observed_order(x0, v0, 10.0, 1.5, "hertz", m, dts, ref) for m in ("srkn6c", "srkn4c", "srkn6")}
    print("Hertz alpha=1.5 observed orders: " + ", ".join(f"{m} {p:.2f} (errors {np.array(e)})"
                                                          for m, (p, e) in orders.items()))
    assert orders["srkn6c"][0] > 4.3
    assert orders["srkn4c"][0] > 3.4
    assert orders["srkn6"][0] < 3.0
    assert orders["srkn6c"][1][-1] < 1e-9  # dt = 0.025: ~5e-11, against 9e-8 uncorrected


@pytest.mark.parametrize("bc", ["periodic", "free"])
@pytest.mark.parametrize("alpha, potential", [(1.5, "hertz"), (2.3, "hertz"), (1.5, "smooth")])
def test_corrected_energy_bookkeeping_and_accuracy(tw11, bc, alpha, potential):
    """The energy updated locally by the corrections is the Hamiltonian of the stored states,
    and srkn6c at dt = 0.01 beats srkn6 at the same step, for both ends, any alpha, both laws."""
    x0, v0, a = tw11
    t = np.linspace(0.0, 30.0, 4)
    kw = dict(alpha=alpha, bc=bc, potential=potential)
    s = integrate_lattice(x0, v0, t, method="srkn6c", dt=0.01, **kw)
    ref = integrate_lattice(x0, v0, t, method="srkn6c", dt=0.0005, **kw)
    plain = integrate_lattice(x0, v0, t, method="srkn6", dt=0.01, **kw)
    if potential == "hertz":
        np.testing.assert_allclose(s.energy, L.hamiltonian(s.x, s.v, alpha, bc), rtol=1e-13)
    err, err_plain = np.abs(s.x - ref.x).max() / a, np.abs(plain.x - ref.x).max() / a
    print(f"{bc} alpha={alpha} {potential}: srkn6c {err:.1e} vs srkn6 {err_plain:.1e}, drift {s.energy_drift:.1e}, "
          f"{s.n_onset_corrections} corrections")
    assert s.n_onset_corrections > 0 and plain.n_onset_corrections == 0
    assert err < 2e-9 and err < err_plain
    assert s.energy_drift < 1e-10


@pytest.mark.parametrize("method", list(CORRECTED_METHODS))
def test_corrected_default_drift_long_time_and_tight_reference(tw11, method):
    """Default step: drift <= 1e-8 at t = 100, bounded at t = 1000 (no secular growth), and the
    states agree with a tight reference (DOP853 in numba, rtol = 1e-13, atol = rtol * a)."""
    x0, v0, a = tw11
    t = np.linspace(0.0, 100.0, 11)
    s100 = integrate_lattice(x0, v0, t, alpha=1.5, method=method)
    s1000 = integrate_lattice(x0, v0, np.linspace(0.0, 1000.0, 11), alpha=1.5, method=method)
    ref = integrate_lattice(x0, v0, t, alpha=1.5, method="dop853_numba", rtol=1e-13, atol=1e-13 * a)
    err = np.abs(s100.x - ref.x).max() / a
    print(f"{method} default (dt={s100.dt:.3g}): drift t=100 {s100.energy_drift:.1e}, t=1000 {s1000.energy_drift:.1e}"
          f"; vs dop853_numba rtol=1e-13: {err:.1e}; wall {s100.wall_time_s:.3f} + {s1000.wall_time_s:.3f} s")
    assert s100.dt == pytest.approx(DEFAULT_DT_FACTOR[method] * 2 * np.pi / omega_max(s100.c_assumed, 1.5))
    assert s100.energy_drift <= 1e-8 and s1000.energy_drift <= 1e-8
    assert s1000.energy_drift < 10 * s100.energy_drift
    assert err < 1e-8


def test_corrected_is_resumable_and_deterministic(tw11):
    """Chunked (progress) and unchunked runs, and two identical calls, give bitwise equal states."""
    x0, v0, a = tw11
    t = np.linspace(0.0, 20.0, 5)
    s1 = integrate_lattice(x0, v0, t, alpha=1.5, method="srkn6c")
    s2 = integrate_lattice(x0, v0, t, alpha=1.5, method="srkn6c", progress=lambda *_: None)
    s3 = integrate_lattice(x0, v0, t, alpha=1.5, method="srkn6c")
    np.testing.assert_array_equal(s1.x, s2.x)
    np.testing.assert_array_equal(s1.x, s3.x)
    assert s1.energy_drift == s2.energy_drift


# ---------------------------------------------------------------- defaults on a paper scene

def test_default_energy_drift_and_long_time(tw11):
    x0, v0, a = tw11
    s100 = integrate_lattice(x0, v0, np.linspace(0.0, 100.0, 11), alpha=1.5)
    s1000 = integrate_lattice(x0, v0, np.linspace(0.0, 1000.0, 11), alpha=1.5)
    print(f"srkn6c default (dt={s100.dt:.3g}): drift t=100 {s100.energy_drift:.2e}, "
          f"t=1000 {s1000.energy_drift:.2e}, wall {s100.wall_time_s:.2f}+{s1000.wall_time_s:.2f}s")
    assert s100.method == "srkn6c" and s100.n_reruns == 0
    assert s100.energy_drift <= 1e-8
    assert s1000.energy_drift < 3 * s100.energy_drift
    assert s100.n_force_evals == 1 + 11 * s100.n_steps
    c_assumed, c_energy = compression_bounds(x0, v0, 1.5)
    assert s100.dt == pytest.approx(DEFAULT_DT_FACTOR["srkn6c"] * 2 * np.pi / omega_max(c_assumed, 1.5))
    assert s100.max_compression <= c_assumed <= c_energy


def test_srkn6_agrees_with_dop853(tw11):
    x0, v0, a = tw11
    t = np.linspace(0.0, 50.0, 6)
    s = integrate_lattice(x0, v0, t, alpha=1.5)
    d = integrate_lattice(x0, v0, t, alpha=1.5, method="dop853", rtol=1e-12)
    dn = integrate_lattice(x0, v0, t, alpha=1.5, method="dop853_numba", rtol=1e-12)
    err = np.abs(s.x - d.x).max() / a
    err_n = np.abs(dn.x - s.x).max() / a
    print(f"srkn6 default vs dop853 rtol=1e-12 at t=50: {err:.2e}; dop853_numba rtol=1e-12 vs srkn6 {err_n:.2e} "
          f"(relative to a); wall {s.wall_time_s:.3f} / {d.wall_time_s:.3f} / {dn.wall_time_s:.3f} s")
    assert err < 1e-8
    assert err_n < 2e-8  # both DOP853 runs carry ~5e-9 global error at rtol = 1e-12
    assert d.atol == pytest.approx(1e-12 * max(np.abs(x0).max(), np.abs(v0).max()))


@pytest.mark.parametrize("method", ["rk45", "lsoda", "radau", "dop853_numba"])
def test_other_adaptive_methods(method):
    x0, v0 = wave(8, np.pi / 2, 0.3, 1.05)
    t = np.linspace(0.0, 5.0, 3)
    ref = integrate_lattice(x0, v0, t, alpha=1.5)
    s = integrate_lattice(x0, v0, t, alpha=1.5, method=method, rtol=1e-9)
    assert s.dt is None and s.rtol == 1e-9
    assert np.abs(s.x - ref.x).max() < 1e-6
    assert s.energy_drift < 1e-6


def test_output_times_progress_and_general_alpha():
    x0, v0 = wave(10, 2 * np.pi / 5, 0.2, 1.05)
    calls = []
    t = np.array([0.5, 1.0, 2.5])
    s = integrate_lattice(x0, v0, t, alpha=2.2, dt=0.01, progress=lambda tr, tf: calls.append((tr, tf)))
    s_all = integrate_lattice(x0, v0, np.array([0.0, 0.5, 1.0, 2.5]), alpha=2.2, dt=0.01)
    np.testing.assert_array_equal(s.t, t)
    assert s.x.shape == (3, 10)
    np.testing.assert_allclose(s.x, s_all.x[1:], rtol=0, atol=1e-15)
    assert calls and calls[-1] == (2.5, 2.5)
    np.testing.assert_allclose(s.energy, L.hamiltonian(s.x, s.v, 2.2), rtol=1e-13)
    d = integrate_lattice(x0, v0, t, alpha=2.2, method="dop853", rtol=1e-11)
    assert np.abs(d.x - s.x).max() < 1e-8


# ---------------------------------------------------------------- DpS

@pytest.mark.parametrize("bc", ["periodic", "free"])
def test_dps_invariants(bc):
    rng = np.random.default_rng(0)
    A0 = rng.standard_normal(12) + 1j * rng.standard_normal(12)
    y = A0.view(np.float64).copy()
    dy = np.empty_like(y)
    SD.dps_rhs(SD.dfnls(1.5, bc == "periodic", 1.0 / (2.0 * D.tau0(1.5))), y, dy)
    np.testing.assert_allclose(dy.view(complex), D.rhs(A0, 1.5, bc), rtol=1e-13, atol=1e-14)
    s = integrate_dps(A0, np.linspace(0.0, 10.0, 5), alpha=1.5, bc=bc, rtol=1e-10)
    print(f"DpS {bc}: max l2 drift {s.max_l2_drift:.1e}, H drift {s.max_energy_drift:.1e}")
    assert s.max_l2_drift < 1e-8 and s.max_energy_drift < 1e-8 and s.P_drift.max() < 1e-12


def test_dps_plane_wave():
    """A_n = R exp(i(Omega tau - q n)), tau0 Omega = 2^alpha R^(alpha-1) |sin(q/2)|^(alpha+1) (ds)."""
    N, alpha, R = 16, 1.5, 0.7
    q = 2 * np.pi * 3 / N
    n = np.arange(N)
    tau = np.linspace(0.0, 20.0, 21)
    s = integrate_dps(D.plane_wave(n, 0.0, R, q, 0.0, alpha), tau, alpha=alpha, rtol=1e-11)
    exact = D.plane_wave(n[None, :], tau[:, None], R, q, 0.0, alpha)
    err = np.abs(s.A - exact).max()
    print(f"DpS plane wave: error {err:.1e}, l2 drift {s.max_l2_drift:.1e}, H drift {s.max_energy_drift:.1e}")
    assert err < 1e-9
    assert s.max_l2_drift < 1e-10 and s.max_energy_drift < 1e-10
    assert s.l2_drift.shape == (21,) and s.atol == pytest.approx(1e-11 * R)
    sn = integrate_dps(D.plane_wave(n, 0.0, R, q, 0.0, alpha), tau, alpha=alpha, rtol=1e-11, method="dop853_numba")
    assert np.abs(sn.A - exact).max() < 1e-9
    assert sn.max_l2_drift < 1e-10 and sn.max_energy_drift < 1e-10 and sn.P_drift.max() < 1e-12
    np.testing.assert_allclose(s.energy_drift, np.abs(D.hamiltonian(s.A, alpha) / D.hamiltonian(s.A[0], alpha) - 1),
                               atol=1e-14)


# ---------------------------------------------------------------- bad inputs

@pytest.mark.parametrize("kwargs, match", [
    (dict(alpha=1.0), "alpha = 1.0"),
    (dict(alpha=1.5, method="euler"), "method = 'euler'"),
    (dict(alpha=1.5, bc="fixed"), "bc = 'fixed'"),
    (dict(alpha=1.5, potential="fpu"), "potential = 'fpu'"),
    (dict(alpha=1.5, t_out=[0.0, 2.0, 1.0]), r"t_out\[1\]=2.0"),
    (dict(alpha=1.5, t_out=[-1.0, 1.0]), r"t_out\[0\]=-1.0"),
    (dict(alpha=1.5, x0=[0.1]), "N=1"),
    (dict(alpha=1.5, x0=[0.1, np.nan, 0.0, 0.0]), r"x0\[1\]=nan"),
    (dict(alpha=1.5, v0=[0.1, np.inf, 0.0, 0.0]), r"v0\[1\]=inf"),
    (dict(alpha=1.5, dt=-0.1), "dt = -0.1"),
    (dict(alpha=1.5, dt=0.1, dt_factor=0.01), "dt=0.1"),
    (dict(alpha=1.5, rtol=1e-8), "rtol=1e-08"),
    (dict(alpha=1.5, method="dop853", dt=0.1), "dt=0.1"),
    (dict(alpha=1.5, method="dop853", rtol=0.0), "rtol = 0.0"),
    (dict(alpha=1.5, x0=[10**400, 0.0, 0.0, 0.0]), "x0 must be an array of finite numbers"),
    (dict(alpha=1.5, t_out=[0.0, 10**400]), "t_out must be an array of finite numbers"),
    (dict(alpha=1.5, x0=["a", 0.0, 0.0, 0.0]), "x0 must be an array of finite numbers"),
    # (2 max|x|)^(alpha+1) beyond float64: H(0) and the step would be inf (a ZeroDivisionError in the kernel before)
    (dict(alpha=1.5, x0=[1e300, 0.0, 0.0, 0.0]), "x0, v0 must be smaller: values up to 1e.300"),
    (dict(alpha=10.0, v0=[1e29, 0.0, 0.0, 0.0]), "x0, v0 must be smaller"),
])
def test_bad_lattice_inputs(kwargs, match):
    args = dict(x0=np.zeros(4), v0=np.zeros(4), t_out=[0.0, 1.0])
    for key in ("x0", "v0", "t_out"):
        if key in kwargs:
            args[key] = kwargs.pop(key)
    if len(args["x0"]) != len(args["v0"]) and len(args["x0"]) >= 2:
        args["v0"] = np.zeros(len(args["x0"]))
    with pytest.raises(ValueError, match=match):
        integrate_lattice(args["x0"], args["v0"], args["t_out"], **kwargs)


def test_bad_dps_inputs():
    A0 = np.ones(4, dtype=complex)
    with pytest.raises(ValueError, match="alpha = 0.5"):
        integrate_dps(A0, [0.0, 1.0], alpha=0.5)
    with pytest.raises(ValueError, match="method = 'srkn6'"):
        integrate_dps(A0, [0.0, 1.0], alpha=1.5, method="srkn6")
    with pytest.raises(ValueError, match=r"tau_out\[1\]=1.0"):
        integrate_dps(A0, [0.0, 1.0, 1.0], alpha=1.5)
    with pytest.raises(ValueError, match=r"A0\[2\]"):
        integrate_dps(np.array([1, 1, np.nan, 1], dtype=complex), [0.0, 1.0], alpha=1.5)


@pytest.mark.parametrize("amplitude, tau_end", [(1e200, 1.0), (1.0, 1e300)])
def test_dps_run_of_hours_is_refused_before_any_step(amplitude, tau_end):
    """DpS's scaling A -> lambda A, tau -> lambda^(1-alpha) tau: at A = 1e200 a unit of tau spans ~1e99 periods
    (the run hung before); refused in one line naming the periods, at once."""
    A0 = np.array([amplitude, 0.0, 0.0, 0.0], dtype=complex)
    t0 = time.process_time()
    with pytest.raises(ValueError, match=r"^A0, tau_out: tau_out\[-1\] = .* periods of the fastest DpS oscillation"):
        integrate_dps(A0, [0.0, tau_end], alpha=1.5)
    assert time.process_time() - t0 < 1.0


def test_dps_pace_matches_the_plane_wave_frequency():
    """The pace :func:`check_dps_pace` bounds is the fastest plane wave's: (ds), tau0 Omega = 2^alpha R^(alpha-1)
    |sin(q/2)|^(alpha+1), at q = pi is (2/tau0) (2R)^(alpha-1); the bound falls between 0.999 and 1.001 times
    MAX_DPS_PERIODS of its periods, and one period brings the wave back."""
    from cradle.integrators._validate import MAX_DPS_PERIODS, check_dps_pace

    alpha, R = 1.5, 0.5
    period = 2 * np.pi / D.plane_wave_frequency(R, np.pi, alpha)
    A0 = D.plane_wave(np.arange(4), 0.0, R, np.pi, 0.0, alpha)
    check_dps_pace(A0, np.array([0.0, 0.999 * MAX_DPS_PERIODS * period]), alpha)
    with pytest.raises(ValueError, match="periods"):
        check_dps_pace(A0, np.array([0.0, 1.001 * MAX_DPS_PERIODS * period]), alpha)
    s = integrate_dps(A0, np.linspace(0.0, period, 2), alpha=alpha, rtol=1e-12)
    np.testing.assert_allclose(s.A[-1], A0, atol=1e-9)   # one period of (freq) brings the wave back
