"""The on-site potential W of a bead of an imperfect cradle (ncimperfect) (:mod:`.lattice_terms`).

* ``harmonic``: W(x) = x^2/2, the linear oscillator of the paper's (nc);
* ``quartic``: W(x) = x^2/2 + beta x^4/4, hard for beta > 0 and soft for beta < 0 (James, Kevrekidis & Cuevas,
  Physica D 251 (2013) 39: surface modes for soft potentials, "boomerons" for hard ones);
* ``pendulum``: the bead is a pendulum of string length l_n whose arc length is x (units X); its horizontal
  position is u = sin(s_n x)/s_n with s_n = X / l_n = scale omega_n^2 (``scale`` = X / l_0), and
  W(x) = (1 - cos(s x))/s^2, W'(x) = sin(s x)/s. The contacts act on the horizontal positions. With
  scale -> 0 it is harmonic; its anharmonicity is W'(x)/x - 1 ~ -(s x)^2/6 = -(X/l)^2 x^2 / 6.

The functions take the scale s of one bead (s = scale omega_n^2 for the pendulum; ignored otherwise).
"""
from __future__ import annotations

import numpy as np

from cradle.specs.declare import check_fields, declared, param

POTENTIALS = ("harmonic", "quartic", "pendulum")
#: the kernels' code of each potential
CODES = {name: i for i, name in enumerate(POTENTIALS)}


@declared("onsite", doc="On-site potential W of the beads of an imperfect cradle (ncimperfect): harmonic "
                        "(the paper's), quartic (beta) or the pendulum's own (scale = X / l_0).")
class OnSite:
    potential: str = param("harmonic", "W: harmonic x^2/2, quartic x^2/2 + beta x^4/4, or pendulum "
                           "(1 - cos(s x))/s^2 with x the arc length and s = scale omega_n^2.",
                           enum=list(POTENTIALS))
    beta: float = param(0.0, "Quartic coefficient beta of W (> 0 hard, < 0 soft); in [-100, 100]; quartic only.",
                        minimum=-100, maximum=100)
    scale: float = param(0.0, "Pendulum: X / l_0, the unit length X of (nc) over the reference string length "
                         "(the bead's angle is scale omega_n^2 x); in [0, 100]; pendulum only.", minimum=0,
                         maximum=100)

    def __post_init__(self) -> None:   # built directly: checked as the config's values are
        check_fields(self, "onsite")

    @property
    def active(self) -> bool:
        """Whether W differs from the harmonic x^2/2 (a quartic with beta = 0 or a pendulum with scale = 0 is
        harmonic)."""
        return (self.potential == "quartic" and self.beta != 0.0) or (self.potential == "pendulum"
                                                                      and self.scale > 0.0)

    def W(self, x, s=None):
        """The on-site potential W(x); ``s`` the pendulum's s_n = scale omega_n^2 (default ``scale``)."""
        x = np.asarray(x, dtype=float)
        if self.potential == "quartic":
            return 0.5 * x**2 + 0.25 * self.beta * x**4
        s = self.scale if s is None else s
        if self.potential == "pendulum" and np.any(np.asarray(s) > 0.0):
            s = np.asarray(s, dtype=float)
            return 2.0 * (np.sin(0.5 * s * x) / s) ** 2   # (1 - cos(s x))/s^2 without its cancellation
        return 0.5 * x**2

    def dW(self, x, s=None):
        """The on-site force per unit mass and omega_n^2, W'(x)."""
        x = np.asarray(x, dtype=float)
        if self.potential == "quartic":
            return x + self.beta * x**3
        s = self.scale if s is None else s
        if self.potential == "pendulum" and np.any(np.asarray(s) > 0.0):
            s = np.asarray(s, dtype=float)
            return np.sin(s * x) / s
        return x

    def u(self, x, s=None):
        """The horizontal position u of a bead at x: sin(s x)/s for the pendulum, else x."""
        x = np.asarray(x, dtype=float)
        s = self.scale if s is None else s
        if self.potential == "pendulum" and np.any(np.asarray(s) > 0.0):
            s = np.asarray(s, dtype=float)
            return np.sin(s * x) / s
        return x
