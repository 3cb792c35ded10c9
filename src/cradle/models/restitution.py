"""The restitution of two viscoelastic spheres against their impact speed, and the Kuwabara-Kono constant A
fitted to measured restitutions.

**The normalisation of A, stated once.** cradle writes the force between two spheres in contact (overlap delta,
its rate delta') as

    F = k (delta^(3/2) + A delta^(1/2) delta'),     k = (4/3) E* sqrt(R*)  (cradle.models.physical),

A in seconds (:mod:`cradle.models.damping`: eta = A omega_0 in (nc)'s units). Other sources write
F = k delta^(3/2) + (3/2) A' k delta^(1/2) delta' (the (3/2) of the Hertz stiffness dF/d delta brought out):
the same force when A = (3/2) A'. :func:`from_three_halves` and :func:`to_three_halves` convert; a value of A
taken from a source must be converted by the convention that source writes.

**The collision.** Two spheres of reduced mass m_eff meeting at relative speed v: the overlap obeys
delta'' = -(k / m_eff) max(delta^(3/2) + A delta^(1/2) delta', 0) (the force never pulls; Schwager & Poeschel,
Phys. Rev. E 78 (2008) 051304). With delta = L y, time T s, L = (m_eff v^2 / k)^(2/5), T = L / v:

    y'' = -max(y^(3/2) + b y^(1/2) y', 0),   y(0) = 0, y'(0) = 1,   b = A / T = A kappa^(2/5) v^(1/5),

kappa = k / m_eff: the restitution e = |y'| when the overlap returns to zero depends on b alone
(:func:`restitution`), so 1 - e grows as v^(1/5) (Kuwabara & Kono, Jpn. J. Appl. Phys. 26 (1987) 1230;
Brilliantov, Spahn, Hertzsch & Poeschel, Phys. Rev. E 53 (1996) 5382). Its small-b series is
1 - e = C1 b - C2 b^2 + ... (the form: Ramirez, Poeschel, Brilliantov & Schwager, Phys. Rev. E 60 (1999) 4465).
C1 follows in closed form from the undamped collision (:func:`first_order_coefficient`):
C1 = (4/5) (5/4)^(3/5) B(3/5, 3/2) = 1.1534489 in this convention, (3/2) C1 = 1.7301733 in the other; the
collision reproduces it (tests/models/test_restitution.py). C2 (about 0.80) is measured on the collision, not
derived here; the next term is of order b^(5/2), not b^3 (the clipped force ends the contact where y < b |y'|).

**The fit.** :func:`fit_constant` fits A to measured (v, e, sigma) of one pair of spheres (:class:`Measurement`,
each with its source) by weighted least squares of e(v; A), and gives its standard uncertainty from the
curvature of chi^2, scaled up by sqrt(chi^2 / dof) when the points scatter more than their stated errors.
The measurements live in :mod:`cradle.models.restitution_data` (none yet: no source's numbers could be read;
docs/dissipation.md), each a :class:`Measurement` with its source.
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

#: A / A': this module's A over that of the (3/2)-normalised force k delta^(3/2) + (3/2) A' k delta^(1/2) delta'
THREE_HALVES = 1.5


def from_three_halves(A_prime: float) -> float:
    """A of F = k (delta^(3/2) + A delta^(1/2) delta') from A' of F = k delta^(3/2) + (3/2) A' k delta^(1/2) delta'."""
    return THREE_HALVES * A_prime


def to_three_halves(A: float) -> float:
    """A' of the (3/2)-normalised force from this module's A (:func:`from_three_halves` inverted)."""
    return A / THREE_HALVES


def restitution(b: float, rtol: float = 1e-11) -> float:
    """e of the scaled collision y'' = -max(y^(3/2) + b y^(1/2) y', 0), y(0) = 0, y'(0) = 1 (module docstring):
    |y'| when the overlap returns to 0; 0 if it never does (the spheres stay in contact)."""
    from scipy.integrate import solve_ivp

    def rhs(_s: float, z: NDArray[np.float64]) -> list[float]:
        y, w = max(z[0], 0.0), z[1]
        return [w, -max(y**1.5 + b * math.sqrt(y) * w, 0.0)]

    def back(_s: float, z: NDArray[np.float64]) -> float:
        return float(z[0])

    setattr(back, "terminal", True)  # noqa: B010 (scipy reads these attributes of the event function)
    setattr(back, "direction", -1)  # noqa: B010
    sol = solve_ivp(rhs, (0.0, 50.0), [0.0, 1.0], events=back, rtol=rtol, atol=rtol * 1e-2, method="DOP853",
                    first_step=1e-6)
    ends = sol.y_events or []
    if not ends or not len(ends[0]):
        return 0.0
    return float(abs(ends[0][0][1]))


def first_order_coefficient() -> float:
    """C1 of 1 - e = C1 b + O(b^2) for the scaled collision (module docstring), in closed form.

    At first order in b the damping acts on the undamped Hertz collision, whose speed obeys
    y'^2 = 1 - (4/5) y^(5/2) (energy y'^2/2 + (2/5) y^(5/2) = 1/2), up to y_max = (5/4)^(2/5) and back. The energy
    it removes is b times the integral of y^(1/2) y'^2 over the contact time, 2 b times the integral of
    y^(1/2) |y'| dy from 0 to y_max; e^2 = 1 - 2 Delta E, so 1 - e = Delta E + O(b^2). With u = (4/5) y^(5/2) the
    integral is (2/5) (5/4)^(3/5) B(3/5, 3/2), so C1 = (4/5) (5/4)^(3/5) Gamma(3/5) Gamma(3/2) / Gamma(21/10)."""
    beta = math.gamma(0.6) * math.gamma(1.5) / math.gamma(2.1)
    return 0.8 * 1.25**0.6 * beta


def scaled_for(e: float) -> float:
    """The b of the scaled collision whose restitution is e (:func:`restitution` inverted, by bisection in log b
    over [1e-8, 10])."""
    from scipy.optimize import brentq

    log_b = brentq(lambda lb: (1.0 - restitution(math.exp(lb))) - (1.0 - e), math.log(1e-8), math.log(10.0),
                   xtol=1e-12)
    return math.exp(log_b)


def scaled_constant(A: float, v: float | NDArray[np.float64], k: float, m_eff: float) -> NDArray[np.float64]:
    """b = A kappa^(2/5) v^(1/5), kappa = k / m_eff: the one number the restitution depends on."""
    return A * (k / m_eff) ** 0.4 * np.asarray(v, dtype=float) ** 0.2


def restitution_at(A: float, v: float | NDArray[np.float64], k: float, m_eff: float) -> NDArray[np.float64]:
    """e(v) of two spheres (Hertz constant k, reduced mass m_eff) with the Kuwabara-Kono constant A (s), at each
    impact speed v (m/s)."""
    bs = np.atleast_1d(scaled_constant(A, v, k, m_eff))
    return np.array([restitution(float(b)) for b in bs])


@dataclass(frozen=True)
class Measurement:
    """A measured restitution: spheres of ``material`` (cradle.models.physical.MATERIALS) and ``radius`` (m) against
    the same, or a flat of the same material when ``flat``; impact speed ``v`` (m/s), restitution ``e`` and its
    standard uncertainty ``sigma``, and where the numbers come from (``source``: the paper, its table or figure)."""

    material: str
    radius: float
    flat: bool
    v: float
    e: float
    sigma: float
    source: str


@dataclass(frozen=True)
class Fit:
    """A fitted to measurements: its value (s), standard uncertainty (s), chi^2 and degrees of freedom, the
    normalised residuals (e - e_fit) / sigma, and the Birge factor sqrt(chi^2 / dof) applied to the uncertainty
    (1 when the points scatter no more than their errors)."""

    A: float
    sigma_A: float
    chi2: float
    dof: int
    residuals: NDArray[np.float64]
    birge: float


def _pair(m: Measurement) -> tuple[float, float]:
    """(k, m_eff) of the measured pair: two equal spheres, or a sphere on a flat of the same material (R* = R,
    m_eff = m)."""
    from cradle.models import physical as ph

    mat = ph.MATERIALS[m.material]
    E_star = ph.reduced_modulus(mat.E, mat.nu, mat.E, mat.nu)
    mass = ph.sphere_mass(mat.rho, m.radius)
    if m.flat:
        return ph.hertz_constant(E_star, m.radius), mass
    return ph.hertz_constant(E_star, ph.reduced_radius(m.radius, m.radius)), mass / 2.0


def fit_constant(data: Sequence[Measurement], A_bounds: tuple[float, float] = (1e-12, 1e-2)) -> Fit:
    """The Kuwabara-Kono A (this module's normalisation) that best fits ``data`` (weighted least squares of e), its
    standard uncertainty from d^2 chi^2 / dA^2 (times the Birge factor when chi^2 > dof)."""
    from scipy.optimize import minimize_scalar

    pairs = [_pair(m) for m in data]
    e = np.array([m.e for m in data])
    sig = np.array([m.sigma for m in data])

    def model(A: float) -> NDArray[np.float64]:
        return np.array([restitution(float(scaled_constant(A, m.v, k, me))) for m, (k, me) in zip(data, pairs,
                                                                                                 strict=True)])

    def chi2(logA: float) -> float:
        return float(np.sum(((e - model(math.exp(logA))) / sig) ** 2))

    lo, hi = (math.log(x) for x in A_bounds)
    best = minimize_scalar(chi2, bounds=(lo, hi), method="bounded", options={"xatol": 1e-10})
    A = math.exp(float(best.x))
    h = 1e-4 * A
    J = (model(A + h) - model(A - h)) / (2.0 * h)   # de/dA at each point
    sigma_A = 1.0 / math.sqrt(float(np.sum((J / sig) ** 2)))
    c2 = chi2(math.log(A))
    dof = max(len(data) - 1, 1)
    birge = max(1.0, math.sqrt(c2 / dof))
    return Fit(A=A, sigma_A=sigma_A * birge, chi2=c2, dof=dof, residuals=(e - model(A)) / sig, birge=birge)
