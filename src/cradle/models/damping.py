"""Dissipation in Newton's cradle: the two damping terms a scene may switch on, declared once.

In the variables of (nc) (time in units of 1/omega_0, lengths in units of X: :mod:`.physical`), a damped
cradle is

    x_n'' + gamma x_n' + x_n = g_n - g_{n-1},                                             (ncdamped)

    g_n = -max(c_n^alpha + eta c_n^(alpha-1) c_n', 0) H(c_n),   c_n = -(x_{n+1} - x_n),

with c_n the compression of bond n and c_n' = -(v_{n+1} - v_n) its rate. With gamma = eta = 0 this is (nc).

* ``onsite`` = gamma >= 0: linear on-site damping, a force -gamma v_n on every bead. It is phenomenological:
  the air drag on a desk toy's balls is nearer quadratic in the speed (Reynolds numbers of 10^2-10^3), and
  the losses at a pendulum's pivot and strings are neither; a linear term is the simplest that gives a
  swing a finite lifetime, and the one whose effect on (dfnls) is exact at first order.
* ``contact`` = eta >= 0: viscoelastic contact damping of Kuwabara & Kono (Jpn. J. Appl. Phys. 26 (1987)
  1230) and Brilliantov, Spahn, Hertzsch & Poeschel (Phys. Rev. E 53 (1996) 5382): in SI the force
  between two spheres is k (delta^(3/2) + A delta^(1/2) delta'), here eta c^(alpha-1) c' (alpha = 3/2:
  c^(1/2) c'), eta = A omega_0 (:func:`contact_eta`). The total bond force is clipped at zero: a contact
  pushes and never pulls (Schwager & Poeschel, Phys. Rev. E 78 (2008) 051304), so on separation, when
  the damping term would outweigh the elastic one, the bond carries no force while its beads still
  overlap.

The energy (ham) then decreases at the rate

    dH/dt = -P,   P = gamma sum_n v_n^2 + sum_n (max(c_n^alpha + eta c_n^(alpha-1) c_n', 0) - c_n^alpha) c_n' >= 0

(the second sum over compressed bonds; each term is eta c^(alpha-1) c'^2 when the force is not clipped and
-c^alpha c' > 0 when it is), and the dissipated energy D(t) = int_0^t P is integrated as a quantity of its
own, never taken as H(0) - H(t): H(t) + D(t) = H(0) measures the integrator's accuracy.

Both terms default to zero, and a scene without them has no damping at all: the integrators take the
undamped (conservative) path, bitwise and at its speed.
"""
from __future__ import annotations

import numpy as np

from cradle.specs.declare import check_fields, declared, param


@declared("damping", doc="Dissipation of a lattice (nc) scene, in the units of (nc) (time 1/omega_0): linear "
                         "on-site damping gamma and Kuwabara-Kono viscoelastic contact damping eta; "
                         "both zero is the conservative (nc).")
class Damping:
    onsite: float = param(0.0, "gamma: on-site damping force -gamma v_n on every bead (the amplitude of a bead "
                          "alone decays as exp(-gamma t / 2)); >= 0.", minimum=0)
    contact: float = param(0.0, "eta: Kuwabara-Kono contact damping, bond force -max(c^alpha + eta c^(alpha-1) "
                           "c', 0) on a compression c > 0 (eta = A omega_0 for the SI constant A in seconds); "
                           ">= 0.", minimum=0)

    def __post_init__(self) -> None:   # built directly: checked as the config's values are
        check_fields(self, "damping")

    @property
    def active(self) -> bool:
        """Whether any damping term is on (False: the conservative (nc), integrated as such)."""
        return self.onsite > 0.0 or self.contact > 0.0


#: no damping: the conservative (nc)
NONE = Damping()


def contact_eta(A_seconds: float, omega0: float) -> float:
    """eta of (ncdamped) for the Kuwabara-Kono constant A (seconds) of the SI force k (delta^(3/2) + A delta^(1/2)
    delta') and the on-site angular frequency omega_0 (rad/s): time is measured in units of 1/omega_0."""
    return A_seconds * omega0


def onsite_gamma(rate_per_second: float, omega0: float) -> float:
    """gamma of (ncdamped) for an SI damping rate (1/s: the force per unit mass -rate u') and omega_0 (rad/s)."""
    return rate_per_second / omega0


def compressions(x, v, bc: str = "periodic"):
    """(c_n, c_n'): the compression -(x_{n+1} - x_n) of every bond and its rate (both 0 on a missing bond)."""
    x, v = np.asarray(x, dtype=float), np.asarray(v, dtype=float)
    c = -(np.roll(x, -1, axis=-1) - x)
    rate = -(np.roll(v, -1, axis=-1) - v)
    if bc == "free":
        c[..., -1] = 0.0
        rate[..., -1] = 0.0
    return c, rate


def bond_forces(x, v, alpha: float, eta: float, bc: str = "periodic"):
    """The bond forces g_n of (ncdamped) (0 on a missing bond): -max(c^alpha + eta c^(alpha-1) c', 0) where
    the bond is compressed (c = -(x_{n+1} - x_n) > 0), else 0. Arrays with the beads on the last axis."""
    c, rate = compressions(x, v, bc)
    on = c > 0.0
    cp = np.where(on, c, 0.0)
    push = cp**alpha + eta * cp ** (alpha - 1.0) * rate
    return np.where(on, -np.maximum(push, 0.0), 0.0)


def dissipated_power(x, v, alpha: float, damping: Damping, bc: str = "periodic"):
    """P of (ncdamped): the rate at which the damping terms remove energy (ham), >= 0 (arrays as above)."""
    c, rate = compressions(x, v, bc)
    cp = np.maximum(c, 0.0)
    elastic = cp**alpha
    total = -bond_forces(x, v, alpha, damping.contact, bc)
    return damping.onsite * np.sum(np.asarray(v, dtype=float) ** 2, axis=-1) + np.sum((total - elastic) * rate,
                                                                                      axis=-1)


def acceleration(x, v, alpha: float, damping: Damping, bc: str = "periodic"):
    """Right-hand side of (ncdamped): -x_n - gamma v_n + g_n - g_{n-1}."""
    g = bond_forces(x, v, alpha, damping.contact, bc)
    g_left = np.roll(g, 1, axis=-1)
    if bc == "free":
        g_left[..., 0] = 0.0
    return -np.asarray(x, dtype=float) - damping.onsite * np.asarray(v, dtype=float) + g - g_left
