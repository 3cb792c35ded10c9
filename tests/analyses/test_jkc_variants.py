"""The measures of the jkc-variants analysis: the reversal detector and the energy centre on synthetic data of
known answer, the local energy against the generalised (ham) of (ncimperfect), the core and tails, and the
conservation of the local energies' sum along a short kicked run."""
from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pytest

from cradle.analyses.jkc_variants import (
    core_and_tails,
    dominant_frequency,
    energy_centre,
    local_energy,
    reversals,
    running_mean,
    touches_end,
)
from cradle.models.inhomogeneity import Inhomogeneity, sites
from cradle.models.lattice_terms import Terms, hamiltonian
from cradle.models.onsite import OnSite
from cradle.models.precompression import Precompression


def _triangle(t, turns, x0=0.0, speed=0.1):
    """A path going up at ``speed`` and reversing at each time of ``turns``."""
    x, out, sign, last = x0, np.empty_like(t), 1.0, t[0]
    k = 0
    for i, ti in enumerate(t):
        x += sign * speed * (ti - last)
        last = ti
        out[i] = x
        if k < len(turns) and ti >= turns[k]:
            sign, k = -sign, k + 1
    return out


def test_reversals_of_a_zigzag_are_its_turning_points():
    t = np.arange(0.0, 1000.0, 1.0)
    turns = [300.0, 550.0, 800.0]
    y = _triangle(t, turns)
    idx = reversals(y, threshold=2.0)
    assert t[idx].tolist() == turns
    # wiggles below the threshold on top of it (a breather's oscillation of its energy centre) change nothing
    wiggle = 0.4 * np.sin(2.0 * t)
    assert t[reversals(y + wiggle, threshold=2.0)].tolist() == pytest.approx(turns, abs=2.0)
    assert reversals(wiggle, threshold=2.0).size == 0
    # a retreat shorter than the threshold is no reversal
    assert reversals(_triangle(t, [300.0, 310.0]), threshold=2.0).size == 0


def test_running_mean_keeps_a_line_and_removes_a_fast_oscillation():
    t = np.arange(0.0, 200.0, 0.5)
    line = 3.0 + 0.1 * t
    assert np.allclose(running_mean(t, line, 20.0)[25:-25], line[25:-25], atol=1e-12)
    osc = np.sin(2.0 * np.pi * t / 2.0)   # period 2 = 4 samples: 41 samples in the window, 10 periods and one
    assert np.max(np.abs(running_mean(t, osc, 20.0)[25:-25])) <= 1.0 / 41.0 + 1e-12   # sample left over


def test_energy_centre_of_a_bead_and_of_a_symmetric_profile():
    e = np.zeros((2, 11))
    e[0, 7] = 2.5
    e[1] = np.exp(-0.5 * (np.arange(11) - 4.0) ** 2)
    assert energy_centre(e).tolist() == pytest.approx([7.0, 4.0], abs=1e-3)


def test_core_and_tails_split_the_energy():
    e = np.full((1, 30), 0.01)
    e[0, 18:21] = 1.0
    e[0, 19] = 2.0
    k, core, left, right = core_and_tails(e, 1)   # the 3-bead window 18..20
    total = e.sum()
    assert k[0] == 19.0
    assert core[0] == pytest.approx(4.0 / total, rel=1e-12)
    assert left[0] == pytest.approx(0.01 * 18 / total, rel=1e-12)
    assert right[0] == pytest.approx(0.01 * 9 / total, rel=1e-12)
    assert core[0] + left[0] + right[0] == pytest.approx(1.0, abs=1e-14)


def test_a_bounce_is_where_the_extent_reaches_a_free_end():
    t = np.arange(0.0, 100.0, 1.0)
    y = _triangle(t, [50.0], x0=10.0)                # up to 15 at t = 50, then down
    low, high = np.zeros_like(t), y + 3.0            # energy from the kicked end to 3 beads beyond the centre
    j = int(reversals(y, 2.0)[0])
    assert not touches_end(t, low, high, y, j, N=60, edge_sites=5, window=10.0)
    assert touches_end(t, low, high + 40.0, y, j, N=60, edge_sites=5, window=10.0)


def test_dominant_frequency_of_a_sine():
    t = np.arange(0.0, 400.0, 0.5)
    # the padded grid's spacing 2 pi / (16 x 400): the peak of a pure sine falls on the nearest grid point
    assert dominant_frequency(t, np.sin(0.97 * t)) == pytest.approx(0.97, abs=np.pi / (16 * 400.0))


@pytest.mark.parametrize("bc", ["free", "periodic"])
def test_local_energies_sum_to_the_hamiltonian(bc):
    """sum_n e_n = H of (ncimperfect), for disorder, a quartic W and (on the ring) a precompression."""
    rng = np.random.default_rng(7)
    N = 9
    terms = Terms(inhomogeneity=Inhomogeneity(sigma=0.05, mass_sigma=0.1, seed=3),
                  precompression=Precompression(delta0=0.02 if bc == "periodic" else 0.0),
                  onsite=OnSite(potential="quartic", beta=-0.7))
    s = sites(terms.inhomogeneity, N)
    x, v = 0.1 * rng.standard_normal((4, N)), 0.1 * rng.standard_normal((4, N))
    e = local_energy(x, v, 1.5, terms, s, bc)
    assert np.allclose(e.sum(-1), hamiltonian(x, v, 1.5, terms, s, bc), rtol=1e-13, atol=0.0)


def test_the_sum_of_the_local_energies_is_conserved_along_a_kicked_run():
    """A soft-quartic free chain kicked at its first bead: sum_n e_n(t) = H(0) = v^2/2 within the run's drift."""
    from cradle.integrators import integrate_lattice

    N, v = 12, 0.5
    terms = Terms(onsite=OnSite(potential="quartic", beta=-1.0))
    s = sites(terms.inhomogeneity, N)
    x0, v0 = np.zeros(N), np.zeros(N)
    v0[0] = v
    t = np.linspace(0.0, 40.0, 81)
    sol = integrate_lattice(x0, v0, t, alpha=1.5, bc="free", method="dop853_numba", rtol=1e-12, terms=terms)
    E = local_energy(sol.x, sol.v, 1.5, terms, s, "free").sum(-1)
    assert E[0] == pytest.approx(0.5 * v**2, rel=1e-15)
    assert np.max(np.abs(E / E[0] - 1.0)) < 1e-7


def test_a_scene_that_cannot_play_its_role_is_refused_in_one_line():
    from cradle.pipeline import config as cc
    from cradle.specs.values import ConfigError

    raw = cc.read_yaml(Path(__file__).resolve().parents[2] / "config.yaml")
    bad = copy.deepcopy(raw)
    bad["scenes"]["boomeron"]["terms"]["onsite"]["beta"] = -1.0
    with pytest.raises(ConfigError) as err:
        cc.validate(bad)
    lines = [ln for ln in str(err.value).splitlines() if "jkc-variants" in ln]
    assert len(lines) == 1 and "beyond.jkc-variants.boomeron" in lines[0] and "hard quartic" in lines[0]
