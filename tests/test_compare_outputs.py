"""benchmarks/compare_outputs.py: two results folders compared netCDF variable by variable, bitwise."""
from __future__ import annotations

import importlib.util
import shutil
import sys
from pathlib import Path

import netCDF4
import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]


def _script():
    spec = importlib.util.spec_from_file_location("compare_outputs", ROOT / "benchmarks" / "compare_outputs.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


compare = _script()


def write(path: Path, string_model: str = "", wall_time_len: int = 3) -> Path:
    """A small file like the pipeline's: root and group variables, a 0-d scalar, strings, a coded coordinate."""
    path.parent.mkdir(parents=True, exist_ok=True)
    with netCDF4.Dataset(path, "w") as ds:
        ds.title = "written at some time"  # attributes other than units are not compared
        ds.model_names = "exact, dps"
        ds.createDimension("t", 4)
        ds.createDimension("model", 2)
        t = ds.createVariable("t", "f8", ("t",))
        t[:], t.units = [0.0, 1.0, 2.0, 3.0], "1"
        x = ds.createVariable("x", "f8", ("model", "t"))
        x[:], x.units = np.array([[0.1, np.nan, 0.3, 0.4], [1.5, 2.5, np.nan, -0.0]]), "1"
        if string_model == "vlen":
            model = ds.createVariable("model", str, ("model",))
            model[0], model[1] = "exact", "dps"
        elif string_model == "char":
            ds.createDimension("string5", 5)
            model = ds.createVariable("model", "S1", ("model", "string5"))
            model[:] = netCDF4.stringtochar(np.array(["exact", "dps"], dtype="S5"))
        else:
            model = ds.createVariable("model", "i8", ("model",))
            model[:], model.units = [0, 1], "1"
        scalar = ds.createVariable("merging_time", "f8", ())
        scalar[...], scalar.units = 2.0 / 3.0, "1"
        ds.createDimension("setting", wall_time_len)
        wall = ds.createVariable("wall_time", "f8", ("setting",))
        wall[:], wall.units, wall.long_name = np.arange(wall_time_len) + 0.5, "s", "wall time of the integration"
        runs = ds.createGroup("runs")
        runs.createDimension("case", 2)
        pair = runs.createVariable("pair", str, ("case",))
        pair[0], pair[1] = "site-site", "site-bond"
        count = runs.createVariable("count", "i8", ("case",))
        count[:], count.units = [3, 4], "1"
    return path


def run(old: Path, new: Path, *options: str) -> tuple[int, str]:
    table = old.parent / "table.md"
    code = compare.main([str(old), str(new), "--table", str(table), *options])
    return code, table.read_text()


@pytest.fixture
def folders(tmp_path):
    old, new = tmp_path / "old", tmp_path / "new"
    write(old / "mi" / "a.nc")
    shutil.copytree(old, new)
    return old, new


def test_a_copy_is_equal(folders):
    code, table = run(*folders)
    assert code == 0, table
    assert "**ALL EQUAL**: 1 file pairs, 7 variables compared" in table
    assert "`mi/a.nc:/wall_time`" in table


def _flip_bit(path: Path, var: str, index=None):
    with netCDF4.Dataset(path, "r+") as ds:
        ds.set_auto_maskandscale(False)
        values = np.array(ds[var][...])
        bits = values.view(np.uint64 if values.dtype.kind == "f" else np.int64)
        if index is None:
            bits[...] ^= 1
        else:
            bits[index] ^= 1
        ds[var][...] = values


def _flip_char(path: Path, var: str):
    with netCDF4.Dataset(path, "r+") as ds:
        word = ds[var][1]
        ds[var][1] = word[:-1] + chr(ord(word[-1]) ^ 1)


def _set_units(path: Path, var: str):
    with netCDF4.Dataset(path, "r+") as ds:
        ds[var].units = "rad"


def _nan_to_number(path: Path, var: str):
    with netCDF4.Dataset(path, "r+") as ds:
        ds[var][0, 1] = 0.2


@pytest.mark.parametrize("change, var", [
    (lambda p: _flip_bit(p, "x", (0, 0)), "/x"),
    (lambda p: _flip_bit(p, "x", (1, 3)), "/x"),  # -0.0 -> a denormal: bits, not just the value
    (lambda p: _flip_bit(p, "merging_time"), "/merging_time"),
    (lambda p: _flip_bit(p, "model", 1), "/model"),
    (lambda p: _flip_bit(p, "/runs/count", 0), "/runs/count"),
    (lambda p: _flip_char(p, "/runs/pair"), "/runs/pair"),
    (lambda p: _set_units(p, "t"), "/t"),
    (lambda p: _set_units(p, "wall_time"), "/wall_time"),
    (lambda p: _nan_to_number(p, "x"), "/x"),
])
def test_one_changed_variable_is_caught(folders, change, var):
    old, new = folders
    change(new / "mi" / "a.nc")
    code, table = run(old, new)
    assert code == 1
    rows = [line for line in table.splitlines() if line.startswith("| `mi/a.nc` | `")]
    assert [row.split(" | ")[1] for row in rows] == [f"`{var}`"], table


def test_a_different_nan_payload_and_the_other_attributes_are_not_differences(folders):
    old, new = folders
    with netCDF4.Dataset(new / "mi" / "a.nc", "r+") as ds:
        ds.set_auto_maskandscale(False)
        values = np.array(ds["x"][...])
        values.view(np.uint64)[0, 1] ^= 1  # still a NaN, another payload
        assert np.isnan(values[0, 1])
        ds["x"][...] = values
        ds.title, ds["x"].long_name = "written later", "a new description"
    assert run(old, new)[0] == 0


def test_a_wall_clock_timing_is_checked_for_shape_and_units_only(tmp_path):
    old = write(tmp_path / "old" / "wp.nc")
    new = write(tmp_path / "new" / "wp.nc")
    with netCDF4.Dataset(new, "r+") as ds:
        ds["wall_time"][:] = [9.0, 8.0, 7.0]
    assert run(old.parent, new.parent)[0] == 0
    write(new, wall_time_len=4)
    code, table = run(old.parent, new.parent)
    assert code == 1 and "`/wall_time` | dimensions" in table


def test_moved_files_pair_through_rename_rules(folders):
    old, new = folders
    (new / "a").mkdir()
    (new / "mi" / "a.nc").rename(new / "a" / "a.nc")
    code, table = run(old, new)
    assert code == 1 and "## Only in old\n\n- `mi/a.nc`" in table and "## Only in new\n\n- `a/a.nc`" in table
    code, table = run(old, new, "--map", r"mi/(\w+)\.nc=\1/\1.nc")
    assert code == 0, table


def test_a_file_only_in_new_is_a_difference(folders):
    old, new = folders
    write(new / "b.nc")
    code, table = run(old, new)
    assert code == 1 and "## Only in new\n\n- `b.nc`" in table


def test_a_renamed_variable_pairs_through_var_map(folders):
    old, new = folders
    with netCDF4.Dataset(new / "mi" / "a.nc", "r+") as ds:
        ds.renameVariable("merging_time", "merging_period")
    code, table = run(old, new)
    assert code == 1 and "`/merging_time` | only in old" in table and "`/merging_period` | only in new" in table
    assert run(old, new, "--var-map", "/merging_time=/merging_period")[0] == 0
    assert run(old, new, "--var-map", r"mi/.*::/merging_time=/merging_period")[0] == 0
    assert run(old, new, "--var-map", r"other/.*::/merging_time=/merging_period")[0] == 1


@pytest.mark.parametrize("storage", ["vlen", "char"])
def test_integer_codes_equal_strings_only_when_asked(tmp_path, storage):
    old = write(tmp_path / "old" / "a.nc")
    new = write(tmp_path / "new" / "a.nc", string_model=storage)
    code, table = run(old.parent, new.parent)
    assert code == 1 and "`/model` | " in table
    code, table = run(old.parent, new.parent, "--coord-names", "model,scene")
    assert code == 0, table
    with netCDF4.Dataset(new, "r+") as ds:
        if storage == "vlen":
            ds["model"][0], ds["model"][1] = "dps", "exact"
        else:
            ds["model"][:] = netCDF4.stringtochar(np.array(["dps", "exact"], dtype="S5"))
    code, table = run(old.parent, new.parent, "--coord-names", "model")
    assert code == 1 and "names ['dps', 'exact'] != ['exact', 'dps']" in table


def test_old_files_compare_with_groups_of_one_gathered_file(tmp_path):
    """--group-map: each old file against its group of the new file; a group no old file stands for is
    only in new, a changed byte in a group is a difference."""
    old_a, old_b = write(tmp_path / "old" / "wp" / "a.nc"), write(tmp_path / "old" / "wp" / "b.nc")
    new = tmp_path / "new" / "wp" / "wp.nc"
    new.parent.mkdir(parents=True)
    with netCDF4.Dataset(new, "w") as out:
        for name, src in (("a", old_a), ("b", old_b)):
            _copy_into(src, out.createGroup(name))
    options = ("--map", r"wp/\w+\.nc=wp/wp.nc", "--group-map", r"wp/(\w+)\.nc=/\1")
    code, table = run(tmp_path / "old", tmp_path / "new", *options)
    assert code == 0, table
    assert "`wp/wp.nc:/a`" in table and "`wp/wp.nc:/b`" in table
    code, table = run(tmp_path / "old", tmp_path / "new", "--map", r"wp/\w+\.nc=wp/wp.nc")
    assert code == 1 and "`/a/x` | only in new" in table  # without the groups the paths differ
    old_b.unlink()
    code, table = run(tmp_path / "old", tmp_path / "new", *options)
    assert code == 1 and "- `wp/wp.nc:/b/x`" in table
    write(old_b)
    _flip_bit(new, "/b/x", (0, 0))
    code, table = run(tmp_path / "old", tmp_path / "new", *options)
    differences = table.split("## Differences", 1)[-1]
    assert code == 1 and "| `wp/b.nc` | `/x` | values |" in differences and "`wp/a.nc`" not in differences, table


def _copy_into(path: Path, group) -> None:
    """Every dimension, variable (values, units, long_name) and subgroup of the file ``path`` into ``group``."""
    def copy(src, dst):
        for name, dim in src.dimensions.items():
            dst.createDimension(name, len(dim))
        for name, var in src.variables.items():
            out = dst.createVariable(name, var.datatype, var.dimensions)
            out.setncatts({k: var.getncattr(k) for k in var.ncattrs()})
            out[...] = var[...]
        for name, sub in src.groups.items():
            copy(sub, dst.createGroup(name))

    with netCDF4.Dataset(path) as src:
        src.set_auto_maskandscale(False)
        copy(src, group)
