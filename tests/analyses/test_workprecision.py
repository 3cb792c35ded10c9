"""Work-precision measurements (cradle.analyses.work_precision): a tiny ladder, the reference logic,
the spec and its forms, the netCDF output (one group per scene) and the figure."""
from __future__ import annotations

import copy
import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest
import yaml

from cradle.analyses import work_precision as wp
from cradle.analyses.protocol import Read
from cradle.data.io import open_dataset, open_tree, write_netcdf
from cradle.pipeline import config as cc
from cradle.scenes import stages
from cradle.specs.declare import from_plain

ROOT = Path(__file__).resolve().parents[2]

TINY = from_plain(wp.WorkPrecision, {
    "scenes": {"tiny": {"t_end": 10.0}}, "compare_every": 1.0, "repeat_time": 0.0,
    "reference": {"method": "srkn6c", "dt_factor": 0.0005, "tolerance": 1e-10},
    "methods": {"srkn6c": {"dt_factor": [0.04, 0.02, 0.01]}, "srkn6": {"dt_factor": [0.004, 0.002, 0.001]},
                "dop853_numba": {"rtol": [1e-6, 1e-8, 1e-10]}, "dop853": {"rtol": [1e-5, 1e-8]}},
})


def tiny_state():
    n = np.arange(16)
    q, a = 2 * np.pi * 3 / 16, 0.5
    return a * np.cos(q * n), 1.1 * a * np.sin(q * n), a


def _measure(spec, *, scene="tiny"):
    x0, v0, a = tiny_state()
    return wp.measure(spec, scene, x0, v0, 1.5, "periodic", a)


@pytest.fixture(scope="module")
def tiny_ds():
    return _measure(TINY)


def test_tiny_ladder_error_decreases_with_cost(tiny_ds):
    ds = tiny_ds
    assert ds.sizes == {"method": 4, "setting": 3, "t_compare": 11}
    assert list(ds["method"].values) == list(TINY.methods)
    for name in ("error", "energy_drift", "wall_time", "n_force_evals", "accuracy_parameter", "statistic_error",
                 "reference_difference", "method", "setting", "t_compare"):
        assert ds[name].attrs["long_name"] and "units" in ds[name].attrs, name
    assert ds["wall_time"].attrs["units"] == "s"
    assert ds.attrs["t_valid"] == 10.0 and ds.attrs["reference_error"] < 1e-10
    for i, m in enumerate(ds["method"].values):
        row = ds.isel(method=i)
        k = np.isfinite(row["error"].values)
        err, nfev = row["error"].values[k], row["n_force_evals"].values[k]
        print(f"{m:12s} error {err} force evals {nfev} wall {row['wall_time'].values[k]}")
        assert np.all(np.diff(err) < 0), m          # finer settings: smaller errors ...
        assert np.all(np.diff(nfev) > 0), m         # ... at a higher cost
        assert err[-1] > 10 * ds.attrs["reference_error"]
        assert np.all(row["energy_drift"].values[k] > 0)
    assert np.isnan(ds["statistic_error"].values).all()  # the reference holds to t_end
    assert np.isnan(ds["error"].sel(setting=2).values[3])  # dop853 has a 2-setting ladder
    # the corrected splitting is the most accurate at equal force evaluations here
    c = ds.isel(method=0)
    assert c["error"].values[2] < ds.isel(method=1)["error"].values[0]
    assert c["n_force_evals"].values[2] < ds.isel(method=1)["n_force_evals"].values[0]


def test_reference_limit_and_statistics():
    """With a tolerance below what the references achieve, t_valid comes early and the
    statistic over (t_valid, t_end] is reported."""
    spec = dataclasses.replace(TINY, reference=dataclasses.replace(TINY.reference, tolerance=1e-16),
                               methods={"srkn6c": wp.WorkPrecisionLadder(dt_factor=[0.02, 0.01])})
    ds = _measure(spec)
    assert ds.attrs["t_valid"] < 10.0
    assert np.isfinite(ds["statistic_error"].values).all()
    D = ds["reference_difference"].values
    t = ds["t_compare"].values
    assert D[t <= ds.attrs["t_valid"]].max() <= 1e-16 or ds.attrs["t_valid"] == 0.0


def test_valid_until_and_compare_grid():
    t = np.arange(6.0)
    assert wp.valid_until(t, np.array([0, 1e-12, 2e-11, 5e-10, 1e-9, 1e-12]), 1e-10) == 2.0
    assert wp.valid_until(t, np.zeros(6), 1e-10) == 5.0
    assert wp.valid_until(t, np.array([0, np.nan, 0, 0, 0, 0]), 1e-10) == 0.0
    np.testing.assert_allclose(wp.compare_grid(2.5, 1.0), [0, 1, 2, 2.5])
    np.testing.assert_allclose(wp.compare_grid(3.0, 1.0), [0, 1, 2, 3])
    np.testing.assert_allclose(wp.compare_grid(621.95, 100.0)[-2:], [600.0, 621.95])


def test_ladder_kind_is_checked():
    spec = dataclasses.replace(TINY, methods={"srkn6c": wp.WorkPrecisionLadder(rtol=[1e-8])})
    with pytest.raises(ValueError, match="dt_factor"):
        _measure(spec)


def test_netcdf_one_group_per_scene_figure_and_summary(tiny_ds, tmp_path):
    from cradle.figures import draw_analysis

    path = write_netcdf(tiny_ds, tmp_path / "tiny.nc")
    back = open_dataset(path)
    np.testing.assert_array_equal(back["error"].values, tiny_ds["error"].values)
    assert list(back["method"].values) == list(TINY.methods)
    assert json.loads(back.attrs["parameter_kind"]) == {m: wp.ladder(TINY, m)[0] for m in TINY.methods}
    lines = wp.summary(back)
    assert len(lines) == 4 and "srkn6c" in lines[0] and "decades" in lines[0]
    # the analysis gathers its batches (here the same one twice) into one group per scene
    two = dataclasses.replace(TINY, scenes={"tiny2": TINY.scenes["tiny"], "tiny": TINY.scenes["tiny"]})
    assert wp.ANALYSIS.batches.keys(two) == ["tiny", "tiny2"]
    tree = open_tree(write_netcdf(wp.compute(two, {"batch/tiny": back, "batch/tiny2": back}), tmp_path / "wp.nc"))
    assert list(tree.children) == ["tiny", "tiny2"] and tree.attrs["scene_names"] == "tiny, tiny2"
    for name in ("tiny", "tiny2"):
        group = tree[name].to_dataset()
        for var in back.variables:
            np.testing.assert_array_equal(group[var].values, back[var].values)
        assert group.attrs["t_valid"] == back.attrs["t_valid"]
    out = draw_analysis("work_precision", tree, tmp_path / "work-precision")
    assert all(p.stat().st_size > 1000 for p in out)


def test_spec_its_forms_and_the_config_checks():
    raw = yaml.safe_load((ROOT / "config.yaml").read_text())
    full = cc.analysis_spec(raw, "work-precision", "full")
    assert isinstance(full, wp.WorkPrecision) and full.reference.method == "srkn6c"
    assert full.scenes["fft106"].t_end == 100.0 and wp.ANALYSIS.batches.keys(full) == ["fft106", "tw-strong", "tw-weak"]
    assert {"srkn6", "srkn4", "strang", "dop853", "lsoda", "dop853_numba", "srkn6c"} <= set(full.methods)
    assert all(len(wp.ladder(full, m)[1]) >= 5 for m in full.methods)
    # the reduced form (declared): tw-weak to t = 100, four methods on the first settings of their ladders
    red = cc.analysis_spec(raw, "work-precision", "reduced")
    assert red.reduced is None and {n: s.t_end for n, s in red.scenes.items()} == {"tw-weak": 100.0}
    assert list(red.methods) == [m for m in full.methods if m in ("srkn6c", "srkn4c", "srkn6", "dop853_numba")]
    assert all(wp.ladder(red, m)[1] == wp.ladder(full, m)[1][:4] for m in red.methods)
    # every batch reads the initial data of its scene; a batch of the full form has the machine to itself
    assert wp.ANALYSIS.batches.reads(red, "tw-weak") == {"initial": Read.of("initial", scene="tw-weak")}
    assert wp.ANALYSIS.batches.threads == {"full": "all"}
    bad = copy.deepcopy(raw)
    bad["beyond"]["work-precision"]["scenes"]["tw-wek"] = {"t_end": 10.0}
    with pytest.raises(cc.ConfigError, match=r"beyond.work-precision.scenes.tw-wek.*did you mean 'tw-weak'"):
        cc.validate(bad)
    bad = copy.deepcopy(raw)
    bad["beyond"]["work-precision"]["methods"]["srkn6c"] = {"rtol": [1e-8]}
    with pytest.raises(cc.ConfigError, match="work-precision.methods.srkn6c"):
        cc.validate(bad)
    bad = copy.deepcopy(raw)
    bad["beyond"]["work-precision"]["methods"]["euler"] = {"dt_factor": [0.1]}
    with pytest.raises(cc.ConfigError, match="euler"):
        cc.validate(bad)
    bad = copy.deepcopy(raw)
    bad["beyond"]["work-precision"] = {"scenes": {}, "reduced": {"scenes": {}}}
    for form in ("full", "reduced"):
        with pytest.raises(cc.ConfigError, match="no scene to measure"):
            wp.ANALYSIS.batches.keys(cc.analysis_spec(bad, "work-precision", form))


def test_a_tiny_scene_through_the_protocol(tmp_path):
    """What the jobs do: a batch from the scene's initial data file (alpha, N, bc read from it), written,
    gathered into the analysis file, drawn."""
    from cradle.figures import draw_analysis

    raw = yaml.safe_load((ROOT / "config.yaml").read_text())
    tiny_cfg = copy.deepcopy(raw)
    tiny_cfg["scenes"] = {"tw-weak": {**raw["scenes"]["tw-weak"], "N": 20, "t_end": 5.0, "store": {"every": 1.0}}}
    tiny_cfg["figures"] = {}
    tiny_cfg["beyond"] = {}   # the other analyses read scenes this config leaves out
    tiny_cfg["beyond"]["work-precision"] = {
        "scenes": {"tw-weak": {"t_end": 5.0}}, "repeat_time": 0.0, "reference": {"dt_factor": 0.001},
        "methods": {"srkn6c": {"dt_factor": [0.02, 0.01]}, "lsoda": {"rtol": [1e-6, 1e-8]}}}
    spec = cc.analysis_spec(tiny_cfg, "work-precision", "full")
    init = write_netcdf(stages.initial_data(cc.scene(tiny_cfg, "tw-weak"), "tw-weak"), tmp_path / "i.nc")
    a = wp.ANALYSIS
    batch = write_netcdf(a.batches.run(spec, "tw-weak", {"initial": open_dataset(init)}), tmp_path / "b.nc")
    tree = open_tree(write_netcdf(a.compute(spec, {"batch/tw-weak": open_dataset(batch)}), tmp_path / "wp.nc"))
    ds = tree["tw-weak"].to_dataset()
    assert ds.attrs["scene"] == "tw-weak" and ds.attrs["a"] == pytest.approx(0.021180, rel=1e-3)
    assert ds.attrs["N"] == 20 and ds.attrs["bc"] == "periodic" and ds.attrs["alpha"] == 1.5
    assert ds.sizes["method"] == 2 and np.all(np.isfinite(ds["error"].values))
    out = draw_analysis("work_precision", tree, tmp_path / "fig")
    assert (tmp_path / "fig.png").stat().st_size > 1000 and len(out) == 2
