"""The operations the right-hand side and the energy of (ncimperfect) ask of their terms, slot by slot.

Each is a generic operation (:mod:`cradle.integrators._generic`): its first argument is the unit in that slot,
whose module registers the implementation. Notation of :mod:`cradle.models.lattice_terms`: bond n joins beads n
and n+1, d = u_{n+1} - u_n its elongation (u the horizontal positions), c its overlap.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

from cradle.integrators._generic import generic

if TYPE_CHECKING:
    from cradle.integrators._types import Floats

# --- the contact law: touching beads (vhertz) or precompressed (precompression) --------------------------------


@generic
def overlap(contact: NamedTuple, n: int, d: float) -> float:
    """c = delta_n - d, the overlap of bond n (delta_n = 0 for touching beads)."""


@generic
def elastic(contact: NamedTuple, n: int, d: float, c: float, el: float, alpha: float, mode: int) -> float:
    """F_n(d) of a bond in contact (c > 0, el = c^alpha): -(delta_n - d)^alpha + (delta_n)_+^alpha."""


@generic
def rest(contact: NamedTuple, n: int) -> float:
    """F_n of a bond out of contact: (delta_n)_+^alpha."""


@generic
def potential(contact: NamedTuple, n: int, d: float, c: float, a1: float) -> float:
    """Phi_n(d) with Phi_n' = F_n, Phi_n(0) = 0 (a1 = alpha + 1)."""


# --- the sites: homogeneous or not (inhomogeneity) -------------------------------------------------------------


@generic
def stiff(sites: NamedTuple, n: int, X: float) -> float:
    """k_n X, X a force or energy of bond n."""


@generic
def per_mass(sites: NamedTuple, n: int, X: float) -> float:
    """X / m_n, X a force on bead n."""


@generic
def onsite_scale(sites: NamedTuple, n: int, X: float) -> float:
    """omega_n^2 X, X = W'(x_n)."""


@generic
def mass_times(sites: NamedTuple, n: int, X: float) -> float:
    """X m_n."""


@generic
def mass_omega2(sites: NamedTuple, n: int, X: float) -> float:
    """m_n omega_n^2 X, X = W(x_n)."""


# --- the on-site potential W (onsite_harmonic, onsite_quartic, onsite_pendulum) ------------------------------


@generic
def position(onsite: NamedTuple, n: int, x: float) -> tuple[float, float]:
    """(u_n, J_n = du_n/dx_n): the horizontal position of bead n at x and its derivative."""


@generic
def onsite_force(onsite: NamedTuple, x: float, u: float) -> float:
    """W'(x) (u the horizontal position at x)."""


@generic
def onsite_energy(onsite: NamedTuple, n: int, x: float) -> float:
    """W(x) of bead n."""


# --- the damping (onsite_damping, contact_damping) ------------------------------------------------------------


@generic
def damp_site(damping: NamedTuple, sites: NamedTuple, n: int, acc: float, v: float, P: float) -> tuple[float, float]:
    """(acceleration of bead n with the on-site damping, dissipated power P with its share)."""


@generic
def damp_bond(damping: NamedTuple, sites: NamedTuple, contact: NamedTuple, n: int, m: int, diff: float, el: float,
              sa: float, y: Floats, J: Floats, N: int, P: float) -> tuple[float, float]:
    """(k_n times the force of bond n (beads n, m) in contact, P with its share): ``diff`` the elastic F_n,
    el = c^alpha, sa = c^(alpha-1), y = [x, v, ...], J the du/dx of the beads."""


# --- the DpS counterparts: what each term becomes in the DpS right-hand side family (systems.dps) --------------


@generic
def dps_coupling(coupling: NamedTuple, r: float, n: int, alpha: float) -> float:
    """W_n / (A_{n+1} - A_n) of bond n at |A_{n+1} - A_n| = r (before its weight): r^(alpha-1) for touching beads
    (vhertz), g(r; delta~_n)/r with precompression or gaps (precompression)."""


@generic
def dps_weight(sites: NamedTuple, n: int, s: float) -> float:
    """k_n s (inhomogeneity: the stiffness of bond n)."""


@generic
def dps_factor(sites: NamedTuple, n: int, inv2tau0: float) -> float:
    """The factor of W_n - W_{n-1} in dA_n/dtau: 1/(2 tau0), over m_n with masses (inhomogeneity)."""


@generic
def dps_kappa(damping: NamedTuple, wr: float, wi: float) -> tuple[float, float]:
    """kappa (wr + i wi): the contact damping's complex factor on the coupling (contact_damping)."""


@generic
def dps_decay(damping: NamedTuple, a: float, b: float, ar: float, ai: float) -> tuple[float, float]:
    """(a, b) - (gamma~/2) (Re A_n, Im A_n): the on-site damping (onsite_damping)."""


@generic
def dps_rotate(onsite: NamedTuple, sites: NamedTuple, n: int, a: float, b: float, ar: float,
               ai: float) -> tuple[float, float]:
    """(a, b) + i rot A_n, rot = delta_n + (3/2) beta~_n |A_n|^2: detuning (inhomogeneity) and quartic (onsite)."""


@generic
def dps_detuning(sites: NamedTuple, n: int, X: float) -> float:
    """delta_n + X, the rotation rate of site n (X the quartic's share)."""


@generic
def dps_rotate_detuned(sites: NamedTuple, n: int, a: float, b: float, ar: float, ai: float) -> tuple[float, float]:
    """(a, b) + i delta_n A_n, the detuning alone (no on-site quartic)."""


@generic
def dps_l2_loss(damping: NamedTuple, l2: float, S: float, inv2tau0: float) -> float:
    """This damping's share of Q_l2' (the balance laws of (dpsdamped)); 0.0 when absent."""


@generic
def dps_S_loss(damping: NamedTuple, L2: float, S: float, inv2tau0: float) -> float:
    """This damping's share of Q_S' / (alpha + 1); 0.0 when absent."""
