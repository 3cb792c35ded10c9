"""The compression c that sets the splittings' default step on (nc)/(meca), bounded from the initial state and
the energy (ham): the step is a fixed fraction (per method) of the shortest linearised period 2 pi / omega_max(c)
(:func:`cradle.models.lattice.default_dt`, beside the dispersion, so the budget reads it without the compiled
kernels). :func:`cradle.integrators.integrate_lattice` reruns
with a larger c when the run meets a larger compression.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.integrators import _kernels as K

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


def compression_bounds(x0: ArrayLike, v0: ArrayLike, alpha: float, bc: str = "periodic",
                       potential: str = "hertz") -> tuple[float, float]:
    """Compression c assumed for the default step, and the energy bound on it.

    Returns ``(c_assumed, c_energy)``:

    * ``c_energy = ((alpha + 1) H)^(1/(alpha+1))``: every term of (ham) is
      >= 0, so a single bond holding all the energy H satisfies
      c^(alpha+1)/(alpha+1) <= H. Rigorous (H is conserved) but pessimistic
      for long chains, where H grows like N;
    * the working guess ``2 c0 + A0`` with c0 the largest initial compression
      and A0 = max_n sqrt(x_n^2 + v_n^2) the largest initial oscillator
      amplitude (a bond is compressed by at most |x_n| + |x_{n+1}|; the factor 2
      on c0 leaves room for moderate energy focusing, e.g. breather formation).

    ``c_assumed = min(2 c0 + A0, c_energy)``. After the run, if a larger
    compression was met, :func:`integrate_lattice` reruns with
    ``min(1.5 max_compression, c_energy)``.
    """
    alpha = float(alpha)
    x0 = np.ascontiguousarray(x0, dtype=float)
    v0 = np.ascontiguousarray(v0, dtype=float)
    mode = K.mode_flag(potential, alpha)
    H0, c0 = K.lattice_energy(x0, v0, alpha, mode, bc == "periodic")
    A0 = float(np.sqrt(np.max(x0**2 + v0**2)))
    c_energy = ((alpha + 1.0) * max(H0, 0.0)) ** (1.0 / (alpha + 1.0))
    return min(2.0 * c0 + A0, c_energy), c_energy

