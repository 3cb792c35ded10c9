"""The signed tail of a lattice TB (cradle.integrators.lattice_tail), checked from its definition.

The reversor R of (nc), x_n -> -x_{2 n0 - n}, v_n -> v_{2 n0 - n} at the symmetric time, with the carrier's phase
xi -> e^{i phi} xi: a state built symmetric about bead n0 has eta_n = xi_n / xi_{n0} = conj(eta_{2 n0 - n}) exactly,
at every phase; moved by one bead it does not. A zero's bracket is a sign change away from which the tail grows
on one side at least and shrinks on neither (a ring resonance's: it grows towards it); without one there is nothing
to locate. The TBs themselves, their zeros
and multipliers are checked in tests/analyses/test_travelling_breathers.py (the lattice fixture).
"""
from __future__ import annotations

import numpy as np
import pytest

from cradle.integrators import lattice_tail as LTail, lattice_travelling as LT

N, N0 = 12, 5


def _symmetric(phi: float) -> tuple[np.ndarray, np.ndarray]:
    """A state R-symmetric about bead N0, its carrier phase turned by phi: xi_n = e^{i phi} (i a_n + b_n), a_n even
    and b_n odd about N0 (so that xi_n = -e^{2 i phi} conj(xi_{2 N0 - n}))."""
    d = (np.arange(N) - N0 + N // 2) % N - N // 2
    a, b = np.exp(-0.3 * d**2), 0.2 * d * np.exp(-0.5 * d**2)
    b[d == -N // 2] = 0.0    # the antipode is its own mirror: an odd part vanishes there
    xi = np.exp(1j * phi) * (1j * a + b)
    return 2.0 * xi.real, -2.0 * xi.imag


@pytest.mark.parametrize("phi", [0.0, 0.7, -2.3])
def test_symmetry_defect_vanishes_on_a_symmetric_state(phi):
    x, v = _symmetric(phi)
    assert LTail.symmetry_defect(x, v, N0, 1.0) < 1e-14
    # the mirror about another bead is not a symmetry of this state
    assert LTail.symmetry_defect(x, v, N0 + 1, 1.0) > 0.1


def _point(c: float, sigma: float) -> tuple[LT.LatticeTB, LTail.SignedTail]:
    b = LT.LatticeTB(np.zeros(2 * N), 1.0 / c, 1.5, 0.0, True, 0)
    return b, LTail.SignedTail(sigma, 0.0, 0.0, 0.0, 1.0, 0.0, 0)


def test_zero_bracket_is_a_sign_change_with_the_tail_growing_away():
    from cradle.analyses.travelling_breathers.tail_zeros import zero_bracket

    # a ring resonance (a pole: |sigma| grows towards it) between points 1 and 2, a zero between 3 and 4
    pts = [_point(1.0, 1e-8), _point(1.1, 3e-8), _point(1.2, -4e-8), _point(1.3, -2e-10), _point(1.4, 1e-10),
           None, _point(1.6, 2e-10)]
    assert zero_bracket(pts) == 3
    # a zero with a resonance just beyond it on one side (the point beyond has flipped sign): still a zero
    assert zero_bracket([_point(1.0, -4e-10), _point(1.1, 6e-11), _point(1.2, -3e-11), _point(1.3, -1e-10)]) == 1
    # no sign change; a resonance alone (|sigma| grows towards the flip on both sides)
    assert zero_bracket([_point(1.0, 1e-10), _point(1.1, 2e-10)]) is None
    assert zero_bracket([_point(1.0, -8e-11), _point(1.1, -9e-10), _point(1.2, 1e-9), _point(1.3, 1e-10)]) is None


def test_locate_zero_needs_a_bracket():
    (a, _), (b, _) = _point(1.0, 0.0), _point(1.1, 0.0)
    with pytest.raises(ValueError, match="bracket"):
        LTail.locate_zero(a, b, 1e-10, 2e-10, 1e-11)
