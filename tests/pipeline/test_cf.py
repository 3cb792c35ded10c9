"""Every output kind is CF-1.10 (IOOS compliance-checker, strict) and carries its provenance.

The six kinds (homoclinic, map, initial, sim exact, sim dps, metrics) are
built with cradle.scenes.stages on the tiny config of test_pipeline, written with
cradle.data.io.write_netcdf and checked with the checker's Python API. Skipped
only when compliance-checker is not installed (it is in the ``test`` extra).

The files of the analyses beyond the paper are trees of netCDF groups; the checker reads the root
group only, so each group is checked as the Dataset ``xarray.open_datatree`` gives for it (its
variables, the coordinates it inherits, the root's global attributes), written as its own file.
The trees are built by :func:`cradle.data.io.make_tree` from every variable each analysis
declares (``VARIABLES`` of its module), filled with increasing numbers.
"""
from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

from cradle.analyses.registry import ANALYSES
from cradle.data import provenance
from cradle.data.io import make_dataset, make_tree, open_dataset, open_tree, write_netcdf
from cradle.data.variables import VARIABLES
from cradle.pipeline import config as cc
from cradle.pipeline.outputs import open_scene
from cradle.scenes import stages
from test_pipeline import TINY  # tests/ is on sys.path (pytest rootdir, no __init__.py)

KINDS = ("homoclinic", "map", "initial", "exact", "dps", "metrics", "map-marks", "metrics-breather", "metrics-pair")


def _localised_run(kind, omega, N=20, t_end=60.0, dt=0.5):
    """A synthetic breathing run of ``kind`` ("breather", "pair"), as exact.nc holds it (x, force)."""
    from cradle.models import lattice

    t = np.arange(0.0, t_end + 1e-9, dt)
    n = np.arange(N)
    prof = 0.01 * (-1.0) ** n * np.exp(-0.5 * ((n - N / 2 + 0.5) / 1.2) ** 2)
    x = prof[None, :] * np.cos(omega * t)[:, None]
    attrs = {"scene": kind, "alpha": 1.5, "N": N, "bc": "periodic", "initial_kind": kind, "omega_sw": 1.1}
    return make_dataset({"x": x, "force": lattice.bond_forces(x, 1.5, "periodic")}, coords={"t": t, "n": n},
                        attrs=attrs)


@pytest.fixture(scope="module")
def outputs(tmp_path_factory):
    """One file of each kind, in the results/ layout (tw-weak-noise: noise fields too)."""
    root = tmp_path_factory.mktemp("cf") / "results"
    cfg = cc.validate(TINY)
    scene = "tw-weak-noise"
    spec = cc.scene(cfg, scene)
    hspec = cc.homoclinic(cfg, "site")
    mspec = cc.map_entry(cfg, "traj3")
    init = stages.initial_data(spec, scene)
    ex = stages.exact_run(spec, init, scene)
    ap = stages.dps_run(spec, init, scene)
    built = {
        "homoclinic": (stages.homoclinic_solution(hspec, "site"), root / "homoclinic" / "site.nc"),
        "map": (stages.map_orbits(mspec, "traj3"), root / "map" / "traj3.nc"),
        "initial": (init, root / "initial" / f"{scene}.nc"),
        "exact": (ex, root / "sim" / scene / "exact.nc"),
        "dps": (ap, root / "sim" / scene / "dps.nc"),
        "metrics": (stages.metrics(spec, ex, ap, scene), root / "metrics" / f"{scene}.nc"),
        "map-marks": (stages.map_orbits(dataclasses.replace(mspec, marks=True), "marked"), root / "map" / "marked.nc"),
    }
    for kind in ("breather", "pair"):  # the breather measurements of localised scenes (plot18, loc1, fini)
        run_ex, run_ap = _localised_run(kind, 1.09), _localised_run(kind, 1.1)
        built[f"metrics-{kind}"] = (stages.metrics(None, run_ex, run_ap, kind), root / "metrics" / f"{kind}.nc")
    return {kind: write_netcdf(ds, path) for kind, (ds, path) in built.items()} | {"root": root, "scene": scene}


def _cf_failures(path, tmp_path) -> list[str]:
    checker = pytest.importorskip("compliance_checker.runner", reason="compliance-checker is not installed")
    suite = checker.CheckSuite()
    suite.load_all_available_checkers()
    report = tmp_path / f"{path.stem}.json"
    passed, errors = checker.ComplianceChecker.run_checker(str(path), ["cf:1.10"], 0, "strict",
                                                           output_filename=str(report), output_format="json")
    results = json.loads(report.read_text())["cf:1.10"]
    failures = []
    for prio in ("high_priorities", "medium_priorities", "low_priorities"):
        for item in results.get(prio, []):
            score = item.get("value", [1, 1])
            if score[0] < score[1]:
                failures.append(f"{prio}: {item['name']}: {'; '.join(item.get('msgs', []))}")
    assert not errors, errors
    if not passed and not failures:
        failures.append("checker reported failure")
    return failures


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
@pytest.mark.parametrize("kind", KINDS)
def test_cf_compliant(outputs, kind, tmp_path):
    assert _cf_failures(outputs[kind], tmp_path) == []


#: analysis -> module declaring its VARIABLES (one dict per netCDF group)
TREES = {a.name: a.module for a in ANALYSES.values()}


def _variables(module: str) -> dict:
    """The declared groups of an analysis, a group per scene (``/{scene}``) or per member (``/dps_site/{k}``) named
    ``s0``."""
    import re
    from importlib import import_module

    variables = import_module(f"cradle.analyses.{module}").VARIABLES
    return {re.sub(r"\{\w+\}", "s0", path): decl for path, decl in variables.items()}


def _declared_tree(module: str):
    """The tree of an analysis with every declared variable, its dims sized 2 or 3, increasing values."""
    variables = _variables(module)
    dims = {}
    for decl in variables.values():
        for d in (d for v in decl.values() for d in v.dims):
            dims.setdefault(d, 2 + len(dims) % 2)
    groups = {}
    for path, decl in variables.items():
        data, coords = {}, {}
        for name, var in decl.items():
            shape = tuple(dims[d] for d in var.dims)
            values = 1.0 + np.arange(int(np.prod(shape))).reshape(shape)
            if "flag_values" in dict(var.attrs):   # a flag variable holds its flags, of their type (CF 3.5)
                flags = np.asarray(dict(var.attrs)["flag_values"])
                values = flags[np.arange(values.size) % flags.size].reshape(shape)
            (coords if var.dims == (name,) else data)[name] = values
        groups[path] = (data, coords)
    return make_tree(groups, variables, attrs={"scene_names": "a, b"}, title=f"{module}: declared variables")


@pytest.fixture(scope="module")
def trees(tmp_path_factory):
    root = tmp_path_factory.mktemp("trees")
    return {label: write_netcdf(_declared_tree(module), root / f"{label}.nc") for label, module in TREES.items()}


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
@pytest.mark.parametrize("label", TREES)
def test_cf_compliant_every_group(trees, label, tmp_path):
    tree = open_tree(trees[label])
    assert len(list(tree.subtree)) == len(_variables(TREES[label]))   # every declared group is there
    failures = {}
    for node in tree.subtree:
        ds = node.to_dataset(inherit=True)
        if not ds.variables:
            continue
        ds.attrs = dict(tree.attrs)
        name = node.path.strip("/").replace("/", "-") or "root"
        failures[node.path] = _cf_failures(write_netcdf(ds, tmp_path / f"{label}-{name}.nc"), tmp_path)
    assert failures and all(f == [] for f in failures.values()), failures


@pytest.mark.parametrize("label", TREES)
def test_groups_declared_named_and_checksummed(trees, label):
    """Every group of a tree holds its declared variables without an analysis prefix, with the declared
    dims, long name and units, each under a Fletcher-32 checksum; provenance on the root only."""
    import xarray as xr

    variables = _variables(TREES[label])
    tree = open_tree(trees[label])
    assert tree.attrs["Conventions"] == "CF-1.10" and tree.attrs["cradle_version"]
    for path, decl in variables.items():
        ds = (tree if path == "/" else tree[path]).to_dataset(inherit=False)
        assert set(ds.variables) == set(decl), path
        for name, var in decl.items():
            assert not name.startswith(("t1_", "mi_", "mig_", "mis_", "fq_")), name
            assert ds[name].dims == var.dims and ds[name].attrs["long_name"] == var.long_name
            assert ds[name].attrs["units"] == var.units
            assert ds[name].encoding["fletcher32"], (path, name)
        if path != "/":
            assert "cradle_version" not in ds.attrs
    with xr.open_datatree(trees[label], engine="netcdf4") as plain:   # what a researcher types
        assert {node.path for node in plain.subtree} == set(variables) | {"/"}


@pytest.mark.parametrize("kind", KINDS)
def test_global_and_variable_attributes(outputs, kind):
    ds = open_dataset(outputs[kind])
    assert ds.attrs["Conventions"] == "CF-1.10"
    for key in ("title", "history", "source", "references"):
        assert ds.attrs[key], key
    assert "Newton's cradle" in ds.attrs["references"]
    for name in list(ds.data_vars) + list(ds.coords):
        assert ds[name].attrs["long_name"] == VARIABLES[name].long_name
        assert ds[name].attrs["units"] == VARIABLES[name].units
        assert "_FillValue" not in ds[name].encoding or name not in ds.coords
        assert not np.iscomplexobj(ds[name].values)
    assert "time" not in ds.variables  # a CF `time` would need calendar units


@pytest.mark.parametrize("kind", KINDS)
def test_provenance_in_every_output(outputs, kind):
    ds = open_dataset(outputs[kind])
    for key in ("cradle_version", "software_versions", "command"):
        assert ds.attrs[key], key
    for lib in ("numpy=", "scipy=", "numba=", "xarray=", "netCDF4="):
        assert lib in ds.attrs["software_versions"]
    git = provenance.git_info()
    if git:
        assert ds.attrs["git_commit"] == git["git_commit"] and ds.attrs["git_dirty"] in (0, 1)
    else:
        assert "git_commit" not in ds.attrs


def test_params_hash_is_canonical():
    a = {"N": 20, "initial": {"q": 0.5, "kind": "travelling"}, "times": [0.0, 1.0]}
    b = {"times": [np.float64(0.0), 1.0], "initial": {"kind": "travelling", "q": np.float64(0.5)}, "N": np.int64(20)}
    assert provenance.params_hash(a) == provenance.params_hash(b)
    assert provenance.params_hash(a) != provenance.params_hash({**a, "N": 21})
    ds = make_dataset({"x0": np.zeros(3)}, coords={"n": np.arange(3)}, attrs={"params_sha256": "stale"}, params=a)
    assert ds.attrs["params_sha256"] == provenance.params_hash(a)
    ds = make_dataset({"x0": np.zeros(3)}, coords={"n": np.arange(3)}, attrs={"params_sha256": "stale"})
    assert "params_sha256" not in ds.attrs  # inherited provenance is never kept


def test_git_info_outside_a_checkout(tmp_path):
    assert provenance.git_info(str(tmp_path)) == {}


def test_open_scene(outputs):
    ds = open_scene(outputs["scene"], root=outputs["root"])
    assert list(ds["model"].values) == ["exact", "dps"]
    assert ds["x"].dims == ("model", "t", "n") and ds["force"].dims == ("model", "t", "n")
    ex = open_dataset(outputs["exact"])
    np.testing.assert_array_equal(ds["x"].sel(model="exact").values, ex["x"].values)
    assert {"v", "energy", "A_re", "A_im", "E", "spectrum_exact"} <= set(ds.data_vars)
    assert "tau" in ds.coords and ds["x"].attrs["units"] == "1"
    assert ds.attrs["exact_energy_drift"] == ex.attrs["energy_drift"] and ds.attrs["N"] == 20
    with pytest.raises(FileNotFoundError, match="cradle run"):
        open_scene("nope", root=outputs["root"])
