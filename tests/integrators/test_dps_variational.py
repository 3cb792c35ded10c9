"""The compiled shooting system of the travelling breathers (cradle.integrators.systems.dps_variational).

Its right-hand side is (dfnls) and the variational equation of (dfnls) column by column: the numpy formulas of
cradle.models.dps_travelling (rhs, linearised_rhs, the latter checked against finite differences of the former in
tests/models/test_dps_travelling.py) to rounding. Integrated, the columns are DPhi_T applied to the initial
columns: linear in them (a column of 2 V gives 2 DPhi_T V to the tolerance); without columns the system is
(dfnls) alone in the same DOP853 loop with the same tolerances as integrate_dps, so the orbit is integrate_dps's,
bitwise.
"""
from __future__ import annotations

import numpy as np

from cradle.integrators import dps_travelling as DT, integrate_dps
from cradle.integrators.systems import dps_variational as DV
from cradle.models import dps, dps_travelling as M

EPS = np.finfo(float).eps


def _state(N: int, m: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    A = rng.normal(size=N) + 1j * rng.normal(size=N)
    V = rng.normal(size=(N, m)) + 1j * rng.normal(size=(N, m))
    A[3] = A[2]            # a bond at rest: Dg(0) = 0 (alpha > 1)
    return A, V


def test_rhs_is_dfnls_and_its_variational_equation():
    N, m = 11, 4
    for alpha in (1.5, 2.3):
        A, V = _state(N, m, 7)
        t0 = dps.tau0(alpha)
        system = DV.dfnls_variational(alpha, 1.0 / (2.0 * t0), m)
        y = np.concatenate([A.view(float), V.view(float).ravel()])
        dy = np.full_like(y, np.nan)
        DV.variational_rhs(system, y, dy)
        dA, dV = dy[:2 * N].view(complex), dy[2 * N:].view(complex).reshape(N, m)
        ref_A, ref_V = M.rhs(A, alpha, t0), M.linearised_rhs(A, V, alpha, t0)
        # each entry is a sum of a few terms of the size of the largest: rounding, relative to the largest
        assert np.max(np.abs(dA - ref_A)) <= 16 * EPS * np.max(np.abs(ref_A))
        assert np.max(np.abs(dV - ref_V)) <= 16 * EPS * np.max(np.abs(ref_V))


def test_flow_is_the_dps_orbit_and_linear_in_the_columns():
    N, alpha, T, rtol = 10, 1.5, 0.7, 1e-12
    A, V = _state(N, 3, 11)
    A = A / np.sqrt(np.sum(np.abs(A) ** 2))
    B, W = DT.flow(A, T, alpha, V, rtol=rtol)
    B2, W2 = DT.flow(A, T, alpha, 2.0 * V, rtol=rtol)
    ref = integrate_dps(A, np.array([0.0, T]), alpha=alpha, rtol=rtol).A[-1]
    assert W is not None and W2 is not None
    assert np.array_equal(DT.flow(A, T, alpha, rtol=rtol)[0], ref)
    # with columns the steps differ (their error counts too): global errors of some hundred steps at rtol,
    # a stated allowance of 1e3 rtol of the state's size
    assert np.max(np.abs(B - ref)) <= 1e3 * rtol * np.max(np.abs(A))
    assert np.max(np.abs(W2 - 2.0 * W)) <= 1e3 * rtol * np.max(np.abs(W))
