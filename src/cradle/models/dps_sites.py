"""The DpS equation of the imperfect cradle (dpsimperfect): site-dependent coefficients.

    2 i tau0 dA_n/dtau = (1/m_n) [k_n Phi_n(A_{n+1} - A_n) - k_{n-1} Phi_{n-1}(A_n - A_{n-1})]
                         - 2 tau0 delta_n A_n - 3 tau0 beta~_n |A_n|^2 A_n                      (dpsimperfect)

    Phi_n(z) = g(|z|; delta~_n) z/|z|,   g(r; 0) = r^alpha (the p-Laplacian of (dfnls)),

the modulation equation of the imperfect lattice (ncimperfect) for x_n(t) ~ eps (A_n(tau) e^{it} + c.c.),
tau = eps^(alpha-1) t (derivation: docs/imperfect-dps.md), with

* detuning delta_n = (omega_n - 1) eps^(1-alpha) (an isolated linear bead turns at exactly omega_n);
* inverse masses 1/m_n dividing the contact forces on bead n; contact stiffness k_n weighting bond n;
* on-site quartic beta~_n = omega_n^2 beta_n eps^(3-alpha) (W = x^2/2 + beta x^4/4; a pendulum of
  s_n = X / l_n is beta_n = -s_n^2/6 at this order);
* precompression delta~_n = delta0 k_n^(-1/alpha) / eps of bond n: g(r; delta~) is tau0 times the first
  Fourier coefficient of the bond force F~(d) = -(delta~ - d)_+^alpha + (delta~)_+^alpha along
  d = 2 r cos(s) (closed form through 2F1 for delta~ >= 2 r, tabulated quadrature below).

With rho = delta~ / r, g(r; delta~) = r^alpha G(rho) and P(r; delta~) = int_0^r g = r^(alpha+1) Pi(rho):

    G(rho)  = -(tau0/pi) int_0^pi (rho - 2 cos s)_+^alpha cos s ds,
    Pi(rho) = tau0/(2 pi (alpha+1)) int_0^pi [(rho - 2 cos s)_+^(alpha+1) - rho_+^(alpha+1)] ds;

for rho >= 2 (the beads never separate) G(rho) = tau0 alpha rho^(alpha-1) 2F1((1-alpha)/2, 1-alpha/2; 2; 4/rho^2)
and Pi(rho) = tau0 rho^(alpha+1) [2F1(-(alpha+1)/2, -alpha/2; 1; 4/rho^2) - 1] / (2 (alpha+1)); G = Pi = 0 for
rho <= -2 (a gap the beads never close). In between, G and Pi are interpolated by Chebyshev series in the
contact-loss angle phi = arccos(rho/2) (rho in [-2, 2]) and in psi = arccosh(rho/2) (rho in [2, 4]), variables
in which the (2 -+ rho)^(alpha+1/2) kinks at rho = +-2 are phi^(2 alpha+1), psi^(2 alpha+1); past rho = 4 the
2F1 series in 4/rho^2 <= 1/4 (:func:`contact_tables`; accuracy measured in tests/models/test_dps_sites.py).

Invariants: the weighted l2 norm sum m_n |A_n|^2 and the Hamiltonian

    H = -(1/tau0) sum_n k_n P(|A_{n+1} - A_n|; delta~_n) - sum_n m_n (delta_n |A_n|^2 + (3/4) beta~_n |A_n|^4),

m_n dA_n/dtau = -i dH/d conj(A_n); with homogeneous coefficients H is the H of (dfnls).
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.models.dps import tau0 as _tau0
from cradle.specs.values import ConfigError

#: the Chebyshev degrees of the tables of G and Pi (rho in [-2, 2] and [2, 4]) and the 2F1 terms kept past rho = 4
CHEB_DEGREE = (128, 64)
SERIES_TERMS = 40
#: psi = arccosh(rho/2) at rho = 4, the end of the second table
PSI_MAX = math.acosh(2.0)


@dataclass(frozen=True, eq=False)
class DpsSites:
    """Coefficients of (dpsimperfect) on a chain of N beads (arrays of shape (N,), read-only).

    detuning : delta_n (slow-time units); inv_mass : 1/m_n; weight : k_n of bond n (beads n, n+1; the last
    is the bond N-1, 0 of a ring, unused with free ends); beta : beta~_n; delta : delta~_n of bond n
    (precompression > 0, gap < 0, 0: the p-Laplacian of (dfnls)).
    """

    detuning: np.ndarray
    inv_mass: np.ndarray
    weight: np.ndarray
    beta: np.ndarray
    delta: np.ndarray

    def __post_init__(self) -> None:
        n = np.asarray(self.detuning).size
        for name in ("detuning", "inv_mass", "weight", "beta", "delta"):
            given = np.asarray(getattr(self, name), dtype=float)
            if given.size not in (1, n):
                raise ConfigError(f"DpsSites.{name}: {given.size} values for {n} sites (detuning's count)")
            v = np.array(np.broadcast_to(given.reshape(-1) if given.size == n else given.reshape(()), (n,)))
            if not np.all(np.isfinite(v)):
                raise ConfigError(f"DpsSites.{name} = {v.tolist()!r}: must be finite")
            if name in ("inv_mass", "weight") and not np.all(v > 0.0):
                raise ConfigError(f"DpsSites.{name} = {v.tolist()!r}: must be > 0")
            v.setflags(write=False)
            object.__setattr__(self, name, v)

    @property
    def N(self) -> int:
        return int(self.detuning.size)

    @property
    def mass(self) -> np.ndarray:
        return 1.0 / self.inv_mass

    @property
    def compressed(self) -> bool:
        """Any bond with a static overlap or gap (delta~_n != 0): g is not the p-Laplacian's."""
        return bool(np.any(self.delta != 0.0))


def homogeneous(N: int) -> DpsSites:
    """The coefficients of (dfnls) itself: no detuning, unit masses and stiffnesses, no on-site or precompression."""
    z = np.zeros(N)
    return DpsSites(z, np.ones(N), np.ones(N), z, z)


def dps_sites(sites_mass: ArrayLike, sites_omega: ArrayLike, sites_stiffness: ArrayLike, *, alpha: float, eps: float,
              beta: float = 0.0, pendulum_scale: float = 0.0, delta0: float = 0.0) -> DpsSites:
    """The coefficients of (dpsimperfect) for the lattice (ncimperfect) at amplitude eps.

    ``sites_mass`` m_n, ``sites_omega`` omega_n, ``sites_stiffness`` k_n (bond n): arrays (N,), > 0 (the
    ``Sites`` of cradle.models.inhomogeneity); ``beta`` the quartic coefficient of W (number or (N,)),
    ``pendulum_scale`` X / l_0 of a pendulum (s_n = scale omega_n^2, beta_n = -s_n^2/6; not with ``beta``),
    ``delta0`` the static overlap of a bond of stiffness 1 (units X; < 0: a gap). Returns delta_n =
    (omega_n - 1) eps^(1-alpha), beta~_n = omega_n^2 beta_n eps^(3-alpha), delta~_n = delta0 k_n^(-1/alpha)/eps.
    """
    m = np.asarray(sites_mass, dtype=float).reshape(-1)
    om = np.asarray(sites_omega, dtype=float).reshape(-1)
    k = np.asarray(sites_stiffness, dtype=float).reshape(-1)
    for name, x, lo in (("alpha", alpha, 1.0), ("eps", eps, 0.0)):
        if not (isinstance(x, int | float) and math.isfinite(x) and x > lo):
            raise ConfigError(f"{name} = {x!r}: must be a finite number > {lo:g}")
    for name, v in (("sites_mass", m), ("sites_omega", om), ("sites_stiffness", k)):
        if v.size != m.size or v.size < 1 or not np.all(np.isfinite(v)) or not np.all(v > 0.0):
            raise ConfigError(f"{name} = {v.tolist()!r}: must be {m.size} finite numbers > 0")
    b = np.broadcast_to(np.asarray(beta, dtype=float), m.shape) if np.ndim(beta) else np.full(m.size, float(beta))
    if not np.all(np.isfinite(b)):
        raise ConfigError(f"beta = {beta!r}: must be finite")
    if not (math.isfinite(pendulum_scale) and pendulum_scale >= 0.0):
        raise ConfigError(f"pendulum_scale = {pendulum_scale!r}: must be a finite number >= 0")
    if pendulum_scale > 0.0 and np.any(b != 0.0):
        raise ConfigError(f"beta = {beta!r}: give beta (quartic) or pendulum_scale (pendulum), not both")
    if not math.isfinite(delta0):
        raise ConfigError(f"delta0 = {delta0!r}: must be finite")
    if pendulum_scale > 0.0:
        b = -((pendulum_scale * om**2) ** 2) / 6.0
    return DpsSites(detuning=(om - 1.0) * eps ** (1.0 - alpha), inv_mass=1.0 / m, weight=k.copy(),
                    beta=om**2 * b * eps ** (3.0 - alpha), delta=delta0 * k ** (-1.0 / alpha) / eps)


# --- the averaged bond force g(r; delta~) and its potential P --------------------------------------------------


def profile_quadrature(rho: float, alpha: float) -> tuple[float, float]:
    """(G(rho), Pi(rho)) by adaptive quadrature (QUADPACK; the (s - s*)^alpha zero at the contact-loss angle s*
    integrated by the algebraic weight of QAWS), or the 2F1 closed forms for rho >= 2. The reference of the tables."""
    from scipy.integrate import quad  # imported here: scipy.integrate costs 0.5 s at start-up
    from scipy.special import hyp2f1

    t0 = _tau0(alpha)
    if rho <= -2.0:
        return 0.0, 0.0
    if rho >= 2.0:
        y = 4.0 / rho**2
        return (t0 * alpha * rho ** (alpha - 1.0) * float(hyp2f1((1.0 - alpha) / 2.0, 1.0 - alpha / 2.0, 2.0, y)),
                t0 * rho ** (alpha + 1.0) * (float(hyp2f1(-(alpha + 1.0) / 2.0, -alpha / 2.0, 1.0, y)) - 1.0)
                / (2.0 * (alpha + 1.0)))
    s_star = math.acos(rho / 2.0)

    def base(s: float) -> float:
        # rho - 2 cos s = 4 sin((s + s*)/2) sin((s - s*)/2); divided by (s - s*): smooth on [s*, pi]
        h = s - s_star
        return 4.0 * math.sin((s + s_star) / 2.0) * (0.5 * np.sinc(h / (2.0 * math.pi)))

    g, _ = quad(lambda s: base(s) ** alpha * math.cos(s), s_star, math.pi, weight="alg", wvar=(alpha, 0.0),
                epsabs=0.0, epsrel=1e-13, limit=400)
    p, _ = quad(lambda s: base(s) ** (alpha + 1.0), s_star, math.pi, weight="alg", wvar=(alpha + 1.0, 0.0),
                epsabs=0.0, epsrel=1e-13, limit=400)
    return -t0 * g / math.pi, t0 * (p - math.pi * max(rho, 0.0) ** (alpha + 1.0)) / (2.0 * math.pi * (alpha + 1.0))


def _series(a: float, b: float, c: float, n: int) -> np.ndarray:
    """Coefficients of 2F1(a, b; c; y) = sum_j t_j y^j, j < n."""
    t = np.empty(n)
    t[0] = 1.0
    for j in range(1, n):
        t[j] = t[j - 1] * (a + j - 1) * (b + j - 1) / ((c + j - 1) * j)
    return t


@functools.lru_cache(maxsize=8)
def contact_tables(alpha: float) -> dict[str, np.ndarray]:
    """Chebyshev coefficients of G and Pi on [-2, 2] (variable phi = arccos(rho/2), mapped to [-1, 1] as
    2 phi/pi - 1) and on [2, 4] (psi = arccosh(rho/2), 2 psi/PSI_MAX - 1), interpolated at Chebyshev points
    from :func:`profile_quadrature` (on [-2, 2] Pi + tau0 rho_+^(alpha+1)/(2 (alpha+1)), smooth at rho = 0);
    and, past rho = 4, the coefficients a_j of G = tau0 alpha rho^(alpha-1)
    sum_j a_j y^j and h_j of Pi = tau0 rho^(alpha+1) sum_{j>=1} h_j y^j / (2 (alpha+1)), y = 4/rho^2."""
    from numpy.polynomial import chebyshev as C

    out = {}
    for key, deg, to_rho in (("1", CHEB_DEGREE[0], lambda t: 2.0 * np.cos((t + 1.0) * np.pi / 2.0)),
                             ("2", CHEB_DEGREE[1], lambda t: 2.0 * np.cosh((t + 1.0) * PSI_MAX / 2.0))):
        t = np.cos(np.pi * (np.arange(deg + 1) + 0.5) / (deg + 1))   # Chebyshev points of the first kind
        vals = np.array([profile_quadrature(float(r), alpha) for r in to_rho(t)])
        if key == "1":
            # Pi + tau0 rho_+^(alpha+1)/(2 (alpha+1)): the integral of (rho - 2 cos s)_+^(alpha+1) alone, smooth at
            # rho = 0 where the subtracted constant has its kink
            vals[:, 1] += _tau0(alpha) * np.maximum(to_rho(t), 0.0) ** (alpha + 1.0) / (2.0 * (alpha + 1.0))
        out["G" + key] = C.chebfit(t, vals[:, 0], deg)
        out["P" + key] = C.chebfit(t, vals[:, 1], deg)
    out["Ga"] = _series((1.0 - alpha) / 2.0, 1.0 - alpha / 2.0, 2.0, SERIES_TERMS)
    out["Ph"] = _series(-(alpha + 1.0) / 2.0, -alpha / 2.0, 1.0, SERIES_TERMS + 1)[1:]
    for v in out.values():
        v.setflags(write=False)
    return out


def coupling(r: ArrayLike, delta: ArrayLike, alpha: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(g(r; delta~), P(r; delta~)) of (dpsimperfect), elementwise (r >= 0; delta~ broadcast with r)."""
    from numpy.polynomial import chebyshev as C

    r, delta = np.broadcast_arrays(np.asarray(r, dtype=float), np.asarray(delta, dtype=float))
    g = np.zeros(r.shape)
    P = np.zeros(r.shape)
    t0 = _tau0(alpha)
    tab = contact_tables(alpha) if np.any(delta != 0.0) else None
    plain = delta == 0.0
    g[plain] = r[plain] ** alpha
    P[plain] = r[plain] ** (alpha + 1.0) / (alpha + 1.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        rho = np.where(r > 0.0, delta / np.where(r > 0.0, r, 1.0), np.sign(delta) * np.inf)
    if tab is None:
        return g, P
    mid = ~plain & (rho > -2.0) & (rho < 2.0)
    t = 2.0 * np.arccos(rho[mid] / 2.0) / np.pi - 1.0
    g[mid] = r[mid] ** alpha * C.chebval(t, tab["G1"])
    P[mid] = (r[mid] ** (alpha + 1.0) * C.chebval(t, tab["P1"])
              - t0 * np.maximum(delta[mid], 0.0) ** (alpha + 1.0) / (2.0 * (alpha + 1.0)))
    near = ~plain & (rho >= 2.0) & (rho < 4.0)
    t = 2.0 * np.arccosh(rho[near] / 2.0) / PSI_MAX - 1.0
    g[near] = r[near] ** alpha * C.chebval(t, tab["G2"])
    P[near] = r[near] ** (alpha + 1.0) * C.chebval(t, tab["P2"])
    far = ~plain & (rho >= 4.0)
    # written in r and delta~ (no 1/r): g = tau0 alpha delta~^(alpha-1) r sum a_j y^j, y = (2 r/delta~)^2
    d, rr = delta[far], r[far]
    y = (2.0 * rr / d) ** 2
    g[far] = t0 * alpha * d ** (alpha - 1.0) * rr * np.polynomial.polynomial.polyval(y, tab["Ga"])
    P[far] = 2.0 * t0 * rr**2 * d ** (alpha - 1.0) * np.polynomial.polynomial.polyval(y, tab["Ph"]) / (alpha + 1.0)
    return g, P


def linear_coupling(delta: float, alpha: float) -> float:
    """kappa~ = alpha delta~^(alpha-1): g(r; delta~) -> tau0 kappa~ r as r/delta~ -> 0 (delta~ > 0)."""
    return alpha * delta ** (alpha - 1.0)


# --- the right-hand side and the invariants (numpy) -------------------------------------------------------------


def _bonds(A: ArrayLike, sites: DpsSites, alpha: float,
           bc: str) -> tuple[NDArray[np.complex128], np.ndarray, NDArray[np.float64]]:
    """(D_n, k_n Phi_n(D_n), k_n P(|D_n|)) along the last axis; zero past a free end."""
    A = np.asarray(A, dtype=complex)
    D = np.roll(A, -1, axis=-1) - A
    if bc == "free":
        D[..., -1] = 0.0
    r = np.abs(D)
    g, P = coupling(r, np.broadcast_to(sites.delta, r.shape), alpha)
    with np.errstate(invalid="ignore", divide="ignore"):
        phi = np.where(r > 0.0, D / np.where(r > 0.0, r, 1.0), 0.0) * g
    return D, sites.weight * phi, sites.weight * P


def rhs(A: ArrayLike, alpha: float, sites: DpsSites, bc: str = "periodic") -> NDArray[np.complex128]:
    """dA_n/dtau of (dpsimperfect)."""
    A = np.asarray(A, dtype=complex)
    _, kPhi, _ = _bonds(A, sites, alpha, bc)
    left = np.roll(kPhi, 1, axis=-1)
    if bc == "free":
        left[..., 0] = 0.0
    t0 = _tau0(alpha)
    return (sites.inv_mass * (kPhi - left) / (2j * t0)
            + 1j * (sites.detuning + 1.5 * sites.beta * np.abs(A) ** 2) * A)


def l2_weighted(A: ArrayLike, sites: DpsSites) -> np.float64 | NDArray[np.float64]:
    """sum_n m_n |A_n|^2, conserved by (dpsimperfect)."""
    return np.sum(sites.mass * np.abs(np.asarray(A)) ** 2, axis=-1)


def hamiltonian(A: ArrayLike, alpha: float, sites: DpsSites, bc: str = "periodic") -> np.float64 | NDArray[np.float64]:
    """H of (dpsimperfect): -(1/tau0) sum k_n P(|D_n|; delta~_n) - sum m_n (delta_n |A_n|^2 + (3/4) beta~_n |A_n|^4)."""
    A = np.asarray(A, dtype=complex)
    _, _, kP = _bonds(A, sites, alpha, bc)
    a2 = np.abs(A) ** 2
    return (-np.sum(kP, axis=-1) / _tau0(alpha)
            - np.sum(sites.mass * (sites.detuning * a2 + 0.75 * sites.beta * a2**2), axis=-1))
