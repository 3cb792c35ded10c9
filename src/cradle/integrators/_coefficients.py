"""Coefficients of the symplectic BAB splittings.

A step of length h is  e^{h b_1 B} e^{h a_1 A} e^{h b_2 B} ... e^{h a_m A} e^{h b_{m+1} B}
with B the contact potential (kicks, v += h b_i F(x)) and A the harmonic
on-site part sum (v^2 + x^2)/2 (exact rotation by the angle h a_i).

The Runge-Kutta-Nystrom (RKN) methods of Blanes & Moan (2002), "Practical
symplectic partitioned Runge-Kutta and Runge-Kutta-Nystrom methods",
J. Comput. Appl. Math. 142, 313-330 (SRKN_6^b order 4, SRKN_11^b order 6),
only satisfy the order conditions of the Lie algebra in which
[B, [B, [B, A]]] = 0. That holds here with B = potential (a function of x
only) and A = kinetic + harmonic: {V, {V, (v^2 + x^2)/2}} = sum (dV/dx)^2
depends on x only, so the RKN orders carry over to the rotation splitting.
The b's (m + 1 of them, first and last applied to the same force: FSAL)
belong to the kicks, the a's (m) to the rotations (checked by the observed
orders 2/4/6 in tests/test_integrators.py).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import ArrayLike

    from cradle.integrators._types import Floats

_SRKN6B_A = [0.245298957184271, 0.604872665711080, -0.350171622895351]
_SRKN6B_B = [0.0829844064174052, 0.396309801498368, -0.0390563049223486, 0.1195241940131508]

_SRKN11B_A = [0.123229775946271, 0.290553797799558, -0.127049212625417,
              -0.246331761062075, 0.357208872795928, 0.2047770542914700]
_SRKN11B_B = [0.0414649985182624, 0.198128671918067, -0.0400061921041533,
              0.0752539843015807, -0.0115113874206879, 0.2366699247869311]


def _palindrome(half: Sequence[float], odd: bool) -> list[float]:
    """Symmetric list from its first half (``odd``: the middle entry is not repeated)."""
    return list(half) + list(half[::-1][1:] if odd else half[::-1])


def _make(a: ArrayLike, b: ArrayLike) -> tuple[Floats, Floats]:
    a = np.array(a, dtype=float)
    b = np.array(b, dtype=float)
    return a, b


#: name -> (a (m,), b (m+1,), order, number of force evaluations per step)
SPLITTINGS = {
    "strang": (*_make([1.0], [0.5, 0.5]), 2),
    "srkn4": (*_make(_palindrome(_SRKN6B_A, odd=False), _palindrome(_SRKN6B_B, odd=True)), 4),
    "srkn6": (*_make(_palindrome(_SRKN11B_A, odd=True), _palindrome(_SRKN11B_B, odd=False)), 6),
}


def splitting(method: str) -> tuple[Floats, Floats, int]:
    """(a, b, order) of a splitting method; a and b are float64 arrays."""
    return SPLITTINGS[method]
