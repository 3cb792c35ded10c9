"""Tests of the compiled term units (cradle.integrators.terms) and of their specialisation.

Each unit's force is minus the gradient of its energy (finite differences); with a dissipation the energy
(ham) falls at the dissipated power P (H + D constant); each DpS counterpart is the lattice force averaged over
the fast phase (first Fourier coefficient along x = eps (A e^{it} + c.c.)); and a combination without a term
computes the bits of a kernel that was never told about it.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from cradle.integrators import _kernels as K
from cradle.integrators._kernels_dps_sites import pack
from cradle.integrators.lattice_adaptive import imperfect_system
from cradle.integrators.systems import dps as SD, imperfect as SI, lattice as SL
from cradle.integrators.terms import (
    contact_damping as CD,
    hertz,
    inhomogeneity as IH,
    onsite_damping as OD,
    onsite_harmonic,
    onsite_pendulum,
    onsite_quartic,
    precompression as PC,
)
from cradle.integrators.terms.slots import (
    damp_bond,
    damp_site,
    dps_coupling,
    dps_decay,
    dps_kappa,
    dps_rotate,
    elastic,
    onsite_energy,
    onsite_force,
    overlap,
    position,
    potential,
    rest,
)
from cradle.models import dps, dps_sites as S
from cradle.models.damping import Damping
from cradle.models.dps_damped import contact_factor
from cradle.models.inhomogeneity import Inhomogeneity, Sites
from cradle.models.lattice_terms import Terms
from cradle.models.onsite import OnSite
from cradle.models.precompression import Precompression

ALPHA = 1.5
ONSITE = {"harmonic": onsite_harmonic.Harmonic(), "quartic": onsite_quartic.Quartic(-0.7),
          "pendulum": onsite_pendulum.Pendulum(np.array([0.8, 1.3]))}
CONTACTS = {"touching": hertz.Touching(), "precompressed": PC.build(np.array([0.3, 0.2]), ALPHA),
            "gap": PC.build(np.array([-0.1, -0.2]), ALPHA)}
TERMS = {
    "none": Terms(),
    "quartic": Terms(onsite=OnSite(potential="quartic", beta=0.8)),
    "pendulum": Terms(onsite=OnSite(potential="pendulum", scale=0.6)),
    "precompression": Terms(precompression=Precompression(delta0=0.05)),
    "gaps": Terms(precompression=Precompression(delta0=-0.03)),
    "inhomogeneity": Terms(inhomogeneity=Inhomogeneity(sigma=0.1, mass_sigma=0.2, seed=7)),
    "all": Terms(onsite=OnSite(potential="pendulum", scale=0.4), precompression=Precompression(delta0=0.02),
                 inhomogeneity=Inhomogeneity(sigma=0.05, mass_sigma=0.1,
                                             stiffness=tuple(1.0 + 0.1 * np.arange(8) / 8))),
}


def _sites(terms: Terms, N: int) -> Sites:
    from cradle.models.inhomogeneity import sites

    return sites(terms.inhomogeneity, N)


def _state(N: int, seed: int, amp: float = 0.3):
    rng = np.random.default_rng(seed)
    return amp * rng.standard_normal(N), amp * rng.standard_normal(N)


# ---------------------------------------------------------------- each unit: force = -grad energy


@pytest.mark.parametrize("name", list(ONSITE))
def test_onsite_force_is_the_derivative_of_its_energy(name):
    unit, h = ONSITE[name], 1e-6
    for n in range(2):
        for x in np.linspace(-1.5, 1.5, 7):
            u, J = position(unit, n, x)
            dW = (onsite_energy(unit, n, x + h) - onsite_energy(unit, n, x - h)) / (2 * h)
            du = (position(unit, n, x + h)[0] - position(unit, n, x - h)[0]) / (2 * h)
            assert onsite_force(unit, x, u) == pytest.approx(dW, rel=1e-8, abs=1e-9)
            assert J == pytest.approx(du, rel=1e-8, abs=1e-9)


@pytest.mark.parametrize("name", list(CONTACTS))
@pytest.mark.parametrize("mode, alpha", [(0, 1.5), (1, 1.8)])
def test_contact_force_is_the_derivative_of_its_potential(name, mode, alpha):
    unit = CONTACTS[name] if name == "touching" else PC.build(CONTACTS[name].delta, alpha)
    h = 1e-7
    for n in range(2):
        for d in np.linspace(-0.6, 0.4, 11):
            def phi(z, n=n):
                return potential(unit, n, z, overlap(unit, n, z), alpha + 1.0)
            c = overlap(unit, n, d)
            if c > 0.0:
                el = hertz.hertz(c, alpha, mode)[0]
                F = elastic(unit, n, d, c, el, alpha, mode)
            else:
                F = rest(unit, n)
            assert F == pytest.approx((phi(d + h) - phi(d - h)) / (2 * h), rel=1e-6, abs=1e-9)
            assert phi(0.0) == 0.0


@pytest.mark.parametrize("name", list(TERMS))
@pytest.mark.parametrize("bc", ["periodic", "free"])
def test_imperfect_rhs_is_minus_the_gradient_of_its_energy(name, bc):
    """m_n x_n'' = -dH/dx_n for the composed right-hand side (H the generalised (ham))."""
    terms = TERMS[name]
    if terms.precompression.delta0 > 0.0 and bc == "free":
        pytest.skip("a precompressed chain is a ring")
    N, h = 8, 1e-6
    s = _sites(terms, N)
    system = imperfect_system(1.5, 0, bc == "periodic", terms, s)
    x, v = _state(N, seed=1)
    y = np.concatenate((x, v))
    dy = np.empty_like(y)
    SI.imperfect_rhs(system, y, dy)
    assert np.array_equal(dy[:N], v)
    for n in range(N):
        e = np.zeros(N)
        e[n] = h
        dH = (SI.imperfect_energy(system, x + e, v)[0] - SI.imperfect_energy(system, x - e, v)[0]) / (2 * h)
        assert s.mass[n] * dy[N + n] == pytest.approx(-dH, rel=1e-6, abs=1e-8)


# ---------------------------------------------------------------- dissipation: dH/dt = -P, H + D constant


@pytest.mark.parametrize("damping", [Damping(onsite=0.3), Damping(contact=2.0), Damping(onsite=0.1, contact=1.0)])
@pytest.mark.parametrize("name", ["none", "quartic", "pendulum", "precompression", "inhomogeneity"])
def test_energy_falls_at_the_dissipated_power(damping, name):
    terms = TERMS[name]
    N, dscale, h = 8, 2.0, 1e-6
    s = _sites(terms, N)
    system = imperfect_system(1.5, 0, True, terms, s, damping, dscale)
    for seed in range(3):
        x, v = _state(N, seed=seed, amp=0.5)
        y = np.concatenate((x, v, [0.0]))
        dy = np.empty_like(y)
        SI.imperfect_rhs(system, y, dy)
        P = dy[2 * N] / dscale
        assert P >= 0.0

        def H(t, x=x, v=v, dy=dy):
            return SI.imperfect_energy(system, x + t * dy[:N], v + t * dy[N:2 * N])[0]

        assert (H(h) - H(-h)) / (2 * h) == pytest.approx(-P, rel=1e-5, abs=1e-9)


def test_a_damped_run_keeps_h_plus_d():
    from cradle.integrators import integrate_lattice

    terms = TERMS["all"]
    x, v = _state(8, seed=2, amp=0.5)
    sol = integrate_lattice(x, v, np.linspace(0.0, 5.0, 6), alpha=1.5, method="dop853_numba", rtol=1e-11,
                            terms=terms, damping=Damping(onsite=0.05, contact=0.5))
    assert sol.dissipated[-1] > 0.0 and np.all(np.diff(sol.dissipated) >= 0.0)
    assert np.max(np.abs(sol.energy + sol.dissipated - sol.energy[0])) < 1e-7 * sol.energy[0]


# ---------------------------------------------------------------- the DpS counterparts: averaged forces


def _first_harmonic(f, points=()):
    """(1/2 pi) int_0^{2 pi} f(s) e^{-i s} ds."""
    re = quad(lambda s: f(s) * np.cos(s), 0.0, 2 * np.pi, limit=400, points=points)[0]
    im = quad(lambda s: -f(s) * np.sin(s), 0.0, 2 * np.pi, limit=400, points=points)[0]
    return complex(re, im) / (2 * np.pi)


@pytest.mark.parametrize("alpha", [1.5, 2.5])
@pytest.mark.parametrize("delta", [0.0, 0.5, -0.3, 1.7, 3.0])
def test_dps_coupling_is_the_averaged_contact_force(alpha, delta):
    """g(r; delta~) = tau0 times the first harmonic of F~(d) along d = 2 r cos s (both signs of 2 r cos s)."""
    mode = 0 if alpha == 1.5 else 1
    r = 0.6
    lattice = hertz.Touching() if delta == 0.0 else PC.build(np.array([delta]), alpha)
    sites = S.DpsSites(np.zeros(2), np.ones(2), np.ones(2), np.zeros(2), np.full(2, delta))
    par = pack(sites, S.contact_tables(alpha) if delta != 0.0 else None, dps.tau0(alpha), S.PSI_MAX)
    counterpart = hertz.PLaplacian() if delta == 0.0 else PC.tabulated(par)

    def F(s):
        d = 2 * r * np.cos(s)
        c = overlap(lattice, 0, d)
        if c <= 0.0:
            return rest(lattice, 0)
        return elastic(lattice, 0, d, c, hertz.hertz(c, alpha, mode)[0], alpha, mode)

    kinks = [s for s in (np.arccos(np.clip(delta / (2 * r), -1, 1)),) if 0 < s < np.pi]
    averaged = dps.tau0(alpha) * _first_harmonic(F, points=kinks + [2 * np.pi - k for k in kinks])
    assert dps_coupling(counterpart, r, 0, alpha) * r == pytest.approx(averaged.real, rel=1e-7, abs=1e-12)


@pytest.mark.parametrize("eta", [0.2, 1.0, 3.0])
def test_dps_kappa_is_the_averaged_contact_damping(eta):
    """kappa of (dpsdamped) = the first harmonic of the damped bond force over that of the Hertz force, along
    d = 2 r cos s, c' = -d' = 2 r sin s (the fast phase)."""
    r = 0.7

    def F(unit):
        def f(s):
            d, rate = 2 * r * np.cos(s), 2 * r * np.sin(s)
            c = overlap(hertz.Touching(), 0, d)
            if c <= 0.0:
                return 0.0
            el, sa = hertz.hertz(c, ALPHA, 0)
            y = np.array([0.0, d, rate, 0.0])
            return damp_bond(unit, IH.Homogeneous(), hertz.Touching(), 0, 1, -el, el, sa, y, np.ones(2), 2, 0.0)[0]
        return f

    points = [np.pi / 2, 3 * np.pi / 2]
    kappa = _first_harmonic(F(CD.ContactDamping(eta)), points) / _first_harmonic(F(CD.NoContactDamping()), points)
    k = contact_factor(eta, ALPHA)
    assert kappa == pytest.approx(k, rel=1e-6)
    ur, ui = dps_kappa(CD.SlowContactDamping(k.real, k.imag), 1.0, 0.0)
    assert complex(ur, ui) == k


def test_dps_decay_is_the_averaged_onsite_damping():
    """x = eps (A e^{it} + c.c.): -gamma x' averaged gives A' = -(gamma~/2) A, gamma~ = gamma eps^(1-alpha)."""
    gamma, eps, A = 0.3, 0.05, 0.4 - 0.7j

    def f(s):
        v = (eps * (1j * A * np.exp(1j * s) - 1j * np.conj(A) * np.exp(-1j * s))).real
        return damp_site(OD.OnsiteDamping(gamma), IH.Homogeneous(), 0, 0.0, v, 0.0)[0]

    dA = _first_harmonic(f) / (2j * eps**ALPHA)     # 2 i eps^alpha A' = first harmonic of the force
    a, b = dps_decay(OD.SlowOnsiteDamping(0.5 * gamma * eps ** (1.0 - ALPHA)), 0.0, 0.0, A.real, A.imag)
    assert complex(a, b) == pytest.approx(dA, rel=1e-10)


@pytest.mark.parametrize("kind", ["quartic", "pendulum"])
def test_dps_rotation_is_the_averaged_onsite_force(kind):
    """The first harmonic of W'(x) - x along x = 2 eps |A| cos s: (3/2) beta~ |A|^2 A, beta~ = beta eps^(3-alpha)
    (a pendulum: beta = -s^2/6, to O(eps^2))."""
    eps, A = 0.02, 0.6 + 0.3j
    beta, unit = (0.9, onsite_quartic.Quartic(0.9)) if kind == "quartic" else (-0.8**2 / 6,
                                                                                onsite_pendulum.Pendulum(np.array([0.8])))

    def f(s):
        x = (eps * (A * np.exp(1j * s) + np.conj(A) * np.exp(-1j * s))).real
        return -(onsite_force(unit, x, position(unit, 0, x)[0]) - x)

    dA = _first_harmonic(f) / (2j * eps**ALPHA)
    a, b = dps_rotate(onsite_quartic.SlowQuartic(np.array([beta * eps ** (3.0 - ALPHA)])), IH.Homogeneous(), 0,
                      0.0, 0.0, A.real, A.imag)
    assert complex(a, b) == pytest.approx(dA, rel=1e-10 if kind == "quartic" else 1e-3)


# ---------------------------------------------------------------- specialisation: an absent term costs no bit


def _rhs_bits(system, y):
    dy = np.empty_like(y)
    (SI.imperfect_rhs if isinstance(system, SI.Imperfect) else SD.dps_rhs)(system, y, dy)
    return dy


@pytest.mark.parametrize("bc", ["periodic", "free"])
def test_no_term_is_the_paper_lattice_bitwise(bc):
    """Every slot absent: the right-hand side of (nc) itself (the kernel of _kernels.py), bit for bit."""
    N = 9
    system = imperfect_system(1.5, 0, bc == "periodic", Terms(), Sites(np.ones(N), np.ones(N), np.ones(N)))
    plain = SL.lattice(N, 1.5, 0, bc == "periodic")
    for seed in range(5):
        y = np.concatenate(_state(N, seed, amp=0.6))
        ref = np.empty_like(y)
        K.lattice_rhs(y, ref, plain.f, plain.F, 1.5, 0, bc == "periodic")
        assert _rhs_bits(system, y).tobytes() == ref.tobytes()


def _imperfect(**units):
    N = 9
    base = dict(contact=hertz.Touching(), sites=IH.Homogeneous(), onsite=onsite_harmonic.Harmonic(),
                onsite_damping=OD.NoOnsiteDamping(), contact_damping=CD.NoContactDamping(),
                dissipation=SI.Dissipation(1.0))
    base.update(units)
    return SI.Imperfect(1.5, 0, True, f=np.empty(N), U=np.empty(N), J=np.empty(N), Ue=np.empty(N), **base)


@pytest.mark.parametrize("slot, neutral", [
    ("contact", PC.build(np.zeros(9), 1.5)),
    ("sites", IH.Inhomogeneous(np.ones(9), np.ones(9), np.ones(9), np.ones(9))),
    ("onsite", onsite_quartic.Quartic(0.0)),
    ("onsite_damping", OD.OnsiteDamping(0.0)),
    ("contact_damping", CD.ContactDamping(0.0)),
])
def test_an_absent_unit_gives_the_bits_of_its_neutral_parameters(slot, neutral):
    """The absent unit does no arithmetic; the unit with parameters that change nothing (x 1, + 0) gives the same
    forces bit for bit: a combination without a term is the kernel never told about it."""
    y = np.concatenate((*_state(9, seed=3, amp=0.6), [0.0]))
    absent, told = _rhs_bits(_imperfect(), y), _rhs_bits(_imperfect(**{slot: neutral}), y)
    assert absent[:18].tobytes() == told[:18].tobytes()


def test_dps_members_without_their_terms_are_dfnls_bitwise():
    N, alpha = 10, 1.5
    inv2tau0 = 1.0 / (2.0 * dps.tau0(alpha))
    rng = np.random.default_rng(4)
    y = rng.standard_normal(2 * N)
    plain = _rhs_bits(SD.dfnls(alpha, True, inv2tau0), y)
    undamped = _rhs_bits(SD.damped(alpha, True, inv2tau0, 0.0, 1.0 + 0.0j), np.concatenate((y, [0.0, 0.0])))
    assert undamped[:2 * N].tobytes() == plain.tobytes() and np.all(undamped[2 * N:] == 0.0)
    sites = S.homogeneous(N)
    par = pack(sites, None, 0.5 / inv2tau0, S.PSI_MAX)
    homogeneous = SD.imperfect(alpha, True, sites, par)
    assert isinstance(homogeneous.sites, IH.Homogeneous) and isinstance(homogeneous.onsite, onsite_harmonic.Harmonic)
    assert _rhs_bits(homogeneous, y).tobytes() == _rhs_bits(SD.dfnls(alpha, True, par[0]), y).tobytes()
