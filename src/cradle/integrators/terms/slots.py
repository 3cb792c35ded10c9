"""The operations the right-hand side and the energy of (ncimperfect) ask of their terms, slot by slot.

Each is a generic operation (:mod:`cradle.integrators._generic`): its first argument is the unit in that slot,
whose module registers the implementation. Notation of :mod:`cradle.models.lattice_terms`: bond n joins beads n
and n+1, d = u_{n+1} - u_n its elongation (u the horizontal positions), c its overlap.
"""
from __future__ import annotations

from cradle.integrators._generic import generic

# --- the contact law: touching beads (vhertz) or precompressed (precompression) --------------------------------


@generic
def overlap(contact, n, d) -> None:
    """c = delta_n - d, the overlap of bond n (delta_n = 0 for touching beads)."""


@generic
def elastic(contact, n, d, c, el, alpha, mode) -> None:
    """F_n(d) of a bond in contact (c > 0, el = c^alpha): -(delta_n - d)^alpha + (delta_n)_+^alpha."""


@generic
def rest(contact, n) -> None:
    """F_n of a bond out of contact: (delta_n)_+^alpha."""


@generic
def potential(contact, n, d, c, a1) -> None:
    """Phi_n(d) with Phi_n' = F_n, Phi_n(0) = 0 (a1 = alpha + 1)."""


# --- the sites: homogeneous or not (inhomogeneity) -------------------------------------------------------------


@generic
def stiff(sites, n, X) -> None:
    """k_n X, X a force or energy of bond n."""


@generic
def per_mass(sites, n, X) -> None:
    """X / m_n, X a force on bead n."""


@generic
def onsite_scale(sites, n, X) -> None:
    """omega_n^2 X, X = W'(x_n)."""


@generic
def mass_times(sites, n, X) -> None:
    """X m_n."""


@generic
def mass_omega2(sites, n, X) -> None:
    """m_n omega_n^2 X, X = W(x_n)."""


# --- the on-site potential W (onsite_harmonic, onsite_quartic, onsite_pendulum) ------------------------------


@generic
def position(onsite, n, x) -> None:
    """(u_n, J_n = du_n/dx_n): the horizontal position of bead n at x and its derivative."""


@generic
def onsite_force(onsite, x, u) -> None:
    """W'(x) (u the horizontal position at x)."""


@generic
def onsite_energy(onsite, n, x) -> None:
    """W(x) of bead n."""


# --- the damping (onsite_damping, contact_damping) ------------------------------------------------------------


@generic
def damp_site(damping, sites, n, acc, v, P) -> None:
    """(acceleration of bead n with the on-site damping, dissipated power P with its share)."""


@generic
def damp_bond(damping, sites, contact, n, m, diff, el, sa, y, J, N, P) -> None:
    """(k_n times the force of bond n (beads n, m) in contact, P with its share): ``diff`` the elastic F_n,
    el = c^alpha, sa = c^(alpha-1), y = [x, v, ...], J the du/dx of the beads."""


# --- the DpS counterparts: what each term becomes in the DpS right-hand side family (systems.dps) --------------


@generic
def dps_coupling(coupling, r, n, alpha) -> None:
    """W_n / (A_{n+1} - A_n) of bond n at |A_{n+1} - A_n| = r (before its weight): r^(alpha-1) for touching beads
    (vhertz), g(r; delta~_n)/r with precompression or gaps (precompression)."""


@generic
def dps_weight(sites, n, s) -> None:
    """k_n s (inhomogeneity: the stiffness of bond n)."""


@generic
def dps_factor(sites, n, inv2tau0) -> None:
    """The factor of W_n - W_{n-1} in dA_n/dtau: 1/(2 tau0), over m_n with masses (inhomogeneity)."""


@generic
def dps_kappa(damping, wr, wi) -> None:
    """kappa (wr + i wi): the contact damping's complex factor on the coupling (contact_damping)."""


@generic
def dps_decay(damping, a, b, ar, ai) -> None:
    """(a, b) - (gamma~/2) (Re A_n, Im A_n): the on-site damping (onsite_damping)."""


@generic
def dps_rotate(onsite, sites, n, a, b, ar, ai) -> None:
    """(a, b) + i rot A_n, rot = delta_n + (3/2) beta~_n |A_n|^2: detuning (inhomogeneity) and quartic (onsite)."""


@generic
def dps_detuning(sites, n, X) -> None:
    """delta_n + X, the rotation rate of site n (X the quartic's share)."""


@generic
def dps_rotate_detuned(sites, n, a, b, ar, ai) -> None:
    """(a, b) + i delta_n A_n, the detuning alone (no on-site quartic)."""


@generic
def dps_l2_loss(damping, l2, S, inv2tau0) -> None:
    """This damping's share of Q_l2' (the balance laws of (dpsdamped)); 0.0 when absent."""


@generic
def dps_S_loss(damping, L2, S, inv2tau0) -> None:
    """This damping's share of Q_S' / (alpha + 1); 0.0 when absent."""
