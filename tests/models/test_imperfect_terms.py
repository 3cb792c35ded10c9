"""Tests of the imperfect cradle's terms (ncimperfect): cradle.models.inhomogeneity, precompression, onsite,
lattice_terms, and the compiled right-hand side composed of the term units (cradle.integrators.systems.imperfect).

* the site coefficients: the same bits from the same seed, the draws' laws (zero mean, std sigma: the uniform law
  with the same std), explicit values overriding the draws;
* Hertz's contact stiffness (4/3) E* sqrt(R*) of two identical spheres against cradle.models.physical;
* the generalised (ham): its gradient is the force of (ncimperfect) (m a = -dH/dx, central differences), and
  along the flow of the damped form dH/dt = -P (the dissipated power), for every on-site potential;
* the compiled right-hand side and energy against these numpy formulas;
* the linear coupling kappa = alpha delta0^(alpha-1): the slope of the bond force at rest;
* bad input: one line naming the key and the value.
"""
from __future__ import annotations

import numpy as np
import pytest

from cradle.integrators.lattice_adaptive import imperfect_system
from cradle.integrators.systems import imperfect as SI
from cradle.models import lattice_terms as T, physical
from cradle.models.damping import Damping
from cradle.models.inhomogeneity import Inhomogeneity, contact_stiffness, homogeneous, material_stiffness, sites
from cradle.models.lattice_terms import Terms
from cradle.models.onsite import OnSite
from cradle.models.precompression import Precompression, coupling, dispersion
from cradle.specs.values import ConfigError

ALPHA = 1.5

#: every on-site potential with disorder, masses, stiffnesses and precompression (or gaps) on top
CASES = {
    "quartic": Terms(inhomogeneity=Inhomogeneity(sigma=0.1, mass_sigma=0.2, seed=5,
                                                 stiffness=tuple(np.linspace(0.8, 1.2, 10))),
                     precompression=Precompression(delta0=0.3), onsite=OnSite(potential="quartic", beta=-0.4)),
    "pendulum": Terms(inhomogeneity=Inhomogeneity(sigma=0.05, mass_sigma=0.1, seed=2, distribution="uniform"),
                      precompression=Precompression(delta0=-0.05), onsite=OnSite(potential="pendulum", scale=0.6)),
    "harmonic": Terms(inhomogeneity=Inhomogeneity(mass=tuple(np.linspace(0.5, 2.0, 10))),
                      precompression=Precompression(delta0=0.1)),
}


def _state(N=10, seed=1, amp=0.4):
    rng = np.random.default_rng(seed)
    return amp * rng.standard_normal(N), amp * rng.standard_normal(N)


def test_sites_are_the_seeded_draws_and_explicit_values_override_them():
    spec = Inhomogeneity(sigma=0.1, mass_sigma=0.2, seed=7)
    a, b = sites(spec, 50), sites(spec, 50)
    assert all(np.array_equal(x, y) for x, y in zip(a, b, strict=True))
    rng = np.random.default_rng(7)
    z = rng.standard_normal(50)
    assert np.array_equal(a.omega, 1.0 + 0.1 * z)
    assert np.array_equal(a.mass, 1.0 + 0.2 * rng.standard_normal(50))
    # a change of mass_sigma does not move the frequencies' draws
    assert np.array_equal(sites(Inhomogeneity(sigma=0.1, seed=7), 50).omega, a.omega)
    given = sites(Inhomogeneity(sigma=0.1, seed=7, omega=(1.0, 2.0, 3.0)), 3)
    assert np.array_equal(given.omega, [1.0, 2.0, 3.0])
    assert np.array_equal(given.stiffness, np.ones(3))


@pytest.mark.parametrize("law", ["normal", "uniform"])
def test_the_disorder_strength_is_the_std_of_omega_minus_one(law):
    """sigma = std(omega_n - 1): over 2e5 draws the sample std is within 5 standard errors of sigma (the
    uniform law on [-sqrt(3) sigma, sqrt(3) sigma] has std sigma), the mean within 5 standard errors of 0."""
    n, sigma = 200_000, 0.05
    w = sites(Inhomogeneity(sigma=sigma, distribution=law, seed=11), n).omega - 1.0
    kurt = 3.0 if law == "normal" else 1.8   # E z^4 of the two laws
    assert abs(np.std(w) - sigma) < 5.0 * sigma * np.sqrt((kurt - 1.0) / (4.0 * n))
    assert abs(np.mean(w)) < 5.0 * sigma / np.sqrt(n)
    if law == "uniform":
        assert np.max(np.abs(w)) <= np.sqrt(3.0) * sigma


def test_contact_stiffness_of_identical_spheres_is_physicals_hertz_constant():
    steel = physical.MATERIALS["steel"]
    R = 0.01
    k = contact_stiffness(R, R, steel.E, steel.nu, steel.E, steel.nu)
    E_star = steel.E / (2.0 * (1.0 - steel.nu**2))
    assert k == pytest.approx(physical.hertz_constant(E_star, R / 2.0), rel=1e-14)
    glass = physical.MATERIALS["glass"]
    k12 = contact_stiffness(R, 2 * R, steel.E, steel.nu, glass.E, glass.nu)
    assert k12 == pytest.approx(contact_stiffness(2 * R, R, glass.E, glass.nu, steel.E, steel.nu), rel=1e-15)
    rel = material_stiffness([R, R, 2 * R], ["steel", "steel", "glass"])
    assert rel[0] == 1.0 and rel[1] == pytest.approx(k12 / k, rel=1e-14)


def test_coupling_is_the_slope_of_the_precompressed_bond_force_at_rest():
    """kappa = alpha delta0^(alpha-1): F(d) = -(delta0 - d)^alpha + delta0^alpha, F'(0) by central differences;
    omega(q)^2 = 1 + 4 kappa sin^2(q/2) is 1 at q = 0 and 1 + 4 kappa at q = pi."""
    for d0, alpha in ((0.3, 1.5), (0.01, 1.5), (2.0, 2.5)):
        s = homogeneous(2)
        terms = Terms(precompression=Precompression(delta0=d0))
        h = 1e-6 * d0
        x = np.array([[0.0, h], [0.0, -h]])
        g = T.bond_forces(x, alpha, terms, s, "periodic")[:, 0]
        assert (g[0] - g[1]) / (2 * h) == pytest.approx(coupling(d0, alpha), rel=1e-8)
        assert dispersion(0.0, d0, alpha) == 1.0
        assert dispersion(np.pi, d0, alpha) ** 2 == pytest.approx(1.0 + 4.0 * coupling(d0, alpha), rel=1e-14)


@pytest.mark.parametrize("name", list(CASES))
@pytest.mark.parametrize("bc", ["periodic", "free"])
def test_the_force_is_minus_the_gradient_of_the_generalised_energy(name, bc):
    """m_n a_n = -dH/dx_n (central differences of the generalised (ham), h = 1e-6: error ~ h^2 H''' + eps H / h)."""
    terms = CASES[name]
    if bc == "free" and terms.precompression.delta0 > 0:
        terms = Terms(inhomogeneity=terms.inhomogeneity, onsite=terms.onsite)
    N = 10
    s = T.check(terms, N, bc)
    x, v = _state(N)
    a = T.acceleration(x, ALPHA, terms, s, bc)
    h = 1e-6
    grad = np.empty(N)
    for n in range(N):
        e = np.zeros(N)
        e[n] = h
        H_plus, H_minus = (T.hamiltonian(x + sign * e, v, ALPHA, terms, s, bc) for sign in (1.0, -1.0))
        grad[n] = (H_plus - H_minus) / (2 * h)
    assert np.max(np.abs(s.mass * a + grad)) < 1e-8 * max(1.0, np.max(np.abs(grad)))


@pytest.mark.parametrize("name", list(CASES))
def test_damped_energy_decreases_at_the_dissipated_power(name):
    """Along (x, v)' = (v, a) of the damped form, dH/dt = -P (H differentiated by central differences in time)."""
    terms = CASES[name]
    N = 10
    s = T.check(terms, N, "periodic")
    x, v = _state(N, seed=4)
    damping = Damping(onsite=0.3, contact=0.7)
    a = T.acceleration(x, ALPHA, terms, s, "periodic", v=v, damping=damping)
    h = 1e-6
    dH = (T.hamiltonian(x + h * v, v + h * a, ALPHA, terms, s) - T.hamiltonian(x - h * v, v - h * a, ALPHA, terms, s))
    P = T.dissipated_power(x, v, ALPHA, terms, s, damping)
    assert P > 0.0
    assert dH / (2 * h) == pytest.approx(-P, rel=1e-6, abs=1e-8)


@pytest.mark.parametrize("name", list(CASES))
@pytest.mark.parametrize("alpha", [1.5, 1.8])
@pytest.mark.parametrize("damped", [False, True])
def test_compiled_rhs_and_energy_match_the_numpy_formulas(name, alpha, damped):
    terms = CASES[name]
    N = 10
    s = T.check(terms, N, "periodic")
    damping = Damping(onsite=0.2, contact=3.0) if damped else None
    mode = 0 if alpha == 1.5 else 1
    system = imperfect_system(alpha, mode, True, terms, s, damping, dscale=2.0)
    for seed in range(4):
        x, v = _state(N, seed=seed)
        y = np.concatenate((x, v, [0.0]) if damped else (x, v))
        dy = np.empty_like(y)
        SI.imperfect_rhs(system, y, dy)
        a = T.acceleration(x, alpha, terms, s, "periodic", v=v, damping=damping)
        assert np.max(np.abs(dy[N:2 * N] - a)) < 1e-13 * max(1.0, np.max(np.abs(a)))
        assert np.array_equal(dy[:N], v)
        if damped:
            P = T.dissipated_power(x, v, alpha, terms, s, damping)
            assert dy[2 * N] == pytest.approx(2.0 * P, rel=1e-12, abs=1e-15)
        H, _ = SI.imperfect_energy(system, x, v)
        assert H == pytest.approx(T.hamiltonian(x, v, alpha, terms, s), rel=1e-13)


def test_the_onsite_force_is_the_derivative_of_the_potential():
    x = np.linspace(-3.0, 3.0, 13)
    h = 1e-6
    for spec in (OnSite(potential="quartic", beta=0.7), OnSite(potential="pendulum", scale=0.9), OnSite()):
        assert np.allclose(spec.dW(x), (spec.W(x + h) - spec.W(x - h)) / (2 * h), rtol=1e-8, atol=1e-9)
    assert not OnSite(potential="quartic").active and not OnSite(potential="pendulum").active
    assert not Terms().active and not Terms(inhomogeneity=Inhomogeneity(mass=(1.0, 1.0))).active


@pytest.mark.parametrize(("terms", "N", "bc", "words"), [
    (lambda: Terms(inhomogeneity=Inhomogeneity(mass=(1.0, -1.0, 1.0))), 3, "periodic", ["mass", "-1.0"]),
    (lambda: Terms(inhomogeneity=Inhomogeneity(sigma=0.6, seed=0)), 200, "periodic", ["sigma", "0.6", "omega"]),
    (lambda: Terms(inhomogeneity=Inhomogeneity(mass_sigma=0.9, seed=1)), 200, "periodic", ["mass_sigma", "0.9"]),
    (lambda: Terms(precompression=Precompression(delta0=0.1)), 8, "free", ["delta0", "0.1", "free"]),
    (lambda: Terms(inhomogeneity=Inhomogeneity(omega=(1.0, 1.1))), 3, "periodic", ["omega", "N = 3"]),
    (lambda: Terms(onsite=OnSite(potential="pendulum", scale=-1.0)), 3, "periodic", ["scale", "-1.0"]),
])
def test_bad_input_is_one_line_naming_key_and_value(terms, N, bc, words):
    """Refused where it is built (a value its declaration refuses) or where it meets the chain (N, bc)."""
    with pytest.raises(ConfigError) as err:
        T.check(terms(), N, bc)
    msg = str(err.value)
    assert "\n" not in msg, msg
    for w in words:
        assert w in msg, msg


def test_spheres_and_strings_give_their_sites():
    """String lengths l_n detune as omega_n = (l_0/l_n)^(1/2); radii and materials weigh the masses as
    R^3 rho and stiffen the bonds as Hertz's (4/3) E* R*^(1/2), relative to the first bead (and its twin);
    in an SI scene the lengths and radii are read in metres against the cradle's own."""
    from cradle.models.inhomogeneity import Inhomogeneity, contact_stiffness, sites
    from cradle.models.physical import MATERIALS
    from cradle.scenes.spec import Scene, in_nc_units
    from cradle.specs.declare import from_plain

    R, names = (1.0, 1.1, 0.9, 1.0), ("steel", "steel", "brass", "glass")
    s = sites(Inhomogeneity(length=(1.0, 1.21, 0.64, 4.0), radius=R, material=names), 4)
    np.testing.assert_allclose(s.omega, [1.0, 1 / 1.1, 1 / 0.8, 0.5], rtol=1e-15)
    rho = np.array([MATERIALS[m].rho for m in names])
    np.testing.assert_allclose(s.mass, np.array(R) ** 3 * rho / rho[0], rtol=1e-15)
    E, nu = (np.array([getattr(MATERIALS[m], a) for m in names]) for a in ("E", "nu"))
    k_ref = 4 / 3 * E[0] / (2 * (1 - nu[0] ** 2)) * np.sqrt(R[0] / 2)
    for n in range(4):
        m = (n + 1) % 4
        assert s.stiffness[n] == pytest.approx(contact_stiffness(R[n], R[m], E[n], nu[n], E[m], nu[m]) / k_ref,
                                               rel=1e-14)
    entry = {"N": 2, "bc": "free", "initial": {"kind": "kick", "velocity": 1e-3, "site": 0}, "t_end": 1.0,
             "store": {"every": 0.5}, "units": "si", "cradle": {"material": "steel", "radius": 0.01, "length": 0.1},
             "terms": {"inhomogeneity": {"length": [0.1, 0.121], "radius": [0.01, 0.011]}}}
    inh = in_nc_units(from_plain(Scene, entry)).terms.inhomogeneity
    np.testing.assert_allclose(inh.length, [1.0, 1.21], rtol=1e-15)
    np.testing.assert_allclose(inh.radius, [1.0, 1.1], rtol=1e-15)
