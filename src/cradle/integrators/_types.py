"""The array types the kernels' annotations name (numba ignores annotations; mypy reads them)."""
from __future__ import annotations

from typing import TypeAlias

import numpy as np
from numpy.typing import NDArray

#: a float64 array: a state, its rate, the stages, a work array, the invariants' drifts
Floats: TypeAlias = NDArray[np.float64]
#: an int64 array: the counters a kernel adds to
Ints: TypeAlias = NDArray[np.int64]
#: what an adaptive run of the lattice returns: (X, V, E, energy drift, steps, rhs evaluations, max compression)
LatticeRun: TypeAlias = tuple[Floats, Floats, Floats, float, int, int, float]
#: the same with D, the dissipated energy, after E (a damped or an imperfect run)
DampedRun: TypeAlias = tuple[Floats, Floats, Floats, Floats, float, int, int, float]
