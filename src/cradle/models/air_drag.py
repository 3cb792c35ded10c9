"""Air drag on a swinging ball as the linear on-site damping of (ncdamped): two rates that bracket it.

(ncdamped)'s on-site term is a force -m rate u' on every ball (:mod:`cradle.models.damping`). The drag of air on a
sphere of radius R moving at speed v is not linear: at the Reynolds numbers of a desk toy (Re = rho_air v 2R /
mu_air, a few hundred for 1 cm balls at 0.3 m/s) it is F = (1/2) rho_air C_d(Re) pi R^2 v^2. No source we have
gives a desk toy's linear drag rate, so the analyses run under two rates that bracket it:

* :func:`stokes_rate`: Stokes' drag F = 6 pi mu_air R v, rate = 6 pi mu_air R / m. It holds for Re << 1 and is
  below the drag at every larger Re: a LOWER bound.
* :func:`quadratic_rate`: the drag F = (1/2) rho_air C_d(Re) pi R^2 v|v| at the largest speed V of the release,
  with C_d of Schiller & Naumann's correlation (:func:`drag_coefficient`), replaced by the linear rate that
  removes the same energy over a swing v = V sin(omega_0 s): <F |v|> = (2/3) rho_air C_d R^2 V^3 against
  rate m V^2 / 2, so rate = (4/3) rho_air C_d R^2 V / m. A swing slower than V loses less: an UPPER bound over
  the minute (the balls' speeds only fall).

The air's constants are those of the ISO 2533:1975 Standard Atmosphere at sea level (15 C, 101 325 Pa):
:data:`AIR_DENSITY`, :data:`AIR_VISCOSITY`.
"""
from __future__ import annotations

import math

from cradle.models.physical import MATERIALS, Cradle, release_speed, sphere_mass

#: density of air (kg/m^3): ISO 2533:1975 Standard Atmosphere, sea level (15 C, 101 325 Pa)
AIR_DENSITY = 1.225
#: dynamic viscosity of air (Pa s): ISO 2533:1975 Standard Atmosphere, sea level (15 C); as
#: cradle.analyses.dissipation's air_viscosity
AIR_VISCOSITY = 1.7894e-5

#: Schiller & Naumann's drag correlation holds below this Reynolds number (Clift, Grace & Weber, Bubbles, Drops and
#: Particles, Academic Press 1978, table 5.2: Re < 800)
SCHILLER_NAUMANN_MAX_RE = 800.0


def reynolds(speed: float, radius: float, density: float = AIR_DENSITY, viscosity: float = AIR_VISCOSITY) -> float:
    """Re = rho_air v 2R / mu_air of a sphere of radius ``radius`` (m) at ``speed`` (m/s)."""
    return density * speed * 2.0 * radius / viscosity


def drag_coefficient(re: float) -> float:
    """C_d = 24 / Re (1 + 0.15 Re^0.687) of a sphere (Schiller & Naumann, Z. Ver. Dtsch. Ing. 77 (1933) 318; Clift,
    Grace & Weber 1978, table 5.2), for 0 < Re < :data:`SCHILLER_NAUMANN_MAX_RE`."""
    if not 0.0 < re < SCHILLER_NAUMANN_MAX_RE:
        raise ValueError(f"Re = {re!r}: the Schiller-Naumann correlation holds for 0 < Re < "
                         f"{SCHILLER_NAUMANN_MAX_RE:g}")
    return 24.0 / re * (1.0 + 0.15 * re**0.687)


def stokes_rate(cradle: Cradle, viscosity: float = AIR_VISCOSITY) -> float:
    """Stokes' linear drag rate 6 pi mu_air R / m (1/s) of one of the cradle's balls: the lower bound."""
    m = sphere_mass(MATERIALS[cradle.material].rho, cradle.radius)
    return 6.0 * math.pi * viscosity * cradle.radius / m


def quadratic_rate(cradle: Cradle, angle_deg: float, density: float = AIR_DENSITY,
                   viscosity: float = AIR_VISCOSITY) -> float:
    """The linear rate (1/s) removing the energy the quadratic drag removes over a swing at the release speed
    V = sqrt(2 g L (1 - cos theta)): (4/3) rho_air C_d(Re) R^2 V / m (module docstring): the upper bound."""
    V = release_speed(cradle, angle_deg)
    cd = drag_coefficient(reynolds(V, cradle.radius, density, viscosity))
    m = sphere_mass(MATERIALS[cradle.material].rho, cradle.radius)
    return 4.0 / 3.0 * density * cd * cradle.radius**2 * V / m


def bracketing_rates(cradle: Cradle, angle_deg: float, density: float = AIR_DENSITY,
                     viscosity: float = AIR_VISCOSITY) -> tuple[float, float]:
    """(lower, upper) linear drag rates (1/s): Stokes, and the quadratic drag at the release speed."""
    return stokes_rate(cradle, viscosity), quadratic_rate(cradle, angle_deg, density, viscosity)
