"""Bloch-Floquet stability of the exact travelling waves (cradle.analyses.floquet; Hill's method and the
ring in cradle.analyses.bloch): trivial multipliers, the reduction against the brute-force ring
monodromy, the small-amplitude DpS limit, a direct run."""
import copy

import numpy as np
import pytest

from cradle.analyses import bloch as B, floquet as F
from cradle.analyses.floquet_spec import Floquet, Numerics
from cradle.analyses.registry import FULL, REDUCED, form_spec
from cradle.specs.declare import from_plain, plain, reduced_defaults
from cradle.specs.values import parse_angle
from tolerance import bound_of, eigenvalue_bounds

ALPHA = 1.5
NUM = Numerics(hill_modes=16, grid_log2=16, wave_modes=64, wave_grid_log2=13)


def _wave(q, omega_tw):
    return B.wave_for(q, ALPHA, omega_tw=omega_tw, modes=NUM.wave_modes, grid_log2=NUM.wave_grid_log2)


@pytest.fixture(scope="module")
def ring10():
    """q = 3 pi / 5 on a ring of 10 sites, omega_tw = 1.1: unstable (Bloch p = 2 pi j / 10)."""
    w = _wave(2 * np.pi * 3 / 10, 1.1)
    return w, B.ring_monodromy(w, 10)


def test_trivial_multipliers_and_hamiltonian_symmetry(ring10):
    w, Mono = ring10
    mu = np.linalg.eigvals(Mono)
    # time translation and the amplitude family: a double multiplier 1 (a Jordan block: error ~ sqrt(tol))
    assert np.sort(np.abs(mu - 1.0))[1] < 1e-4
    # volume preserving (no damping): det = 1; symplectic: the multipliers come as mu, 1/conj(mu)
    assert abs(np.prod(mu) - 1.0) < 1e-8
    mirrored = 1.0 / np.conj(mu)
    assert B.match_distance(mu, mirrored) < 1e-6
    # Bloch: the central pair at p = 0 is (0, 0) up to the discretisation error; stable modes are neutral
    H = B.Hill(w, L=NUM.hill_modes, M=2 ** NUM.grid_log2)
    assert H.trivial_defect() < 1e-3
    # the pencil keeps the Hamiltonian symmetry lambda <-> -conj(lambda), so these hold to the rounding bound of
    # each eigenvalue of its companion matrix (tolerance.eigenvalue_bounds)
    c = H.central(0.3)                     # q = 3pi/5, omega_tw = 1.1: p = 0.3 is unstable ...
    lam, bounds = eigenvalue_bounds(H.matrix(0.3))
    assert c.size == 2 and abs(c[0].real + c[1].real) <= np.sum(bound_of(c, lam, bounds))   # ... as lambda, -conj
    c = H.central(0.9 * np.pi)             # ... and 0.9 pi stable: on the imaginary axis
    lam, bounds = eigenvalue_bounds(H.matrix(0.9 * np.pi))
    assert np.max(np.abs(c.real)) <= np.max(bound_of(c, lam, bounds))


def test_bloch_reduction_equals_brute_force_monodromy(ring10):
    w, Mono = ring10
    T = 2 * np.pi / w.omega
    mu = np.linalg.eigvals(Mono)
    H = B.Hill(w, L=NUM.hill_modes, M=2 ** NUM.grid_log2)
    lam = B.ring_exponents_hill(H, 10)
    assert lam.size == 20                   # two central exponents per Bloch wavenumber
    mu_h = B.multipliers(lam, T)
    assert B.match_distance(mu, mu_h) < 2e-3   # the neutral double multiplier 1 dominates the distance
    top, top_h = np.max(np.log(np.abs(mu))) / T, np.max(np.log(np.abs(mu_h))) / T
    assert top > 0.005
    assert abs(top_h / top - 1.0) < 1e-4


@pytest.mark.parametrize("q", [0.6 * np.pi, 0.8 * np.pi])
def test_small_amplitude_growth_matches_dps(q):
    """omega_tw = 1.001: max growth within 1 % of the DpS prediction, the band against p within 2 %."""
    w = _wave(q, 1.001)
    H = B.Hill(w, L=NUM.hill_modes, M=2 ** NUM.grid_log2)
    g, p = H.max_growth(61)
    gd, pd = F.dps_max_growth(q, ALPHA, w.a)
    assert abs(g / gd - 1.0) < 0.01
    assert abs(p - pd) < 0.02 * np.pi
    ps = np.linspace(0.05, np.pi, 30)
    np.testing.assert_allclose(H.growth(ps), F.dps_growth(q, ps, ALPHA, w.a), atol=0.02 * gd)
    # at omega_tw = 1.01 the finite-amplitude correction is a few per cent
    w = _wave(q, 1.01)
    g1 = B.Hill(w, L=NUM.hill_modes, M=2 ** NUM.grid_log2).max_growth(61)[0]
    assert abs(g1 / F.dps_max_growth(q, ALPHA, w.a)[0] - 1.0) < 0.05


def test_lattice_threshold_lies_below_pi_over_2_at_omega_tw_1_1():
    """The spectral result: stable at 0.46 pi, unstable at 0.49 pi and pi/2 (DpS: stable up to pi/2)."""
    assert F._hill_at(0.46 * np.pi, ALPHA, 1.1, NUM).max_signed(61)[0] < 0
    for qf in (0.49, 0.5):
        g, p = F._hill_at(qf * np.pi, ALPHA, 1.1, NUM).max_growth(61)
        assert g > 3e-3 and p > 0.8 * np.pi
        assert F.dps_max_growth(qf * np.pi, ALPHA, 1.0)[0] == 0.0


def test_direct_simulation_grows_at_the_top_floquet_rate():
    w = _wave(2 * np.pi * 3 / 10, 1.1)
    rate_mode, rate_dist, rate, t, dist = B.direct_growth(w, 10, growth_factor=300.0)
    assert rate > 0.005
    assert abs(rate_mode / rate - 1.0) < 0.02
    assert dist[-1] / dist[0] > 30


def test_floquet_spec_names_the_key():
    from cradle.pipeline import config as cc

    cfg = cc.load("config.yaml")
    spec = cc.analysis_spec(cfg, "floquet", FULL)
    assert abs(parse_angle(spec.q_min) - 0.4 * np.pi) < 1e-15 and spec.fine.hill_modes >= spec.hill_modes
    bad = copy.deepcopy(cfg)
    bad["beyond"].setdefault("floquet", {})["q_max"] = "0.3pi"
    with pytest.raises(ValueError, match="beyond.floquet.q_max"):
        cc.analysis_spec(bad, "floquet", FULL)
    bad = copy.deepcopy(cfg)
    bad["beyond"].setdefault("floquet", {})["ring_k"] = bad["beyond"]["floquet"]["ring_N"]
    with pytest.raises(ValueError, match="beyond.floquet.ring_k"):
        cc.analysis_spec(bad, "floquet", FULL)
    bad = copy.deepcopy(cfg)
    bad["beyond"].setdefault("floquet", {})["threshold_omega_tw"] = [1.05]
    with pytest.raises(ValueError, match="threshold_omega_tw"):
        cc.analysis_spec(bad, "floquet", FULL)


def test_both_forms_round_trip_through_plain_values():
    """What a rule's params carry (angles in their one form by value, the finer numerics as declared)
    rebuilds the same form, value for value (``0.4pi`` comes back as ``2pi/5``, the same angle); the
    reduced form takes the reduced keys, convergence included."""
    spec = Floquet()
    for form in (REDUCED, FULL):
        one = form_spec(spec, form)
        back = form_spec(from_plain(Floquet, plain(one)), FULL)
        assert plain(back) == plain(one)
        for key in ("q_min", "q_max", "threshold_q_min", "threshold_q_max"):
            assert parse_angle(getattr(back, key)) == parse_angle(getattr(one, key)), key
    reduced, declared = form_spec(spec, REDUCED), reduced_defaults(Floquet)
    assert (reduced.n_q, reduced.q_profiles, reduced.q_min) == (declared["n_q"], declared["q_profiles"], "0.4pi")
    conv = declared["convergence"]
    assert reduced.fine == Numerics(conv.hill_modes, conv.grid_log2, conv.wave_modes, declared["wave_grid_log2"])
