"""The operations the right-hand side and the energy of (ncimperfect) ask of their terms, slot by slot.

Each is a generic operation (:mod:`cradle.integrators._generic`): its first argument is the unit in that slot,
whose module registers the implementation. Notation of :mod:`cradle.models.lattice_terms`: bond n joins beads n
and n+1, d = u_{n+1} - u_n its elongation (u the horizontal positions), c its overlap.
"""
from __future__ import annotations

from cradle.integrators._generic import generic

# --- the contact law: touching beads (hertz) or precompressed (precompression) --------------------------------


@generic
def overlap(contact, n, d):
    """c = delta_n - d, the overlap of bond n (delta_n = 0 for touching beads)."""


@generic
def elastic(contact, n, d, c, el, alpha, mode):
    """F_n(d) of a bond in contact (c > 0, el = c^alpha): -(delta_n - d)^alpha + (delta_n)_+^alpha."""


@generic
def rest(contact, n):
    """F_n of a bond out of contact: (delta_n)_+^alpha."""


@generic
def potential(contact, n, d, c, a1):
    """Phi_n(d) with Phi_n' = F_n, Phi_n(0) = 0 (a1 = alpha + 1)."""


# --- the sites: homogeneous or not (inhomogeneity) -------------------------------------------------------------


@generic
def stiff(sites, n, X):
    """k_n X, X a force or energy of bond n."""


@generic
def per_mass(sites, n, X):
    """X / m_n, X a force on bead n."""


@generic
def onsite_scale(sites, n, X):
    """omega_n^2 X, X = W'(x_n)."""


@generic
def mass_times(sites, n, X):
    """X m_n."""


@generic
def mass_omega2(sites, n, X):
    """m_n omega_n^2 X, X = W(x_n)."""


# --- the on-site potential W (onsite_harmonic, onsite_quartic, onsite_pendulum) ------------------------------


@generic
def position(onsite, n, x):
    """(u_n, J_n = du_n/dx_n): the horizontal position of bead n at x and its derivative."""


@generic
def onsite_force(onsite, x, u):
    """W'(x) (u the horizontal position at x)."""


@generic
def onsite_energy(onsite, n, x):
    """W(x) of bead n."""


# --- the damping (onsite_damping, contact_damping) ------------------------------------------------------------


@generic
def damp_site(damping, sites, n, acc, v, P):
    """(acceleration of bead n with the on-site damping, dissipated power P with its share)."""


@generic
def damp_bond(damping, sites, contact, n, m, diff, el, sa, y, J, N, P):
    """(k_n times the force of bond n (beads n, m) in contact, P with its share): ``diff`` the elastic F_n,
    el = c^alpha, sa = c^(alpha-1), y = [x, v, ...], J the du/dx of the beads."""
