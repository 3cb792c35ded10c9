"""cradle.models.multipliers: the trivial multipliers told apart from the others."""
import numpy as np

from cradle.models.multipliers import split_trivial


def test_the_trivial_ones_are_the_nearest_1_and_the_rest_keep_every_other_in_order_of_distance():
    # a symplectic spectrum: a quartet off the circle, a pair on it, a pair at -1 and a Jordan pair at 1
    quartet = 1.2 * np.exp(0.3j)
    mu = np.array([quartet, 1 - 2e-7, np.exp(1j), -1.0, 1 / quartet, np.exp(-1j), 1 + 3e-7, np.conj(quartet),
                   -1.0, 1 / np.conj(quartet)])
    near, rest = split_trivial(mu, 2)
    assert sorted(near) == [1, 6]
    assert sorted(np.concatenate([near, rest])) == list(range(mu.size))
    d = np.abs(mu[rest] - 1.0)
    assert np.all(np.diff(d) >= 0)
    assert np.isclose(np.max(np.abs(mu[near] - 1.0)), 3e-7, rtol=1e-6, atol=0)
    assert d[0] > 1e-3                     # every non-trivial one is far from 1
