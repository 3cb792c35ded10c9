"""The solitary wave of the Hertz chain without on-site potential, and Nesterenko's long-wave approximation.

Without the on-site term of (nc), a chain of touching beads (unit masses, unit spacing of the sites, Hertz
force c^(3/2) on a compressed bond, c_n = x_n - x_{n+1} the compression of bond n) obeys

    x_n'' = c_{n-1}^(3/2) - c_n^(3/2),      c_n'' = f(c_{n-1}) - 2 f(c_n) + f(c_{n+1}),   f(r) = r_+^(3/2).

A travelling wave c_n(t) = R(n - c t) (speed c in sites per unit time) solves the advance-delay equation

    c^2 R''(xi) = f(R(xi+1)) - 2 f(R(xi)) + f(R(xi-1)),                                         (sw)

equivalently, integrated twice against the tent Lambda(s) = max(1 - |s|, 0) (whose Fourier transform is
sinc^2(k/2)), R = c^-2 Lambda * f(R). English & Pego (Proc. Amer. Math. Soc. 133 (2005)) proved that the
Hertz chain has a solitary wave whose tails decay doubly exponentially; Ahnert & Pikovsky (Phys. Rev. E 79
(2009) 026209) found it "superexponentially localized" and computed it numerically for any exponent. Far out
R(xi + 1) ~ R(xi)^(3/2), so -log R grows like (3/2)^|xi| (log(-log R) has slope log(3/2)); the next terms are
those of :func:`cradle.analyses.solitary_wave.tail_slopes`.

:func:`solve` finds it by Petviashvili's iteration (V. I. Petviashvili, 1976; for L u = N(u) with N
homogeneous of degree p, as in Alvarez & Duran, "Petviashvili type methods for traveling wave computations:
I. Analysis of convergence", arXiv:1311.2546) on the Fourier form: R_new = S^gamma c^-2 Lambda * f(R), with the
stabilising factor S = <R, R> / <R, c^-2 Lambda * f(R)> (S = 1 at the fixed point) and gamma = p/(p-1) = 3
for f homogeneous of degree p = 3/2. The shifts xi +- 1 are exact on a grid of an integer number of points per
site, and the periodic box of ``length`` sites is wide enough that the wave is below the rounding at its edge.

The wave's particle velocity follows from x_n(t) = X(n - c t), c^2 X'' = f(R(xi-1)) - f(R(xi)) and beads
at rest ahead of the wave: v(xi) = c^-1 int_{xi-1}^{xi} f(R(s)) ds (:func:`velocity`).

Homogeneity: R_c(xi) = c^4 R_1(xi) solves (sw) at speed c, so the strain amplitude grows as c^4, the force
amplitude as c^6 and the velocity amplitude as c^5: c = c_1 (v_m / v_1)^(1/5) exactly.

Nesterenko's long-wave approximation (V. F. Nesterenko, J. Appl. Mech. Tech. Phys. 24 (1983) 733; Dynamics
of Heterogeneous Materials, Springer 2001, section 1.3): the strain xi = -u_x obeys

    u_tt = -c0^2 [ xi^(3/2) + (a^2/10) xi^(1/4) (xi^(5/4))_xx ]_x,

whose solitary wave, in the units above (c0 = 1, a = 1), is R(z) = R_m cos^4(sqrt(2/5) z) for
|z| <= (pi/2) sqrt(5/2), zero beyond: a compact pulse of total width pi sqrt(5/2) = 4.97 sites ("about five
particle diameters") moving at c_N = (2/sqrt(5)) R_m^(1/4) = (16/25)^(1/5) v_m^(1/5) (:func:`nesterenko`).

:func:`solve`, :func:`velocity` and :func:`residual` also take another exponent alpha > 1 of f(r) = r_+^alpha (the
"FPU lattice with Hertzian potential" of James & Pelinovsky, Proc. R. Soc. A 470 (2014) 20130462), for the limit
alpha -> 1+ of :mod:`cradle.models.continuum`; the rest of this module (homogeneity exponents, Nesterenko's wave,
the tail) is that of alpha = 3/2.

The tail of :func:`solve` is limited by the rounding of the Fourier transforms (about 1e-16 of the peak);
:func:`tail` continues it beyond that in real space, on log R (which never underflows), by the dominant part
of the integral form: R(xi) = c^-2 int_{xi-1}^{xi} (1 - (xi - s)) f(R(s)) ds, the neglected part
c^-2 int_xi^{xi+1} ... being smaller by a factor of order R(xi)^(1/2).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

#: Hertz's exponent p of the contact force f(r) = r^p (alpha of (vhertz) for spheres)
P = 1.5
#: Petviashvili's exponent gamma = p / (p - 1) for a nonlinearity homogeneous of degree p
GAMMA = P / (P - 1.0)
#: Nesterenko's long-wave wavenumber sqrt(2/5) (per site) of the cos^4 profile
NESTERENKO_KAPPA = math.sqrt(0.4)
#: the total width pi / kappa = pi sqrt(5/2) (sites) of Nesterenko's compact pulse
NESTERENKO_WIDTH = math.pi / NESTERENKO_KAPPA
#: :func:`tail` takes over where R falls below this fraction of R_m: there the Fourier solution still has about
#: eight correct digits (its rounding is about 1e-16 of R_m) and the neglected part of the integral form is
#: of order R^(1/2), about 1e-4 relative
TAIL_FLOOR = 1e-8


@dataclass(frozen=True)
class SolitaryWave:
    """The solitary wave of (sw) at speed ``c`` sampled on ``xi`` (sites, centred on the peak): the strain
    (compression) R, the particle velocity v, Petviashvili's iteration count, its last relative increment
    max|R_new - R| / max R and its stabilising factor S (1 at the fixed point)."""

    c: float
    xi: NDArray[np.float64]
    strain: NDArray[np.float64]
    velocity: NDArray[np.float64]
    iterations: int
    increment: float
    stabiliser: float
    alpha: float = P


    @property
    def strain_max(self) -> float:
        """R_m = max R (at xi = 0)."""
        return float(np.max(self.strain))

    @property
    def velocity_max(self) -> float:
        """v_m = max v."""
        return float(np.max(self.velocity))

    @property
    def force_max(self) -> float:
        """f(R_m) = R_m^alpha, the largest contact force."""
        return self.strain_max**self.alpha


def _grid(length: float, points: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    n = int(round(length * points))
    h = 1.0 / points
    xi = ((np.arange(n) - n // 2) * h).astype(np.float64)
    k = (2.0 * np.pi * np.fft.rfftfreq(n, d=h)).astype(np.float64)
    return xi, k


def _tent(k: NDArray[np.float64]) -> NDArray[np.float64]:
    """The Fourier multiplier sinc^2(k/2) of the tent Lambda (np.sinc(x) = sin(pi x)/(pi x))."""
    return np.sinc(k / (2.0 * np.pi)) ** 2


def solve(c: float = 1.0, length: float = 40.0, points: int = 64, tol: float = 1e-15,
          max_iterations: int = 500, alpha: float = P) -> SolitaryWave:
    """The solitary wave of (sw) at speed ``c`` by Petviashvili's iteration (module docstring) on a periodic grid
    of ``length`` sites and ``points`` points per site, until the relative increment is below ``tol`` (or
    ``max_iterations``). ``alpha``: the exponent of the contact force f(r) = r_+^alpha (Hertz's 3/2 by default);
    Petviashvili's exponent is then alpha / (alpha - 1). The start is Nesterenko's profile at the same speed for
    alpha = 3/2, the log-KdV Gaussian of the limit alpha -> 1+ otherwise, exp((c^2 - 1)/eps + 1/2) exp(-3 eps xi^2),
    eps = alpha - 1 (:mod:`cradle.models.continuum`)."""
    xi, k = _grid(length, points)
    n = xi.size
    mult = _tent(k) / c**2
    if alpha == P:
        R, p, gamma = nesterenko_profile(xi, nesterenko_amplitude(c)), P, GAMMA
    else:   # the log-KdV wave at speed c (cradle.models.continuum, which imports this module)
        eps = alpha - 1.0
        R, p, gamma = math.exp((c * c - 1.0) / eps + 0.5) * np.exp(-3.0 * eps * xi**2), alpha, alpha / eps
    increment, S, it = math.inf, math.nan, 0
    for it in range(1, max_iterations + 1):  # noqa: B007 (the count is returned)
        Rh = np.fft.rfft(R)
        Nh = mult * np.fft.rfft(R**p)
        S = float(np.vdot(Rh, Rh).real / np.vdot(Rh, Nh).real)
        new = np.maximum(np.fft.irfft(S**gamma * Nh, n), 0.0)
        increment = float(np.max(np.abs(new - R)) / np.max(new))
        R = new
        if increment < tol:
            break
    return SolitaryWave(c=c, xi=xi, strain=R, velocity=velocity(xi, R, c, p), iterations=it, increment=increment,
                        stabiliser=S, alpha=p)


def velocity(xi: NDArray[np.float64], strain: NDArray[np.float64], c: float, alpha: float = P) -> NDArray[np.float64]:
    """v(xi) = c^-1 int_{xi-1}^{xi} f(R(s)) ds, f(r) = r^alpha, on the periodic grid ``xi`` (an integer number of
    points per site), by the Fourier multiplier (1 - e^(-ik)) / (ik) of the unit box."""
    h = float(xi[1] - xi[0])
    k = 2.0 * np.pi * np.fft.rfftfreq(xi.size, d=h)
    box = np.ones_like(k, dtype=complex)
    nz = k != 0.0
    box[nz] = (1.0 - np.exp(-1j * k[nz])) / (1j * k[nz])
    return np.fft.irfft(box * np.fft.rfft(strain**alpha), xi.size) / c


def residual(w: SolitaryWave) -> float:
    """max |c^2 R'' - (f(R(xi+1)) - 2 f(R(xi)) + f(R(xi-1)))| / max f(R), f(r) = r^alpha of the wave: (sw) in its
    differential form, R'' by Fourier differentiation and the shifts exact on the grid (not the integrated form the
    iteration solves)."""
    h = float(w.xi[1] - w.xi[0])
    m = int(round(1.0 / h))
    k = 2.0 * np.pi * np.fft.rfftfreq(w.xi.size, d=h)
    d2 = np.fft.irfft(-(k**2) * np.fft.rfft(w.strain), w.xi.size)
    f = w.strain**w.alpha
    rhs = np.roll(f, -m) - 2.0 * f + np.roll(f, m)
    return float(np.max(np.abs(w.c**2 * d2 - rhs)) / np.max(f))


def scaled(w: SolitaryWave, c: float) -> SolitaryWave:
    """The wave at speed ``c`` from ``w`` by the homogeneity of (sw): R -> (c/c_w)^4 R, v -> (c/c_w)^5 v (alpha =
    3/2 only: the exponents are 2/(alpha-1) and (alpha+1)/(alpha-1))."""
    s = c / w.c
    return SolitaryWave(c=c, xi=w.xi, strain=s**4 * w.strain, velocity=s**5 * w.velocity, iterations=w.iterations,
                        increment=w.increment, stabiliser=w.stabiliser)


def speed_for_velocity(w: SolitaryWave, v_max: float | NDArray[np.float64]) -> float | NDArray[np.float64]:
    """The speed c of the solitary wave whose largest particle velocity is ``v_max``: c_w (v_max / v_m)^(1/5)."""
    return w.c * (np.asarray(v_max) / w.velocity_max) ** 0.2


def fwhm(xi: NDArray[np.float64], y: NDArray[np.float64]) -> float:
    """Full width at half maximum of a single-peaked profile ``y(xi)``, crossings by linear interpolation."""
    y = np.asarray(y, dtype=float)
    i = int(np.argmax(y))
    half = 0.5 * y[i]
    above = np.flatnonzero(y >= half)
    lo, hi = int(above[0]), int(above[-1])
    left = xi[lo - 1] + (half - y[lo - 1]) * (xi[lo] - xi[lo - 1]) / (y[lo] - y[lo - 1])
    right = xi[hi] + (half - y[hi]) * (xi[hi + 1] - xi[hi]) / (y[hi + 1] - y[hi])
    return float(right - left)


# ----------------------------------------------------------------- Nesterenko's long-wave solitary wave


def nesterenko_amplitude(c: float) -> float:
    """R_m of Nesterenko's wave at speed c: c = (2/sqrt(5)) R_m^(1/4), R_m = (sqrt(5) c / 2)^4."""
    return (math.sqrt(5.0) * c / 2.0) ** 4


def nesterenko_speed(strain_max: float | NDArray[np.float64]) -> float | NDArray[np.float64]:
    """c_N = (2/sqrt(5)) R_m^(1/4) (sites per unit time) at strain amplitude R_m."""
    return 2.0 / math.sqrt(5.0) * np.asarray(strain_max) ** 0.25


def nesterenko_speed_v(v_max: float | NDArray[np.float64]) -> float | NDArray[np.float64]:
    """c_N = (16/25)^(1/5) v_m^(1/5) at particle-velocity amplitude v_m (v = c R in the long-wave limit)."""
    return (16.0 / 25.0) ** 0.2 * np.asarray(v_max) ** 0.2


def nesterenko_profile(xi: NDArray[np.float64], strain_max: float) -> NDArray[np.float64]:
    """R_m cos^4(sqrt(2/5) xi) on |xi| <= (pi/2) sqrt(5/2), 0 beyond."""
    z = NESTERENKO_KAPPA * np.asarray(xi, dtype=float)
    return np.where(np.abs(z) <= 0.5 * np.pi, strain_max * np.cos(z) ** 4, 0.0)


# ----------------------------------------------------------------- the doubly exponential tail


def _cell_integrals(delta: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(int_0^1 e^(delta t) dt, int_0^1 t e^(delta t) dt), by series where delta is small."""
    d = np.asarray(delta, dtype=float)
    small = np.abs(d) < 1e-4
    ds = np.where(small, 1.0, d)
    e1 = np.where(small, 1.0 + d / 2.0 + d**2 / 6.0, np.expm1(ds) / ds)
    e2 = np.where(small, 0.5 + d / 3.0 + d**2 / 8.0, (ds * np.exp(ds) - np.expm1(ds)) / ds**2)
    return e1, e2


def tail_start(w: SolitaryWave, floor: float = TAIL_FLOOR) -> float:
    """The last xi > 0 where R >= ``floor`` R_m: where :func:`tail` takes over from the Fourier solution."""
    right = (w.xi > 0.0) & (w.strain >= floor * w.strain_max)
    return float(w.xi[np.flatnonzero(right)[-1]])


def tail(w: SolitaryWave, stop: float, start: float | None = None) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(xi, log R) of the right tail from ``start`` (default :func:`tail_start`) to ``stop`` (sites), on the grid of
    ``w``: log R taken from ``w`` on [start - 1, start], then marched by the dominant part of the integral form
    (module docstring), each cell's integral exact for log R linear across the cell."""
    h = float(w.xi[1] - w.xi[0])
    m = int(round(1.0 / h))
    i0 = int(np.searchsorted(w.xi, tail_start(w) if start is None else start))
    n_new = int(round((stop - w.xi[i0]) / h))
    L = np.empty(m + 1 + n_new)
    L[: m + 1] = np.log(w.strain[i0 - m: i0 + 1])
    u = np.arange(m + 1) * h            # the weight 1 - (xi - s) = s - (xi - 1) at the cell ends
    for j in range(m + 1, L.size):
        # the cell [xi_j - h, xi_j] needs L_j: extrapolated linearly (its share is ~h R^(1/2) of the integral)
        seg = np.empty(m + 1)
        seg[:m] = L[j - m: j]
        seg[m] = 2.0 * L[j - 1] - L[j - 2]
        g = P * seg
        e1, e2 = _cell_integrals(np.diff(g))
        terms = g[:-1] + np.log(h * (u[:-1] * e1 + h * e2))
        top = float(np.max(terms))
        L[j] = top + math.log(float(np.sum(np.exp(terms - top)))) - 2.0 * math.log(w.c)
    xi = w.xi[i0] + h * np.arange(-m, L.size - m)
    return xi[m:], L[m:]
