"""Natural continuation of a family of travelling breathers in the velocity c = 1/T: the loop both solvers share
(:mod:`cradle.integrators.dps_travelling` for (dfnls), :mod:`cradle.integrators.lattice_travelling` for (nc))."""
from __future__ import annotations

from collections.abc import Callable
from typing import Protocol, TypeVar

import numpy as np
from numpy.typing import ArrayLike


class Member(Protocol):
    """A solved member: its velocity and whether its Newton converged."""

    @property
    def c(self) -> float: ...

    @property
    def converged(self) -> bool: ...


M = TypeVar("M", bound=Member)


def continue_in_c(first: M, cs: ArrayLike, correct: Callable[[M, float], M], min_step: float,
                  say: Callable[[str], object], label: str,
                  describe: Callable[[M], str]) -> tuple[list[M], float | None]:
    """The members at the velocities ``cs`` (in order, from ``first``'s c): ``correct(previous, c)`` predicts from
    the previous member and corrects at c; a step that fails is halved down to ``min_step`` (relative to c), and
    there the family is said to end or turn (``label`` names it). Returns the members reached at the grid's c and
    the last c reached; ``describe`` words each member for ``say``."""
    out: list[M] = []
    cur = first
    for c in np.asarray(cs, float):
        while abs(cur.c - c) > 1e-14 * c:
            step = c - cur.c
            while True:
                b = correct(cur, cur.c + step)
                if b.converged:
                    cur = b
                    break
                step *= 0.5
                if abs(step) < min_step * abs(c):
                    say(f"{label}: the family ends or turns near c = {cur.c:.6g}")
                    return out, cur.c
        out.append(cur)
        say(f"{label}: c = {cur.c:.6g}: {describe(cur)}")
    return out, out[-1].c if out else None
