"""Spatial inhomogeneity of a cradle: per-bead masses and on-site frequencies, per-contact stiffnesses.

In the units of (nc) (time 1/omega_0 of the reference bead, lengths X of :mod:`.physical`), the imperfect
cradle (ncimperfect) of :mod:`.lattice_terms` is

    m_n ( x_n'' + omega_n^2 W'(x_n) ) = k_n F_n(x_{n+1} - x_n) - k_{n-1} F_{n-1}(x_n - x_{n-1})

with three sets of site coefficients, each relative to the reference bead or pair (all 1: the paper's (nc)):

* ``mass`` m_n: bead masses (a sphere's m = (4/3) pi R^3 rho over the reference one);
* ``omega`` omega_n: on-site angular frequencies. A pendulum of string length l_n has omega_n^2 = l_0 / l_n,
  so a string longer by dl detunes it by d omega / omega = -dl / (2 l). A mass alone does not detune a bead
  (omega_n = sqrt(g / l_n) whatever m_n): it reweights the contact forces, which accelerate it as 1/m_n;
* ``stiffness`` k_n: Hertz constant of bond n (beads n, n+1) over the reference pair's,
  :func:`contact_stiffness` of the two radii and materials (Johnson, Contact Mechanics, 1985, section 4.2).

The disorder strength ``sigma`` is the standard deviation of omega_n - 1; the masses get ``mass_sigma``, the
relative standard deviation of m_n. Both are drawn from ``np.random.default_rng(seed)`` (first N draws for
omega, the next N for the masses, whatever the sigmas: changing one does not move the other's draws), from
a normal law or a uniform one of the same standard deviation. Explicit tuples override the draws.
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from cradle.models.physical import MATERIALS
from cradle.specs.declare import check_fields, declared, param
from cradle.specs.values import ConfigError

DISTRIBUTIONS = ("normal", "uniform")

#: the longest explicit list of site coefficients: the largest N (cradle.specs.declare.SHARED)
_MAX_SITES = 10_000_000
_POSITIVE = {"type": "number", "exclusiveMinimum": 0, "maximum": 1e6}


@declared("inhomogeneity", doc="Per-bead masses and on-site frequencies and per-contact stiffnesses of an "
                               "imperfect cradle (ncimperfect), relative to the reference bead and pair: drawn "
                               "with a recorded seed (sigma, mass_sigma) or given explicitly.")
class Inhomogeneity:
    sigma: float = param(0.0, "Disorder strength: standard deviation of omega_n - 1 (on-site frequencies); "
                         "in [0, 1].", minimum=0, maximum=1)
    distribution: str = param("normal", "Law of the draws: normal, or uniform with the same standard "
                              "deviation.", enum=list(DISTRIBUTIONS))
    mass_sigma: float = param(0.0, "Relative standard deviation of the bead masses m_n; in [0, 1].", minimum=0,
                              maximum=1)
    seed: int = param(0, "Seed of np.random.default_rng for the draws; in [0, 2^32).", minimum=0,
                      maximum=2**32 - 1)
    omega: tuple[float, ...] | None = param(None, "Explicit on-site frequencies omega_n (one per bead, > 0), "
                                            "overriding sigma.", items=_POSITIVE, minItems=1, maxItems=_MAX_SITES)
    mass: tuple[float, ...] | None = param(None, "Explicit bead masses m_n (one per bead, > 0), overriding "
                                           "mass_sigma.", items=_POSITIVE, minItems=1, maxItems=_MAX_SITES)
    stiffness: tuple[float, ...] | None = param(None, "Explicit contact stiffnesses k_n of bond n (beads n, n+1; "
                                                "one per bead, > 0; the last one closes the ring).",
                                                items=_POSITIVE, minItems=1, maxItems=_MAX_SITES)
    length: tuple[float, ...] | None = param(None, "String lengths l_n over the reference l_0 (in m with `units: si`; "
                                             "one per bead, > 0): omega_n = (l_0 / l_n)^(1/2), in place of omega "
                                             "and sigma.", items=_POSITIVE, minItems=1, maxItems=_MAX_SITES)
    radius: tuple[float, ...] | None = param(None, "Sphere radii R_n over the reference R_0 (in m with `units: si`; "
                                             "one per bead, > 0): the masses (R_n/R_0)^3 rho_n/rho_0 unless `mass` "
                                             "is given, and the stiffnesses of Hertz's law from the radii and "
                                             "materials unless `stiffness` is given.", items=_POSITIVE, minItems=1,
                                             maxItems=_MAX_SITES)
    material: tuple[str, ...] | None = param(None, "Sphere materials (names of cradle.models.physical.MATERIALS, one "
                                             "per bead), relative to the first bead's: their densities weigh the "
                                             "masses and their moduli the stiffnesses as `radius` does (radii 1 if "
                                             "not given).", items={"type": "string", "enum": list(MATERIALS)},
                                             minItems=1, maxItems=_MAX_SITES)

    def __post_init__(self) -> None:   # built directly: checked as the config's values are
        check_fields(self, "inhomogeneity")

    @property
    def active(self) -> bool:
        """Whether any site differs from the homogeneous chain (False: every coefficient is 1)."""
        return (self.sigma > 0.0 or self.mass_sigma > 0.0
                or any(v is not None and any(e != 1.0 for e in v)
                       for v in (self.omega, self.mass, self.stiffness, self.length, self.radius))
                or (self.material is not None and len(set(self.material)) > 1))


class Sites(NamedTuple):
    """The site coefficients of (ncimperfect), arrays of shape (N,): bead masses m_n, on-site frequencies
    omega_n, stiffness k_n of bond n (beads n, n+1; entry N-1 closes the ring and is unused with free ends)."""

    mass: np.ndarray
    omega: np.ndarray
    stiffness: np.ndarray


def _draw(rng: np.random.Generator, law: str, N: int) -> np.ndarray:
    """N draws of zero mean and unit standard deviation."""
    if law == "uniform":
        return rng.uniform(-math.sqrt(3.0), math.sqrt(3.0), N)
    return rng.standard_normal(N)


def _given(spec: Inhomogeneity, key: str, N: int) -> np.ndarray | None:
    value = getattr(spec, key)
    if value is None:
        return None
    arr = np.array(value, dtype=float)
    if arr.shape != (N,):
        raise ConfigError(f"inhomogeneity.{key} = {len(value)} values: must give one per bead, N = {N}")
    bad = np.flatnonzero(~(np.isfinite(arr) & (arr > 0.0)))
    if bad.size:
        raise ConfigError(f"inhomogeneity.{key}[{bad[0]}] = {arr[bad[0]]!r}: must be finite and > 0")
    return arr


def sites(spec: Inhomogeneity, N: int) -> Sites:
    """The site coefficients of ``spec`` for N beads, the same bits for the same spec (seeded draws).

    omega_n = 1 + sigma z_n, m_n = 1 + mass_sigma z'_n with z, z' of zero mean and unit variance
    (``distribution``); a draw giving omega_n <= 0 or m_n <= 0 raises a one-line ConfigError naming the key."""
    rng = np.random.default_rng(spec.seed)
    z_omega = _draw(rng, spec.distribution, N)
    z_mass = _draw(rng, spec.distribution, N)
    drawn = {"omega": 1.0 + spec.sigma * z_omega, "mass": 1.0 + spec.mass_sigma * z_mass}
    spheres = _spheres(spec, N)
    out = {}
    for key, width in (("omega", "sigma"), ("mass", "mass_sigma")):
        given = _given(spec, key, N)
        lengths = _given(spec, "length", N) if key == "omega" else None
        if given is None and lengths is not None:
            given = lengths**-0.5
        elif given is None and key == "mass" and spheres is not None:
            given = spheres[0]
        if given is not None:
            out[key] = given
            continue
        arr = drawn[key]
        if np.any(arr <= 0.0):
            i = int(np.argmin(arr))
            raise ConfigError(f"inhomogeneity.{width} = {getattr(spec, width)!r}: the draw of seed {spec.seed} "
                              f"gives {key}[{i}] = {arr[i]:.6g} <= 0 ({spec.distribution} law, N = {N})")
        out[key] = arr
    k = _given(spec, "stiffness", N)
    if k is None and spheres is not None:
        k = spheres[1]
    return Sites(mass=out["mass"], omega=out["omega"], stiffness=np.ones(N) if k is None else k)


def _spheres(spec: Inhomogeneity, N: int) -> tuple[np.ndarray, np.ndarray] | None:
    """(masses, stiffnesses) of spheres of the given radii and materials relative to the first bead: m_n =
    (R_n/R_0)^3 rho_n/rho_0, k_n of :func:`material_stiffness` (bond N-1 closes the ring); None if neither is given."""
    if spec.radius is None and spec.material is None:
        return None
    from cradle.models.physical import lookup_material

    given = _given(spec, "radius", N)
    R = np.ones(N) if given is None else given
    names = spec.material if spec.material is not None else ("steel",) * N
    if len(names) != N:
        raise ConfigError(f"inhomogeneity.material = {len(names)} names: must give one per bead, N = {N}")
    rho = np.array([lookup_material(m).rho for m in names])
    return (R / R[0]) ** 3 * rho / rho[0], material_stiffness(R, names)


def homogeneous(N: int) -> Sites:
    """The sites of the paper's (nc): every coefficient 1."""
    return Sites(mass=np.ones(N), omega=np.ones(N), stiffness=np.ones(N))


def contact_stiffness(R1, R2, E1, nu1, E2, nu2):
    """Hertz constant k = (4/3) E* sqrt(R*) of two spheres (radii R1, R2; Young's moduli E1, E2; Poisson's
    ratios nu1, nu2): 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2, R* = R1 R2 / (R1 + R2) (Johnson, Contact
    Mechanics, 1985, section 4.2; the materials' E and nu with their sources in
    :data:`cradle.models.physical.MATERIALS`). SI in, SI out (N/m^(3/2)); k_n of (ncimperfect) is its ratio to
    the reference pair's. Arrays broadcast."""
    R1, R2 = np.asarray(R1, dtype=float), np.asarray(R2, dtype=float)
    E1, E2 = np.asarray(E1, dtype=float), np.asarray(E2, dtype=float)
    nu1, nu2 = np.asarray(nu1, dtype=float), np.asarray(nu2, dtype=float)
    E_star = 1.0 / ((1.0 - nu1**2) / E1 + (1.0 - nu2**2) / E2)
    return 4.0 / 3.0 * E_star * np.sqrt(R1 * R2 / (R1 + R2))


def material_stiffness(radii, materials, *, periodic: bool = True) -> np.ndarray:
    """Relative contact stiffnesses k_n of a chain of spheres of radii ``radii`` (m) and named ``materials``
    (:data:`cradle.models.physical.MATERIALS`): k_n = k(bead n, bead n+1) / k(bead 0, bead 0's twin), the last
    bond closing the ring (with ``periodic=False`` it is set to 1: unused)."""
    from cradle.models.physical import lookup_material

    R = np.asarray(radii, dtype=float)
    mats = [lookup_material(m) for m in materials]
    E = np.array([m.E for m in mats])
    nu = np.array([m.nu for m in mats])
    k = contact_stiffness(R, np.roll(R, -1), E, nu, np.roll(E, -1), np.roll(nu, -1))
    k_ref = contact_stiffness(R[0], R[0], E[0], nu[0], E[0], nu[0])
    out = np.asarray(k / k_ref, dtype=float)
    if not periodic:
        out[-1] = 1.0
    return out
