"""Every stored value is protected: the variables HDF5's Fletcher-32 filter cannot carry (0-d, strings,
empty) carry a recorded SHA-256 of their values (``checksum_sha256``, cradle.data.checksums), written
by every writer and compared by every reader (open_dataset, open_tree, verify_file, `cradle verify`,
`cradle describe`). An edited scalar or string is one DamagedOutput line naming the file, the variable
and the rebuild; a fresh file verifies with no note."""
from __future__ import annotations

import hashlib
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import xarray as xr

from cradle.data import checksums, io
from cradle.data.appending import Appender
from cradle.pipeline import cli

REL = "results/breather-interactions/breather-interactions.nc"


def _dataset() -> xr.Dataset:
    """Scalars, strings (a coordinate and a data variable) and arrays, as an analysis file holds them."""
    return xr.Dataset(
        {"merging_time_exact": ((), 223.0), "outcome_kicked": ((), np.int64(2)),
         "verdict": (("case",), np.array(["agrees", "disagrees: see loc1"], dtype=object)),
         "growth": (("case", "t"), np.arange(6.0).reshape(2, 3)), "none_kicked": (("kick",), np.zeros(0))},
        coords={"case": np.array(["loc1", "fini"], dtype=object), "t": [0.0, 0.5, 1.0]},
        attrs={"title": "a file with scalars and strings"})


def _one_line(text: str) -> bool:
    return len(text.strip().splitlines()) == 1


@pytest.fixture
def written(tmp_path) -> Path:
    path = tmp_path / REL
    io.write_netcdf(_dataset(), path)
    return path


def _edit(path: Path, name: str, value, group: str = "") -> None:
    """Overwrite a variable's values in place with netCDF4, as a user editing the file would."""
    with netCDF4.Dataset(path, "a") as nc:
        (nc[group] if group else nc)[name][...] = value


def test_fresh_file_verifies_with_no_note(written, capsys):
    """Every variable carries the filter or a recorded checksum; verify and describe say so, no note."""
    with netCDF4.Dataset(written) as nc:
        for name, var in nc.variables.items():
            assert checksums.has_filter(var) != (checksums.ATTR in var.ncattrs()), name
        assert checksums.ATTR in nc["merging_time_exact"].ncattrs() and checksums.ATTR in nc["verdict"].ncattrs()
    assert io.verify_file(written) == []
    assert cli.main(["verify", str(written.parents[1])]) == 0
    out = capsys.readouterr().out
    assert "note" not in out and "1 files checked: 1 verified, 0 without checksums, 0 to rebuild" in out, out
    assert cli.main(["describe", str(written)]) == 0
    out = capsys.readouterr().out
    assert "verified (every variable)" in out and "before checksums" not in out, out


@pytest.mark.parametrize(("name", "value", "says"), [
    ("merging_time_exact", 2230.0, "merging_time_exact: stored value does not match its checksum"),
    ("outcome_kicked", 3, "outcome_kicked: stored value does not match its checksum"),
    ("verdict", np.array(["agrees", "agrees"], dtype=object), "verdict: stored values do not match their checksum"),
    ("case", np.array(["loc1", "fin1"], dtype=object), "case: stored values do not match their checksum"),
])
def test_edited_scalar_or_string_is_refused_by_every_reader(written, capsys, name, value, says):
    """223 -> 2230 in merging_time_exact (the issue's probe), an outcome, a verdict string, a string
    coordinate: open_dataset, open_tree, verify_file, `cradle verify` and `cradle describe` refuse, one line."""
    _edit(written, name, value)
    for reader in (io.open_dataset, io.open_tree, io.verify_file):
        with pytest.raises(io.DamagedOutput) as err:
            reader(written)
        msg = str(err.value)
        assert msg == f"{written}: {says}; rebuild it: snakemake --force {REL} (see docs/recovery.md)", msg
    assert cli.main(["verify", str(written)]) == 1
    out = capsys.readouterr().out
    assert f"DAMAGED {written}: {says}" in out and "1 to rebuild" in out, out
    assert cli.main(["describe", str(written)]) == 2
    err = capsys.readouterr().err
    assert _one_line(err) and says in err, err


def test_edit_undone_reads_again(written):
    """The checksum is of the values: the original value written back verifies again."""
    _edit(written, "merging_time_exact", 2230.0)
    with pytest.raises(io.DamagedOutput):
        io.open_dataset(written)
    _edit(written, "merging_time_exact", 223.0)
    assert float(io.open_dataset(written)["merging_time_exact"]) == 223.0


def test_tree_with_groups_scalars_and_strings(tmp_path, capsys):
    """A DataTree: every group's scalars and strings recorded; a fresh file verifies with no note, reads
    back identical; an edited scalar in a child group is named by its path in the file."""
    child = xr.Dataset({"omega_exact": ((), 1.0625), "label": ((), "site breather"),
                        "names": (("k",), np.array(["a", "bb", ""], dtype=object)), "y": (("k",), [1.0, 2.0, 3.0])})
    tree = xr.DataTree.from_dict({"/": _dataset(), "/scenes": child, "/scenes/deep": xr.Dataset({"n": ((), 7)})})
    path = tmp_path / "results" / "t" / "t.nc"
    io.write_netcdf(tree, path)
    assert io.verify_file(path) == []
    back = io.open_tree(path)
    assert back.identical(tree)
    assert cli.main(["verify", str(path.parent)]) == 0
    assert "note" not in capsys.readouterr().out
    _edit(path, "omega_exact", 1.5, group="scenes")
    for reader in (io.open_tree, io.verify_file):
        with pytest.raises(io.DamagedOutput, match=r"t\.nc: scenes/omega_exact: stored value does not match"):
            reader(path)
    io.write_netcdf(tree, path)
    _edit(path, "n", 8, group="scenes/deep")
    with pytest.raises(io.DamagedOutput, match=r"scenes/deep/n: stored value does not match"):
        io.open_tree(path)


def test_attribute_is_the_documented_sha256(written):
    """The definition docs/recovery.md gives, recomputed by hand: SHA-256 of "<dtype>|<shape>\\n" and the
    values (little-endian bytes; strings as UTF-8, each after its length in 8 little-endian bytes)."""
    def strings(values):
        return b"".join(len(s.encode()).to_bytes(8, "little") + s.encode() for s in values)

    expected = {
        "merging_time_exact": hashlib.sha256(b"<f8|\n" + np.float64(223.0).tobytes()).hexdigest(),
        "outcome_kicked": hashlib.sha256(b"<i8|\n" + np.int64(2).tobytes()).hexdigest(),
        "verdict": hashlib.sha256(b"str|2\n" + strings(["agrees", "disagrees: see loc1"])).hexdigest(),
        "none_kicked": hashlib.sha256(b"<f8|0\n").hexdigest(),
    }
    with netCDF4.Dataset(written) as nc:
        assert {k: nc[k].getncattr(checksums.ATTR) for k in expected} == expected


def test_what_xarray_users_see(written, tmp_path):
    """Plain xarray shows the attribute (and reads the file); cradle's readers drop it, so a file read,
    edited and written again through write_netcdf carries a checksum of its new values, never a stale
    copy, and ds.equals/identical hold against what was written."""
    plain = xr.load_dataset(written)  # and closed: HDF5 may crash on a file with strings open twice at once
    assert checksums.ATTR in plain["merging_time_exact"].attrs
    back = io.open_dataset(written)
    assert back.identical(_dataset()) and plain.equals(back)
    assert not any(checksums.ATTR in v.attrs for v in back.variables.values())
    plain["merging_time_exact"] = plain["merging_time_exact"] * 10  # keeps the old attribute
    plain["growth"].attrs[checksums.ATTR] = "0" * 64                 # a stale copy on a filtered variable
    again = tmp_path / "results" / "again.nc"
    io.write_netcdf(plain, again)
    assert float(io.open_dataset(again)["merging_time_exact"]) == 2230.0
    assert io.verify_file(again) == []
    with netCDF4.Dataset(again) as nc:
        assert checksums.ATTR not in nc["growth"].ncattrs()


def test_files_written_before_recorded_checksums_are_notes(tmp_path, capsys):
    """A file written as before (Fletcher-32 only): its scalars and strings are listed as notes, as is
    a numeric variable without the filter; an empty variable (nothing stored) is not; the values read."""
    ds = _dataset()
    old = tmp_path / "results" / "old.nc"
    old.parent.mkdir(parents=True)
    encoding = io.encoding_of(ds)
    encoding["t"] = {"_FillValue": None}  # no filter on a variable that could carry it
    ds.to_netcdf(old, engine="netcdf4", encoding=encoding)
    assert sorted(io.verify_file(old)) == ["case", "merging_time_exact", "outcome_kicked", "t", "verdict"]
    assert io.open_dataset(old).equals(ds)
    assert cli.main(["verify", str(old)]) == 0
    assert "written before checksums" in capsys.readouterr().out


def test_appender_records_checksums_of_values_set_at_the_end(tmp_path):
    """Files written block by block (long exact runs, streamed scenes): the values without t are set
    at the end, and recorded at commit."""
    first = xr.Dataset({"x": (("t", "n"), np.zeros((2, 3))), "energy_drift_final": ((), 0.0)},
                       coords={"t": [0.0, 1.0], "n": [0, 1, 2]})
    app = Appender(tmp_path / "results" / "run.nc", first)
    app.append([2.0], {"x": np.ones((1, 3))})
    app.set_values({"energy_drift_final": 1e-12})
    app.commit()
    path = tmp_path / "results" / "run.nc"
    assert io.verify_file(path) == []
    assert float(io.open_dataset(path)["energy_drift_final"]) == 1e-12
    _edit(path, "energy_drift_final", 0.0)
    with pytest.raises(io.DamagedOutput, match="energy_drift_final: stored value does not match its checksum"):
        io.open_dataset(path)
