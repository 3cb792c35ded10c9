"""The DpS equation with dissipation: what the damping terms of (ncdamped) become in (dfnls) at first order.

With the ansatz (ansatz) x_n ~ eps (A_n(tau) e^{it} + c.c.), tau = eps^(alpha-1) t, the damped cradle
(ncdamped) of :mod:`cradle.models.damping` (on-site damping gamma, Kuwabara-Kono contact damping eta) gives
at order eps^alpha (derivation, assumptions and what is neglected: docs/damped-dps.md)

    2 i tau0 dA_n/dtau = kappa [g(A_{n+1} - A_n) - g(A_n - A_{n-1})] - i tau0 gamma~ A_n,          (dpsdamped)

    g(z) = z |z|^(alpha-1),   gamma~ = gamma eps^(1-alpha),   kappa = kappa(eta, alpha) = 1 + i eta / alpha + ...

* the on-site term: gamma must be O(eps^(alpha-1)) to act on the slow time scale; it becomes the linear
  decay -(gamma~/2) A_n (a bead alone: |A| ~ exp(-gamma t / 2), as in (ncdamped));
* the contact term: eta c^(alpha-1) c' is of the order eps^alpha of the Hertz force for eta = O(1) (c' is
  O(eps) on the fast scale), so eta is not rescaled; averaged over the fast phase it multiplies the
  p-Laplacian by the complex factor kappa (:func:`contact_factor`): Re kappa = 1 + O(eta^(alpha+2)),
  Im kappa = eta/alpha + O(eta^(alpha+1)), the corrections coming from the clipping of the bond force at
  zero; Im kappa >= 0 makes it a nonlinear (p-Laplacian) diffusion of the bond differences.

With gamma~ = 0 and eta = 0 this is (dfnls). The squared l2 norm and the Hamiltonian H of (dfnls) obey

    d/dtau sum |A_n|^2 = -gamma~ sum |A_n|^2 - (Im kappa / tau0) S <= 0,
    d/dtau H = (1/tau0) [ (Im kappa / (2 tau0)) sum |L_n|^2 + (gamma~/2) S ] >= 0,

(S = sum |A_{n+1} - A_n|^(alpha+1), H = -S / ((alpha+1) tau0), L_n = g(A_{n+1} - A_n) - g(A_n - A_{n-1})):
both |H| and the l2 norm decay. Since g is homogeneous of degree alpha, the on-site term reduces exactly:
A_n(tau) = e^{-gamma~ tau/2} B_n(s(tau)) with B the solution of the same equation without gamma~ and
s(tau) = (1 - e^{-(alpha-1) gamma~ tau/2}) / ((alpha-1) gamma~/2) (:func:`onsite_reduction`).
"""
from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.models import dps
from cradle.models.damping import Damping
from cradle.specs.checked import checked
from cradle.specs.declare import declared, param


@declared(doc="Dissipation of a DpS (dpsdamped) run, in its slow time tau: gamma~ = gamma eps^(1-alpha) and "
              "the Kuwabara-Kono eta of (ncdamped) (not rescaled); both zero is (dfnls).")
class DpsDamping:
    gamma: float = param(0.0, "gamma~ = gamma eps^(1-alpha): the amplitudes decay as exp(-gamma~ tau / 2) through "
                         "the on-site damping; >= 0.", minimum=0)
    eta: float = param(0.0, "eta of (ncdamped): Kuwabara-Kono contact damping, the same number as on the lattice; "
                       ">= 0.", minimum=0)

    @property
    def active(self) -> bool:
        """Whether any damping term is on (False: (dfnls), integrated as such)."""
        return self.gamma > 0.0 or self.eta > 0.0


@checked
def slow_damping(damping: Damping, eps: float, alpha: float) -> DpsDamping:
    """The DpS damping of the lattice damping ``damping`` of (ncdamped) at small parameter eps of (ansatz)."""
    if not (eps > 0.0 and math.isfinite(eps)):
        raise ValueError(f"eps must be a finite number > 0, got eps={eps!r}")
    return DpsDamping(gamma=damping.onsite * eps ** (1.0 - alpha), eta=damping.contact)


def _wallis(p: float) -> float:
    """W(p) = int_{-pi/2}^{pi/2} cos(u)^p du = B(1/2, (p+1)/2)."""
    return math.exp(math.lgamma(0.5) + math.lgamma(0.5 * (p + 1.0)) - math.lgamma(0.5 * p + 1.0))


def _wallis_to(p: float, sin2: float) -> float:
    """int_{-pi/2}^{u} cos(v)^p dv for u in [0, pi/2] with sin(u)^2 = sin2 (regularised incomplete beta)."""
    from scipy.special import betainc

    return 0.5 * _wallis(p) * (1.0 + float(betainc(0.5, 0.5 * (p + 1.0), sin2)))


@checked
def contact_factor(eta: float, alpha: float) -> complex:
    """kappa(eta, alpha) of (dpsdamped): the Kuwabara-Kono bond force of (ncdamped) averaged over the fast phase,
    over the Hertz one (closed form, the clipping at zero included).

    On a bond with A_{n+1} - A_n = r e^{i theta}, the compression is c = 2 eps r cos(u) during the contact
    u in (-pi/2, pi/2) (u = t + theta - pi), c' = -2 eps r sin(u), and the force
    c^(alpha-1) max(c - eta sin(u) 2 eps r, 0) is clipped for u > u* = arctan(1/eta). Projected on e^{it}:

        kappa W(alpha+1) = J_{alpha+1} + eta k^(alpha+1)/(alpha+1)
                           + i [k^(alpha+1)/(alpha+1) + eta (J_{alpha-1} - J_{alpha+1})]

    with W(p) = int_{-pi/2}^{pi/2} cos^p = pi c_alpha for p = alpha + 1 (wallis), J_p = int_{-pi/2}^{u*} cos^p,
    k = cos u* = eta / sqrt(1 + eta^2). Without the clipping (u* = pi/2) kappa = 1 + i eta/alpha.
    """
    if not (eta >= 0.0 and math.isfinite(eta)):
        raise ValueError(f"eta must be a finite number >= 0, got eta={eta!r}")
    if eta == 0.0:
        return 1.0 + 0.0j
    sin2 = 1.0 / (1.0 + eta * eta)            # sin(u*)^2
    k = eta / math.sqrt(1.0 + eta * eta)      # cos(u*)
    J_hi, J_lo = _wallis_to(alpha + 1.0, sin2), _wallis_to(alpha - 1.0, sin2)
    edge = k ** (alpha + 1.0) / (alpha + 1.0)
    W = _wallis(alpha + 1.0)
    return complex((J_hi + eta * edge) / W, (edge + eta * (J_lo - J_hi)) / W)


def contact_factor_unclipped(eta: float, alpha: float) -> complex:
    """1 + i eta / alpha: :func:`contact_factor` with the force allowed to pull (no clipping at zero)."""
    return complex(1.0, eta / alpha)


def rhs(A: ArrayLike, alpha: float, damping: DpsDamping, bc: str = "periodic", tau0_value: float | None = None,
        kappa: complex | None = None) -> NDArray[np.complex128]:
    """dA_n/dtau of (dpsdamped): kappa L_n / (2 i tau0) - (gamma~/2) A_n, L the p-Laplacian of (dfnls).

    ``kappa`` defaults to :func:`contact_factor` of ``damping.eta`` (pass it when calling in a loop)."""
    t0 = dps.tau0(alpha) if tau0_value is None else tau0_value
    kap = contact_factor(damping.eta, alpha) if kappa is None else kappa
    return kap * dps.p_laplacian(A, alpha, bc) / (2j * t0) - 0.5 * damping.gamma * np.asarray(A)


def bond_sum(A: ArrayLike, alpha: float, bc: str = "periodic") -> np.float64 | NDArray[np.float64]:
    """S = sum_n |A_{n+1} - A_n|^(alpha+1) (H = -S / ((alpha+1) tau0))."""
    return np.sum(np.abs(dps.differences(A, bc)) ** (alpha + 1.0), axis=-1)


def l2_rate(A: ArrayLike, alpha: float, damping: DpsDamping,
            bc: str = "periodic") -> np.float64 | NDArray[np.float64]:
    """d/dtau sum |A_n|^2 along (dpsdamped): -gamma~ sum |A_n|^2 - (Im kappa / tau0) S <= 0."""
    kap = contact_factor(damping.eta, alpha)
    return -damping.gamma * dps.l2_norm_squared(A) - kap.imag / dps.tau0(alpha) * bond_sum(A, alpha, bc)


def energy_rate(A: ArrayLike, alpha: float, damping: DpsDamping,
                bc: str = "periodic") -> np.float64 | NDArray[np.float64]:
    """d/dtau H along (dpsdamped), H the Hamiltonian of (dfnls):
    (1/tau0) [(Im kappa / (2 tau0)) sum |L_n|^2 + (gamma~/2) S] >= 0 (H < 0 rises to 0: |H| decays)."""
    kap = contact_factor(damping.eta, alpha)
    t0 = dps.tau0(alpha)
    L2 = np.sum(np.abs(dps.p_laplacian(A, alpha, bc)) ** 2, axis=-1)
    return (kap.imag / (2.0 * t0) * L2 + 0.5 * damping.gamma * bond_sum(A, alpha, bc)) / t0


def onsite_reduction(tau: ArrayLike, gamma: float, alpha: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(decay, s): A_n(tau) = decay B_n(s) solves (dpsdamped) with on-site rate gamma~ = ``gamma`` when B solves it
    with gamma~ = 0 (the same eta): decay = e^{-gamma~ tau/2}, s = (1 - e^{-(alpha-1) gamma~ tau/2}) /
    ((alpha-1) gamma~/2), since the p-Laplacian is homogeneous of degree alpha. s < 2 / ((alpha-1) gamma~): the
    undamped motion freezes."""
    tau = np.asarray(tau, dtype=float)
    rate = 0.5 * (alpha - 1.0) * gamma
    s = tau if rate == 0.0 else -np.expm1(-rate * tau) / rate
    return np.exp(-0.5 * gamma * tau), s


def lattice_state(A0: ArrayLike, eps: float, alpha: float, damping: DpsDamping,
                  bc: str = "periodic") -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(x_n(0), v_n(0)) of (ansatz) for DpS data A0: x = 2 eps Re A0, v = 2 eps (-Im A0 + eps^(alpha-1) Re dA/dtau)
    with dA/dtau of (dpsdamped) (:func:`cradle.models.initial.lattice_state` with the damped right-hand side)."""
    A0 = np.asarray(A0, dtype=complex)
    dA = rhs(A0, alpha, damping, bc)
    return 2.0 * eps * A0.real, 2.0 * eps * (-A0.imag + eps ** (alpha - 1.0) * dA.real)
