"""Writes that fail or are killed: a full disk is one line (the path, the bytes needed, the bytes free),
in the job log too; a killed write leaves a temporary file named after its writer, which `cradle verify`
names and :func:`cradle.data.io.remove_stale_temporaries` deletes once the writer is gone."""
from __future__ import annotations

import errno
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr

from cradle.data import io, temporaries
from cradle.pipeline import cli

ROOT = Path(__file__).resolve().parents[2]
ENV = {**os.environ, "PYTHONPATH": str(ROOT / "src")}


def _statvfs(free_bytes: int):
    return lambda _path: SimpleNamespace(f_bavail=free_bytes // 4096, f_frsize=4096)


def _failing_write(exc):
    """A to_netcdf that writes part of the file, then fails as netCDF does on a full disk."""
    def to_netcdf(self, path, *args, **kwargs):
        Path(path).write_bytes(b"\x89HDF\r\n\x1a\n" + bytes(50_000))
        raise exc
    return to_netcdf


def _big() -> xr.Dataset:
    return xr.Dataset({"x": (("t", "n"), np.zeros((1000, 300)))})  # 2.4 MB


@pytest.mark.parametrize("exc", [OSError(errno.ENOSPC, "No space left on device"), RuntimeError("NetCDF: HDF error")])
def test_full_disk_is_one_line_naming_path_need_and_free(tmp_path, monkeypatch, exc):
    """ENOSPC, or HDF5's bare "HDF error" while the disk is (nearly) full: one DiskFull line; nothing is
    left at the target or beside it."""
    monkeypatch.setattr(xr.Dataset, "to_netcdf", _failing_write(exc))
    monkeypatch.setattr(os, "statvfs", _statvfs(8192))
    path = tmp_path / "results" / "sim" / "tw" / "exact.nc"
    with pytest.raises(io.DiskFull) as err:
        io.write_netcdf(_big(), path)
    msg = str(err.value)
    assert "\n" not in msg and msg.startswith(f"{path}: no space left on the file system"), msg
    assert "needs about 2.4 MB" in msg and "8.19 kB free" in msg and "50 kB written" in msg, msg
    assert err.value.errno == errno.ENOSPC
    assert list(path.parent.iterdir()) == []


def test_an_hdf_error_with_room_to_spare_is_not_called_a_full_disk(tmp_path, monkeypatch):
    monkeypatch.setattr(xr.Dataset, "to_netcdf", _failing_write(RuntimeError("NetCDF: HDF error")))
    monkeypatch.setattr(os, "statvfs", _statvfs(10 * 2**30))
    with pytest.raises(RuntimeError, match="HDF error") as err:
        io.write_netcdf(_big(), tmp_path / "a.nc")
    assert not isinstance(err.value, io.DiskFull)


def test_full_disk_in_write_text_and_on_the_command_line(tmp_path, monkeypatch, capsys):
    def no_space(self, *args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(Path, "write_text", no_space)
    with pytest.raises(io.DiskFull, match=r"paper-checks.md: no space left.*needs about 10 B"):
        io.write_text("| a | b |\n", tmp_path / "paper-checks.md")
    assert [p.name for p in tmp_path.iterdir()] == []

    def command(args):
        io.write_text("text", tmp_path / "out.txt")

    monkeypatch.setattr(cli, "cmd_verify", command)
    assert cli.main(["verify", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1, err
    assert err.startswith(f"cradle: error: {tmp_path / 'out.txt'}: no space left on the file system"), err


def test_full_disk_is_one_line_in_the_job_log(tmp_path):
    """A job (runner.run, as every workflow script) whose output does not fit: one line in its log, no traceback."""
    out, log = tmp_path / "results" / "sim" / "tw" / "exact.nc", tmp_path / "logs" / "tw.log"
    script = textwrap.dedent(f"""
        import errno
        import xarray as xr
        from cradle.pipeline.runner import run

        def full(self, *args, **kwargs):
            raise OSError(errno.ENOSPC, "No space left on device")

        xr.Dataset.to_netcdf = full
        run(lambda: xr.Dataset({{"x": ("n", [1.0, 2.0])}}), {str(out)!r}, {str(log)!r}, label="simulate tw")
    """)
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=ENV, timeout=120)
    assert proc.returncode == 1 and "Traceback" not in proc.stderr, proc.stderr
    errors = [line for line in log.read_text().splitlines() if "error" in line]
    assert len(errors) == 1 and f"output error: {out}: no space left on the file system" in errors[0], errors


def test_temporary_names_its_writer(tmp_path):
    seen = []
    io._atomic(tmp_path / "exact.nc", lambda tmp: seen.append(Path(tmp).name) or Path(tmp).write_text("x"))
    m = temporaries.PATTERN.match(seen[0])
    assert m is not None and m["name"] == "exact.nc" and m["pid"] == str(os.getpid()), seen


def test_stale_temporaries_named_by_verify_and_removed(tmp_path, capsys):
    """Only temporaries of atomic writes whose writer is gone: a dead process of this host at once; no
    process id (an older version) or another host's only once unmodified for older_than_s."""
    folder = tmp_path / "results" / "sim" / "tw"
    folder.mkdir(parents=True)
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    host = temporaries._host()
    old = time.time() - 7200
    files = {
        f".exact.nc.pid-{dead.pid}@{host}.k2j4h6g8.tmp": True,    # killed writer of this host
        f".plot4-5.png.pid-{dead.pid}@{host}.a1b2c3d4.tmp.png": True,  # a figure's
        f".dps.nc.pid-{os.getpid()}@{host}.abcdefgh.tmp": False,   # a live writer (this process)
        ".metrics.nc.q1w2e3r4.tmp": True,                          # no process id, old
        ".initial.nc.z9x8c7v6.tmp": False,                         # no process id, recent
        ".map.nc.pid-1@another-host.abcdefgh.tmp": False,          # another host's, recent
        ".hom.nc.pid-1@another-host.hgfedcba.tmp": True,           # another host's, old
        "exact.tmp": False, ".hidden": False, "notes.txt.tmp": False,
    }
    for name in files:
        (folder / name).write_text("partial")
        if name.startswith((".metrics", ".hom")):
            os.utime(folder / name, (old, old))
    expected = sorted(folder / n for n, stale in files.items() if stale)
    assert io.stale_temporaries(tmp_path / "results", older_than_s=3600) == expected
    assert cli.main(["verify", str(tmp_path / "results")]) == 0
    out = capsys.readouterr().out
    for path in expected:
        assert f"note    stale temporary file {path} (a killed write; delete it)" in out, out
    assert "4 stale temporary files" in out and out.count("stale temporary file ") == 4, out
    assert io.remove_stale_temporaries(tmp_path / "results", older_than_s=3600) == expected
    assert sorted(p.name for p in folder.iterdir()) == sorted(n for n, stale in files.items() if not stale)


def test_a_killed_write_is_found_and_removed(tmp_path):
    """A writer killed (SIGKILL) mid-write leaves its temporary beside the target, nothing at the target;
    it is stale at once, and removed."""
    target = tmp_path / "results" / "sim" / "tw" / "exact.nc"
    script = textwrap.dedent(f"""
        import time
        from pathlib import Path
        from cradle.data import io

        def slow(tmp):
            Path(tmp).write_bytes(bytes(1000))
            time.sleep(120)

        io._atomic(Path({str(target)!r}), slow)
    """)
    proc = subprocess.Popen([sys.executable, "-c", script], env=ENV)
    try:
        deadline = time.time() + 60
        while not (target.parent.exists() and any(target.parent.iterdir())) and time.time() < deadline:
            time.sleep(0.05)
        tmp = next(target.parent.iterdir())
        assert io.stale_temporaries(tmp_path) == []  # its writer runs
    finally:
        proc.send_signal(signal.SIGKILL)
        proc.wait()
    assert not target.exists() and tmp.exists()
    assert io.stale_temporaries(tmp_path) == [tmp]
    assert io.remove_stale_temporaries(tmp_path) == [tmp] and not tmp.exists()


def test_full_disk_in_a_file_written_block_by_block(tmp_path, monkeypatch):
    """The Appender (long exact runs, streamed scenes) says the same; its temporary is gone."""
    from cradle.data.appending import Appender

    monkeypatch.setattr(xr.Dataset, "to_netcdf", _failing_write(RuntimeError("NetCDF: HDF error")))
    monkeypatch.setattr(os, "statvfs", _statvfs(4096))
    path = tmp_path / "results" / "sim" / "big" / "exact.nc"
    first = xr.Dataset({"x": (("t", "n"), np.zeros((2, 3)))}, coords={"t": [0.0, 1.0]})
    with pytest.raises(io.DiskFull, match=r"exact.nc: no space left.*needs more than 50 kB, 4.1 kB free") as err:
        Appender(path, first)
    assert "\n" not in str(err.value)
    assert list(path.parent.iterdir()) == []
