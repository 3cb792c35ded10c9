"""A damped scene of a real cradle through the pipeline's stages: initial data, the damped lattice (ncdamped) and
the damped DpS (dpsdamped), metrics; its files record the dissipated energy and the cradle's SI scales."""
from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pytest
import yaml

from cradle.models import physical
from cradle.pipeline import config as cc
from cradle.scenes import stages
from test_config import CONFIG  # tests/pipeline is on sys.path (rootdir, no __init__.py)

SCENE = {"N": 16, "bc": "periodic", "cradle": {"material": "steel", "radius": 0.01, "length": 0.1},
         "damping": {"onsite": 0.02, "contact": 0.05},
         "initial": {"kind": "packet", "amplitude": 0.05, "width": 8},
         "exact": {"method": "dop853_numba", "rtol": 1e-10}, "t_end": 40.0, "store": {"every": 0.5}}


@pytest.fixture(scope="module")
def runs():
    cfg = yaml.safe_load(CONFIG.read_text())
    cfg["scenes"]["damped"] = copy.deepcopy(SCENE)
    spec = cc.scene(cc.validate(cfg), "damped")
    init = stages.initial_data(spec, "damped")
    exact = stages.exact_run(spec, init, "damped")
    dps = stages.dps_run(spec, init, "damped")
    return spec, init, exact, dps, stages.metrics(spec, exact, dps, "damped")


def test_the_dissipated_energy_closes_the_balance(runs):
    """H(t) + D(t) = H(0) to the integrator's accuracy (the file's energy_drift; within 1e-8 at rtol 1e-10, the issue's
    bound: docs/dissipation.md), D nondecreasing from 0, and the damping removing a visible share of the energy."""
    _, _, exact, _, _ = runs
    H, D = exact["energy"].values, exact["dissipated"].values
    assert D[0] == 0.0 and np.all(np.diff(D) >= 0.0)
    assert D[-1] > 0.05 * H[0]
    balance = np.max(np.abs(H + D - H[0])) / H[0]
    assert balance <= exact.attrs["energy_drift"] * (1 + 1e-9) <= exact.attrs["max_energy_drift_allowed"]
    assert balance <= 1e-8
    assert exact["dissipated"].attrs["units"] == "1" and "ncdamped" in exact["dissipated"].attrs["long_name"]
    assert exact.attrs["model"].startswith("damped lattice (ncdamped)")


def test_the_forces_are_those_the_damped_run_felt(runs):
    """The stored bond forces are g_n of (ncdamped): never pulling, and equal to the Kuwabara-Kono force of the
    stored state."""
    from cradle.models import damping

    spec, _, exact, _, _ = runs
    f = exact["force"].values
    assert np.all(f <= 0.0)
    g = damping.bond_forces(exact["x"].values, exact["v"].values, spec.alpha, spec.damping.contact, spec.bc)
    np.testing.assert_array_equal(f, g)


def test_the_dps_run_is_damped_and_its_decay_matches_the_on_site_law(runs):
    """The DpS run integrates (dpsdamped): P = sum A_n decays exactly as exp(-gamma~ tau / 2) (the contact term
    leaves it alone: docs/damped-dps.md), which its P_drift measures."""
    _, _, _, dps, _ = runs
    assert dps.attrs["model"].startswith("damped DpS (dpsdamped)")
    assert dps.attrs["dps_damping_gamma"] == pytest.approx(0.02) and dps.attrs["dps_damping_eta"] == 0.05
    assert float(np.max(dps["P_drift"].values)) < 1e-8


def test_the_files_hold_the_cradle_and_its_scales(runs):
    """Every file of the scene converts to SI: the cradle and the SI value of one unit of each variable."""
    _, init, exact, dps, _ = runs
    s = physical.scales(physical.real_cradle("steel", 0.01, length=0.1))
    for ds in (init, exact, dps):
        assert ds.attrs["cradle_material"] == "steel" and ds.attrs["cradle_radius_m"] == 0.01
        assert ds.attrs["scale_time_s"] == s.T and ds.attrs["scale_length_m"] == s.X
        assert ds.attrs["scale_energy_J"] == s.E
        assert ds.attrs["damping_onsite"] == 0.02 and ds.attrs["damping_contact"] == 0.05


def test_a_file_of_a_real_cradle_reads_in_si(runs):
    """:func:`cradle.data.si.in_si`: t in s (t omega_0 = t_nc), x in m (X x_nc), energies in J (the balance holds in
    joules too); a file without a cradle is refused in one line."""
    from cradle.data.si import in_si

    _, _, exact, _, _ = runs
    s = physical.scales(physical.real_cradle("steel", 0.01, length=0.1))
    si = in_si(exact)
    np.testing.assert_array_equal(si["t"].values, exact["t"].values * s.T)
    np.testing.assert_array_equal(si["x"].values, exact["x"].values * s.X)
    assert si["t"].attrs["units"] == "s" and si["x"].attrs["units"] == "m" and si["energy"].attrs["units"] == "J"
    # a time in seconds is not called dimensionless; the other names are those of (nc), unchanged
    assert si["t"].attrs["long_name"] == "time t of (nc)" and "dimensionless" in exact["t"].attrs["long_name"]
    assert si["x"].attrs["long_name"] == exact["x"].attrs["long_name"]
    E = si["energy"].values + si["dissipated"].values
    assert np.max(np.abs(E - E[0])) <= 1e-8 * E[0]
    with pytest.raises(ValueError, match="no SI scales"):
        in_si(exact.drop_attrs())


def test_open_scene_in_si_and_its_movie_clock(runs, tmp_path):
    """The stored runs read back with `open_scene(units="si")` in SI, and the movie of the scene runs its clock in
    seconds as well."""
    from cradle.data.io import write_netcdf
    from cradle.figures.movie import MovieSpec, render
    from cradle.pipeline import layout
    from cradle.pipeline.outputs import open_scene

    _, _, exact, dps, _ = runs
    root = tmp_path / "results"
    for part, ds in (("exact", exact), ("dps", dps)):
        path = Path(layout.path(part, root, scene="damped"))
        path.parent.mkdir(parents=True, exist_ok=True)
        write_netcdf(ds, path)
    si = open_scene("damped", root, metrics=False, check=False, units="si")
    assert si["t"].attrs["units"] == "s" and si["x"].attrs["units"] == "m"
    np.testing.assert_allclose(si["t"].values, exact["t"].values * exact.attrs["scale_time_s"], rtol=1e-15)
    frames = render(open_scene("damped", root, metrics=False, check=False), MovieSpec(fps=2, duration=1.0,
                                                                                        width=320, height=180))
    info = next(frames)
    assert next(frames).shape == (180, 320, 3) and len(info["times"]) >= 2
    with pytest.raises(ValueError, match="units = 'SI': must be nc or si"):
        open_scene("damped", root, metrics=False, check=False, units="SI")
