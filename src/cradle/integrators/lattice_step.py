"""The default step of the splittings on (nc)/(meca): a fraction of the shortest linearised period.

Linearised about bonds compressed by c, (nc) has the dispersion
omega(q)^2 = 1 + 4 alpha c^(alpha-1) sin^2(q/2); the step is a fixed fraction
(per method) of 2 pi / omega_max(c), with c bounded from the initial state
and the energy (ham). :func:`cradle.integrators.integrate_lattice` reruns
with a larger c when the run meets a larger compression.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from cradle.integrators import _kernels as K
from cradle.models.lattice import omega_max

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

#: Default step, as a fraction of the shortest linearised period 2 pi / omega_max(c)
#: (see :func:`default_dt`). Chosen (benchmarks/tune_dt_factor.py, which prints the drifts
#: measured) so that the relative energy drift stays <= 1e-8, with a margin of >= 2, on every
#: scene of config.yaml run to its t_end; the breather and loc1 scenes (long runs, slow contact
#: onsets) are the hardest. The uncorrected splittings need small steps because of the Hertz
#: non-smoothness at contact onset; the onset correction allows far larger steps at a smaller drift.
DEFAULT_DT_FACTOR = {"strang": 0.00003, "srkn4": 0.00025, "srkn6": 0.0005, "srkn4c": 0.004, "srkn6c": 0.01}


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


def default_dt(c: float, alpha: float, method: str = "srkn6c", dt_factor: float | None = None) -> float:
    """dt = dt_factor * 2 pi / omega_max(c) (default dt_factor from DEFAULT_DT_FACTOR)."""
    fac = DEFAULT_DT_FACTOR[method] if dt_factor is None else dt_factor
    return fac * 2.0 * math.pi / omega_max(c, alpha)
