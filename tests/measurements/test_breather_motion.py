"""cradle.measurements.breather_motion: the weights, the tracked position and the radiation, against closed forms."""
from __future__ import annotations

import numpy as np
import pytest

from cradle.measurements import breather_motion as BM
from cradle.models import lattice


def test_energy_density_sums_to_the_hamiltonian():
    rng = np.random.default_rng(20261128)
    x, v = rng.normal(0, 0.1, (3, 20)), rng.normal(0, 0.1, (3, 20))
    e = BM.energy_density(x, v, 1.5)
    assert np.all(e >= 0)
    np.testing.assert_allclose(e.sum(axis=-1), lattice.hamiltonian(x, v, 1.5), rtol=1e-14)


def test_a_symmetric_bump_is_tracked_round_the_ring_to_rounding():
    """w_n = exp(-(n - m)^2) centred on site m: the centroid over the symmetric core is m exactly, and the position
    keeps counting past the end of the ring."""
    M = 12
    n = np.arange(M)
    centres = np.arange(0, 30) * 1.0      # a site per sample, over two and a half turns
    d = (n[None, :] - centres[:, None] + M / 2) % M - M / 2
    w = np.exp(-(d**2))
    p = BM.track(w, core=3)
    assert np.max(np.abs(p - p[0] - centres)) < 1e-12
    assert BM.velocity(np.arange(centres.size), p) == pytest.approx(1.0, rel=1e-12)


def test_a_jump_beyond_the_reach_is_refused():
    w = np.zeros((2, 20))
    w[0, 2] = w[1, 12] = 1.0
    with pytest.raises(ValueError, match="sample more often"):
        BM.track(w, core=2)


def test_radiation_is_the_weight_outside_the_window():
    w = np.ones((1, 20))
    w[0, 5] = 11.0                        # total 30, the window of 2 either side holds 15
    assert BM.radiation(w, np.array([5.2]), window=2)[0] == pytest.approx(0.5, rel=1e-15)
    # the window wraps round the ring
    assert BM.radiation(w, np.array([0.0]), window=2)[0] == pytest.approx(25 / 30, rel=1e-15)
