"""cradle.measurements.floquet_bubbles: Krein signatures, the spectrum's symmetries and the two-mode collision model,
checked against closed forms.

* A complex-linear map z -> L z written in (Re z, Im z) is symplectic; its eigenvalue lambda carries the Krein
  signature +1 and conj(lambda) -1 (the real eigenvector of lambda is (z, -i z)).
* exp(J S) for a symmetric S is symplectic: M^T J M = J and its spectrum comes in quadruples (to rounding).
* Two modes of opposite signature coupled by g (i da/dt = w1 a + g conj(b), i d conj(b)/dt = -w2 conj(b) - g a):
  over unit time ln |mu| = sqrt(g^2 - (Delta/2)^2), Delta = w1 + w2 the detuning of their angles; the bubble is
  4 g wide in Delta and g high, which collision_peak returns from the width and the detuning rate.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import expm

from cradle.measurements import floquet_bubbles as FB


def _real_form(L: np.ndarray) -> np.ndarray:
    """The real 2n x 2n matrix of the complex-linear map z -> L z in the coordinates (Re z, Im z)."""
    return np.block([[L.real, -L.imag], [L.imag, L.real]])


def test_signatures_of_a_complex_linear_map():
    phi = np.array([0.3, 1.1, 2.0, -2.5])
    M = _real_form(np.diag(np.exp(1j * phi)))
    assert FB.symplectic_defect(M) < 1e-15
    mu, sigma = FB.krein_signatures(M)
    for p in phi:
        assert sigma[np.argmin(np.abs(mu - np.exp(1j * p)))] == 1.0
        assert sigma[np.argmin(np.abs(mu - np.exp(-1j * p)))] == -1.0
    assert FB.quartet_defect(mu) < 1e-14
    # + at phi, - at -phi: the closest opposite pair is 2.0 (+) and 2.5 (-, from -2.5), 0.5 apart
    assert FB.krein_gap(mu, sigma, 0) == pytest.approx(0.5, abs=1e-14)


def test_exponential_of_a_hamiltonian_matrix_is_symplectic_with_quadruples():
    rng = np.random.default_rng(1)
    n = 5
    S = rng.normal(size=(2 * n, 2 * n))
    S = 0.3 * (S + S.T)        # indefinite: some quartets off the circle
    M = expm(FB.symplectic_form(n) @ S)
    assert FB.symplectic_defect(M) < 1e-12
    mu = np.linalg.eigvals(M)
    assert FB.quartet_defect(mu) < 1e-10


def _two_modes(w1: float, w2: float, g: float) -> np.ndarray:
    """The unit-time flow of i da/dt = w1 a + g conj(b), i d conj(b)/dt = -w2 conj(b) - g a (the Hamiltonian
    w1 |a|^2 + w2 |b|^2 + coupling; uncoupled, a -> e^{-i w1} a and b -> e^{-i w2} b, so that for w2 = -w1 the
    multiplier e^{+i w1} is b's of signature + and a's conjugate of signature -) in the real coordinates
    (Re a, Re b, Im a, Im b): a symplectic 4 x 4 matrix, its generator built column by column."""
    def f(y: np.ndarray) -> np.ndarray:
        a, b = y[0] + 1j * y[2], y[1] + 1j * y[3]
        da = -1j * (w1 * a + g * np.conj(b))
        db = np.conj(1j * (w2 * np.conj(b) + g * a))
        return np.array([da.real, db.real, da.imag, db.imag])

    return expm(np.column_stack([f(e) for e in np.eye(4)]))


def test_two_mode_collision_is_the_bubble_model():
    g, w = 0.02, 1.0
    delta = np.linspace(-0.1, 0.1, 2000)      # no grid point on an edge (+-2 g)
    logmod = np.array([np.max(np.log(np.abs(np.linalg.eigvals(_two_modes(w + d, -w, g))))) for d in delta])
    # at the bubble's edges the multiplier is double: the eigensolver gives it to the square root of rounding
    assert np.max(np.abs(logmod - FB.collision_log_modulus(delta, g))) < np.sqrt(np.finfo(float).eps)
    # outside the bubble all four on the circle, two of each signature
    mu, sigma = FB.krein_signatures(_two_modes(w + 0.1, -w, g))
    assert sorted(sigma) == [-1.0, -1.0, 1.0, 1.0]
    assert FB.symplectic_defect(_two_modes(w, -w, g)) < 1e-14
    h = delta[1] - delta[0]
    inside = delta[logmod > np.sqrt(np.finfo(float).eps)]
    width = inside[-1] - inside[0] + h
    # the width on a grid of spacing h is the true 4 g to within h
    assert FB.collision_peak(width, 1.0) == pytest.approx(np.max(logmod), rel=h / (4 * g))


def test_collision_fit_recovers_the_bubble_from_outside():
    """The pair's splitting outside the bubble of the two-mode flow (exact, from its eigenvalues) fitted by
    collision_fit gives back the coupling g (the bubble's height) and the detuning rate s = 1 of Delta = w1 + w2:
    the model is exact, so to the eigensolver's rounding away from the edges."""
    g, w = 0.02, 1.0
    d = np.concatenate([np.linspace(-0.08, -0.045, 15), np.linspace(0.045, 0.08, 15)])
    split = []
    for x in d:
        mu, sigma = FB.krein_signatures(_two_modes(w + x, -w, g))
        split.append(FB.pair_splitting(mu, sigma, w, 0.2))
    s, gfit = FB.collision_fit(d, split, 0.0)
    assert s == pytest.approx(1.0, abs=1e-9)
    assert gfit == pytest.approx(g, abs=1e-9)


def test_windows_are_runs_of_unstable_points():
    c = np.arange(10) * 0.1
    u = np.array([0, 1, 1, 0, 0, 1, 0, 1, 1, 1], bool)
    assert FB.windows(c, u) == [(0.1, 0.2), (0.5, 0.5), (pytest.approx(0.7), pytest.approx(0.9))]
    assert FB.windows(c, np.zeros(10, bool)) == []


def test_fit_limit_recovers_a_series_and_its_limit():
    """fit_limit on exact series g_inf + b N^-k over rings 24-112 gives them back (the model is exact: to the
    solver's tolerance); a pure finite-size series (g_inf = 0) gives g_inf consistent with 0 within its error; the
    error covers the change when a ring is left out; fewer than four finite rings give NaN."""
    N = np.array([24.0, 32.0, 48.0, 64.0, 96.0, 112.0])
    for g_inf, b, k in ((1e-4, 2e-2, 1.3), (3e-4, -5e-3, 0.5), (0.0, 2e-2, 0.65)):
        f = FB.fit_limit(N, g_inf + b * N ** (-k))
        assert f["g_inf"] == pytest.approx(g_inf, abs=1e-9 * abs(b))
        assert f["k"] == pytest.approx(k, rel=1e-6) and f["b"] == pytest.approx(b, rel=1e-6)
        assert f["points"] == 6 and f["degenerate"] == 0
    f = FB.fit_limit(N, 2e-2 * N ** -0.65 * (1 + 0.05 * np.array([1, -1, 1, -1, 1, -1])))
    assert abs(f["g_inf"]) <= 2 * f["g_inf_error"]
    # a series one ring moves: g_inf's error is at least that move
    y = 1e-4 + 2e-2 * N ** -1.3
    y[0] *= 3.0
    f, g5 = FB.fit_limit(N, y), FB.fit_once(N[1:], y[1:])
    assert f["g_inf_error"] >= abs(f["g_inf"] - g5["g_inf"]) and f["g_inf_stderr"] <= f["g_inf_error"]
    f = FB.fit_limit(N, [1e-3, np.nan, 5e-4, np.nan, 3e-4, np.nan])
    assert np.isnan(f["g_inf"]) and f["points"] == 3
