"""Where DpS is known to approximate the lattice: the amplitudes the dps-validity analysis measures.

The analysis `dps-validity` (:mod:`cradle.analyses.dps_validity`, docs/analyses.md) measures the error of
(ansatz) against the lattice for eps up to :data:`EPS_MEASURED` (its declared ``eps_max``), i.e. for amplitudes
a = 2 eps up to :func:`measured_amplitude`. There the error follows its consistency law (relative size
eps^(alpha-1)); above it nothing is measured, and eps^(alpha-1) is no longer small. :func:`outside_range` is the
one line a scene's job writes when its amplitude is above it.
"""
from __future__ import annotations

import numpy as np
import numpy.typing as npt

from cradle.specs.values import DPS_EPS_MEASURED

#: the largest eps of (ansatz) at which dps-validity measures DpS against the lattice (its spec's eps_max)
EPS_MEASURED = DPS_EPS_MEASURED


def measured_amplitude() -> float:
    """The largest amplitude a = 2 eps at which DpS was measured against the lattice: 2 :data:`EPS_MEASURED`."""
    return 2.0 * EPS_MEASURED


def amplitude_of(x0: npt.ArrayLike, v0: npt.ArrayLike) -> float:
    """A lattice state's amplitude as (ansatz) counts it: max_n sqrt(x_n^2 + v_n^2) (with omega_0 = 1 this is
    2 eps |A_n| for x = eps (A e^{it} + c.c.); for a bead kicked from rest, its velocity)."""
    return float(np.max(np.hypot(np.asarray(x0, dtype=float), np.asarray(v0, dtype=float))))


def outside_range(name: str, x0: npt.ArrayLike, v0: npt.ArrayLike) -> str | None:
    """One line when scene ``name``'s initial state (x0, v0) is above :func:`measured_amplitude`, where DpS is not
    known to approximate the lattice; None within it."""
    a, top = amplitude_of(x0, v0), measured_amplitude()
    if not a > top:
        return None
    return (f"{name}: amplitude a = {a:.3g} (units of (nc)) is above {top:g}, the largest amplitude at which DpS "
            f"was measured to approximate the lattice (analysis dps-validity, eps <= {EPS_MEASURED:g}; "
            "docs/analyses.md): its DpS run and the error E of its metrics compare the lattice with DpS outside "
            "DpS's range")
