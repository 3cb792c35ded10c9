"""The array types the kernels' annotations name (numba ignores annotations; mypy reads them)."""
from __future__ import annotations

from typing import TypeAlias

import numpy as np
from numpy.typing import NDArray

#: a float64 array: a state, its rate, the stages, a work array, the invariants' drifts
Floats: TypeAlias = NDArray[np.float64]
#: an int64 array: the counters a kernel adds to
Ints: TypeAlias = NDArray[np.int64]
