"""The algebra of DpS travelling breathers (cradle.models.dps_travelling): the linearisation of (dfnls) against
finite differences of its right-hand side, the shift and the residual of (tb) on an exact relation, the scaling."""
from __future__ import annotations

import numpy as np

from cradle.models import dps, dps_travelling as M


def _state(N: int = 9, seed: int = 3) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return rng.normal(size=N) + 1j * rng.normal(size=N)


def test_linearised_rhs_is_the_derivative_of_the_rhs():
    """Central differences of rhs along a direction agree with linearised_rhs to O(h^2) (g is smooth away from
    zero differences, which a random state avoids)."""
    alpha, t0 = 1.5, dps.tau0(1.5)
    A, V = _state(), _state(seed=4)
    h = 1e-6
    fd = (M.rhs(A + h * V, alpha, t0) - M.rhs(A - h * V, alpha, t0)) / (2 * h)
    lin = M.linearised_rhs(A, V, alpha, t0)
    assert np.max(np.abs(fd - lin)) <= 1e-8 * np.max(np.abs(lin))
    # columns are linearised one by one
    cols = M.linearised_rhs(A, np.stack([V, 1j * V], axis=1), alpha, t0)
    assert np.array_equal(cols[:, 0], lin)


def test_residual_vanishes_on_an_exact_shifted_state():
    """B = e^{i theta} S A is a TB's state one period later: R = 0 to rounding, and phase_of recovers theta."""
    A, theta = _state(), 0.7
    B = np.exp(1j * theta) * M.shift(A, 1)
    assert M.relative_residual(A, B, theta) < 1e-15
    assert abs(M.phase_of(A, B) - theta) < 1e-14


def test_real_and_complex_are_inverse():
    A = _state()
    assert np.array_equal(M.complex_(M.real(A)), A)


def test_scaling_keeps_the_rhs_homogeneous():
    """rhs(lambda A) = lambda^alpha rhs(A): the scaling lambda A(lambda^(alpha-1) tau) solves (dfnls)."""
    alpha, t0, lam = 1.5, dps.tau0(1.5), 2.5
    A = _state()
    assert np.allclose(M.rhs(lam * A, alpha, t0), lam**alpha * M.rhs(A, alpha, t0), rtol=1e-14, atol=0)
    A2, T2 = M.scaled(A, 10.0, lam, alpha)
    assert T2 == 10.0 * lam ** (1 - alpha) and np.array_equal(A2, lam * A)


def test_tail_amplitude_of_a_localised_state_and_a_background():
    """A state zero on the far quarter ring has no tail; adding eps everywhere gives a tail eps / max."""
    N = 16
    A = np.zeros(N, complex)
    A[7:10] = [0.5, 1.0, 0.5]
    assert M.tail_amplitude(A) == 0.0
    assert abs(M.tail_amplitude(A + 1e-3) - 1e-3 / 1.001) < 1e-15
