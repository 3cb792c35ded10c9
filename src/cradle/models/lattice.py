"""Newton's cradle lattice (nc) with the Hertz contact potential V0 (vhertz).

    d^2 x_n / dt^2 + x_n = V'(x_{n+1} - x_n) - V'(x_n - x_{n-1})          (nc)

with V = V0, V0(x) = |x|^(1+alpha) H(-x) / (1+alpha) for any alpha > 1.
Bead index n runs 0..N-1. Bond n joins beads n and n+1 and carries the
force f_n = V0'(x_{n+1} - x_n) <= 0 (zero when the beads are apart).

Boundary conditions:
  * ``periodic``: x_N = x_0 (a closed ring, section 4 of the paper);
  * ``free``: beads 0 and N-1 have one neighbour; bond N-1 is absent and its
    force is reported as 0 (figure fini).

All functions take arrays whose last axis is n, so they work on one state
(shape (N,)) or on a stored trajectory (shape (T, N)). They are formulas that
right-hand sides and measurements call, and trust their caller: alpha > 1 and
bc one of ``BOUNDARY_CONDITIONS`` (the entry points check them, ``@checked``).
"""
from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

BOUNDARY_CONDITIONS = ("periodic", "free")


def omega_max(c: float, alpha: float) -> float:
    """Highest linearised frequency sqrt(1 + 4 alpha c^(alpha-1)) at bond compression c.

    Linearising (nc) about a state where every bond is compressed by c gives
    the bond stiffness k = V0''(-c) = alpha c^(alpha-1) and the dispersion
    omega(q)^2 = 1 + 4 k sin^2(q/2), maximal at q = pi.
    """
    try:
        return math.sqrt(1.0 + 4.0 * alpha * max(c, 0.0) ** (alpha - 1.0))
    except OverflowError:   # a compression whose stiffness float64 cannot hold: no finite step resolves it
        return math.inf


#: Default step, as a fraction of the shortest linearised period 2 pi / omega_max(c)
#: (see :func:`default_dt`). Chosen (benchmarks/tune_dt_factor.py, which prints the drifts
#: measured) so that the relative energy drift stays <= 1e-8, with a margin of >= 2, on every
#: scene of config.yaml run to its t_end; the breather and loc1 scenes (long runs, slow contact
#: onsets) are the hardest. The uncorrected splittings need small steps because of the Hertz
#: non-smoothness at contact onset; the onset correction allows far larger steps at a smaller drift.
DEFAULT_DT_FACTOR = {"strang": 0.00003, "srkn4": 0.00025, "srkn6": 0.0005, "srkn4c": 0.004, "srkn6c": 0.01}


def default_dt(c: float, alpha: float, method: str = "srkn6c", dt_factor: float | None = None) -> float:
    """dt = dt_factor * 2 pi / omega_max(c) (default dt_factor from DEFAULT_DT_FACTOR)."""
    fac = DEFAULT_DT_FACTOR[method] if dt_factor is None else dt_factor
    return fac * 2.0 * math.pi / omega_max(c, alpha)


def V0(d: ArrayLike, alpha: float) -> NDArray[np.float64]:
    """Hertz potential V0(d) = |d|^(1+alpha) H(-d) / (1+alpha)   (vhertz)."""
    c = np.maximum(-np.asarray(d, dtype=float), 0.0)
    return c ** (1.0 + alpha) / (1.0 + alpha)


def dV0(d: ArrayLike, alpha: float) -> NDArray[np.float64]:
    """Hertz force V0'(d) = -|d|^alpha H(-d)   (vhertzd)."""
    c = np.maximum(-np.asarray(d, dtype=float), 0.0)
    return -(c**alpha)


def bond_elongations(x: ArrayLike, bc: str = "periodic") -> NDArray[np.float64]:
    """d_n = x_{n+1} - x_n for n = 0..N-1; with free ends d_{N-1} = 0 (no bond)."""
    x = np.asarray(x, dtype=float)
    d = np.roll(x, -1, axis=-1) - x
    if bc == "free":
        d[..., -1] = 0.0
    return d


def bond_forces(x: ArrayLike, alpha: float, bc: str = "periodic") -> NDArray[np.float64]:
    """Contact forces f_n = V0'(x_{n+1} - x_n) on every bond (0 on a missing bond)."""
    return dV0(bond_elongations(x, bc), alpha)


def acceleration(x: ArrayLike, alpha: float, bc: str = "periodic") -> NDArray[np.float64]:
    """Right-hand side of (nc): -x_n + f_n - f_{n-1}."""
    f = bond_forces(x, alpha, bc)
    f_left = np.roll(f, 1, axis=-1)
    if bc == "free":
        f_left[..., 0] = 0.0
    return -np.asarray(x, dtype=float) + f - f_left


def hamiltonian(x: ArrayLike, v: ArrayLike, alpha: float, bc: str = "periodic") -> np.float64 | NDArray[np.float64]:
    """Total energy (ham): sum_n v_n^2/2 + x_n^2/2 + V0(x_{n+1} - x_n)."""
    x = np.asarray(x, dtype=float)
    v = np.asarray(v, dtype=float)
    d = bond_elongations(x, bc)
    return np.sum(0.5 * v**2 + 0.5 * x**2 + V0(d, alpha), axis=-1)


def binary_oscillation_rhs(a: float, alpha: float) -> float:
    """Acceleration of the integrable reduction (inteq): a'' = -a - 2^alpha a |a|^(alpha-1).

    x_n(t) = (-1)^n a(t) solves (nc) with V = V0 for N even and periodic ends.
    """
    return -a - 2.0**alpha * a * abs(a) ** (alpha - 1.0)
