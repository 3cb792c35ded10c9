"""The desk-toy experiments: a Newton's cradle of identical spheres, some lifted at one end and released.

A cradle of ``n_beads`` identical spheres (a :class:`cradle.models.physical.Cradle`: material, radius,
pendulum length) hangs at rest, each ball touching its neighbours without compression. The ``lifted``
balls at the left end (beads 0 .. lifted-1) are pulled out together to the angle theta from the vertical
and released at rest. In the variables of (nc) (:mod:`.physical`: lengths in units of X, time in units of
1/omega_0)

    x_n(0) = -L sin(theta) / X   for n < lifted  (negative side: they swing into the line),
    x_n(0) = 0                   otherwise,          v_n(0) = 0 for every n.

(nc)'s on-site force is the small-angle (linear) pendulum: the released balls reach the line at t = pi/2 with
the speed A = L sin(theta) / X, where the real pendulum has sqrt(2 g L (1 - cos theta)), A times
2 sin(theta/2) / sin(theta) (1.5 % more at 20 degrees).

A desk toy's swing is enormous in (nc)'s units (A about 3.7e17 for 1 cm steel balls on 10 cm strings at
20 degrees: docs/physical-units.md), and (nc) is homogeneous: with x = A y,

    y_n'' + y_n = A^(alpha-1) [V0'(y_{n+1} - y_n) - V0'(y_n - y_{n-1})],

so a large amplitude is a stiff contact next to the on-site oscillator, and the one number that measures how
instantaneous the impacts are is the ratio of the Hertz collision time at the impact speed A to the swing
period 2 pi: :func:`collision_fraction`, which falls as A^(-1/5).
"""
from __future__ import annotations

import math

import numpy as np

from cradle.models.physical import (
    COLLISION_INTEGRAL,
    HERTZ_ALPHA,
    Cradle,
    Scales,
    release_amplitude,
    scales,
)
from cradle.specs.declare import declared, from_plain, param, plain
from cradle.specs.values import ConfigError, Errors

#: the largest chain of the desk-toy experiments: a bound for the config (a desk toy has 5 to 10 balls; a
#: longer chain is a lattice scene)
MAX_BEADS = 1000


@declared(doc="A desk-toy experiment: a cradle of n_beads identical spheres touching at rest, the lifted "
              "ones at the left end pulled out to angle_deg and released at rest.")
class DeskToy:
    n_beads: int = param(5, "Number of balls; in [2, 1000].", minimum=2, maximum=MAX_BEADS)
    lifted: int = param(1, "Number of balls lifted together at the left end; in [1, n_beads - 1].", minimum=1,
                        maximum=MAX_BEADS - 1)
    angle_deg: float = param(20.0, "Angle theta of the lifted balls' strings from the vertical (degrees); in "
                             "(0, 90).", exclusiveMinimum=0, exclusiveMaximum=90)
    cradle: Cradle = param(doc="The spheres and their pendulum strings (cradle.models.physical.Cradle); a "
                               "desk toy needs the pendulum length.")

    def check(self, where: list[str | int], context: object, out: Errors) -> None:
        """What the schema cannot say: at least one ball stays in the line, and the balls hang on strings."""
        if self.lifted >= self.n_beads:
            out.add(where + ["lifted"], f"must be < n_beads = {self.n_beads} (one ball at least stays in the line)",
                    self.lifted)
        if self.cradle.length is None:
            out.add(where + ["cradle"], "a desk toy needs the pendulum length (a stiff oscillator has no angle)")


def desk_toy(n_beads: int, lifted: int, angle_deg: float, cradle: Cradle) -> DeskToy:
    """A validated :class:`DeskToy`; a bad value is one ConfigError line naming the key and the value."""
    spec = from_plain(DeskToy, {"n_beads": n_beads, "lifted": lifted, "angle_deg": angle_deg,
                                "cradle": plain(cradle)}, "desk_toy")
    _refuse_inconsistent(spec)
    return spec


def _refuse_inconsistent(spec: DeskToy) -> None:
    errors = Errors()
    spec.check(["desk_toy"], None, errors)
    errors.raise_any()


def desk_toy_initial(spec: DeskToy) -> tuple[np.ndarray, np.ndarray, Scales]:
    """(x0, v0, scales): the released state in (nc)'s variables and the cradle's SI scales (module docstring).

    ``spec`` is checked again for what its schema cannot say (lifted < n_beads, a pendulum): one ConfigError
    line."""
    _refuse_inconsistent(spec)
    s = scales(spec.cradle)
    x0 = np.zeros(spec.n_beads)
    x0[: spec.lifted] = -release_amplitude(spec.cradle, spec.angle_deg)
    return x0, np.zeros(spec.n_beads), s


def collision_time_nc(v: float) -> float:
    """Hertz collision time of two beads of (nc) meeting at relative speed ``v`` without the on-site force:
    t_c = 2 I delta_max / v with mu = 1/2, k = 1 (the SI formula of :func:`cradle.models.physical.collision_time`
    in (nc)'s units), delta_max = (5 v^2 / 8)^(2/5); it falls as v^(-1/5)."""
    if not v > 0.0:
        raise ConfigError(f"v = {v!r}: must be > 0 (an approach speed)")
    delta_max = (5.0 * 0.5 * v**2 / 4.0) ** (1.0 / (HERTZ_ALPHA + 1.0))
    return 2.0 * COLLISION_INTEGRAL * delta_max / v


def collision_fraction(spec: DeskToy) -> float:
    """t_c / (2 pi): the Hertz collision time at the released balls' impact speed in (nc) (the amplitude A, since
    (nc)'s pendulum is linear) over the swing period 2 pi."""
    x0, _, _ = desk_toy_initial(spec)
    return collision_time_nc(-float(x0[0])) / (2.0 * math.pi)


def equivalent_amplitude(fraction: float) -> float:
    """The (nc) amplitude A whose impact lasts ``fraction`` of a swing: the inverse of t_c(A) / (2 pi)."""
    if not 0.0 < fraction < 1.0:
        raise ConfigError(f"fraction = {fraction!r}: must be in (0, 1) (a collision time over a swing period)")
    # t_c(v) = t_c(1) v^(-1/5)
    return (collision_time_nc(1.0) / (2.0 * math.pi) / fraction) ** 5
