"""Nothing overwritten that another job owns: `cradle extend`, `cradle run` and `cradle animate` refuse, in one line
and before writing anything, a destination that is a workflow output of another scene or rule, or an existing file
they did not make; `--overwrite` writes anyway (cradle.pipeline.destinations)."""
from __future__ import annotations

import shutil
from pathlib import Path

import pytest
import yaml

from cradle.data import digests
from cradle.pipeline import cli
from cradle.pipeline.destinations import workflow_output

TW = {"N": 20, "bc": "periodic", "t_end": 5.0, "store": {"every": 1.0}}
CONFIG = {
    "defaults": {"alpha": 1.5},
    "map": {"m": {"box": 0.1, "iterations": 20, "starts": [[0.0, 1.0e-3]]}},
    "scenes": {"tw-weak": {**TW, "initial": {"kind": "travelling", "q": "pi/5", "omega_tw": 1.01}},
               "tw-moderate": {**TW, "initial": {"kind": "travelling", "q": "pi/5", "omega_tw": 1.05}}},
    "figures": {},
}


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    work = tmp_path_factory.mktemp("destinations")
    (work / "config.yaml").write_text(yaml.safe_dump(CONFIG, sort_keys=False))
    for name in ("tw-weak", "tw-moderate"):
        assert cli.main(["run", name, "--out", str(work / "results"), "--config", str(work / "config.yaml")]) == 0
    return work


@pytest.fixture
def work(built, tmp_path, monkeypatch):
    shutil.copytree(built, tmp_path / "w")
    monkeypatch.chdir(tmp_path / "w")
    return tmp_path / "w"


def _snapshot(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def _refused(argv, capsys) -> str:
    """Run the command: exit 2, nothing on stdout, one line on stderr."""
    capsys.readouterr()
    assert cli.main(argv) == 2
    captured = capsys.readouterr()
    err = captured.err.strip()
    assert "\n" not in err and "Traceback" not in err and err.startswith("cradle: error: refusing to write "), err
    return err


def test_extend_out_onto_another_scenes_run_is_refused_and_it_is_kept(work, capsys):
    before = _snapshot(work)
    err = _refused(["extend", "results/sim/tw-weak/exact.nc", "--t-end", "8", "--out",
                    "results/sim/tw-moderate/exact.nc"], capsys)
    assert err == ("cradle: error: refusing to write results/sim/tw-moderate/exact.nc: it is the exact run of scene "
                   "'tw-moderate' in the workflow's results (its rule writes it; snakemake --force "
                   "results/sim/tw-moderate/exact.nc rebuilds it); give --overwrite to replace it anyway")
    assert _snapshot(work) == before                        # tw-moderate's run is there, nothing written


def test_extend_out_onto_a_file_it_did_not_make_is_refused(work, capsys):
    Path("notes.nc").write_text("my notes")
    before = _snapshot(work)
    err = _refused(["extend", "results/sim/tw-weak/exact.nc", "--t-end", "8", "--out", "notes.nc"], capsys)
    assert "notes.nc: it exists and holds not a cradle netCDF file, not exact 'tw-weak'" in err
    assert "--overwrite" in err and _snapshot(work) == before


def test_extend_may_replace_its_own_file_and_overwrite_replaces_any(work, capsys):
    args = ["extend", "results/sim/tw-weak/exact.nc", "--t-end", "8", "--out", "longer.nc"]
    assert cli.main(args) == 0
    assert cli.main(args) == 0                              # an exact run of tw-weak: its own product
    Path("notes.nc").write_text("my notes")
    assert cli.main(["extend", "results/sim/tw-weak/exact.nc", "--t-end", "8", "--out", "notes.nc",
                     "--overwrite"]) == 0
    assert cli.main(["verify", "notes.nc"]) == 0 and digests.read_record("notes.nc") is not None


def test_run_into_a_folder_holding_another_scenes_file_is_refused(work, capsys):
    shutil.copytree("results", "runs")
    shutil.copy2("runs/sim/tw-moderate/exact.nc", "runs/sim/tw-weak/exact.nc")
    before = _snapshot(work)
    err = _refused(["run", "tw-weak", "--out", "runs"], capsys)
    assert err == ("cradle: error: refusing to write runs/sim/tw-weak/exact.nc: it exists and holds exact "
                   "'tw-moderate', not exact 'tw-weak' that cradle run writes; give --overwrite to replace it")
    assert _snapshot(work) == before
    assert cli.main(["run", "tw-weak", "--out", "runs", "--overwrite"]) == 0
    assert cli.main(["run", "tw-weak", "--out", "runs"]) == 0   # its own files now: rerun freely


def test_animate_onto_another_scenes_movie_or_a_foreign_file_is_refused(work, capsys):
    Path("results/movies").mkdir()
    Path("results/movies/tw-moderate.mp4").write_bytes(b"the workflow's movie")
    Path("talk.mp4").write_bytes(b"my talk")
    before = _snapshot(work)
    err = _refused(["animate", "tw-weak", "--out", "results/movies/tw-moderate.mp4"], capsys)
    assert "results/movies/tw-moderate.mp4: it is the workflow's movie 'tw-moderate'" in err
    err = _refused(["animate", "tw-weak", "--out", "talk.mp4"], capsys)
    assert err == ("cradle: error: refusing to write talk.mp4: it exists and cradle animate did not make it; give "
                   "--overwrite to replace it")
    assert _snapshot(work) == before


@pytest.mark.parametrize("argv, said", [
    (["extend", "results/sim/tw-weak/exact.nc", "--t-end", "8", "--out", "notes.nc/longer.nc"],
     "cannot write notes.nc/longer.nc: notes.nc is a file, not a folder"),
    (["extend", "results/sim/tw-weak/exact.nc", "--t-end", "8", "--out", "notes.nc/a/b/longer.nc", "--overwrite"],
     "cannot write notes.nc/a/b/longer.nc: notes.nc is a file, not a folder"),
    (["extend", "results/sim/tw-weak/exact.nc", "--t-end", "8", "--out", "results"],
     "cannot write results: it is a folder"),
    (["run", "tw-weak", "--out", "notes.nc"], "cannot write notes.nc/initial/tw-weak.nc: notes.nc is a file, not a "
                                              "folder"),
    (["animate", "tw-weak", "--out", "notes.nc/talk.mp4"],
     "cannot write notes.nc/talk.mp4: notes.nc is a file, not a folder"),
])
def test_a_destination_that_cannot_be_made_is_one_line_before_any_work(work, capsys, argv, said):
    """A file where a folder must be (or a folder where the file goes) is said before the run, not by the write
    at its end, even with --overwrite."""
    Path("notes.nc").write_text("my notes")
    before = _snapshot(work)
    capsys.readouterr()
    assert cli.main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "Traceback" not in err and err == f"cradle: error: {said}", err
    assert _snapshot(work) == before


def test_workflow_outputs_are_found_by_their_path(tmp_path):
    root = tmp_path / "results"
    assert workflow_output(root / "sim" / "a" / "exact.nc") == ("exact", {"scene": "a"})
    assert workflow_output(root / "figures" / "plot4-5.png") == ("figure", {"label": "plot4-5", "ext": "png"})
    assert workflow_output(root / "sim" / "a" / "exact-t700.nc") is None      # an extended run written there by --out
    assert workflow_output(tmp_path / "cradle-runs" / "sim" / "a" / "exact.nc") is None
