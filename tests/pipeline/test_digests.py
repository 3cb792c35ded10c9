"""An edit made through the netCDF library (HDF5 recomputes Fletcher-32 as it writes; global attributes carry no
checksum) is refused by every reader against the digest recorded beside the file (cradle.data.digests): one line
naming the file, what differs and the rebuild. A fresh file verifies clean; a write killed between the sidecar and
the file keeps the old file readable."""
from __future__ import annotations

import copy
import os
import shutil
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import xarray as xr
import yaml

from cradle.data import digests, io
from cradle.data.io import DamagedOutput, open_dataset, open_tree, verify_file, write_datatree, write_netcdf
from cradle.pipeline import cli, config as cc, layout
from cradle.pipeline.identity import job_expectations, open_checked
from cradle.pipeline.outputs import load_inputs, open_scene

TW = {"N": 20, "bc": "periodic", "t_end": 5.0, "store": {"every": 1.0}}
CONFIG = {
    "defaults": {"alpha": 1.5, "exact": {"method": "srkn6c"}, "dps": {"method": "dop853_numba", "rtol": 1e-9}},
    "map": {"m": {"box": 0.1, "iterations": 20, "starts": [[0.0, 1.0e-3]]}},
    "scenes": {"tw-weak": {**TW, "initial": {"kind": "travelling", "q": "pi/5", "omega_tw": 1.01}},
               "tw-moderate": {**TW, "initial": {"kind": "travelling", "q": "pi/5", "omega_tw": 1.05}}},
    "figures": {},
}


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """config.yaml and results/ with both scenes, written by `cradle run` (the stages the workflow's jobs call)."""
    work = tmp_path_factory.mktemp("digests")
    (work / "config.yaml").write_text(yaml.safe_dump(CONFIG, sort_keys=False))
    for name in ("tw-weak", "tw-moderate"):
        assert cli.main(["run", name, "--out", str(work / "results"), "--config", str(work / "config.yaml")]) == 0
    return work


@pytest.fixture
def work(built, tmp_path, monkeypatch):
    """A copy of the built folder, free to edit, as the working directory (the workflow's relative paths)."""
    shutil.copytree(built, tmp_path / "w")
    monkeypatch.chdir(tmp_path / "w")
    return tmp_path / "w"


def _one_line(text: str) -> str:
    text = text.strip()
    assert "\n" not in text and "Traceback" not in text, text
    return text


def _refusals(work: Path, rel: str, capsys) -> dict[str, str]:
    """The line of every reader that opens ``rel``: open_scene, a job's input, a figure's, verify, describe."""
    out: dict[str, str] = {}
    scene = rel.split("/")[2] if rel.startswith("results/sim/") else None
    valid = cc.validate(copy.deepcopy(CONFIG))   # as the Snakefile hands it to the jobs
    readers = {"open_dataset": lambda: open_dataset(rel),
               "job input": lambda: open_checked(rel, job_expectations(valid))}
    if scene:
        readers["open_scene"] = lambda: open_scene(scene, root="results")
        readers["figure input"] = lambda: load_inputs({scene: "scenes"}, "results", config=valid)
    for name, read in readers.items():
        with pytest.raises(DamagedOutput) as err:
            read()
        out[name] = _one_line(str(err.value))
    capsys.readouterr()
    assert cli.main(["verify", "results"]) == 1
    lines = capsys.readouterr().out.splitlines()
    out["verify"] = _one_line("\n".join(line for line in lines if line.startswith("DAMAGED")))
    assert cli.main(["describe", rel]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    out["describe"] = _one_line(captured.err)
    return out


def test_a_fresh_build_verifies_clean_every_file_with_its_digest(work, capsys):
    files = sorted((work / "results").rglob("*.nc"))
    assert files and all(digests.sidecar(p).is_file() for p in files)
    assert cli.main(["verify", "results"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[-1] == f"{len(files)} files checked: {len(files)} verified, 0 without checksums, 0 to rebuild", out
    assert cli.main(["describe", "results/sim/tw-weak/exact.nc"]) == 0
    assert "values and attributes as written (recorded in .exact.nc.digest)" in capsys.readouterr().out


def test_values_edited_through_netcdf4_are_refused_by_every_reader(work, capsys):
    rel = "results/sim/tw-moderate/exact.nc"
    with netCDF4.Dataset(rel, "a") as d:
        d["x"][2, :] *= 3                      # HDF5 recomputes the chunk's Fletcher-32: its own check passes
    for reader, line in _refusals(work, rel, capsys).items():
        assert rel in line and "edited since it was written: variable x changed" in line, (reader, line)
        assert f"rebuild it: snakemake --force {rel}" in line, (reader, line)


@pytest.mark.parametrize("rel, key, value", [
    ("results/initial/tw-weak.nc", "a", 1.0),                   # the amplitude theorem1 reads
    ("results/sim/tw-moderate/exact.nc", "energy_drift", 0.0),  # the drift describe prints
])
def test_a_global_attribute_edited_through_netcdf4_is_refused_by_every_reader(work, capsys, rel, key, value):
    with netCDF4.Dataset(rel, "a") as d:
        d.setncattr(key, value)
    for reader, line in _refusals(work, rel, capsys).items():
        assert rel in line and f"global attribute {key} changed" in line, (reader, line)
        assert f"rebuild it: snakemake --force {rel}" in line, (reader, line)


def test_an_added_attribute_and_a_variable_attribute_are_named(work):
    rel = "results/sim/tw-weak/dps.nc"
    with netCDF4.Dataset(rel, "a") as d:
        d["x"].units = "m"
        d.note = "checked by hand"
    with pytest.raises(DamagedOutput) as err:
        verify_file(rel)
    assert "attribute units of variable x changed" in str(err.value)
    assert "global attribute note added" in str(err.value)


def test_a_file_copied_without_its_digest_over_another_is_refused(work):
    """A whole other file in its place (check=False skips the identity, not the digest)."""
    shutil.copy2("results/sim/tw-moderate/exact.nc", "results/sim/tw-weak/exact.nc")
    with pytest.raises(DamagedOutput, match="results/sim/tw-weak/exact.nc: edited since it was written"):
        open_scene("tw-weak", root="results", check=False)


def test_a_file_without_a_digest_is_read_and_noted(work, capsys):
    """Written before digests (or copied alone): readable, and verify says it is not fully protected."""
    os.remove(digests.sidecar("results/metrics/tw-weak.nc"))
    assert open_dataset("results/metrics/tw-weak.nc").sizes["t"] > 0
    assert cli.main(["verify", "results"]) == 0
    notes = [line for line in capsys.readouterr().out.splitlines() if line.startswith("note")]
    assert len(notes) == 1 and "results/metrics/tw-weak.nc: readable, but no digest recorded" in notes[0]


@pytest.mark.parametrize("record", [b"", b"garbage", b"{}", b'{"format": "%s"}', b"[1, 2]"])
def test_a_damaged_digest_record_is_refused_by_every_reader(work, capsys, record):
    """A record that is there but is no record (truncated, overwritten, another format) cannot vouch for its file:
    refused, not taken as "no digest" (which would let an edit through unnoticed)."""
    rel = "results/sim/tw-moderate/exact.nc"
    digests.sidecar(rel).write_bytes(record.replace(b"%s", digests.FORMAT.encode()))
    for reader, line in _refusals(work, rel, capsys).items():
        assert rel in line and "its digest record .exact.nc.digest is damaged" in line, (reader, line)
        assert f"rebuild it: snakemake --force {rel}" in line, (reader, line)


def _small() -> xr.Dataset:
    return xr.Dataset({"x": (("t", "n"), np.arange(12.0).reshape(4, 3))}, attrs={"a": 2.0})


def test_a_write_killed_between_the_digest_and_the_rename_keeps_the_old_file_readable(tmp_path, monkeypatch):
    path = tmp_path / "f.nc"
    write_netcdf(_small(), path)
    before = path.read_bytes()
    real = os.replace

    def killed(src, dst):
        if Path(dst) == path:
            raise KeyboardInterrupt
        return real(src, dst)

    monkeypatch.setattr(os, "replace", killed)
    with pytest.raises(KeyboardInterrupt):
        write_netcdf(_small() * 2, path)
    monkeypatch.undo()
    assert path.read_bytes() == before and len(digests.read_record(path)["previous"]) == 1
    assert np.array_equal(open_dataset(path)["x"].values, _small()["x"].values)   # the digest it replaced
    for k in range(3):   # failed reruns, the backup put back each time: still the file written here
        with monkeypatch.context() as m:
            m.setattr(os, "replace", killed)
            with pytest.raises(KeyboardInterrupt):
                write_netcdf(_small() * (3 + k), path)
    assert path.read_bytes() == before and open_dataset(path).attrs["a"] == 2.0


def test_an_edit_in_a_group_is_named_with_its_group(tmp_path):
    path = tmp_path / "tree.nc"
    tree = xr.DataTree.from_dict({"/": xr.Dataset(attrs={"title": "t"}),
                                  "/waves": xr.Dataset({"omega": ("k", np.array([1.0, 2.0]))})})
    write_datatree(tree, path)
    assert float(open_tree(path)["waves"]["omega"][1]) == 2.0
    with netCDF4.Dataset(path, "a") as d:
        d["waves"]["omega"][1] = 5.0
    with pytest.raises(DamagedOutput) as err:
        open_tree(path)
    assert _one_line(str(err.value)).endswith("edited since it was written: variable omega of group waves changed "
                                              "(against the digest recorded in .tree.nc.digest); rebuild it: rerun "
                                              "the command that wrote it (see docs/recovery.md)")


def test_the_digest_leaves_every_stored_value_as_written(tmp_path):
    """The record is beside the file: the file holds what xarray wrote, values and attributes."""
    path = tmp_path / "f.nc"
    write_netcdf(_small(), path)
    with netCDF4.Dataset(path) as d:
        assert "digest" not in " ".join(d.ncattrs()) and np.array_equal(d["x"][:], _small()["x"].values)
    assert layout.ROOT == "results"


def test_the_values_digested_from_memory_are_those_read_back(tmp_path):
    """A writer digests its numeric arrays from memory (no read back): the file read raw gives the same digests."""
    ds = xr.Dataset({"f8": (("t", "n"), np.array([[1.0, np.nan], [-0.0, np.inf]])),
                     "f4": ("t", np.array([1.5, np.nan], dtype=np.float32)),
                     "i8": ("t", np.array([-3, 2**40])), "i4": (("t", "n", "k"), np.ones((2, 2, 3), dtype=np.int32)),
                     "u1": ("n", np.array([0, 255], dtype=np.uint8)), "s": ((), 2.5), "names": ("n", ["a", "bc"])},
                    coords={"t": np.array([0.0, 0.5]), "n": np.arange(2)}, attrs={"a": 1.0})
    path = write_netcdf(ds, tmp_path / "f.nc")
    with netCDF4.Dataset(path) as nc:
        assert digests.items(nc) == digests.read_record(path)["items"]
    assert sorted(io.stored_digests(ds, io.encoding_of(ds))) == ["f4", "f8", "i4", "i8", "n", "t", "u1"]


#: an attribute of every kind a writer may hand over: those whose read-back form is known are digested as handed,
#: the others (bytes, a string with NUL, a list of strings, a name xarray or netCDF4 rewrites) read back
EVERY_KIND = {"empty": "", "ascii": "abc", "unicode": "é∂", "nul": "a\x00b", "blanks": "ab  ", "int": 1, "neg": -1,
              "big": 2**62, "float": 1.5, "nan": float("nan"), "inf": -float("inf"), "f4": np.float32(1.5),
              "i4": np.int32(3), "i1": np.int8(3), "u1": np.uint8(3), "u8": np.uint64(2**63),
              "array": np.array([1.0, 2.0]), "one": np.array([1.0]), "none": np.array([], float), "list": [1.0, 2.0],
              "ints": [1, 2], "mixed": [1, 2.5], "single": (1.0,), "strings": ["a", "b"], "string": ["a"],
              "i2": np.array([1, 2], dtype=np.int16), "bytes": b"bytes", "i8one": np.array([5]), "long": "x" * 10**5,
              "coordinates": "t", "scale_factor": 1.0, "_Custom": 2.0, digests.checksums.ATTR: "stale"}


def _every_kind() -> xr.Dataset:
    attrs = {k: v for k, v in EVERY_KIND.items() if k != "coordinates"}
    return xr.Dataset({"x": (("t", "n"), np.arange(6.0).reshape(3, 2), dict(attrs)),
                       "k": ("n", np.array([1, 2], dtype=np.int32), dict(attrs)),
                       "when": ("t", np.array(["2026-01-01", "2026-01-02", "2026-01-03"], dtype="datetime64[ns]")),
                       "flag": ("t", np.array([True, False, True])), "s": ((), 2.5, {"units": "1"}),
                       "names": ("n", ["a", "bc"], {"long_name": "names"})},
                      coords={"t": np.array([0.0, 0.5, 1.0]), "n": np.arange(2), "label": ("n", [10.0, 20.0])},
                      attrs=attrs)


def test_attributes_digested_as_handed_over_are_those_every_reader_reads_back(tmp_path, monkeypatch):
    """A writer digests the attributes it hands to netCDF4 where their read-back form is known and reads the others
    back: the record equals the file's digest read cold, for attributes of every kind, on numeric, time, boolean,
    string and 0-d variables, a coordinate xarray lists in `coordinates`, in a flat file and in a tree's groups."""
    monkeypatch.delenv(io.SELF_CHECK_ENV)   # the comparison is made here
    ds = _every_kind()
    handed, names = io.stored_attributes(ds)
    assert names == {"": list(ds.attrs)}
    assert {"@ascii", "@one", "x@array", "k@u8", "@mixed", "x@coordinates"} <= set(handed)   # not read back
    assert not {"@nul", "@strings", "@bytes", "x@scale_factor", "x@_Custom", "when@units", "names@long_name",
                f"x@{digests.checksums.ATTR}"} & set(handed)
    path = write_netcdf(ds, tmp_path / "f.nc")
    tree = write_datatree(xr.DataTree.from_dict({"/": xr.Dataset(attrs=ds.attrs), "/g": ds.drop_vars("label")}),
                          tmp_path / "tree.nc")
    for p in (path, tree):
        with netCDF4.Dataset(p) as nc:
            assert digests.items(nc) == digests.read_record(p)["items"]
        verify_file(p)


def test_a_writer_whose_digest_is_not_the_file_s_is_caught_by_the_self_check(tmp_path, monkeypatch):
    """The suite runs with the self-check on (tests/conftest.py): a digest of an attribute made wrong is an error
    at the write, and nothing is written."""
    assert os.environ.get(io.SELF_CHECK_ENV) == "1"
    real = digests.stored_attribute
    monkeypatch.setattr(digests, "stored_attribute", lambda k, v: "0" * 64 if k == "a" else real(k, v))
    with pytest.raises(io.DigestDisagrees, match="differs from the file's at @a$"):
        write_netcdf(_small(), tmp_path / "f.nc")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("value", [1.5, np.float64(-0.0), float("nan"), 7, np.int64(-3), 2**63 - 1, -2**63])
def test_an_attribute_s_shortcut_digest_is_the_general_one(value):
    """A float or int64 attribute is digested without making an array: the same bytes as the array's."""
    assert digests._attribute(value) == digests._attribute(np.asarray(value))


def test_a_record_s_text_is_json_s_own(tmp_path):
    """The record is written without serialising its items twice: the text json.dumps gives, sorted."""
    import json

    parts = {"@a": "1" * 64, "x": "2" * 64, 'q"uote\\': "é"}
    text = digests._record_text("f.nc", parts, ["3" * 64])
    assert text == json.dumps({"format": digests.FORMAT, "file": "f.nc", "sha256": digests.whole(parts),
                               "previous": ["3" * 64], "items": parts}, sort_keys=True)
