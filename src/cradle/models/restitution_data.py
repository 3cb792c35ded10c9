"""Measured restitutions of the table's materials, and the one assumed value the analyses use while there are none.

:data:`MEASUREMENTS` holds the measured e(v) that :func:`cradle.models.restitution.fit_constant` fits the
Kuwabara-Kono constant A to: each a :class:`cradle.models.restitution.Measurement` with its source (paper, table or
figure, where in it), entered only when its numbers were read in that source's text. It is empty: no text with a
measured e(v) of steel, brass or glass spheres at a desk toy's speeds (0.05-1 m/s) was reached (issue 38;
docs/dissipation.md, "Measured restitution: what was searched", lists each source, what its reachable text gave and
why it is not usable).

Until it is filled, the desk-toy, desk-toy-minute and dissipation analyses take their restitution from
:data:`STEEL_ASSUMED`: e = 0.95 at an impact speed of 0.3 m/s for two steel balls, a value nobody measured for
these balls, said so wherever it is used (the analyses' parameter descriptions and output attributes, their docs
pages). A measurement replaces it by the fitted A (the analyses' ``kk_constant`` / ``restitution`` keys), not by a
new default here.
"""
from __future__ import annotations

from dataclasses import dataclass

from cradle.models.restitution import Measurement


@dataclass(frozen=True)
class AssumedRestitution:
    """A restitution ``e`` of two spheres of ``material`` at impact speed ``v`` (m/s) that was NOT measured, the
    values ``bracket`` = (low, high) on either side of it that a run repeats under to show what the assumption moves,
    and ``status``: one sentence saying so, for docs and output attributes."""

    material: str
    e: float
    v: float
    bracket: tuple[float, float]
    status: str


#: measured e(v) with their sources, for cradle.models.restitution.fit_constant: none was read (module docstring)
MEASUREMENTS: tuple[Measurement, ...] = ()

#: the assumed restitution of two steel balls of a desk toy, and the bracket the desk-toy-minute runs repeat under
STEEL_ASSUMED = AssumedRestitution(
    material="steel", e=0.95, v=0.3, bracket=(0.9, 0.98),
    status="ASSUMED, not measured: no measured steel-on-steel restitution at 0.05-1 m/s was read in a source's "
           "text (docs/dissipation.md, 'Measured restitution: what was searched')")
