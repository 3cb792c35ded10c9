"""Tests of the damped lattice (ncdamped) in integrate_lattice(damping=...): closed forms only.

* the compiled right-hand side against the numpy reference of cradle.models.damping;
* damped small oscillations x'' + gamma x' + x = 0 (two beads moving together: no contact) against
  e^(-gamma t/2) [x0 cos(w t) + (v0 + gamma x0/2)/w sin(w t)], and the dissipated energy against the
  energy the exact solution loses;
* the Hertz collision time of two spheres t_c = 2 I delta_max / v (Landau & Lifshitz, Theory of
  Elasticity, section 9), with the on-site force negligible (omega_0 t_c < 1e-3);
* the Kuwabara-Kono restitution coefficient, 1 - e proportional to v^(1/5) at small 1 - e (Brilliantov,
  Spahn, Hertzsch & Poeschel, Phys. Rev. E 53 (1996) 5382; Schwager & Poeschel, Phys. Rev. E 78 (2008)
  051304 for the force clipped at zero);
* the contact onsets located by the default treatment (steps end at the contact events,
  cradle.integrators._dop853_events) against the closed-form time at which the gap of two free beads
  closes, and the treatment changing nothing on a run without contacts;
* the energy balance H + D = H(0) on a damped localised binary oscillation (figure loc1's data);
* damping off (None or Damping()): bitwise the conservative run.

In (nc) units two beads with free ends have the relative coordinate c = x_0 - x_1 (the compression of
their bond), c'' = -c - 2 max(c^(3/2) + eta c^(1/2) c', 0) H(c): reduced mass mu = 1/2, k = 1.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import CubicHermiteSpline

from cradle.integrators import _kernels as K, integrate_lattice
from cradle.integrators.lattice_adaptive import run_dop853_damped
from cradle.models import damping as DM
from cradle.models.damping import Damping
from cradle.models.initial import packet
from cradle.models.physical import COLLISION_INTEGRAL


def test_damped_rhs_kernel_matches_the_numpy_reference():
    """lattice_damped_rhs: acceleration and dissipated power of cradle.models.damping, with bonds in
    contact, out of contact and clipped (the damping term outweighing the elastic one)."""
    rng = np.random.default_rng(3)
    N = 12
    for alpha in (1.5, 1.7):
        for periodic in (True, False):
            x, v = rng.normal(0, 0.3, N), rng.normal(0, 3.0, N)
            d = Damping(onsite=0.07, contact=0.4)
            y = np.concatenate((x, v, [0.0]))
            dy = np.empty_like(y)
            K.lattice_damped_rhs(y, dy, np.empty(N), np.empty(N), alpha, K.mode_flag("hertz", alpha), d.onsite,
                                 d.contact, 1.0, periodic)
            bc = "periodic" if periodic else "free"
            g = DM.bond_forces(x, v, alpha, d.contact, bc)
            c = -(np.roll(x, -1) - x)
            assert np.any((c > 0) & (g == 0.0)) and np.any(g < 0.0)   # clipped and pushing bonds both met
            np.testing.assert_array_equal(dy[:N], v)
            np.testing.assert_allclose(dy[N:2 * N], DM.acceleration(x, v, alpha, d, bc), rtol=1e-13, atol=1e-13)
            P = DM.dissipated_power(x, v, alpha, d, bc)
            assert P > 0.0
            assert dy[2 * N] == pytest.approx(P, rel=1e-13)


def test_damped_small_oscillations_match_the_closed_form():
    """Two beads with the same initial state never touch (c = 0 exactly) and each solves
    x'' + gamma x' + x = 0; D(t) is the energy the exact solution has lost."""
    gamma, x0, v0 = 0.3, 1.0, -0.4
    t = np.linspace(0.0, 20.0, 41)
    sol = integrate_lattice([x0, x0], [v0, v0], t, alpha=1.5, bc="free", method="dop853_numba", rtol=1e-12,
                            damping=Damping(onsite=gamma))
    w = np.sqrt(1.0 - gamma**2 / 4.0)
    decay = np.exp(-gamma * t / 2.0)
    b = (v0 + gamma * x0 / 2.0) / w
    x = decay * (x0 * np.cos(w * t) + b * np.sin(w * t))
    v = -gamma / 2.0 * x + decay * (-x0 * w * np.sin(w * t) + b * w * np.cos(w * t))
    assert np.abs(sol.x - x[:, None]).max() < 1e-8
    assert np.abs(sol.v - v[:, None]).max() < 1e-8
    lost = (x0**2 + v0**2) - (x**2 + v**2)          # H of two beads, (x^2 + v^2)/2 each
    assert lost[-1] > 0.9 * (x0**2 + v0**2)         # most of the energy is gone: D is tested, not ~0
    assert np.abs(sol.dissipated - lost).max() < 1e-8
    assert sol.max_compression == 0.0


def contact_interval(t, c, cdot):
    """(start, end) of the first contact c > 0 in the sampled c(t): each crossing of c = 0 located by the
    root of the cubic Hermite interpolant of (c, c') between the two samples around it."""
    crossings = []
    for k in np.flatnonzero((c[:-1] > 0.0) != (c[1:] > 0.0)):
        spline = CubicHermiteSpline(t[k:k + 2], c[k:k + 2], cdot[k:k + 2])
        roots = [r for r in spline.roots(extrapolate=False) if t[k] <= r <= t[k + 1]]
        crossings.append(roots[0])
    return crossings[0], crossings[1]


def collision(v, damping, n_out=400, rtol=1e-12):
    """Two beads approaching at speed v from a gap closed after about t_c / 4 (on-site force included):
    returns (times, c, c', t_c at the contact speed, solution)."""
    t_c = collision_time(v)
    gap = v * t_c / 4.0
    t = np.linspace(0.0, 1.6 * t_c, n_out)
    sol = integrate_lattice([-gap / 2.0, gap / 2.0], [v / 2.0, -v / 2.0], t, alpha=1.5, bc="free",
                            method="dop853_numba", rtol=rtol, damping=damping)
    # before contact c = -gap cos t + v sin t exactly: the contact speed is hypot(v, gap)
    return t, sol.x[:, 0] - sol.x[:, 1], sol.v[:, 0] - sol.v[:, 1], collision_time(np.hypot(v, gap)), sol


def collision_time(v):
    """t_c = 2 I delta_max / v, delta_max = (5 mu v^2 / (4 k))^(2/5), mu = 1/2, k = 1 (two beads of (nc))."""
    delta_max = (5.0 * 0.5 * v**2 / 4.0) ** 0.4
    return 2.0 * COLLISION_INTEGRAL * delta_max / v


@pytest.mark.parametrize("damping", [None, Damping()], ids=["none", "off"])
def test_hertz_collision_time_matches_the_closed_form(damping):
    """Speeds such that omega_0 t_c < 1e-3 (the on-site force changes t_c by ~(omega_0 t_c)^2)."""
    for v in (1e17, 1e18, 1e19):
        t, c, cdot, t_c, sol = collision(v, damping)
        assert t_c < 1e-3
        start, end = contact_interval(t, c, cdot)
        assert abs((end - start) / t_c - 1.0) < 1e-3
        assert sol.energy_drift < 1e-8


def test_collision_time_of_the_damped_kernel_without_damping():
    """The damped right-hand side (kind 2) with gamma = eta = 0, driven directly: the same closed form."""
    for v in (1e17, 1e18, 1e19):
        t_c = collision_time(v)
        gap = v * t_c / 4.0
        t = np.linspace(0.0, 1.6 * t_c, 400)
        x0, v0 = np.array([-gap / 2.0, gap / 2.0]), np.array([v / 2.0, -v / 2.0])
        X, V, E, D, drift, *_ = run_dop853_damped(x0, v0, t, 1e-12, 1e-12 * v / 2.0, 1.5, K.HERTZ_15, False,
                                                  Damping(), None)
        start, end = contact_interval(t, X[:, 0] - X[:, 1], V[:, 0] - V[:, 1])
        assert abs((end - start) / collision_time(np.hypot(v, gap)) - 1.0) < 1e-3
        assert np.all(D == 0.0) and drift < 1e-8


def test_kuwabara_kono_restitution_exponent_is_one_fifth():
    """e = (relative speed after) / (before), each from the free relative motion c'' = -c, whose
    c'^2 + c^2 is the squared speed at c = 0; 1 - e fitted as C v^p over two decades of v with
    0.01 < 1 - e <= 0.05: p = 1/5 within 0.01 (the next term of the expansion, ~(1 - e)^2, biases it low)."""
    eta = 5e-6
    speeds = np.logspace(17.0, 19.0, 9)
    loss = []
    for v in speeds:
        t, c, cdot, t_c, sol = collision(v, Damping(contact=eta), n_out=50)
        assert t_c < 1e-3 and c[-1] < 0.0 and cdot[-1] < 0.0    # separated, in free flight
        loss.append(1.0 - np.hypot(cdot[-1], c[-1]) / np.hypot(cdot[0], c[0]))
        assert sol.energy_drift < 1e-8
    loss = np.array(loss)
    assert np.all((loss > 0.01) & (loss <= 0.05))
    p = np.polyfit(np.log(speeds), np.log(loss), 1)[0]
    assert abs(p - 0.2) < 0.01


@pytest.mark.parametrize("damping", [Damping(onsite=0.2, contact=0.3), Damping(contact=0.3), Damping(onsite=0.2)],
                         ids=["both", "contact", "onsite"])
def test_located_onset_is_the_closed_form_gap_closing_time(damping):
    """Two free beads, gap g, approaching at relative speed v: before contact the elongation d = x_1 - x_0
    solves d'' + gamma d' + d = 0, d = e^(-gamma t/2) [g cos(w t) + (gamma g/2 - v)/w sin(w t)],
    w = sqrt(1 - gamma^2/4), which closes at t_on = atan2(g, (v - gamma g/2)/w)/w. The first located
    event is the onset; its time error is that of the root of a trajectory held to rtol (|d'| ~ v ~ g
    here): within 10 rtol."""
    g, v, rtol = 0.1, 0.5, 1e-10
    w = np.sqrt(1.0 - damping.onsite**2 / 4.0)
    t_on = np.arctan2(g, (v - damping.onsite * g / 2.0) / w) / w
    times, events = np.full(4, np.nan), np.zeros(4, dtype=np.int64)
    *_, drift, _, _, _ = run_dop853_damped(np.array([-g / 2.0, g / 2.0]), np.array([v / 2.0, -v / 2.0]),
                                           np.array([0.0, 1.0]), rtol, rtol * v / 2.0, 1.5, K.HERTZ_15, False,
                                           damping, None, events=events, event_times=times)
    assert events[0] == 1 and events[1] == 0      # the onset, located; the release comes after t = 1
    assert abs(times[0] - t_on) < 10.0 * rtol
    assert drift < 1e-8


def test_located_onset_of_a_fast_hertz_collision():
    """The collisions of test_hertz_collision_time_matches_the_closed_form (on-site force negligible
    during contact, not before it), with the damped kernel and gamma = eta = 0: the gap g closes at
    t_on = atan2(g, v), then the contact lasts t_c; the onset and the release are both located."""
    for v in (1e17, 1e18, 1e19):
        t_c = collision_time(v)
        gap = v * t_c / 4.0
        times, events = np.full(4, np.nan), np.zeros(4, dtype=np.int64)
        t = np.array([0.0, 1.6 * t_c])
        run_dop853_damped(np.array([-gap / 2.0, gap / 2.0]), np.array([v / 2.0, -v / 2.0]), t, 1e-12,
                          1e-12 * v / 2.0, 1.5, K.HERTZ_15, False, Damping(), None, events=events, event_times=times)
        assert events[0] == 2 and events[1] == 0      # onset and release
        t_on = np.arctan2(gap, v)
        assert abs(times[0] / t_on - 1.0) < 1e-10
        assert abs((times[1] - times[0]) / collision_time(np.hypot(v, gap)) - 1.0) < 1e-3


def test_touching_beads_at_rest_switch_with_the_onset_that_pushes_them():
    """Five touching beads at rest, the first released into them (a desk toy in (nc)'s units, x0 = -A): at the first
    onset the next bond starts at c = 0 with c' = 0 and grows like a power of t - t_on, so it switches at that
    onset, not at a located event inside the next step (where the cubic Hermite of its flat start puts a root);
    each bond's onset is then counted once, and the state after the first impact converges with rtol (it
    wandered by up to 5e-8 of the amplitude, whatever rtol, when the spurious event was located)."""
    A = 3.7e17                                 # the desk toy's amplitude (docs/physical-units.md)
    x0, v0 = np.zeros(5), np.zeros(5)
    x0[0] = -A
    damping = Damping(onsite=1e-4, contact=1.2e-6)
    t = np.array([0.0, 1.2, 2.0])              # the first impact at t = pi/2, the state stored after it
    ends, counts = {}, {}
    for rtol in (1e-10, 1e-11, 1e-12, 1e-14):
        events = np.zeros(4, dtype=np.int64)
        X, V, *_ = run_dop853_damped(x0, v0, t, rtol, rtol * A, 1.5, K.HERTZ_15, False, damping, None,
                                     events=events)
        ends[rtol] = np.concatenate([X[-1], V[-1]]) / A
        counts[rtol] = events.copy()
    for rtol in (1e-10, 1e-11, 1e-12):
        assert np.max(np.abs(ends[rtol] - ends[1e-14])) < 10.0 * rtol
        assert counts[rtol][1] == 0 and counts[rtol][0] == counts[1e-14][0]


def test_events_change_nothing_without_contacts():
    """The damped small oscillations (no bond ever compressed): the default treatment takes DOP853's plain
    steps, bitwise."""
    t = np.linspace(0.0, 20.0, 41)
    x0, v0 = np.array([1.0, 1.0]), np.array([-0.4, -0.4])
    runs = [run_dop853_damped(x0, v0, t, 1e-12, 1e-12, 1.5, K.HERTZ_15, False, Damping(onsite=0.3), None,
                              onset=onset) for onset in (True, False)]
    for a, b in zip(*runs, strict=True):
        assert np.asarray(a).tobytes() == np.asarray(b).tobytes()


def test_energy_balance_of_a_damped_localised_oscillation():
    """figure loc1's localised binary oscillation, 50 beads on a ring, both damping terms: H + D = H(0)
    to 1e-8 at every step, D increasing, at rtol = 1e-10 with the steps ending at the contact events;
    without them (DOP853 stepping across the onsets, where the contact damping's force rises like
    sqrt(t - t_on)) the drift at that rtol is above 1e-8, and 1e-8 took rtol = 1e-14
    (benchmarks/damped_orders.py tabulates both against rtol)."""
    data = packet(50, 1.5, amplitude=0.2, width=8.0)
    t = np.linspace(0.0, 30.0, 61)
    damping = Damping(onsite=0.01, contact=0.05)
    sol = integrate_lattice(data.x0, data.v0, t, alpha=1.5, method="dop853_numba", rtol=1e-10, damping=damping)
    H0 = sol.energy[0]
    assert sol.energy_drift <= 1e-8
    plain = run_dop853_damped(data.x0, data.v0, t, sol.rtol, sol.atol, 1.5, K.HERTZ_15, True, damping, None,
                              onset=False)
    assert plain[4] > 1e-8
    assert np.abs(sol.energy + sol.dissipated - H0).max() / H0 <= 1e-8
    assert np.all(np.diff(sol.dissipated) > 0.0)
    assert sol.dissipated[-1] > 0.3 * H0        # a lot dissipated: the balance is not trivially met
    assert sol.max_compression > 0.0


@pytest.mark.parametrize("method", ["dop853_numba", "srkn6c"])
def test_damping_off_is_bitwise_the_conservative_run(method):
    data = packet(16, 1.5, amplitude=0.2, width=6.0)
    t = np.linspace(0.0, 10.0, 6)
    kw = {"rtol": 1e-9} if method == "dop853_numba" else {}
    ref = integrate_lattice(data.x0, data.v0, t, alpha=1.5, method=method, **kw)
    for damping in (None, Damping()):
        sol = integrate_lattice(data.x0, data.v0, t, alpha=1.5, method=method, damping=damping, **kw)
        for name in ("x", "v", "energy"):
            assert getattr(sol, name).tobytes() == getattr(ref, name).tobytes()
        assert (sol.energy_drift, sol.n_steps, sol.n_force_evals) == (ref.energy_drift, ref.n_steps,
                                                                      ref.n_force_evals)
        assert sol.damping is damping and np.all(sol.dissipated == 0.0)


@pytest.mark.parametrize("kwargs, words", [
    ({"method": "srkn6c"}, "method='srkn6c' with damping"),
    ({"method": "dop853"}, "method='dop853' with damping"),
    ({"method": "dop853_numba", "potential": "smooth"}, "potential='smooth' with damping"),
    ({"method": "srkn6c", "t0": 0.5}, "method='srkn6c' with damping"),
    ({"method": "dop853_numba", "energy0": 1.0}, "energy0=1.0 with damping"),
])
def test_what_the_damped_lattice_is_not_integrated_with_is_refused_in_one_line(kwargs, words):
    with pytest.raises(ValueError, match=words) as err:
        integrate_lattice([0.1, 0.0], [0.0, 0.0], [0.5, 1.0], alpha=1.5, damping=Damping(onsite=0.1), **kwargs)
    assert "\n" not in str(err.value)
    with pytest.raises(ValueError, match="damping must be"):
        integrate_lattice([0.1, 0.0], [0.0, 0.0], [1.0], alpha=1.5, damping=0.1)
