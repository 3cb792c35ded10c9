"""Tests of the imperfect cradle (ncimperfect) in integrate_lattice(terms=...) (kind 4 of _dop853): closed forms.

* an isolated detuned bead (beads held apart by gaps, delta0 < 0) oscillates at its omega_n, whatever its mass;
* a precompressed ring's linear dispersion omega(q)^2 = 1 + 4 kappa sin^2(q/2), kappa = alpha delta0^(alpha-1),
  against the frequency measured from a small-amplitude run of the Hertz lattice (amplitude 1e-4 delta0, one
  Fourier mode: the phase of its projection fitted over 30 periods), not from the linearised matrix;
* a large-angle pendulum's period 4 K(m), m = sin^2(theta0/2) (scipy.special.ellipk's convention);
* the pendulum tends to the harmonic bead as its scale X/l -> 0, the difference ~ scale^2;
* the generalised energy (ham) conserved on a disordered, precompressed, quartic ring; H + D = H(0) with damping;
* trivial terms forced through kind 4 give kind 0's run, bitwise; inactive terms leave every method's run bitwise;
* refusals: one line, before any work.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.special import ellipk

from cradle.integrators import integrate_lattice
from cradle.integrators.lattice_adaptive import run_dop853_terms
from cradle.models.damping import Damping
from cradle.models.inhomogeneity import Inhomogeneity, homogeneous
from cradle.models.lattice_terms import Terms
from cradle.models.onsite import OnSite
from cradle.models.precompression import Precompression, dispersion
from cradle.specs.values import ConfigError

ALPHA = 1.5


def test_isolated_detuned_beads_oscillate_at_their_omega_whatever_their_mass():
    """Beads kept apart by gaps of 1 (delta0 = -1, amplitudes 0.1): x_n(t) = a_n cos(omega_n t); the masses
    (4, 1/4, 1) only weight the contact forces, which never act."""
    omega = (0.9, 1.15, 1.3)
    terms = Terms(inhomogeneity=Inhomogeneity(omega=omega, mass=(4.0, 0.25, 1.0)),
                  precompression=Precompression(delta0=-1.0))
    a = np.array([0.1, -0.07, 0.05])
    t = np.linspace(0.0, 60.0, 61)
    sol = integrate_lattice(a, np.zeros(3), t, alpha=ALPHA, bc="free", method="dop853_numba", rtol=1e-13,
                            terms=terms)
    exact = a * np.cos(np.outer(t, omega))
    assert np.max(np.abs(sol.x - exact)) < 1e-11
    assert np.max(np.abs(sol.v + a * np.array(omega) * np.sin(np.outer(t, omega)))) < 1e-11
    assert sol.max_compression == 0.0


@pytest.mark.parametrize("j", [1, 3, 6])
def test_precompressed_ring_dispersion_measured_from_a_small_amplitude_run(j):
    """One mode x_n = a cos(q n), q = 2 pi j / N, a = 1e-4 delta0, at rest: its projection A(t) + i B(t)/omega
    turns at omega(q); the phase, unwrapped and fitted by a line over 30 periods, gives omega to 1e-6 relative.
    The amplitude's own frequency shift is of second order, O((a/delta0)^2) ~ 1e-8 relative (the quadratic term
    of F acts at second order, like the cubic one), far below the tolerance."""
    N, d0 = 16, 0.2
    q = 2 * np.pi * j / N
    w = dispersion(q, d0, ALPHA)
    n = np.arange(N)
    a = 1e-4 * d0
    t = np.linspace(0.0, 30 * 2 * np.pi / w, 30 * 12 + 1)
    sol = integrate_lattice(a * np.cos(q * n), np.zeros(N), t, alpha=ALPHA, method="dop853_numba", rtol=1e-12,
                            atol=1e-20, terms=Terms(precompression=Precompression(delta0=d0)))
    mode = np.cos(q * n) * (2.0 / N if j != N // 2 else 1.0 / N)
    A, B = sol.x @ mode, sol.v @ mode
    phase = np.unwrap(np.arctan2(-B / w, A))
    measured = np.polyfit(t, phase, 1)[0]
    assert measured == pytest.approx(w, rel=1e-6)
    assert abs(measured - 1.0) > 0.01   # the band is widened: not the on-site frequency
    assert np.allclose(np.hypot(A, B / w), a, rtol=1e-4)   # one mode stays one mode


@pytest.mark.parametrize("theta0", [1.0, 2.5])
def test_large_angle_pendulum_period_is_4K(theta0):
    """A pendulum (scale s = X/l = 0.5) released at rest from the angle theta0 = s x0, its neighbour at rest
    behind a gap of 6 > the horizontal reach 2/s: x(t) returns to x0 after T = 4 K(sin^2(theta0/2)) (in units of
    1/omega_0 = sqrt(l/g)) and passes 0 at T/4."""
    s = 0.5
    terms = Terms(onsite=OnSite(potential="pendulum", scale=s), precompression=Precompression(delta0=-6.0))
    T = 4.0 * ellipk(np.sin(theta0 / 2) ** 2)
    x0 = theta0 / s
    sol = integrate_lattice([x0, 0.0], [0.0, 0.0], [0.0, T / 4, T / 2, T], alpha=ALPHA, bc="free",
                            method="dop853_numba", rtol=1e-13, terms=terms)
    assert sol.max_compression == 0.0
    assert abs(sol.x[1, 0]) < 1e-9 * x0
    assert sol.x[2, 0] == pytest.approx(-x0, rel=1e-9)
    assert sol.x[3, 0] == pytest.approx(x0, rel=1e-9)
    assert abs(sol.v[3, 0]) < 1e-9 * x0
    # the harmonic period 2 pi is visibly wrong at these angles
    assert T / (2 * np.pi) - 1 > 0.06


def test_pendulum_tends_to_the_harmonic_bead_as_its_scale_vanishes():
    """On a binary oscillation with contacts, the run with scale s differs from the harmonic one by O(s^2)
    (W'(x) = x - s^2 x^3/6 + ...; u = x - s^2 x^3/6 + ...): halving s divides the difference by 4 (to 10 %)."""
    N = 8
    x0 = 0.5 * (-1.0) ** np.arange(N)
    t = np.linspace(0.0, 20.0, 5)
    ref = integrate_lattice(x0, np.zeros(N), t, alpha=ALPHA, method="dop853_numba", rtol=1e-12)
    diffs = []
    for s in (0.02, 0.01):
        sol = integrate_lattice(x0, np.zeros(N), t, alpha=ALPHA, method="dop853_numba", rtol=1e-12,
                                terms=Terms(onsite=OnSite(potential="pendulum", scale=s)))
        diffs.append(np.max(np.abs(sol.x - ref.x)))
    assert diffs[0] / diffs[1] == pytest.approx(4.0, rel=0.1)


DISORDERED = Terms(inhomogeneity=Inhomogeneity(sigma=0.08, mass_sigma=0.1, seed=3,
                                               stiffness=tuple(1.0 + 0.1 * np.sin(np.arange(24)))),
                   precompression=Precompression(delta0=0.1), onsite=OnSite(potential="quartic", beta=0.5))


def _kicked(N=24):
    v0 = np.zeros(N)
    v0[5] = 0.8
    v0[6] = -0.8
    return np.zeros(N), v0


def test_generalised_energy_is_conserved_on_a_disordered_precompressed_quartic_ring():
    """The drift of the generalised (ham) is the integrator's error: it falls with rtol (DOP853 across the
    contact releases converges like kind 0 on (nc), order ~ 1 in rtol) and is below 1e-8 at rtol 1e-13."""
    x0, v0 = _kicked()
    t = np.linspace(0.0, 50.0, 6)
    drifts = []
    for rtol in (1e-11, 1e-13):
        sol = integrate_lattice(x0, v0, t, alpha=ALPHA, method="dop853_numba", rtol=rtol, terms=DISORDERED)
        drifts.append(sol.energy_drift)
    assert sol.max_compression > 0.2   # the contacts are loaded beyond their static overlap
    assert drifts[1] < 1e-8 and drifts[1] < drifts[0] / 10.0
    assert np.max(np.abs(sol.energy - sol.energy[0])) <= drifts[1] * sol.energy[0] * (1.0 + 1e-6)   # at outputs
    assert np.array_equal(sol.dissipated, np.zeros(len(t)))


def test_damped_imperfect_ring_keeps_h_plus_d():
    """H + D = H(0) to the integrator's error (D integrated as a component of the state, never H(0) - H)."""
    x0, v0 = _kicked()
    t = np.linspace(0.0, 100.0, 11)
    sol = integrate_lattice(x0, v0, t, alpha=ALPHA, method="dop853_numba", rtol=1e-13, terms=DISORDERED,
                            damping=Damping(onsite=0.01, contact=0.2))
    H0 = sol.energy[0]
    assert sol.dissipated[-1] > 0.5 * H0   # most of the energy is gone
    assert np.all(np.diff(sol.dissipated) > 0.0)
    assert np.max(np.abs(sol.energy + sol.dissipated - H0)) <= sol.energy_drift * H0 * (1.0 + 1e-6)   # at outputs
    assert sol.energy_drift < 1e-7


@pytest.mark.parametrize("bc", ["periodic", "free"])
def test_trivial_terms_through_kind_4_are_kind_0_bitwise(bc):
    """Every coefficient 1, delta0 = 0, harmonic: kind 4 computes kind 0's floats (x 1, + 0), so the run is
    kind 0's, bitwise (the energy, summed in another order, to rounding)."""
    N = 16
    n = np.arange(N)
    x0, v0 = 0.3 * np.cos(np.pi / 4 * n), 0.3 * np.sin(np.pi / 4 * n)
    t = np.linspace(0.0, 30.0, 7)
    ref = integrate_lattice(x0, v0, t, alpha=ALPHA, bc=bc, method="dop853_numba", rtol=1e-12)
    X, V, E, D, drift, steps, _nfev, cmax = run_dop853_terms(x0, v0, t, 1e-12, ref.atol, ALPHA, 0, bc == "periodic",
                                                              Terms(), homogeneous(N), None, None)
    assert np.array_equal(X, ref.x) and np.array_equal(V, ref.v) and steps == ref.n_steps
    assert np.max(np.abs(E - ref.energy)) < 1e-14
    assert cmax == ref.max_compression
    assert drift == pytest.approx(ref.energy_drift, rel=1e-6, abs=1e-15)


@pytest.mark.parametrize("method", ["srkn6c", "dop853_numba"])
def test_inactive_terms_leave_the_run_bitwise(method):
    N = 12
    x0, v0 = _kicked(N)
    t = np.linspace(0.0, 10.0, 3)
    kw = {"rtol": 1e-10} if method == "dop853_numba" else {}
    ref = integrate_lattice(x0, v0, t, alpha=ALPHA, method=method, **kw)
    for terms in (Terms(), Terms(onsite=OnSite(potential="quartic")), Terms(inhomogeneity=Inhomogeneity(seed=9))):
        sol = integrate_lattice(x0, v0, t, alpha=ALPHA, method=method, terms=terms, **kw)
        assert np.array_equal(sol.x, ref.x) and np.array_equal(sol.v, ref.v)
        assert np.array_equal(sol.energy, ref.energy)


@pytest.mark.parametrize(("kw", "N", "words"), [
    ({"method": "srkn6c"}, 4, ["srkn6c", "dop853_numba"]),
    ({"potential": "smooth"}, 4, ["smooth", "hertz"]),
    ({"bc": "free", "terms": lambda: Terms(precompression=Precompression(delta0=0.1))}, 4, ["delta0 = 0.1", "free"]),
    ({"terms": lambda: Terms(inhomogeneity=Inhomogeneity(mass=(1.0, 1.0, -2.0, 1.0)))}, 4, ["mass", "-2.0"]),
    ({"terms": lambda: Terms(inhomogeneity=Inhomogeneity(sigma=0.5, seed=0))}, 400, ["sigma = 0.5", "omega"]),
])
def test_refusals_are_one_line(kw, N, words):
    """Refused before any work (where the terms are built, or by the run): the run asked for would take hours
    (t = 4e6, below the 2^22 that stored times may reach)."""
    args = {"method": "dop853_numba", "terms": lambda: Terms(onsite=OnSite(potential="quartic", beta=0.1)), **kw}
    with pytest.raises((ValueError, ConfigError)) as err:
        args["terms"] = args["terms"]()
        integrate_lattice(np.zeros(N), np.ones(N), [0.0, 4e6], alpha=ALPHA, **args)
    msg = str(err.value)
    assert "\n" not in msg, msg
    for w in words:
        assert w in msg, msg
