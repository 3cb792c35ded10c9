"""A DpS travelling breather (tb) launched in the lattice (nc) through the ansatz (ansatz).

The TB's profile A_n(0), computed on a ring of N sites (:mod:`cradle.integrators.dps_travelling`), is set on a
longer ring of M sites (:func:`embedded`: its N sites with the centre at site N // 2, zeros elsewhere, so that it
has M - N sites ahead of it), and the lattice state is the one the project builds from any DpS amplitude
(:func:`cradle.models.initial.lattice_state`), the ansatz

    x_n^app(t) = eps (A_n(tau) e^{it} + conj(A_n(tau)) e^{-it}),   tau = eps^(alpha-1) t          (ansatz)

at t = 0 with dA_n/dtau from (dfnls):

    x_n(0) = 2 eps Re A_n(0),   v_n(0) = 2 eps (-Im A_n(0) + eps^(alpha-1) Re dA_n/dtau(0)).

A TB of period T (one site per T in tau) moves, in the lattice's time, one site per T / eps^(alpha-1):
its velocity there is c eps^(alpha-1) sites per unit t (:func:`lattice_velocity`).
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.models import dps_travelling as M
from cradle.models.initial import InitialData, lattice_state


def embedded(A: ArrayLike, ring: int) -> NDArray[np.complex128]:
    """The TB's N sites on a ring of ``ring`` >= N sites: rolled so that its centre
    (:func:`cradle.models.dps_travelling.centre`) is at site N // 2, then zeros (the TB's own ring when
    ``ring`` = N)."""
    A = np.asarray(A, dtype=np.complex128)
    N = A.size
    if ring < N:
        raise ValueError(f"ring = {ring}: must be >= the TB's {N} sites")
    out = np.zeros(ring, dtype=np.complex128)
    out[:N] = np.roll(A, N // 2 - int(round(M.centre(A))) % N)
    return out


def lattice_velocity(c: float, eps: float, alpha: float) -> float:
    """The DpS TB's velocity in the lattice's time: c eps^(alpha-1) sites per unit t (tau = eps^(alpha-1) t)."""
    return float(c * eps ** (alpha - 1.0))


def launch(A: ArrayLike, eps: float, alpha: float, ring: int) -> InitialData:
    """The lattice state (x_n(0), v_n(0)) of (ansatz) for the TB profile ``A`` on a ring of ``ring`` sites
    (:func:`embedded`), small parameter ``eps``."""
    A0 = embedded(A, ring)
    x0, v0 = lattice_state(A0, eps, alpha)
    return InitialData(A0=A0, eps=float(eps), x0=x0, v0=v0, info={"eps": float(eps), "ring": int(ring)})
