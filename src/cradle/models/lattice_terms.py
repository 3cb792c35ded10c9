"""The imperfect cradle (ncimperfect): disorder, precompression and the on-site potential, declared together.

In the units of (nc) (time 1/omega_0 of the reference bead, lengths X of :mod:`.physical`),

    m_n ( x_n'' + omega_n^2 W'(x_n) ) = J_n [ k_n F_n(u_{n+1} - u_n) - k_{n-1} F_{n-1}(u_n - u_{n-1}) ]   (ncimperfect)

* m_n, omega_n, k_n: the site coefficients of :mod:`.inhomogeneity` (:class:`.inhomogeneity.Sites`);
* W: the on-site potential of :mod:`.onsite`; u_n the horizontal position of bead n and J_n = du_n/dx_n
  (u = x, J = 1 except for the pendulum, whose x is the arc length: u = sin(s_n x)/s_n, J = cos(s_n x),
  s_n = scale omega_n^2);
* F_n(d) = -(delta_n - d)_+^alpha + (delta_n)_+^alpha: Hertz's law (vhertz) with the static overlap
  delta_n = delta_0 k_n^(-1/alpha) of :mod:`.precompression` (F_n(0) = 0).

With every coefficient 1, delta_0 = 0 and W = x^2/2 it is (nc). It is Hamiltonian, with the generalised (ham)

    H = sum_n [ m_n v_n^2/2 + m_n omega_n^2 W(x_n) + k_n Phi_n(u_{n+1} - u_n) ],
    Phi_n(d) = ((delta_n - d)_+^(alpha+1) - (delta_n)_+^(alpha+1))/(alpha+1) + (delta_n)_+^alpha d   (Phi_n' = F_n),

and the damping of :mod:`.damping` adds -gamma m_n v_n to the bead forces and the Kuwabara-Kono term to the
total overlap c = delta_n - d of a bond: k_n [(delta_n)_+^alpha - max(c^alpha + eta c^(alpha-1) c', 0)], so that
H + D = H(0) with D = int P, P = gamma sum m_n v_n^2 + sum k_n (max(c^alpha + eta c^(alpha-1) c', 0) - c^alpha) c'.
For the pendulum the state x is the arc variable (the angle is s_n x), v its rate.

Functions take arrays with the beads on the last axis; they trust their caller (:func:`check` is the gate).
"""
from __future__ import annotations

import numpy as np

from cradle.models.damping import Damping
from cradle.models.inhomogeneity import Inhomogeneity, Sites, homogeneous, sites
from cradle.models.onsite import OnSite
from cradle.models.precompression import Precompression
from cradle.specs.declare import check_fields, declared, from_plain, param, plain
from cradle.specs.values import ConfigError


@declared("terms", doc="The terms of an imperfect cradle (ncimperfect) beyond the paper's (nc): inhomogeneity, "
                       "precompression and the on-site potential; all at their defaults is (nc).")
class Terms:
    inhomogeneity: Inhomogeneity = param(Inhomogeneity(), "Site masses, on-site frequencies, contact stiffnesses.")
    precompression: Precompression = param(Precompression(), "Static overlap delta0 of the contacts.")
    onsite: OnSite = param(OnSite(), "On-site potential W.")

    def __post_init__(self) -> None:   # built directly: checked as the config's values are
        check_fields(self, "terms")

    @property
    def active(self) -> bool:
        """Whether any term differs from (nc) (False: the paper's lattice, integrated as such)."""
        return self.inhomogeneity.active or self.precompression.active or self.onsite.active


#: the paper's (nc): no term
NONE = Terms()


def check(terms: Terms, N: int, bc: str) -> Sites:
    """Validate ``terms`` for N beads with ends ``bc`` (one ConfigError line per problem, naming key and value)
    and return its sites: the declared bounds, the draws, and the refusal of a precompressed free chain."""
    if not isinstance(terms, Terms):
        raise ConfigError(f"terms = {terms!r}: must be a cradle.models.lattice_terms.Terms")
    if terms == NONE:   # the declared defaults: valid, and (nc)'s sites (no schema pass on every call)
        return homogeneous(N)
    from_plain(Terms, plain(terms), "terms")
    if terms.precompression.delta0 > 0.0 and bc != "periodic":
        raise ConfigError(f"terms.precompression.delta0 = {terms.precompression.delta0!r}: a precompressed chain "
                          f"needs bc = 'periodic' (with bc = {bc!r} nothing holds the static force at the ends and "
                          f"the chain flies apart; walls are not modelled)")
    return sites(terms.inhomogeneity, N)


def static_overlaps(delta0: float, stiffness, alpha: float) -> np.ndarray:
    """delta_n = delta_0 k_n^(-1/alpha): the overlaps (or gaps, delta_0 < 0) carrying one static force."""
    return delta0 * np.asarray(stiffness, dtype=float) ** (-1.0 / alpha)


def pendulum_scales(terms: Terms, s: Sites) -> np.ndarray:
    """s_n = scale omega_n^2 (X over the string length of bead n); zeros unless the on-site is a pendulum."""
    if terms.onsite.potential != "pendulum":
        return np.zeros_like(s.omega)
    return terms.onsite.scale * s.omega**2


def positions(x, terms: Terms, s: Sites):
    """Horizontal positions u_n of the beads: sin(s_n x_n)/s_n for the pendulum (x the arc length), else x."""
    return terms.onsite.u(x, pendulum_scales(terms, s)) if terms.onsite.active else np.asarray(x, dtype=float)


def _elongations(u, bc: str):
    d = np.roll(u, -1, axis=-1) - u
    if bc == "free":
        d[..., -1] = 0.0
    return d


def _open(bonds, bc: str):
    """Zero on the missing bond N-1 of a free chain."""
    if bc == "free":
        bonds = np.array(bonds, dtype=float, copy=True)
        bonds[..., -1] = 0.0
    return bonds


def bond_forces(x, alpha: float, terms: Terms, s: Sites, bc: str = "periodic", v=None, eta: float = 0.0):
    """k_n times the bond force of bond n (0 on a missing bond): k_n F_n(d_n) (with ``v`` and ``eta``, the
    Kuwabara-Kono damped force, clipped at zero push)."""
    delta = static_overlaps(terms.precompression.delta0, s.stiffness, alpha)
    u = positions(x, terms, s)
    d = _elongations(u, bc)
    c = np.maximum(delta - d, 0.0)
    push = c**alpha
    if v is not None and eta != 0.0:
        rate = -_elongations(np.asarray(v, dtype=float) * jacobian(x, terms, s), bc)
        push = np.maximum(push + eta * c ** (alpha - 1.0) * rate, 0.0) * (c > 0.0)
    return _open(s.stiffness * (np.maximum(delta, 0.0) ** alpha - push), bc)


def jacobian(x, terms: Terms, s: Sites):
    """J_n = du_n/dx_n: cos(s_n x_n) for the pendulum, else 1."""
    sn = pendulum_scales(terms, s)
    if terms.onsite.potential == "pendulum":
        return np.cos(sn * np.asarray(x, dtype=float))
    return np.ones_like(np.asarray(x, dtype=float))


def acceleration(x, alpha: float, terms: Terms, s: Sites, bc: str = "periodic", v=None,
                 damping: Damping | None = None):
    """Right-hand side of (ncimperfect) (with ``v`` and ``damping``, of its damped form):
    x_n'' = -omega_n^2 W'(x_n) - gamma v_n + J_n (g_n - g_{n-1}) / m_n."""
    x = np.asarray(x, dtype=float)
    eta = 0.0 if damping is None else damping.contact
    g = bond_forces(x, alpha, terms, s, bc, v=v, eta=eta)
    g_left = np.roll(g, 1, axis=-1)
    if bc == "free":
        g_left[..., 0] = 0.0
    a = -s.omega**2 * terms.onsite.dW(x, pendulum_scales(terms, s)) + jacobian(x, terms, s) * (g - g_left) / s.mass
    if damping is not None and v is not None:
        a = a - damping.onsite * np.asarray(v, dtype=float)
    return a


def hamiltonian(x, v, alpha: float, terms: Terms, s: Sites, bc: str = "periodic"):
    """The generalised energy (ham) of (ncimperfect):
    sum_n m_n v_n^2/2 + m_n omega_n^2 W(x_n) + k_n Phi_n(u_{n+1} - u_n)."""
    x = np.asarray(x, dtype=float)
    v = np.asarray(v, dtype=float)
    delta = static_overlaps(terms.precompression.delta0, s.stiffness, alpha)
    dp = np.maximum(delta, 0.0)
    d = _elongations(positions(x, terms, s), bc)
    phi = (np.maximum(delta - d, 0.0) ** (alpha + 1.0) - dp ** (alpha + 1.0)) / (alpha + 1.0) + dp**alpha * d
    bonds = _open(s.stiffness * phi, bc)
    onsite = s.mass * s.omega**2 * terms.onsite.W(x, pendulum_scales(terms, s))
    return np.sum(0.5 * s.mass * v**2 + onsite + bonds, axis=-1)


def dissipated_power(x, v, alpha: float, terms: Terms, s: Sites, damping: Damping, bc: str = "periodic"):
    """P of the damped (ncimperfect), >= 0: gamma sum m_n v_n^2 + sum k_n (max(c^alpha + eta c^(alpha-1) c', 0)
    - c^alpha) c' over the bonds with overlap c = delta_n - (u_{n+1} - u_n) > 0, c' its rate (dH/dt = -P)."""
    x = np.asarray(x, dtype=float)
    v = np.asarray(v, dtype=float)
    delta = static_overlaps(terms.precompression.delta0, s.stiffness, alpha)
    c = np.maximum(delta - _elongations(positions(x, terms, s), bc), 0.0)
    rate = -_elongations(v * jacobian(x, terms, s), bc)
    push = np.maximum(c**alpha + damping.contact * c ** (alpha - 1.0) * rate, 0.0) * (c > 0.0)
    contacts = _open(s.stiffness * (push - c**alpha) * rate, bc)
    return damping.onsite * np.sum(s.mass * v**2, axis=-1) + np.sum(contacts, axis=-1)
