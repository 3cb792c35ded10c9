"""Physical units: the map between a real cradle and the dimensionless variables of (nc).

The introduction of the paper derives (nc) from a chain of identical beads of mass m, each a linear
oscillator of angular frequency omega_0 (a pendulum: omega_0 = sqrt(g/L)), touching its neighbours
through Hertz's force f(delta) = k delta^alpha, alpha = 3/2 (figure boules). In SI, with u_n the
horizontal displacement of bead n and s the time,

    m u_n'' + m omega_0^2 u_n = k (u_{n-1} - u_n)_+^alpha - k (u_n - u_{n+1})_+^alpha .

With s = T t, u_n = X x_n, T = 1/omega_0 and X chosen so that the on-site and contact forces balance
at the displacement X,

    m omega_0^2 X = k X^alpha,   X = (m omega_0^2 / k)^(1/(alpha-1))   (= (m omega_0^2/k)^2 for alpha = 3/2),

the equation becomes (nc) with V = V0 of (vhertz): x_n'' + x_n = V0'(x_{n+1}-x_n) - V0'(x_n-x_{n-1}),
V0'(r) = -|r|^alpha H(-r) (:mod:`cradle.models.lattice`). The other scales follow: velocity
X omega_0, force m omega_0^2 X, energy m omega_0^2 X^2 (the energy (ham) times this is the SI energy).

Hertz between spheres i and j (Johnson, Contact Mechanics, 1985, section 4.2; Landau & Lifshitz,
Theory of Elasticity, section 9): F = (4/3) E* sqrt(R*) delta^(3/2), 1/E* = (1-nu_i^2)/E_i +
(1-nu_j^2)/E_j, R* = R_i R_j/(R_i+R_j); for identical spheres E* = E/(2(1-nu^2)), R* = R/2.

The materials' values and their sources are in :data:`MATERIALS` (docs/physical-units.md lists them).
This module imports no numpy: ``import cradle`` stays light and the command line starts fast.
"""
from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, TypeVar, overload

from cradle.specs.checked import checked
from cradle.specs.declare import check_fields, declared, from_plain, param
from cradle.specs.values import ConfigError, did_you_mean

_T = TypeVar("_T")

if TYPE_CHECKING:
    import numpy as np
    from numpy.typing import NDArray

#: standard acceleration of gravity g_n (m/s^2), exact by definition (3rd CGPM, 1901; BIPM, The International
#: System of Units, 9th edition, 2019)
STANDARD_GRAVITY = 9.80665

#: Hertz's exponent alpha of (vhertz) for spheres
HERTZ_ALPHA = 1.5

#: the collision integral I = int_0^1 du / sqrt(1 - u^(5/2)) of the Hertz collision time (Landau & Lifshitz,
#: Theory of Elasticity, section 9, problem), in closed form: (2/5) B(2/5, 1/2)
COLLISION_INTEGRAL = 0.4 * math.gamma(0.4) * math.sqrt(math.pi) / math.gamma(0.9)

_PSI = 6894.757293168361          # Pa per psi (NIST SP 811, appendix B: 1 lbf/in^2 = 6.894 757 kPa)
_LB_PER_IN3 = 27679.90471020313   # kg/m^3 per lb/in^3 (NIST SP 811, appendix B)


def _validated(cls: type[_T], values: dict, where: str) -> _T:
    """:func:`cradle.specs.declare.from_plain`, a NaN refused first (JSON Schema's bounds let it through): one
    ConfigError line naming the key, the value and why."""
    for key, value in values.items():
        if isinstance(value, float) and math.isnan(value):
            raise ConfigError(f"config error: {where}.{key} = nan: not a number")
    return from_plain(cls, values, where)


# The bounds below are those of real solids and cradles, wide enough for any of them and narrow enough that
# every scale of (nc) (:func:`scales`: m, k, T, X, V, F, E, and a release's speed and collision time) is a finite,
# nonzero double at every corner of the box they make (tests/models/test_physical.py checks the corners):
# X = (m omega_0^2 / k)^2 grows as R^5 omega_0^4 (rho / E*)^2, so a radius of 1e-300 m underflows it to 0.


@declared(doc="The elastic constants of a sphere material, within the range of real solids.")
class Elastic:
    E: float = param(doc="Young's modulus E (Pa); in [1e3, 1e13]: from soft gels (kPa) to above diamond "
                         "(1.2e12).", minimum=1e3, maximum=1e13)
    nu: float = param(doc="Poisson's ratio nu; in (-1, 0.5]: an isotropic solid with positive bulk and shear "
                          "moduli (1 - nu^2 > 0).", exclusiveMinimum=-1, maximum=0.5)
    rho: float = param(doc="Density rho (kg/m^3); in [1, 1e5]: from aerogels to above osmium (22.6e3).",
                       minimum=1, maximum=1e5)


@dataclasses.dataclass(frozen=True)
class Material:
    """An elastic material of the spheres: Young's modulus E (Pa), Poisson's ratio nu, density rho (kg/m^3),
    and where each value comes from. The constants are checked against :class:`Elastic` when it is made: a bad
    one (negative, zero, NaN, a string, ...) is one ConfigError line."""

    name: str
    E: float
    nu: float
    rho: float
    source: str

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not isinstance(self.source, str):
            raise ConfigError(f"config error: material.name = {self.name!r}, source = {self.source!r}: must be "
                              f"strings (the material's name and where its values come from)")
        read = _validated(Elastic, {"E": self.E, "nu": self.nu, "rho": self.rho}, f"material {self.name!r}")
        for key in ("E", "nu", "rho"):   # as the validation read them ('7800' is 7800.0)
            object.__setattr__(self, key, getattr(read, key))


def _ptfe() -> Material:
    # isotropic elasticity from the ultrasonic sound speeds: nu = (vL^2 - 2 vT^2) / (2 (vL^2 - vT^2)),
    # E = 2 rho vT^2 (1 + nu); a polymer's modulus depends on the rate of loading (quasi-static tensile values
    # are lower, 0.4-0.6 GPa), so this is the modulus of a fast impact, not of a slow squeeze
    v_l, v_t, rho = 1410.0, 730.0, 2150.0
    nu = (v_l**2 - 2.0 * v_t**2) / (2.0 * (v_l**2 - v_t**2))
    return Material("ptfe", 2.0 * rho * v_t**2 * (1.0 + nu), nu, rho,
                    "sound speeds vL = 1410 m/s, vT = 730 m/s: Martienssen & Warlimont (eds.), Springer Handbook "
                    "of Condensed Matter and Materials Data (2005), table 3.3-12; density 2.15 g/cm^3: AZoM, "
                    "'Polytetrafluoroethylene - PTFE' (azom.com article 804, from Plascams)")


#: the named materials: values as their sources give them, converted to SI here
MATERIALS: dict[str, Material] = {m.name: m for m in (
    Material("steel", 29.5e6 * _PSI, 0.30, 0.283 * _LB_PER_IN3,
             "AISI 52100 chrome steel balls, 'Materials & Specifications' datasheet: modulus of elasticity "
             "29,500,000 psi, density 0.283 lb/in^3; Poisson's ratio 0.27-0.30 for 52100 (United Metals, "
             "'SUJ2 / 52100 bearing steel'), 0.30 taken"),
    Material("brass", 117e9, 0.34, 8530.0,
             "cartridge brass UNS C26000 (70/30): AZoM, 'Cartridge Brass UNS C26000' (azom.com article 6341): "
             "elastic modulus 117 GPa, Poisson's ratio 0.34, density 8.53 g/cm^3"),
    Material("glass", 72e9, 0.23, 2520.0,
             "soda-lime glass: Young's modulus 72 GPa and density 2.52 g/cm^3 at 20 C (container glass; "
             "Wikipedia 'Soda-lime glass', table of typical properties, after Fluegel's glass database); "
             "Poisson's ratio 0.23 (MakeItFrom, 'Annealed Soda-Lime Glass')"),
    _ptfe(),
)}


def lookup_material(name: str) -> Material:
    """The named material of :data:`MATERIALS`; an unknown name is one line with the closest known one."""
    found = MATERIALS.get(name) if isinstance(name, str) else None
    if not isinstance(name, str):
        raise ConfigError(f"material = {name!r}: must be a name, one of {', '.join(MATERIALS)}")
    if found is None:
        raise ConfigError(f"material = {name!r}: unknown{did_you_mean(name, MATERIALS)} "
                          f"(known: {', '.join(MATERIALS)})")
    return found


@declared(doc="A Newton's cradle of identical spheres on linear on-site oscillators (figure boules): a pendulum "
              "of length L (omega_0 = sqrt(g/L)) or a stiff oscillator of given omega_0.")
class Cradle:
    material: str = param(doc="Material of the spheres: a name of cradle.models.physical.MATERIALS.",
                          enum=list(MATERIALS))
    radius: float = param(doc="Sphere radius R (m); in [1e-6, 10] (a micrometre bead to a wrecking ball; the "
                                  "scales of (nc) stay finite and nonzero).", minimum=1e-6, maximum=10)
    length: float | None = param(None, doc="Pendulum length L, pivot to the sphere's centre (m); in [1e-3, 1e3]. "
                                           "Give it or omega0.", minimum=1e-3, maximum=1e3)
    omega0: float | None = param(None, doc="Angular frequency omega_0 of a stiff on-site oscillator (rad/s); in "
                                           "[1e-3, 1e9]. Give it or length.", minimum=1e-3, maximum=1e9)
    g: float = param(STANDARD_GRAVITY, doc="Acceleration of gravity g (m/s^2) of a pendulum; in [1e-3, 1e3]; "
                                           "default the standard g_n.", minimum=1e-3, maximum=1e3)

    def __post_init__(self) -> None:   # built directly: checked as the config's values are
        # a material registered in MATERIALS after this declaration is as good as a declared one
        registered = isinstance(self.material, str) and self.material in MATERIALS
        check_fields(self, "cradle", skip=("material",) if registered else ())


@declared(doc="A pendulum's release: the string lifted to an angle theta from the vertical.")
class Release:
    angle: float = param(doc="Angle theta of the string from the vertical (degrees); in [1e-3, 90): below, "
                             "1 - cos(theta) of the release speed keeps fewer than 6 digits in double precision.",
                         minimum=1e-3, exclusiveMaximum=90)

    def __post_init__(self) -> None:   # built directly: checked as the config's values are
        check_fields(self, "release")


def real_cradle(material: str, radius: float, *, length: float | None = None, omega0: float | None = None,
           g: float = STANDARD_GRAVITY) -> Cradle:
    """A validated :class:`Cradle`: ``material`` by name, ``radius`` in metres, and either the pendulum
    ``length`` (m) or the stiff oscillator's ``omega0`` (rad/s). Bad input is one ConfigError line."""
    lookup_material(material)  # an unknown name: one line with the closest known one
    given = {k: v for k, v in (("length", length), ("omega0", omega0)) if v is not None}
    if len(given) != 1:
        raise ConfigError(f"cradle: give the pendulum length or omega0, one of them (given: "
                          f"{', '.join(given) or 'neither'})")
    return _validated(Cradle, {"material": material, "radius": radius, "g": g, **given}, "cradle")


@dataclasses.dataclass(frozen=True)
class Scales:
    """The SI values of one unit of (nc)'s variables for a cradle, and what they are made of.

    ``T`` (s) = 1/omega_0, ``X`` (m) from m omega_0^2 X = k X^alpha, ``V`` = X omega_0 (m/s), ``F`` = m omega_0^2 X
    (N), ``E`` = m omega_0^2 X^2 (J); ``m`` (kg), ``k`` (N/m^alpha) = (4/3) E* sqrt(R*), ``E_star`` (Pa), ``R_star``
    (m), ``omega0`` (rad/s)."""

    m: float
    k: float
    E_star: float
    R_star: float
    omega0: float
    T: float
    X: float
    V: float
    F: float
    E: float


def reduced_modulus(E_i: float, nu_i: float, E_j: float, nu_j: float) -> float:
    """E* of two spheres: 1/E* = (1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j."""
    return 1.0 / ((1.0 - nu_i**2) / E_i + (1.0 - nu_j**2) / E_j)


def reduced_radius(R_i: float, R_j: float) -> float:
    """R* = R_i R_j / (R_i + R_j)."""
    return R_i * R_j / (R_i + R_j)


def hertz_constant(E_star: float, R_star: float) -> float:
    """k of Hertz's force F = k delta^(3/2) between two spheres: k = (4/3) E* sqrt(R*)."""
    return 4.0 / 3.0 * E_star * math.sqrt(R_star)


def sphere_mass(rho: float, radius: float) -> float:
    """m = (4/3) pi R^3 rho."""
    return 4.0 / 3.0 * math.pi * radius**3 * rho


def pendulum_omega0(length: float, g: float = STANDARD_GRAVITY) -> float:
    """Small-angle angular frequency of a pendulum: omega_0 = sqrt(g/L)."""
    return math.sqrt(g / length)


def scales(spec: Cradle) -> Scales:
    """The scales of (nc) for the cradle ``spec`` (alpha = 3/2)."""
    if (spec.length is None) == (spec.omega0 is None):   # a Cradle built directly: real_cradle says so first
        raise ConfigError(f"cradle: give the pendulum length or omega0, one of them (given: "
                          f"{'both' if spec.length is not None else 'neither'})")
    mat = MATERIALS[spec.material]
    E_star = reduced_modulus(mat.E, mat.nu, mat.E, mat.nu)
    R_star = reduced_radius(spec.radius, spec.radius)
    k = hertz_constant(E_star, R_star)
    m = sphere_mass(mat.rho, spec.radius)
    w0 = spec.omega0 if spec.omega0 is not None else pendulum_omega0(spec.length, spec.g)  # type: ignore[arg-type]
    X = (m * w0**2 / k) ** (1.0 / (HERTZ_ALPHA - 1.0))
    return Scales(m=m, k=k, E_star=E_star, R_star=R_star, omega0=w0, T=1.0 / w0, X=X, V=X * w0,
                  F=m * w0**2 * X, E=m * w0**2 * X**2)


#: the quantities :func:`to_si` and :func:`from_si` convert, with their scale's field of :class:`Scales` and SI unit
QUANTITIES = {"displacement": ("X", "m"), "time": ("T", "s"), "velocity": ("V", "m/s"), "energy": ("E", "J"),
              "force": ("F", "N")}


def _scale(quantity: str, s: Scales) -> float:
    if quantity not in QUANTITIES:
        raise ConfigError(f"quantity = {quantity!r}: unknown{did_you_mean(quantity, QUANTITIES)} "
                          f"(known: {', '.join(QUANTITIES)})")
    return getattr(s, QUANTITIES[quantity][0])


@overload
def to_si(value: float, quantity: str, s: Scales) -> float: ...
@overload
def to_si(value: NDArray[np.float64], quantity: str, s: Scales) -> NDArray[np.float64]: ...
def to_si(value: float | NDArray[np.float64], quantity: str, s: Scales) -> float | NDArray[np.float64]:
    """A value of (nc)'s ``quantity`` (displacement, time, velocity, energy, force) in SI units."""
    return value * _scale(quantity, s)


@overload
def from_si(value: float, quantity: str, s: Scales) -> float: ...
@overload
def from_si(value: NDArray[np.float64], quantity: str, s: Scales) -> NDArray[np.float64]: ...
def from_si(value: float | NDArray[np.float64], quantity: str, s: Scales) -> float | NDArray[np.float64]:
    """An SI value of ``quantity`` in (nc)'s dimensionless units."""
    return value / _scale(quantity, s)


def release_speed(spec: Cradle, angle: float) -> float:
    """Speed (m/s) at the bottom of a pendulum released at rest from ``angle`` degrees: sqrt(2 g L (1 - cos theta))
    (the whole swing, not the small-angle one)."""
    theta = _release_angle(spec, angle)
    return math.sqrt(2.0 * spec.g * spec.length * (1.0 - math.cos(theta)))  # type: ignore[operator]


def _release_angle(spec: Cradle, angle: float) -> float:
    _validated(Release, {"angle": angle}, "release")
    if spec.length is None:
        raise ConfigError("release: the cradle has no pendulum length (a stiff oscillator has no angle)")
    return math.radians(angle)


def release_amplitude(spec: Cradle, angle: float) -> float:
    """(nc) amplitude of a sphere lifted to ``angle`` degrees: its horizontal displacement L sin(theta) / X."""
    theta = _release_angle(spec, angle)
    return spec.length * math.sin(theta) / scales(spec).X  # type: ignore[operator]


@checked(v="speed")
def collision_time(spec: Cradle, v: float) -> float:
    """Hertz collision time (s) of two of the cradle's spheres meeting at relative speed ``v`` (m/s), without the
    on-site force: t_c = 2 I delta_max / v, delta_max = (5 mu v^2 / (4 k))^(2/5), mu = m/2, I =
    :data:`COLLISION_INTEGRAL` (Landau & Lifshitz, Theory of Elasticity, section 9)."""
    s = scales(spec)
    delta_max = (5.0 * (s.m / 2.0) * v**2 / (4.0 * s.k)) ** 0.4
    return 2.0 * COLLISION_INTEGRAL * delta_max / v
