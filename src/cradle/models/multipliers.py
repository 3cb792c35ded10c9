"""Floquet multipliers of a periodic orbit with continuous symmetries: the trivial ones told apart from the others.

Each continuous symmetry of the flow (a phase turn, a time shift) puts a multiplier at 1 in a Jordan block with its
conserved quantity (norm, H): ``trivial`` multipliers at 1 in exact arithmetic, near 1 in a computed monodromy, where
the largest |mu - 1| among them is the precision of every verdict read from the others.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray


def split_trivial(mu: ArrayLike, trivial: int) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """(trivial indices, the others' indices): the ``trivial`` multipliers nearest 1 and the rest, each in order of
    |mu - 1|."""
    order = np.argsort(np.abs(np.asarray(mu, complex) - 1.0))
    return order[:trivial], order[trivial:]
