"""Precompression of a cradle: a uniform static overlap delta_0 of the contacts, or small gaps.

In the units of (nc), a ring of beads squeezed so that every bond of stiffness 1 overlaps by delta_0 > 0 at rest
(a bond of stiffness k_n by delta_n = delta_0 k_n^(-1/alpha): the static force delta_0^alpha is the same on every
bond) has the bond force of (ncimperfect) (:mod:`.lattice_terms`)

    F_n(d) = -(delta_n - d)_+^alpha + (delta_n)_+^alpha,     F_n(0) = 0,

whose constant cancels on a ring. Linearised about rest, F ~ kappa d with kappa = alpha delta_0^(alpha-1)
(= (3/2) delta_0^(1/2) for Hertz), which widens the flat on-site band of (nc) into

    omega(q)^2 = 1 + 4 kappa sin^2(q/2)                               (the linear dispersion, :func:`dispersion`)

delta_0 < 0 gives the beads gaps -delta_0 (a real cradle's): F_n(d) = -(delta_n - d)_+^alpha, no static force.
A precompressed chain with free ends would fly apart (nothing holds the static force at its ends): it is refused
(:func:`cradle.models.lattice_terms.check`); walls are not modelled.
"""
from __future__ import annotations

import numpy as np

from cradle.specs.declare import check_fields, declared, param


@declared("precompression", doc="Uniform static overlap delta0 of the contacts of an imperfect cradle "
                                "(ncimperfect), in units of X: > 0 precompressed (a ring only), < 0 gaps.")
class Precompression:
    delta0: float = param(0.0, "Static overlap delta_0 of a bond of stiffness 1 (units X): > 0 precompressed "
                          "(periodic chains only: a free chain would fly apart), < 0 gaps of -delta_0; in "
                          "[-100, 100].", minimum=-100, maximum=100)

    def __post_init__(self) -> None:   # built directly: checked as the config's values are
        check_fields(self, "precompression")

    @property
    def active(self) -> bool:
        """Whether the contacts are precompressed or gapped (False: the touching beads of (nc))."""
        return self.delta0 != 0.0


def coupling(delta0: float, alpha: float) -> float:
    """Linear coupling kappa = alpha delta_0^(alpha-1) of a precompressed bond (0 without precompression)."""
    return alpha * delta0 ** (alpha - 1.0) if delta0 > 0.0 else 0.0


def dispersion(q, delta0: float, alpha: float):
    """Linear dispersion omega(q) = sqrt(1 + 4 kappa sin^2(q/2)) of the precompressed homogeneous ring."""
    return np.sqrt(1.0 + 4.0 * coupling(delta0, alpha) * np.sin(0.5 * np.asarray(q, dtype=float)) ** 2)
