"""Extending a finished exact run and streaming long runs to disk (cradle.pipeline.extend, `cradle extend`)."""
from __future__ import annotations

import os

import numpy as np
import pytest

from cradle.data import io
from cradle.pipeline import cli, extend
from cradle.scenes import stages
from cradle.scenes.spec import DpsIntegrator, ExactIntegrator, Scene, Store, Travelling


def spec(T, method="srkn6c", bc="periodic"):
    """A resolved scene stored every 0.5 to T."""
    return Scene(alpha=1.5, N=16, bc=bc, t_end=T, store=Store(every=0.5), exact=ExactIntegrator(method=method),
                 max_energy_drift=1e-6, initial=Travelling(kind="travelling", q=np.pi / 4, omega_tw=1.1),
                 dps=DpsIntegrator(method="dop853"))


@pytest.fixture(scope="module")
def runs():
    """exact_run to T = 20 and to 2T = 40 from the same initial data (same default dt)."""
    init = stages.initial_data(spec(20.0), "ext")
    short, long = stages.exact_run(spec(20.0), init, "ext"), stages.exact_run(spec(40.0), init, "ext")
    assert short.attrs["dt"] == long.attrs["dt"]
    return short, long


@pytest.mark.parametrize("chunk_bytes", [extend.DEFAULT_CHUNK_BYTES, 3 * 8 * 16 * 7])
def test_extend_T_to_2T_is_bitwise_one_run(runs, tmp_path, chunk_bytes):
    """Run to T, extend to 2T (in one chunk, or in chunks of 7 stored times): x, v, force, energy, t
    and the energy drift are bitwise those of one run to 2T; the step counts add up."""
    short, long = runs
    path = tmp_path / "exact.nc"
    io.write_netcdf(short, path)
    s = extend.extend(path, 40.0, chunk_bytes=chunk_bytes)
    got = io.open_dataset(path)
    for k in ("t", "x", "v", "force", "energy"):
        assert np.array_equal(got[k].values, long[k].values), k
    assert got.attrs["energy_drift"] == long.attrs["energy_drift"]
    assert got.attrs["n_steps"] == long.attrs["n_steps"]
    assert got.attrs["t_end"] == 40.0 and s["rows_added"] == 40
    assert "t=20.0 -> 40.0" in got.attrs["extended"]
    assert got["x"].attrs["long_name"] == long["x"].attrs["long_name"]
    assert sorted(os.listdir(tmp_path)) == [".exact.nc.digest", "exact.nc"]   # its digest, no temporary file left


def test_stream_lattice_chunks_match_one_call(runs, tmp_path):
    """stream_lattice from t = 0 in chunks of 5 stored times = integrate_lattice in one call, bitwise;
    the file's t dimension is unlimited."""
    import netCDF4

    short, _ = runs
    x0, v0 = short["x"].values[0], short["v"].values[0]
    s = extend.stream_lattice(x0, v0, short["t"].values, tmp_path / "s.nc", alpha=1.5, method="srkn6c",
                              dt=float(short.attrs["dt"]), chunk_bytes=3 * 8 * 16 * 5)
    got = io.open_dataset(tmp_path / "s.nc")
    assert s["chunk_rows"] == 5 and s["rows"] == short.sizes["t"]
    assert np.array_equal(got["x"].values, short["x"].values)
    assert np.array_equal(got["energy"].values, short["energy"].values)
    assert s["energy_drift"] == short.attrs["energy_drift"]
    with netCDF4.Dataset(tmp_path / "s.nc") as nc:
        assert nc.dimensions["t"].isunlimited()


def test_extend_refuses_with_clear_messages(runs, tmp_path):
    short, _ = runs
    path = tmp_path / "exact.nc"
    io.write_netcdf(short, path)
    with pytest.raises(ValueError, match=r"t_end=10.0 must be > the last stored time t=20.0"):
        extend.extend(path, 10.0)
    ad = short.copy()
    ad.attrs["integrator"] = "dop853"
    io.write_netcdf(ad, tmp_path / "adaptive.nc")
    with pytest.raises(ValueError, match=r"integrator='dop853' is adaptive"):
        extend.extend(tmp_path / "adaptive.nc", 40.0)
    io.write_netcdf(short[["energy"]], tmp_path / "noxv.nc")
    with pytest.raises(ValueError, match=r"no x, v, force"):
        extend.extend(tmp_path / "noxv.nc", 40.0)
    assert np.array_equal(io.open_dataset(path)["x"].values, short["x"].values)   # untouched


def test_cli_extend(runs, tmp_path, capsys):
    short, long = runs
    path = tmp_path / "exact.nc"
    io.write_netcdf(short, path)
    assert cli.main(["extend", str(path), "--t-end", "40", "--out", str(tmp_path / "long.nc")]) == 0
    assert "t = 20 -> 40, 40 stored times added" in capsys.readouterr().out
    assert np.array_equal(io.open_dataset(tmp_path / "long.nc")["x"].values, long["x"].values)
    assert io.open_dataset(path).sizes["t"] == short.sizes["t"]            # --out leaves the input alone
    assert cli.main(["extend", str(path), "--t-end", "5"]) == 2
    assert "must be > the last stored time" in capsys.readouterr().err


def test_extend_estimates_and_refuses_before_any_work(runs, tmp_path, capsys):
    """`cradle extend` prints its estimate (cradle.pipeline.budget) and refuses, in one line and before
    anything is written, a t_end beyond a scene's longest run (a limit of float64), and a run over the budget of
    the config (a grid of many stored times among them)."""
    short, _ = runs
    path = tmp_path / "exact.nc"
    io.write_netcdf(short, path)
    out = tmp_path / "long.nc"
    why = "a scene's longest run (float64 tells stored times 1e-9 apart only below 2^22 = 4194304)"
    for argv, words in ((["--t-end", "1e300"], f"t_end=1e+300: must be <= 4194304, {why}"),
                        (["--t-end", "1e7"], f"t_end=10000000.0: must be <= 4194304, {why}"),
                        (["--t-end", "100", "--every", "1e-9"], "N = 16, t = 20 -> 100: 8e+10 stored times added, "
                                                                "~8e+10 steps of srkn6c (dt = 0.020814): estimated "
                                                                "peak memory 3.84 TB exceeds budget.memory_gb = 8"),
                        (["--t-end", "1e6", "--every", "0.5"], "exceeds budget.disk_gb = 0.1")):
        (tmp_path / "config.yaml").write_text("scenes: {s: {N: 2, initial: {kind: travelling, q: pi, a: 0.01}, "
                                              "t_end: 1, store: {every: 1}}}\nbudget: {disk_gb: 0.1}\n")
        argv = ["extend", str(path), "--out", str(out), "--config", str(tmp_path / "config.yaml"), *argv]
        assert cli.main(argv) == 2
        err = capsys.readouterr().err
        assert err.startswith("cradle: error: ") and words in err and err.count("\n") == 1, err
        assert not out.exists()
    assert cli.main(["extend", str(path), "--t-end", "30", "--out", str(out), "--config", str(tmp_path / "none")]) == 0
    assert "estimated peak memory" in capsys.readouterr().err


def test_big_chain_streamed_peak_memory_below_1GiB(tmp_path):
    """N = 1e4, 100 stored times (t = 2), streamed in a subprocess: peak RSS (numba and libraries included) < 1 GiB;
    the file holds 101 rows. (t = 1e3 at this N: benchmarks/extremes.py.) The peak is the process's own, VmHWM of
    /proc/self/status: getrusage's ru_maxrss survives execve, so a child of a large pytest process would report
    the parent's resident size at the fork."""
    import json
    import subprocess
    import sys

    code = f"""
import json, resource, numpy as np
from cradle.models import initial
from cradle.pipeline.extend import stream_lattice
d = initial.travelling_wave(10_000, np.pi / 5, 1.5, omega_tw=1.1)
s = stream_lattice(d.x0, d.v0, np.linspace(0.0, 2.0, 101), {str(tmp_path / 'big.nc')!r}, alpha=1.5,
                   chunk_bytes=8 * 2**20)
try:
    hwm = [line for line in open("/proc/self/status") if line.startswith("VmHWM:")][0]
    rss = int(hwm.split()[1]) * 1024
except (OSError, IndexError):   # no procfs: getrusage (an upper bound)
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
print(json.dumps({{"rss": rss, "rows": s["rows"], "drift": s["energy_drift"]}}))
"""
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    out = json.loads(r.stdout.strip().splitlines()[-1])
    assert out["rows"] == 101 and out["drift"] < 1e-10
    assert out["rss"] < 2**30
    assert io.open_dataset(tmp_path / "big.nc").sizes == {"t": 101, "n": 10_000}
