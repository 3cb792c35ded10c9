"""trapping (cradle.analyses.trapping, cradle.measurements.trapping): energy per bead, static-breather detector,
incident waves and the bookkeeping of a run.

What is checked is fixed by the definitions: the beads' energies sum to the (generalised) Hamiltonian (ham) of
(ncimperfect) exactly; the detector finds a fixed localised profile with exactly the energy of its region, rejects
a plateau (no peak) and a profile moving faster than max_shift / W, is mirror-symmetric and finds more (never
fewer) breathers at a lower threshold; the striker puts in a^2 / 2 and the kicked breather its potential energy
plus (kick a)^2 / 2; a run's zones and dissipated energy add up to H(0) within the integrator's own balance drift.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from cradle.analyses import trapping as tr
from cradle.analyses.protocol import FULL, REDUCED, form_spec
from cradle.measurements import trapping as m
from cradle.specs.declare import from_plain

ALPHA = tr.ALPHA


def test_site_energies_sum_to_the_hamiltonian():
    """sum_n e_n = H of (ham) (homogeneous) and of (ncimperfect) (random omega_n, m_n, k_n), free ends."""
    from cradle.models import lattice
    from cradle.models.inhomogeneity import Inhomogeneity, Sites
    from cradle.models.lattice_terms import Terms, hamiltonian

    rng = np.random.default_rng(3)
    x, v = rng.normal(0, 0.3, (5, 17)), rng.normal(0, 0.3, (5, 17))
    H = lattice.hamiltonian(x, v, ALPHA, "free")
    assert np.allclose(m.site_energies(x, v, ALPHA).sum(axis=-1), H, rtol=1e-14, atol=0)
    s = Sites(mass=rng.uniform(0.8, 1.2, 17), omega=rng.uniform(0.8, 1.2, 17), stiffness=rng.uniform(0.8, 1.2, 17))
    terms = Terms(inhomogeneity=Inhomogeneity(omega=tuple(s.omega), mass=tuple(s.mass), stiffness=tuple(s.stiffness)))
    H = hamiltonian(x, v, ALPHA, terms, s, "free")
    e = m.site_energies(x, v, ALPHA, omega=s.omega, mass=s.mass, stiffness=s.stiffness)
    assert np.allclose(e.sum(axis=-1), H, rtol=1e-13, atol=0)


def _moving(N: int, t, speed: float, centre: float, energy: float = 1.0, width: float = 1.0):
    """e_n(t): a Gaussian profile of total ~energy centred at centre + speed t, on a background of 1e-6."""
    n = np.arange(N)
    prof = np.exp(-0.5 * ((n[None, :] - centre - speed * np.asarray(t)[:, None]) / width) ** 2)
    return energy * prof / prof.sum(axis=1, keepdims=True) + 1e-6


def test_detector_finds_a_fixed_peak_with_its_region_energy():
    t = np.linspace(0.0, 100.0, 201)
    e = _moving(60, t, 0.0, 30.0, energy=0.4)
    d = m.static_breathers(t, e, 100.0, 50.0, 0.01, radius=4, contrast=0.25, max_shift=1.0)
    assert d.start.tolist() == [26] and d.stop.tolist() == [35]
    assert d.total == pytest.approx(float(e[-1, 26:35].sum()), rel=1e-15)
    assert d.centre[0] == pytest.approx(30.0, abs=1e-9) and d.shift[0] == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("speed, static", [(0.005, True), (0.05, False)])
def test_detector_excludes_a_peak_moving_faster_than_max_shift_over_the_window(speed, static):
    """A profile translating at `speed` moves its centre by speed W (0.25 and 2.5 beads over W = 50); with
    max_shift = 1 the first is static, the second mobile."""
    t = np.linspace(0.0, 100.0, 401)
    e = _moving(80, t, speed, 30.0)
    d = m.static_breathers(t, e, 100.0, 50.0, 0.01, radius=4, contrast=0.25, max_shift=1.0)
    assert (d.energy.size == 1) is static


def test_detector_rejects_a_plateau_and_is_mirror_symmetric():
    t = np.linspace(0.0, 10.0, 11)
    plateau = np.full((t.size, 50), 1e-6)
    plateau[:, 10:40] = 0.03
    assert m.static_breathers(t, plateau, 10.0, 5.0, 0.01, radius=4, contrast=0.25, max_shift=1.0).energy.size == 0
    two = _moving(70, t, 0.0, 20.0, energy=0.5) + _moving(70, t, 0.0, 45.0, energy=0.2, width=1.5)
    d = m.static_breathers(t, two, 10.0, 5.0, 0.01, radius=4, contrast=0.25, max_shift=1.0)
    r = m.static_breathers(t, two[:, ::-1], 10.0, 5.0, 0.01, radius=4, contrast=0.25, max_shift=1.0)
    assert d.energy.size == 2
    assert sorted(d.energy.tolist()) == pytest.approx(sorted(r.energy.tolist()), rel=1e-14)
    assert sorted((69 - r.centre).tolist()) == pytest.approx(sorted(d.centre.tolist()), abs=1e-12)


def test_lower_threshold_finds_a_superset():
    rng = np.random.default_rng(5)
    t = np.linspace(0.0, 20.0, 41)
    e = sum(_moving(90, t, 0.0, c, energy=w) for c, w in zip((10, 30, 55, 75), rng.uniform(0.01, 0.5, 4),
                                                           strict=True))
    hi = m.static_breathers(t, e, 20.0, 10.0, 0.05, radius=4, contrast=0.25, max_shift=1.0)
    lo = m.static_breathers(t, e, 20.0, 10.0, 0.002, radius=4, contrast=0.25, max_shift=1.0)
    assert set(np.round(hi.centre, 9)) <= set(np.round(lo.centre, 9)) and lo.total >= hi.total


def _small(**over):
    """A small spec: short chains and runs (a fast test), every other key as declared."""
    base = {"launch": 5, "back": 10, "length": 12, "lengths": [], "lead": 30, "edge": 5, "tau_end": 40.0,
            "times": [30.0, 40.0], "windows": [10.0, 20.0], "striker": [1.0], "breather": [0.3], "sigmas": [0.1],
            "seeds": 1}
    return from_plain(tr.Trapping, {**base, **over})


def test_incident_energies():
    """The striker puts in a^2 / 2; the kicked breather its potential energy at rest plus (kick a)^2 / 2 (e has
    unit norm), with max |x_n(0)| = a and a velocity pushing it towards the target."""
    spec = _small()
    b = tr.bounds(spec, "striker", spec.length)
    x0, v0 = tr.incident(spec, "striker", 0.7, b[3])
    assert m.site_energies(x0, v0, ALPHA).sum() == 0.5 * 0.7**2
    b = tr.bounds(spec, "breather", spec.length)
    x0, v0 = tr.incident(spec, "breather", 0.3, b[3])
    assert np.max(np.abs(x0)) == pytest.approx(0.3, rel=1e-12)
    rest = m.site_energies(x0, 0 * v0, ALPHA).sum()
    assert m.site_energies(x0, v0, ALPHA).sum() == pytest.approx(rest + 0.5 * (spec.kick * 0.3) ** 2, rel=1e-14)
    # the breather's energy centre moves right: d/dt sum n e_n > 0 at t = 0 is sum n (v0 . grad e); check by a step
    from cradle.integrators import integrate_lattice

    sol = integrate_lattice(x0, v0, np.linspace(0.0, 60.0, 3), alpha=ALPHA, bc="free", method="dop853_numba",
                            rtol=1e-9)
    e = m.site_energies(sol.x, sol.v, ALPHA)
    centre = (e @ np.arange(b[3])) / e.sum(axis=1)
    assert centre[-1] > centre[0] + 1.0


def test_omegas_are_one_outside_the_target_and_nested_in_length():
    spec = _small()
    w = tr.omegas(spec, "breather", 12, 0.1, 4)
    b = tr.bounds(spec, "breather", 12)
    assert np.all(w[:b[1]] == 1.0) and np.all(w[b[2]:] == 1.0) and np.all(w[b[1]:b[2]] != 1.0)
    longer = tr.omegas(spec, "breather", 20, 0.1, 4)
    assert np.array_equal(longer[b[1]:b[2]], w[b[1]:b[2]])
    assert np.array_equal(tr.omegas(spec, "breather", 12, 0.1, 4), w)   # same seed, same bits


@pytest.mark.parametrize("damping", [None, (0.01, 0.0), (0.0, 0.3)])
def test_zones_and_dissipated_energy_add_up_to_the_energy_put_in(damping):
    """sum of the zones' energies + D = H(0) at each measurement time, within the run's own balance drift
    (disordered target: the (ncimperfect) path with the run's omega_n)."""
    from cradle.models.damping import Damping

    spec = _small()
    d = None if damping is None else Damping(onsite=damping[0], contact=damping[1])
    r = tr.run_one(spec, "striker", 1.0, spec.length, 0.1, 0, d)
    total = r["zone_energy"].sum(axis=1) + r["dissipated"]
    assert np.all(np.abs(total - 1.0) <= r["balance_drift"] + 1e-12)
    assert r["reach"] == 0.0          # the lead is long enough here: nothing reached its last beads
    if d is not None:
        assert np.all(r["dissipated"] > 0)


def test_forms_and_checks():
    """Both forms validate; a measurement time beyond the run, or a scan amplitude not in its list, is one line."""
    from cradle.specs.values import Errors

    spec = from_plain(tr.Trapping, {})
    for form in (REDUCED, FULL):
        out = Errors()
        form_spec(spec, form).check(["beyond", "trapping"], None, out)
        assert not out.lines
    bad = dataclasses.replace(spec, times=[700.0], scan_breather=0.5)
    out = Errors()
    bad.check(["beyond", "trapping"], None, out)
    lines = out.lines
    assert len(lines) == 2 and any("times" in s and "tau_end" in s for s in lines)
    assert any("scan_breather" in s for s in lines)


def test_summary_groups_the_seeds_of_each_case():
    """/summary: one case per (incident, amplitude, length, sigma, gamma, eta), mean / std (ddof 1) / range over
    its seeds, and the share of seeds above one half."""
    f = np.array([0.9, 0.0, 0.3, 0.2])[:, None, None, None] * np.ones((4, 1, 2, 1))
    runs = {"incident": np.array([1, 1, 1, 0]), "amplitude": np.array([0.3, 0.3, 0.3, 1.0]),
            "length": np.array([50, 50, 50, 50]), "sigma": np.array([0.1, 0.1, 0.0, 0.1]),
            "gamma": np.zeros(4), "eta": np.zeros(4), "fraction": f, "fraction_target": f,
            "zone_energy": np.zeros((4, 1, 3))}
    s = tr.summary(runs)
    assert s["n_seeds"].tolist() == [2, 1, 1]
    assert s["target_mean"][0, 0, 0, 0] == pytest.approx(0.45, rel=1e-15)
    assert s["target_std"][0, 0, 0, 0] == pytest.approx(np.std([0.9, 0.0], ddof=1), rel=1e-15)
    assert s["target_trapping"][0, 0, 0, 0] == 0.5 and s["target_std"][1].max() == 0.0
    assert s["fraction_min"][0, 0, 1, 0] == 0.0 and s["fraction_max"][0, 0, 1, 0] == 0.9
