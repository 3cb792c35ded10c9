"""The time-dependent continuum equations of (dfnls) as alpha -> 1+, their travelling solutions, and the map of a
travelling breather's velocity c and phase theta onto a boost (issue 37, item 5; the derivation is ours).

Write alpha = 1 + eps and g(z) = z |z|^eps (complex z). A staggered solution A_n = (-1)^n B_n of (dfnls),
2 i tau0 dA_n/dtau = g(A_{n+1} - A_n) - g(A_n - A_{n-1}), solves exactly (g is odd)

    -2 i tau0 dB_n/dtau = g(B_n + B_{n+1}) + g(B_n + B_{n-1}).                                (stagt)

For a slowly varying U = 2B(x, tau), B_n + B_{n+-1} = U +- U'/2 + U''/4 + ..., and with the real derivatives of g,
Dg(z)[h] = |z|^eps h + eps |z|^(eps-2) z Re(conj(z) h) and D^2 g(z)[h, h] (:func:`d2g`), to second order in the
derivatives

    -2 i tau0 U_tau = 4 g(U) + Dg(U)[U''] + D^2 g(U)[U', U'] / 2                               (Ct)

and, as in :mod:`cradle.models.compacton`, two shorter forms as consistent at this order:

    -2 i tau0 U_tau = 4 g(U) + (g(U))''  = 4 g(U) + Dg(U)[U''] + D^2 g(U)[U', U']               (At)
    -2 i tau0 U_tau = 4 g(U) + Dg(U)[U'']                                                      (Bt)

Each reduces to its stationary form (A)-(C) for U = u e^{-i omega tau}, u real (g commutes with rotations).
Expanding g in eps instead, g(U) = U (1 + eps ln|U|) + O(eps^2), gives the time-dependent log-NLS equation

    -2 i tau0 U_tau = 4 U + 4 eps U ln|U| + U''                                                (lognlst)

(with U = e^{2 i tau / tau0} V, X = sqrt(eps) x, s = eps tau / (2 tau0): i V_s + V_XX + 4 V ln|V| = 0).

**Galilean invariance.** (lognlst) is invariant under the boost U(x, tau) -> U(x - v tau, tau) e^{i (k x -
(k^2 / (2 tau0)) tau)} with v = k / tau0 (the dispersion term is linear: U'' of phi e^{ikx} is e^{ikx} (phi'' + 2 i
k phi' - k^2 phi), whose first-derivative term the moving frame cancels). So the staggered Gaussian of the static
breather (:mod:`cradle.models.continuum`), boosted, is an exact travelling solution:

    B_n(tau) = beta exp(-eps (n - n_c - c tau)^2) e^{i (kappa (n - n_c) - Omega tau)},
    c = kappa / tau0,   2 tau0 Omega = kappa^2 - nu(beta),   nu(beta) = 4 + eps (4 ln(2 beta) - 2).   (boost)

It satisfies the TB condition (tb), A_n(tau + T) = e^{i theta} A_{n-1}(tau) with T = 1/c, when

    theta = kappa - Omega T - pi = kappa / 2 + nu / (2 kappa) - pi   (mod 2 pi),   kappa = tau0 c       (theta)

(the -pi from the staggering). The forms (At)-(Ct) are **not** Galilean-invariant: their dispersion Dg(U)[U''] is
nonlinear, so the boost's first-derivative term 2 i k Dg(U)[U'] is not the moving frame's 2 i tau0 v U'; for a
real profile the difference is 2 i k (1 - |phi|^eps) phi' e^{ikx} (form B; :func:`residual` computes every form's),
O(eps ln|phi|) relative in the core and O(1) near a compacton's edge, where |phi|^eps -> 0. No boosted compacton is
a solution, and the travelling-wave ODE admits no moving compact edge either: near an edge at distance d, a profile
U ~ C d^s (s complex, Re s > 0) makes the transport term 2 i tau0 v U' of order d^(Re s - 1) and the degenerate
dispersion |U|^eps U'' of order d^(eps Re s + Re s - 2); they balance only for eps Re s = 1, and then the
coefficients demand s (s - 1) = -2 i tau0 v s / |C|^eps up to O(eps) (B; the same contradiction for A and C), so
s = 1 - 2 i tau0 v / |C|^eps, whose real part is 1 + O(eps), not 1/eps: a compact edge moves only at v = 0. (A
heuristic argument on power-law edges, ours; it does not exclude travelling solutions with other edges.) So the
travelling compactons of A-C are taken here as the boosted static compactons: approximate solutions whose residual
(:func:`residual`) is stored beside the TBs' distance to them.

**The lattice's carrier.** At a carrier kappa the linear staggered lattice has frequency 2 tau0 Omega = -(2 + 2 cos
kappa) and group velocity sin(kappa) / tau0; to leading order the envelope of a modulated wave of carrier kappa
solves (lognlst) with dispersion cos(kappa) and nonlinearity 4 cos^2(kappa / 2) (B_n + B_{n+1} = (1 + e^{i kappa}) B
+ ...), whose Gaussian is exp(-a (n - n_c)^2), a = eps (1 + cos kappa) / (2 cos kappa) (:func:`carrier_width`):
narrower than the static one by a relative kappa^2 / 4. With kappa = K sqrt(eps) (a boost K fixed in the units of
X) this is an O(eps) change, of the order of the distance itself, so the TBs are compared with both.
"""
from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

#: the continuum equations with travelling solutions compared here: the log-NLS and the degenerate forms
EQUATIONS = ("log-NLS", "A", "B", "C")


def boost_kappa(c: float, tau0: float) -> float:
    """kappa = tau0 c: the phase gradient per site of the boost of (lognlst) that travels at c sites per unit tau."""
    return tau0 * c


def carrier_kappa(c: float, tau0: float) -> float:
    """kappa with group velocity sin(kappa) / tau0 = c on the linear lattice (module docstring)."""
    return math.asin(min(1.0, tau0 * c))


def carrier_width(eps: float, kappa: float) -> float:
    """a of the carrier-corrected Gaussian exp(-a (n - n_c)^2): eps (1 + cos kappa) / (2 cos kappa)."""
    return eps * (1.0 + math.cos(kappa)) / (2.0 * math.cos(kappa))


def nu_gaussian(eps: float, beta: float) -> float:
    """nu of the log-NLS Gaussian of envelope amplitude beta = max|B|: 4 + eps (4 ln(2 beta) - 2)."""
    return 4.0 + eps * (4.0 * math.log(2.0 * beta) - 2.0)


def wrap(angle: float) -> float:
    """The angle in (-pi, pi]."""
    return float(-((-angle + math.pi) % (2.0 * math.pi) - math.pi))


def boost_theta(c: float, tau0: float, nu: float) -> float:
    """theta of (tb) of the boosted Gaussian of velocity c and static nu: kappa / 2 + nu / (2 kappa) - pi, wrapped
    into (-pi, pi] (module docstring, (theta))."""
    kappa = boost_kappa(c, tau0)
    return wrap(0.5 * kappa + 0.5 * nu / kappa - math.pi)


#: |z| below which g's derivatives are taken as 0 (their limits for alpha > 1; a subnormal |z| would overflow)
TINY = 1e-290


def _unit(z: NDArray[np.complex128], r: NDArray[np.float64]) -> NDArray[np.complex128]:
    """z / |z| where |z| > TINY, else 0: written through the unit vector, no power of a tiny |z| overflows."""
    big = r > TINY
    safe = np.where(big, r, 1.0)
    return np.asarray(np.where(big, z.real / safe + 1j * (z.imag / safe), 0.0), dtype=np.complex128)


def dg(z: ArrayLike, h: ArrayLike, eps: float) -> NDArray[np.complex128]:
    """Dg(z)[h] = |z|^eps h + eps |z|^(eps-2) z Re(conj(z) h), g(z) = z |z|^eps (0 where z = 0)."""
    z, h = np.asarray(z, complex), np.asarray(h, complex)
    r = np.abs(z)
    unit = _unit(z, r)
    re = r**eps
    return np.asarray(re * h + eps * re * unit * np.real(np.conj(unit) * h), dtype=np.complex128)


def d2g(z: ArrayLike, h: ArrayLike, eps: float) -> NDArray[np.complex128]:
    """D^2 g(z)[h, h] = 2 eps r^(eps-2) Re(conj(z) h) h + z (eps (eps-2) r^(eps-4) Re(conj(z) h)^2 + eps r^(eps-2)
    |h|^2), r = |z| (0 where z = 0); for real z, h: g''(z) h^2 = eps (1 + eps) |z|^(eps-1) h^2."""
    z, h = np.asarray(z, complex), np.asarray(h, complex)
    r = np.abs(z)
    unit = _unit(z, r)
    q = np.real(np.conj(unit) * h)
    big = r > TINY
    w = np.where(big, eps * np.where(big, r, 1.0) ** (eps - 1.0), 0.0)
    return np.asarray(w * (2.0 * q * h + unit * ((eps - 2.0) * q**2 + np.abs(h) ** 2)), dtype=np.complex128)


def rhs(equation: str, U: ArrayLike, dU: ArrayLike, d2U: ArrayLike, eps: float) -> NDArray[np.complex128]:
    """The right-hand side of (lognlst), (At), (Bt) or (Ct) (``equation`` one of :data:`EQUATIONS`): what
    -2 i tau0 U_tau equals, given U and its first two x-derivatives."""
    U, dU, d2U = (np.asarray(v, complex) for v in (U, dU, d2U))
    r = np.abs(U)
    with np.errstate(divide="ignore", invalid="ignore"):
        g = U * np.where(r > 0, r**eps, 0.0)
        log = np.where(r > 0, np.log(np.where(r > 0, r, 1.0)), 0.0)
    if equation == "log-NLS":
        return np.asarray(4.0 * U + 4.0 * eps * U * log + d2U, dtype=np.complex128)
    half = {"A": 1.0, "B": 0.0, "C": 0.5}.get(equation)
    if half is None:
        raise ValueError(f"equation = {equation!r}: must be one of {', '.join(EQUATIONS)}")
    out = 4.0 * g + dg(U, d2U, eps)
    return np.asarray(out + half * d2g(U, dU, eps) if half else out, dtype=np.complex128)


def residual(equation: str, phi: ArrayLike, dphi: ArrayLike, d2phi: ArrayLike, x: ArrayLike, k: float, omega: float,
             eps: float, tau0: float) -> NDArray[np.complex128]:
    """-2 i tau0 U_tau - rhs at tau = 0 for U = phi(x - v tau) e^{i (k x - omega tau)}, v = k / tau0 (the boost's
    velocity), from the profile phi (real or complex) and its derivatives on the points x."""
    phi, dphi, d2phi = (np.asarray(v, complex) for v in (phi, dphi, d2phi))
    e = np.exp(1j * k * np.asarray(x, float))
    U = phi * e
    dU = (dphi + 1j * k * phi) * e
    d2U = (d2phi + 2j * k * dphi - k * k * phi) * e
    v = k / tau0
    U_tau = (-v * dphi - 1j * omega * phi) * e
    return np.asarray(-2j * tau0 * U_tau - rhs(equation, U, dU, d2U, eps), dtype=np.complex128)


def gaussian_profile(x: ArrayLike, eps: float, amplitude: float) -> tuple[NDArray[np.float64], ...]:
    """(phi, phi', phi''): the log-NLS Gaussian U = amplitude exp(-eps x^2) and its derivatives."""
    x = np.asarray(x, float)
    p = amplitude * np.exp(-eps * x**2)
    return p, -2.0 * eps * x * p, (4.0 * eps**2 * x**2 - 2.0 * eps) * p


def compacton_profile(x: ArrayLike, eps: float, kappa: float, amplitude: float) -> tuple[NDArray[np.float64], ...]:
    """(phi, phi', phi''): the compacton amplitude cos^(2/eps)(kappa x) on |kappa x| < pi/2 (0 beyond) and its
    derivatives (m = 2/eps: phi' = -m kappa tan phi, phi'' = m kappa^2 ((m - 1) tan^2 - 1) phi)."""
    z = kappa * np.asarray(x, float)
    inside = np.abs(z) < 0.5 * math.pi
    zz = np.where(inside, z, 0.0)
    m = 2.0 / eps
    with np.errstate(under="ignore"):
        p = np.where(inside, amplitude * np.cos(zz) ** m, 0.0)
    t = np.tan(zz)
    return p, -m * kappa * t * p, m * kappa**2 * ((m - 1.0) * t**2 - 1.0) * p


def boost_residual(equation: str, eps: float, k: float, points: int = 4001) -> float:
    """max |residual| / max |U| of the boosted unit-amplitude (max|B| = 1, U = 2B) travelling solution of
    ``equation``: the Gaussian for log-NLS (exact: rounding), the boosted static compacton of form A, B or C
    (:mod:`cradle.models.compacton`), with omega = -(nu - k^2) / (2 tau0) and nu the static one; tau0 = 1 (the
    residual scales with it only through v = k / tau0, which the boost fixes)."""
    from cradle.models import compacton as K

    tau0 = 1.0
    if equation == "log-NLS":
        nu = 4.0 + eps * (4.0 * math.log(2.0) - 2.0)
        span = math.sqrt(40.0 / eps)
        x = np.linspace(-span, span, points)
        phi, d1, d2 = gaussian_profile(x, eps, 2.0)
    else:
        kap = K.dps_kappa(eps, equation)
        nu = K.dps_nu(eps, equation)
        x = np.linspace(-0.5 * math.pi / kap, 0.5 * math.pi / kap, points)
        phi, d1, d2 = compacton_profile(x, eps, kap, 2.0)
    omega = -(nu - k * k) / (2.0 * tau0)
    R = residual(equation, phi, d1, d2, x, k, omega, eps, tau0)
    return float(np.max(np.abs(R)) / np.max(np.abs(phi)))


#: the travelling profiles a TB is compared with: the boosted log-NLS Gaussian and the boosted static compactons of
#: forms A, B, C (module docstring), and each narrowed by the lattice's carrier ("... carrier": n - n_c scaled by
#: sqrt(a / eps), a of :func:`carrier_width`, the phase gradient asin(tau0 c))
MODELS = ("gaussian", "A", "B", "C", "gaussian carrier", "A carrier", "B carrier", "C carrier")


def travelling_profile(model: str, n: ArrayLike, centre: float, eps: float, c: float,
                       tau0: float) -> NDArray[np.complex128]:
    """The envelope B_n / max|B| of ``model`` (one of :data:`MODELS`) centred at ``centre`` and travelling at c, at
    the instant its centre is there: a real profile of unit maximum times its boost's phase e^{i kappa (n - centre)}
    (kappa = tau0 c); a "carrier" model has the lattice's kappa = asin(tau0 c) and n - centre scaled by
    sqrt(a / eps) (:func:`carrier_width`: the Gaussian becomes exp(-a (n - centre)^2)). At c = 0 each is the static
    profile of :mod:`cradle.models.continuum` or :mod:`cradle.models.compacton`."""
    from cradle.models import compacton as K

    base, _, carrier = model.partition(" ")
    if carrier not in ("", "carrier") or base not in ("gaussian", *K.FORMS):
        raise ValueError(f"model = {model!r}: must be one of {', '.join(MODELS)}")
    y = np.asarray(n, float) - centre
    if carrier:
        kap = carrier_kappa(c, tau0)
        z = y * math.sqrt(carrier_width(eps, kap) / eps)
    else:
        kap = boost_kappa(c, tau0)
        z = y
    env = np.exp(-eps * z**2) if base == "gaussian" else K.dps_compacton(z, 0.0, eps, base)
    return np.asarray(env / np.max(env) * np.exp(1j * kap * y), dtype=np.complex128)
