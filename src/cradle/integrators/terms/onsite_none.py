"""No on-site potential, W = 0: the beads of the Hertz chain are free but for their contacts.

The on-site slot's absent unit: a bead's horizontal position is its x (J = 1), its on-site force and energy are
0 with no arithmetic (:func:`cradle.integrators._generic.absent`). Parameters: none, and no config key: a
scene's DpS counterpart needs the on-site oscillation (the carrier e^{it} of (ansatz)), so a chain without it
has no DpS counterpart, and it is built only by the drivers that integrate the Hertz chain alone
(:func:`cradle.integrators.lattice_adaptive.run_dop853_hertz_chain`: the solitary wave of
:mod:`cradle.models.solitary` and the first impact of a desk toy).
"""
from __future__ import annotations

from typing import NamedTuple

from cradle.integrators._generic import absent
from cradle.integrators.terms.slots import onsite_energy, onsite_force, position


class NoOnsite(NamedTuple):
    """W = 0: no on-site force."""


absent(position, NoOnsite, "x", "1.0")
absent(onsite_force, NoOnsite, "0.0")
absent(onsite_energy, NoOnsite, "0.0")
