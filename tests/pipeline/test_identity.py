"""Every reader checks what it reads (cradle.pipeline.identity): a file that is another scene's, or was made
from other parameters than the config resolves to now, is refused by open_scene and the figures' loader and
reported by `cradle verify` and `cradle describe`, one line naming the file, what it holds, what was
expected and the command that rebuilds it; a file that matches passes, and one outside the layout is not
checked."""
from __future__ import annotations

import copy
import shutil
import time
from pathlib import Path

import pytest
import yaml

from cradle.data import digests
from cradle.data.io import open_dataset, open_tree, write_netcdf
from cradle.data.provenance import identify, params_hash
from cradle.pipeline import cli, config as cc, layout
from cradle.pipeline.identity import Expectations, WrongOutput, locate
from cradle.pipeline.outputs import load_inputs, open_scene
from cradle.specs.declare import plain

TW = {"N": 20, "bc": "periodic", "t_end": 5.0, "store": {"every": 1.0}}
CONFIG = {
    "defaults": {"alpha": 1.5, "exact": {"method": "srkn6c"}, "dps": {"method": "dop853_numba", "rtol": 1e-9}},
    "map": {"m": {"box": 0.1, "iterations": 20, "starts": [[0.0, 1.0e-3]]}},
    "homoclinic": {"h": {"guess": "bond", "N": 20, "bc": "periodic"}},
    "scenes": {"tw-weak": {**TW, "initial": {"kind": "travelling", "q": "pi/5", "omega_tw": 1.01}},
               "tw-moderate": {**TW, "initial": {"kind": "travelling", "q": "pi/5", "omega_tw": 1.05}}},
    "figures": {},
}


def _write_config(folder: Path, config: dict) -> Path:
    path = folder / "config.yaml"
    path.write_text(yaml.safe_dump(config, sort_keys=False))
    return path


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """A workflow folder: config.yaml and results/ with both scenes and the map entry, built by `cradle run`
    (the stages the workflow's jobs call)."""
    work = tmp_path_factory.mktemp("identity")
    config = _write_config(work, CONFIG)
    for name in ("tw-weak", "tw-moderate", "m"):
        assert cli.main(["run", name, "--out", str(work / "results"), "--config", str(config)]) == 0
    return work


@pytest.fixture
def work(built, tmp_path):
    """A copy of the built folder, free to damage."""
    shutil.copytree(built, tmp_path / "w")
    return tmp_path / "w"


def _verify(work: Path, capsys, *extra) -> tuple[int, list[str]]:
    capsys.readouterr()
    code = cli.main(["verify", str(work / "results"), "--config", str(work / "config.yaml"), *extra])
    return code, capsys.readouterr().out.splitlines()


def _one_line(text: str) -> bool:
    return "\n" not in text.strip() and "Traceback" not in text


def test_files_name_themselves(built):
    """Every file a scene's job writes says its kind, its name and its parameter hash."""
    cfg = cc.validate(CONFIG)
    want = params_hash(plain(cc.scene(cfg, "tw-weak")))
    for part, path in layout.scene_paths("tw-weak", built / "results").items():
        attrs = open_dataset(path).attrs
        assert (attrs["cradle_kind"], attrs["cradle_name"], attrs["params_sha256"]) == (part, "tw-weak", want)
    assert open_dataset(built / "results" / "map" / "m.nc").attrs["cradle_kind"] == "map"


def _copy(source, target) -> None:
    """A faithful copy: the file and the record of its digest (cradle.data.digests), so only its identity is wrong."""
    shutil.copy2(source, target)
    shutil.copy2(digests.sidecar(source), digests.sidecar(target))


def test_another_scenes_file_is_refused_naming_both(work, capsys):
    """(a) tw-moderate's exact.nc copied over tw-weak's (checksums valid, mtime kept)."""
    root = work / "results"
    target = Path(layout.path("exact", root, scene="tw-weak"))
    _copy(layout.path("exact", root, scene="tw-moderate"), target)
    with pytest.raises(WrongOutput) as err:
        open_scene("tw-weak", root=root)
    text = str(err.value)
    assert _one_line(text) and text.startswith(f"{target} holds scene 'tw-moderate' (params ")
    assert "expected scene 'tw-weak' (params " in text and f"from {work / 'config.yaml'}" in text
    assert "rebuild it: snakemake --force results/sim/tw-weak/exact.nc" in text
    with pytest.raises(WrongOutput, match="holds scene 'tw-moderate'.*expected scene 'tw-weak'"):
        load_inputs({"tw-weak": "scenes"}, root, config=yaml.safe_load((work / "config.yaml").read_text()))
    code, out = _verify(work, capsys)
    mismatched = [line for line in out if line.startswith("MISMATCH")]
    assert code == 1 and len(mismatched) == 1, out
    assert "sim/tw-weak/exact.nc holds scene 'tw-moderate'" in mismatched[0]
    assert "expected scene 'tw-weak'" in mismatched[0]
    assert cli.main(["describe", str(target), "--config", str(work / "config.yaml")]) == 0  # says it, goes on
    described = capsys.readouterr().out
    assert "identity" in described and "MISMATCH" in described and "holds scene 'tw-moderate'" in described
    assert open_scene("tw-weak", root=root, check=False).attrs["exact_scene"] == "tw-moderate"


def test_another_scenes_file_beside_this_paths_digest_is_described_by_its_identity(work, capsys):
    """tw-moderate's exact.nc copied over tw-weak's without its digest (the probe's copy: tw-weak's sidecar stays):
    describe says whose file it is and goes on, rather than refusing it as edited against the sidecar of the file
    the path held; an edit of tw-weak's own file is still refused by the digest."""
    root = work / "results"
    target = Path(layout.path("exact", root, scene="tw-weak"))
    saved = target.read_bytes()
    shutil.copy2(layout.path("exact", root, scene="tw-moderate"), target)
    capsys.readouterr()
    assert cli.main(["describe", str(target), "--config", str(work / "config.yaml")]) == 0
    described = capsys.readouterr().out
    assert "holds scene 'tw-moderate'" in described and "not compared: another entry's file" in described
    target.write_bytes(saved)
    import netCDF4

    with netCDF4.Dataset(target, "a") as nc:
        nc.setncattr("a", 1.0)
    assert cli.main(["describe", str(target), "--config", str(work / "config.yaml")]) == 2
    assert "edited since it was written: global attribute a changed" in capsys.readouterr().err


def test_a_file_of_another_kind_is_refused(work):
    """tw-weak's dps.nc copied over its exact.nc: same scene, same parameters, not an exact run."""
    root = work / "results"
    _copy(layout.path("dps", root, scene="tw-weak"), layout.path("exact", root, scene="tw-weak"))
    with pytest.raises(WrongOutput, match="holds the DpS run of scene 'tw-weak'.*expected the exact run"):
        open_scene("tw-weak", root=root)


def test_changed_config_without_rebuild_names_every_stale_file(work, capsys):
    """(b) issue 23: a scene changed and rebuilt, then the config changed back without a rebuild (here: the
    config changed after the build): verify names the scene's four files and no other; open_scene refuses
    them unless check=False."""
    changed = copy.deepcopy(CONFIG)
    changed["scenes"]["tw-weak"]["initial"]["omega_tw"] = 1.02
    _write_config(work, changed)
    code, out = _verify(work, capsys)
    mismatched = sorted(line.split(" ", 2)[1] for line in out if line.startswith("MISMATCH"))
    root = work / "results"
    assert code == 1 and mismatched == sorted(map(str, layout.scene_paths("tw-weak", root).values())), out
    assert all("holds scene 'tw-weak' (params" in line and "expected scene 'tw-weak' (params" in line
               and f": initial.omega_tw 1.01 in the file, 1.02 in {work / 'config.yaml'}; rebuild it" in line
               for line in out if line.startswith("MISMATCH"))
    with pytest.raises(WrongOutput, match=r"sim/tw-weak/exact\.nc holds scene 'tw-weak' \(params [0-9a-f]{12}\)"):
        open_scene("tw-weak", root=root)
    assert open_scene("tw-moderate", root=root)["x"].sizes["model"] == 2     # untouched scene: fine
    ds = open_scene("tw-weak", root=root, check=False)                        # the user's own risk
    assert float(ds.attrs["omega_tw"]) == 1.01


def test_matching_files_pass(built, capsys):
    """(c) a tree built from the config it is checked against: nothing to say, exit 0."""
    code, out = _verify(built, capsys)
    assert code == 0 and not [line for line in out if line.startswith(("MISMATCH", "DAMAGED"))], out
    root = built / "results"
    assert open_scene("tw-weak", root=root)["x"].sizes["model"] == 2
    data = load_inputs({"tw-weak": "scenes", "m": "map"}, root, config=yaml.safe_load(
        (built / "config.yaml").read_text()))
    assert data["tw-weak"]["exact"].attrs["cradle_name"] == "tw-weak"
    assert cli.main(["describe", str(root / "sim" / "tw-weak" / "exact.nc"), "--config",
                     str(built / "config.yaml")]) == 0
    line = next(li for li in capsys.readouterr().out.splitlines() if li.strip().startswith("identity"))
    assert "scene 'tw-weak', params" in line and "expects" in line and "MISMATCH" not in line


def test_without_config_or_outside_the_layout_nothing_is_checked(work, tmp_path, capsys):
    """No config.yaml beside the results: open_scene checks nothing; files under cradle-runs/ (or failed/)
    have no expectation, so verify says nothing of them even when they are another scene's."""
    root = work / "results"
    _copy(layout.path("exact", root, scene="tw-moderate"), layout.path("exact", root, scene="tw-weak"))
    runs = work / "cradle-runs"
    shutil.copytree(root, runs)
    (work / "config.yaml").rename(work / "elsewhere.yaml")
    assert open_scene("tw-weak", root=root).attrs["exact_scene"] == "tw-moderate"  # no config: not checked
    with pytest.raises(WrongOutput):
        open_scene("tw-weak", root=root, config=work / "elsewhere.yaml")           # given one: checked
    cfg = cc.read_yaml(work / "elsewhere.yaml")
    assert Expectations(cfg, root).expected(runs / "sim" / "tw-weak" / "exact.nc") is None
    assert Expectations(cfg, root).expected(root / "failed" / "sim" / "tw-weak" / "exact.nc") is None
    assert Expectations(cfg, root).expected(root / "sim" / "gone" / "exact.nc") is None   # no such scene
    capsys.readouterr()
    assert cli.main(["verify", str(runs), "--config", str(work / "elsewhere.yaml")]) == 0
    assert "MISMATCH" not in capsys.readouterr().out


def test_layout_inverted_for_every_kind(tmp_path):
    """Every netCDF kind of the layout, analyses and their batches included, maps back to its kind and names."""
    root = tmp_path / "results"
    cases = {layout.path("homoclinic", root, name="h"): ("homoclinic", {"name": "h"}),
             layout.path("initial", root, scene="s"): ("initial", {"scene": "s"}),
             layout.path("dps", root, scene="s"): ("dps", {"scene": "s"}),
             layout.analysis_output("floquet", "full", "reduced", root): ("analysis", {"analysis": "floquet",
                                                                                       "form": "full"}),
             layout.analysis_output("paper-checks", "full", "full", root): ("analysis", {"analysis": "paper-checks",
                                                                                         "form": "full"}),
             layout.path("analysis-batch", root, analysis="mi-statistics", form="reduced", key="N200-exact-0"):
                 ("analysis-batch", {"analysis": "mi-statistics", "form": "reduced", "key": "N200-exact-0"})}
    for path, want in cases.items():
        assert locate(path, root) == want, path
    for path in (root / "figures" / "plot4-5.nc", root / "floquet" / "other" / "floquet.nc", tmp_path / "x.nc"):
        assert locate(path, root) is None, path


def test_analysis_outputs_and_batches_are_checked(tmp_path):
    """An analysis's file and a batch (named by the workflow's adapters, identify) against the form's spec."""
    cfg = cc.validate(CONFIG)
    root = tmp_path / "results"
    spec = cc.analysis_spec(cfg, "mi-statistics", "reduced")
    key = "N200-exact-0"
    batch_path = Path(layout.path("analysis-batch", root, analysis="mi-statistics", form="reduced", key=key))
    batch = identify(open_dataset(_tiny(tmp_path)), "analysis-batch", f"mi-statistics/{key}", params=plain(spec))
    assert batch.attrs["params_sha256"] == params_hash(plain(spec))   # a batch storing no parameters gets them
    Expectations(cfg, root).check(batch_path, batch)
    full = cc.analysis_spec(cfg, "mi-statistics", "full")
    with pytest.raises(WrongOutput, match="holds batch 'mi-statistics/N200-exact-0'"):  # a full-form batch
        Expectations(cfg, root).check(batch_path, {**batch.attrs, "params_sha256": params_hash(plain(full))})
    out_path = layout.analysis_output("paper-checks", "full", "full", root)
    ok = identify(open_dataset(_tiny(tmp_path)), "analysis", "paper-checks",
                  params=plain(cc.analysis_spec(cfg, "paper-checks", "full")))
    Expectations(cfg, root).check(out_path, ok)
    with pytest.raises(WrongOutput, match="holds analysis 'floquet'"):
        Expectations(cfg, root).check(out_path, {**ok.attrs, "cradle_name": "floquet"})
    tree_path = write_netcdf(ok, tmp_path / "tree.nc")
    assert open_tree(tree_path).attrs["cradle_kind"] == "analysis"


def _tiny(tmp_path: Path) -> Path:
    """A small netCDF file with no parameters of its own."""
    import numpy as np

    from cradle.data.io import make_dataset

    return write_netcdf(make_dataset({"x0": np.zeros(3)}, coords={"n": np.arange(3)}), tmp_path / "tiny.nc")


def test_check_costs_no_data_read(built):
    """The check reads attributes only: per file well under the cost of reading it (measured, reported)."""
    cfg = cc.validate(CONFIG)
    root = built / "results"
    files = sorted(root.rglob("*.nc"))
    expect = Expectations(cfg, root)
    for p in files:
        expect.expected(p)                      # the config resolved once per entry
    t0 = time.perf_counter()
    for _ in range(20):
        for p in files:
            assert expect.check_file(p) is None
    per_file = (time.perf_counter() - t0) / (20 * len(files))
    loaded = {p: open_dataset(p) for p in files}
    t0 = time.perf_counter()
    for _ in range(20):
        for p, ds in loaded.items():
            Expectations(cfg, root).check(p, ds)   # a reader's check: resolves its entry, compares attributes
    in_memory = (time.perf_counter() - t0) / (20 * len(files))
    print(f"identity check: {per_file * 1e3:.2f} ms per file from disk (attributes only), "
          f"{in_memory * 1e3:.2f} ms per opened file (entry resolved each time), {len(files)} files")
    assert per_file < 0.05 and in_memory < 0.05
