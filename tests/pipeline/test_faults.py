"""Fault injection: damaged, truncated, foreign and half-written outputs, over-budget configs.

Every output kind (homoclinic, map, initial, exact, dps, metrics) is written with
``write_netcdf`` from a tiny real run; each test damages a copy and checks that every reader
stops with one line naming the file and its rebuild command, that nothing good is deleted or
overwritten first, and that an over-budget config is refused before any allocation.
"""
from __future__ import annotations

import dataclasses
import os
import shutil
import time
import tracemalloc
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import xarray as xr
import yaml

from cradle.data import io
from cradle.pipeline import budget, cli, config as cc, extend
from cradle.pipeline.outputs import open_scene
from cradle.scenes import stages
from cradle.scenes.spec import DpsIntegrator, ExactIntegrator, Scene, Store, Travelling
from cradle.specs.declare import from_plain, plain

ROOT = Path(__file__).resolve().parents[2]

TINY = {
    "defaults": {"alpha": 1.5, "exact": {"method": "srkn6c"}, "dps": {"method": "dop853_numba", "rtol": 1e-9}},
    "map": {"m": {"box": 0.1, "iterations": 30, "starts": [[0.0, 1.0e-3], [0.0, 2.0e-3]]}},
    "homoclinic": {"h": {"guess": "bond", "N": 20, "bc": "periodic"}},
    "scenes": {"tw": {"N": 20, "bc": "periodic", "initial": {"kind": "travelling", "q": "pi/5", "omega_tw": 1.01},
                      "t_end": 5.0, "store": {"every": 0.5}}},
    "figures": {},
}

#: the variable whose bytes each test damages, per output kind
TARGET = {"homoclinic": "a", "map": "map_a", "initial": "x0", "exact": "x", "dps": "A_re", "metrics": "spectrum_exact"}


@pytest.fixture(scope="module")
def outputs(tmp_path_factory):
    """{kind: (in-memory Dataset, path under .../results/...)} for the six output kinds."""
    root = tmp_path_factory.mktemp("faults") / "results"
    cfg = cc.validate(TINY)
    spec = cc.scene(cfg, "tw")
    init = stages.initial_data(spec, "tw")
    ex, ap = stages.exact_run(spec, init, "tw"), stages.dps_run(spec, init, "tw")
    made = {"homoclinic": (stages.homoclinic_solution(cc.homoclinic(cfg, "h"), "h"), "homoclinic/h.nc"),
            "map": (stages.map_orbits(cc.map_entry(cfg, "m"), "m"), "map/m.nc"),
            "initial": (init, "initial/tw.nc"), "exact": (ex, "sim/tw/exact.nc"), "dps": (ap, "sim/tw/dps.nc"),
            "metrics": (stages.metrics(spec, ex, ap, "tw"), "metrics/tw.nc")}
    out = {}
    for kind, (ds, rel) in made.items():
        io.write_netcdf(ds, root / rel)
        out[kind] = (ds, root / rel)
    return out


def _scene(**values) -> Scene:
    """A resolved travelling-wave scene with the declared defaults, ``values`` in place."""
    return dataclasses.replace(Scene(N=20, alpha=1.5, t_end=5.0, store=Store(every=0.5), exact=ExactIntegrator(),
                                     dps=DpsIntegrator(), max_energy_drift=1e-6,
                                     initial=Travelling(kind="travelling", q="pi/5", omega_tw=1.01)), **values)


def _copy(path: Path, tmp_path: Path) -> Path:
    """A copy of ``path`` keeping its results/... layout (so the rebuild hint is a snakemake command)."""
    rel = Path(*path.parts[path.parts.index("results"):])
    dst = tmp_path / rel
    dst.parent.mkdir(parents=True, exist_ok=True)
    shutil.copy2(path, dst)
    return dst


def _flip_in_data(path: Path, values: np.ndarray) -> int:
    """Flip one byte inside the stored data of ``values`` (found by its last bytes); the offset."""
    raw = path.read_bytes()
    head = np.ascontiguousarray(values).tobytes()[-48:]
    at = raw.find(head)
    assert at > 0 and raw.find(head, at + 1) < 0, "the data's last bytes are not found exactly once"
    at += 20
    with open(path, "r+b") as f:
        f.seek(at)
        byte = f.read(1)
        f.seek(at)
        f.write(bytes([byte[0] ^ 0x5A]))
    return at


def _one_line(text: str) -> bool:
    return text.count("\n") == 1 and "Traceback" not in text


@pytest.mark.parametrize("kind", list(TARGET))
def test_every_variable_checksummed_and_values_bitwise(outputs, kind):
    """Every non-scalar variable of every output kind carries fletcher32; reading gives the same bits."""
    ds, path = outputs[kind]
    with netCDF4.Dataset(path) as nc:
        bare = [n for n, v in nc.variables.items() if v.ndim > 0 and not v.filters()["fletcher32"]]
    assert bare == []
    back = io.open_dataset(path)
    for name in list(ds.data_vars) + list(ds.coords):
        assert back[name].dtype == ds[name].dtype, name
        assert np.array_equal(back[name].values, ds[name].values), name
        assert back[name].values.tobytes() == np.asarray(ds[name].values).tobytes(), name


@pytest.mark.parametrize("kind", list(TARGET))
def test_flipped_byte_in_data_is_detected_by_every_reader(outputs, kind, tmp_path, capsys):
    """One flipped byte in the data (size and layout unchanged): open_dataset, verify_file,
    `cradle describe` and `cradle verify` all stop with one line naming the file and the rebuild."""
    ds, good = outputs[kind]
    path = _copy(good, tmp_path)
    mtime = path.stat().st_mtime_ns
    _flip_in_data(path, ds[TARGET[kind]].values)
    os.utime(path, ns=(mtime, mtime))                      # the damage keeps the modification time
    rel = str(Path(*path.parts[path.parts.index("results"):]))
    for reader in (io.open_dataset, io.verify_file):
        with pytest.raises(io.DamagedOutput) as err:
            reader(path)
        msg = str(err.value)
        assert "\n" not in msg and str(path) in msg and f"snakemake --force {rel}" in msg, msg
    assert cli.main(["describe", str(path)]) == 2
    err = capsys.readouterr().err
    assert _one_line(err) and str(path) in err and "damaged" in err, err
    assert cli.main(["verify", str(tmp_path / "results")]) == 1
    out = capsys.readouterr().out
    assert f"DAMAGED {path}" in out and "1 to rebuild" in out, out


def test_damaged_scene_stops_open_scene_and_figure_inputs(outputs, tmp_path):
    from cradle.pipeline.outputs import load_inputs

    for kind in ("exact", "dps", "metrics"):
        _copy(outputs[kind][1], tmp_path)
    root = tmp_path / "results"
    assert open_scene("tw", root=root)["x"].sizes["model"] == 2
    _flip_in_data(root / "sim/tw/dps.nc", outputs["dps"][0]["A_re"].values)
    with pytest.raises(io.DamagedOutput, match=r"sim/tw/dps.nc: damaged"):
        open_scene("tw", root=root)
    with pytest.raises(io.DamagedOutput, match=r"sim/tw/dps.nc: damaged"):
        load_inputs({"tw": "scenes"}, root)


@pytest.mark.parametrize("keep", [0.3, 0.7, 0.99])
def test_truncated_file_is_detected(outputs, tmp_path, capsys, keep):
    path = _copy(outputs["exact"][1], tmp_path)
    size = path.stat().st_size
    os.truncate(path, int(size * keep))
    with pytest.raises(io.DamagedOutput, match=r"damaged or truncated.*rebuild it: snakemake --force"):
        io.open_dataset(path)
    assert cli.main(["verify", str(path)]) == 1
    assert "DAMAGED" in capsys.readouterr().out


def test_not_netcdf_is_one_readable_line(tmp_path, capsys):
    path = tmp_path / "notes.nc"
    path.write_text("this is a text file, not netCDF\n")
    with pytest.raises(io.DamagedOutput, match=r"notes.nc: not a netCDF file"):
        io.open_dataset(path)
    assert cli.main(["describe", str(path)]) == 2
    err = capsys.readouterr().err
    assert _one_line(err) and "not a netCDF file" in err and len(err) < 300, err


@pytest.mark.parametrize("what", ["text", "empty", "folder"])
def test_extend_of_what_is_no_netcdf_file_is_one_line_and_writes_nothing(tmp_path, capsys, what):
    """``cradle extend`` of a text file, an empty file or a folder: one line naming it (not the reader's)."""
    path = tmp_path / "exact.nc"
    if what == "folder":
        path.mkdir()
    else:
        path.write_text("" if what == "empty" else "this is a text file, not netCDF\n")
    before = sorted(tmp_path.rglob("*"))
    assert cli.main(["extend", str(path), "--t-end", "10"]) == 2
    err = capsys.readouterr().err
    assert _one_line(err) and str(path) in err and ("not a netCDF file" in err) and len(err) < 300, err
    assert sorted(tmp_path.rglob("*")) == before


def test_write_failing_part_way_keeps_the_previous_output(outputs, tmp_path, monkeypatch):
    """to_netcdf raises after writing half a file: the previous output is untouched, no temporary left."""
    ds, good = outputs["exact"]
    path = tmp_path / "exact.nc"
    io.write_netcdf(ds, path)
    before = path.read_bytes()
    real = xr.Dataset.to_netcdf

    def half_then_fail(self, target, *a, **k):
        real(self, target, *a, **k)
        os.truncate(target, os.path.getsize(target) // 2)
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", half_then_fail)
    with pytest.raises(OSError, match="No space left"):
        io.write_netcdf(ds.isel(t=slice(0, 3)), path)
    assert path.read_bytes() == before
    assert sorted(os.listdir(tmp_path)) == [".exact.nc.digest", "exact.nc"]  # the digest of the previous output, kept
    monkeypatch.undo()
    assert np.array_equal(io.open_dataset(path)["x"].values, ds["x"].values)


def test_figure_failing_part_way_keeps_the_previous_figure(tmp_path, monkeypatch):
    """The PDF fails after the PNG was drawn: both previous files stay as they were."""
    from cradle.figures import figure, save_figure

    fig, ax = figure()
    ax.plot([0, 1], [0, 1])
    save_figure(fig, tmp_path / "f")
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    fig, ax = figure()
    ax.plot([0, 1], [1, 0])
    real = type(fig).savefig

    def fail_on_pdf(self, fname, *a, **k):
        if k.get("format") == "pdf":
            raise RuntimeError("disk full while writing the PDF")
        return real(self, fname, *a, **k)

    monkeypatch.setattr(type(fig), "savefig", fail_on_pdf)
    with pytest.raises(RuntimeError, match="disk full"):
        save_figure(fig, tmp_path / "f")
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before


@pytest.mark.parametrize("patch, key", [
    # the largest N the schema allows, with an adaptive method (its store cannot stream): refused on memory
    ({"N": 10_000_000, "exact": {"method": "dop853"}}, "budget.memory_gb"),
    # a store this large would stream in bounded memory (cradle.scenes.streamed): refused on disk
    ({"t_end": 99000.0, "store": {"every": 0.01}}, "budget.disk_gb"),
    ({"N": 100_000, "t_end": 1e6, "store": {"snapshots": [1.0]}}, "budget.hours"),
])
def test_over_budget_refused_fast_before_allocating(patch, key):
    cfg = yaml.safe_load((ROOT / "config.yaml").read_text())
    cc.validate(cfg)  # the schema validator is built once per process: not part of the refusal
    cfg["scenes"]["fft106"].update(patch)
    tracemalloc.start()
    t0 = time.perf_counter()
    with pytest.raises(cc.ConfigError) as err:
        cc.validate(cfg)
    elapsed = time.perf_counter() - t0
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    lines = str(err.value).splitlines()
    # the scene's job, and the work-precision batch that runs fft106 too (at N = 1e7 also over budget)
    assert lines[0].startswith("config error: scenes.fft106: ") and key in lines[0], lines
    assert all(line.startswith(("config error: scenes.fft106: ", "config error: beyond.work-precision: scene "
                                                                 "fft106: ")) for line in lines), lines
    assert "estimated" in lines[0] and "exceeds" in lines[0]
    assert elapsed < 5.0 and peak < 50 * 2**20, (elapsed, peak)   # the issue: refused in under 5 s


def test_mi_statistics_batch_over_budget_refused():
    """The batch jobs of beyond.mi-statistics are estimated too: 1000 seeds to t = 1e5 are refused in
    one line naming the form (the full one: the top of the section); the reduced form's batch is estimated
    within a factor 2 of its measured 7.9 s (results/benchmarks/mi-statistics/reduced)."""
    from cradle.pipeline import budget

    cfg = yaml.safe_load((ROOT / "config.yaml").read_text())
    cfg["beyond"].setdefault("mi-statistics", {})["n_seeds"] = 1000
    cfg["beyond"]["mi-statistics"]["t_end"] = 1e5
    with pytest.raises(cc.ConfigError) as err:
        cc.validate(cfg)
    lines = str(err.value).splitlines()
    assert len(lines) == 1
    assert lines[0].startswith("config error: beyond.mi-statistics: ") and "budget." in lines[0]
    e = budget.mi_statistics_estimate(cc.typed(cc.load(ROOT / "config.yaml")), "reduced")
    assert 7.9 / 2 < e.seconds < 7.9 * 2 and e.key == "beyond.mi-statistics.reduced"


def test_two_gb_store_validates_and_streams():
    """fft106 stored every 0.004 (~2 GB, ~3 GB in memory) fits the default budget: its job streams."""
    from cradle.pipeline import budget

    cfg = yaml.safe_load((ROOT / "config.yaml").read_text())
    cfg["scenes"]["fft106"]["store"]["every"] = 0.004
    cc.validate(cfg)
    assert budget.streams(cc.scene(cfg, "fft106"))


def test_budget_key_raises_the_limit_and_cli_refuses(tmp_path, capsys):
    # an adaptive method for (nc) cannot continue block by block: the job would hold the whole store
    big = {**TINY, "scenes": {"tw": {**TINY["scenes"]["tw"], "t_end": 5000.0, "store": {"every": 0.001},
                                     "exact": {"method": "dop853_numba"}}}}
    with pytest.raises(cc.ConfigError, match=r"scenes.tw: N = 20, t_end = 5000, store.every = 0.001: .*"
                                             r"exceeds budget.memory_gb = 8"):
        cc.validate(big)
    assert cc.validate({**big, "budget": {"memory_gb": 64}})["budget"]["memory_gb"] == 64
    with pytest.raises(cc.ConfigError, match=r"budget.disk_gb = 0: must be > 0"):
        cc.validate({**TINY, "budget": {"disk_gb": 0}})
    path = tmp_path / "big.yaml"
    path.write_text(yaml.safe_dump(big))
    assert cli.main(["run", "tw", "--config", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert _one_line(err) and "budget.memory_gb" in err
    assert not (tmp_path / "out").exists()


def test_estimates_of_the_paper_config_fit_and_are_sane():
    """Every job of config.yaml fits the default budget; the measured fft106 store of the issue
    (every 0.001 to 543.7: 11 GB peak in memory, 7.5 GB written on main) is estimated within 20 %
    (in memory: with a DpS method that cannot stream); with the defaults it streams, under 1 GB."""
    cfg = cc.load(ROOT / "config.yaml")
    assert budget.over_budget(cc.typed(cfg)) == []
    spec = _scene(N=200, t_end=543.7, store=Store(every=0.001), dps=DpsIntegrator(method="dop853"))
    e = budget.spec_estimate(spec, "fft106")
    assert not e.streamed
    assert 0.8 * 11e9 < e.memory_bytes < 1.2 * 11e9 and 0.8 * 7.5e9 < e.disk_bytes < 1.2 * 7.5e9
    s = budget.spec_estimate(dataclasses.replace(spec, dps=DpsIntegrator(method="dop853_numba")), "fft106")
    assert s.streamed and s.memory_bytes < 1e9 and s.disk_bytes == e.disk_bytes


def test_recorded_dt_is_the_step_taken(tmp_path):
    """Stored every 0.01, below the default step: dt is the store spacing actually stepped,
    dt_nominal the bound; extend continues with the bound and stays bitwise one run."""
    spec = cc.scene(cc.validate({**TINY, "scenes": {"tw": {**TINY["scenes"]["tw"], "t_end": 0.5,
                                                           "store": {"every": 0.01}}}}), "tw")
    init = stages.initial_data(spec, "tw")
    ex = stages.exact_run(spec, init, "tw")
    assert ex.attrs["dt_nominal"] > 0.02
    assert ex.attrs["dt"] == pytest.approx(0.01, rel=1e-9)
    assert ex.attrs["n_steps"] == 50
    long_spec = dataclasses.replace(spec, t_end=1.0)
    long = stages.exact_run(long_spec, init, "tw")
    io.write_netcdf(ex, tmp_path / "exact.nc")
    extend.extend(tmp_path / "exact.nc", 1.0, out=tmp_path / "long.nc")
    got = io.open_dataset(tmp_path / "long.nc")
    assert np.array_equal(got["x"].values, long["x"].values)
    assert got.attrs["dt"] == pytest.approx(0.01, rel=1e-9) and got.attrs["dt_nominal"] == ex.attrs["dt_nominal"]


@pytest.mark.parametrize("value", ["inf", "nan", "-inf"])
def test_extend_refuses_non_finite_t_end(outputs, tmp_path, capsys, value):
    path = _copy(outputs["exact"][1], tmp_path)
    assert cli.main(["extend", str(path), f"--t-end={value}"]) == 2
    err = capsys.readouterr().err
    assert _one_line(err) and "must be a finite time" in err and "Overflow" not in err, err


def test_extend_writes_a_new_file_and_refuses_a_workflow_scene_in_place(outputs, tmp_path, capsys, monkeypatch):
    """Without --out, a run of the workflow's results/ is continued under cradle run's folder (cradle-runs/ of the
    working directory, as `cradle run`), nothing written into results/; --in-place is refused for it."""
    exact = _copy(outputs["exact"][1], tmp_path)
    _copy(outputs["dps"][1], tmp_path)
    before = sorted(p.name for p in exact.parent.iterdir()), exact.read_bytes()
    monkeypatch.chdir(tmp_path)
    assert cli.main(["extend", str(exact), "--t-end", "6"]) == 0
    made = tmp_path / "cradle-runs" / "sim" / "tw" / "exact-t6.nc"
    assert str(made.relative_to(tmp_path)) in capsys.readouterr().out
    assert io.open_dataset(made).attrs["t_end"] == 6.0
    assert (sorted(p.name for p in exact.parent.iterdir()), exact.read_bytes()) == before
    capsys.readouterr()
    assert cli.main(["extend", str(exact), "--t-end", "6", "--in-place"]) == 2
    err = capsys.readouterr().err
    assert _one_line(err) and "refusing to extend" in err and "scenes.tw.t_end: 6" in err, err
    assert exact.read_bytes() == before[1]
    alone = tmp_path / "alone" / "exact.nc"                  # a standalone exact run may be extended in place
    alone.parent.mkdir()
    shutil.copy2(exact, alone)
    assert cli.main(["extend", str(alone), "--t-end", "6", "--in-place"]) == 0
    assert io.open_dataset(alone).attrs["t_end"] == 6.0


def test_rule_params_hold_no_stored_times():
    """The simulate rule gets the plain values of the typed scene: small, sorted, and built back into
    the same scene (the same stored times) bitwise."""
    cfg = cc.load(ROOT / "config.yaml")
    for name in cfg["scenes"]:
        scene = cc.scene(cfg, name)
        values = plain(scene)
        assert "times" not in values and len(repr(values)) < 2000, name
        assert list(values) == sorted(values) and from_plain(Scene, values) == scene
        assert from_plain(Scene, values).times == scene.times
    text = (ROOT / "workflow" / "rules" / "simulate.smk").read_text()
    assert "spec=lambda w: plain(cc.scene(config, w.scene))" in text and "resolved_scene" not in text


def test_cli_run_defaults_to_its_own_folder():
    from cradle.pipeline.cli.run import RUN_OUT

    assert cli.parser().parse_args(["run", "tw"]).out == RUN_OUT != "results"


def test_progress_lines_give_eta_and_estimate(caplog):
    import logging

    from cradle.pipeline.runner import Progress

    est = budget.spec_estimate(_scene(N=200, t_end=1e5, store=Store(snapshots=[])), "long")
    p = Progress("exact long", every=0.0, estimate=est)
    with caplog.at_level(logging.INFO, logger="cradle"):
        time.sleep(0.01)
        p(10.0, 100.0)
        p(100.0, 100.0)
    lines = [r.getMessage() for r in caplog.records]
    assert lines[0].startswith("exact long: scenes.long: estimated peak memory") and "about" in lines[0]
    assert "(10.0%)" in lines[1] and "ETA " in lines[1] and "estimated" in lines[1] and "in all" in lines[1]
    assert "(100.0%)" in lines[2] and "done" in lines[2]


def test_every_figure_rule_keeps_its_previous_figure_on_failure():
    """Figure outputs are flagged update(): Snakemake backs them up and restores them if the job fails."""
    import re

    for path in sorted((ROOT / "workflow" / "rules").glob("*.smk")):
        for m in re.finditer(r"^\s+(pdf|png)=(.*)$", path.read_text(), re.M):
            assert m.group(2).startswith("update("), f"{path.name}: {m.group(0).strip()}"


def test_flipped_byte_in_a_group_of_a_tree_is_detected(tmp_path, capsys):
    """An analysis file is a tree of netCDF groups: every variable of every group is checksummed, read
    back bitwise by open_tree, and one flipped byte in a child group stops open_tree, verify_file and
    `cradle describe` with one line."""
    from cradle.analyses.mi_statistics import VARIABLES

    rng = np.random.default_rng(5)
    ratio = rng.random((1, 2, 3, 4, 64))
    root = {"fraction_unstable": rng.random((1, 2, 3)), "threshold": rng.random((1, 2))}
    tree = io.make_tree({"/": (root, {"N": [200], "model": [0, 1], "q": [1.4, 1.5, 1.6]}),
                         "/runs": ({"ratio": ratio}, {"seed": np.arange(4), "t": 0.5 * np.arange(64)})},
                        VARIABLES, title="a tree")
    path = tmp_path / "results" / "mi-statistics" / "mi-statistics.nc"
    io.write_netcdf(tree, path)
    with netCDF4.Dataset(path) as nc:
        assert all(v.filters()["fletcher32"] for g in (nc, nc["runs"]) for v in g.variables.values())
    back = io.open_tree(path)
    assert back["runs"]["ratio"].values.tobytes() == ratio.tobytes()
    assert back["threshold"].values.tobytes() == root["threshold"].tobytes()
    assert io.verify_file(path) == []
    _flip_in_data(path, ratio)
    for reader in (io.open_tree, io.verify_file):
        with pytest.raises(io.DamagedOutput) as err:
            reader(path)
        assert "\n" not in str(err.value)
        assert "snakemake --force results/mi-statistics/mi-statistics.nc" in str(err.value)
    assert cli.main(["describe", str(path)]) == 2
    assert _one_line(capsys.readouterr().err)


def test_empty_variable_is_not_reported_unprotected(tmp_path):
    """A variable of length 0 (an analysis's reduced form with no kicks, say) has no data to checksum:
    cradle verify does not list it as written before checksums; the others still are checksummed."""
    ds = xr.Dataset({"a": ("k", np.zeros(0)), "b": ("m", np.arange(3.0))})
    io.write_netcdf(ds, tmp_path / "e.nc")
    assert io.verify_file(tmp_path / "e.nc") == []
