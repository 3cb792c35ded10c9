"""A scene's job block by block (cradle.scenes.streamed): the same values as the in-memory job,
bounded memory, nothing left behind on failure; which scenes stream (cradle.pipeline.budget)."""
from __future__ import annotations

import dataclasses
import os

import numpy as np
import pytest

from conftest import ROOT
from cradle.data import io
from cradle.integrators import integrate_dps
from cradle.integrators.dps_solver import iter_dps
from cradle.pipeline import budget, config as cc
from cradle.pipeline.runner import run_chain
from cradle.scenes import stages, streamed
from cradle.scenes.failure import StageFailure
from cradle.scenes.spec import Breather, Store

PARTS = ("initial", "exact", "dps", "metrics")
#: attributes that say how the job ran, not what it computed: the block-by-block job evaluates the
#: forces once more per block, and its wall time and provenance are its own
HOW = {"wall_time_s", "history", "n_force_evals", "streamed", "c_assumed"}


@pytest.fixture(scope="module")
def config():
    return cc.load(ROOT / "config.yaml")


def short_spec(config, name, t_end):
    """Scene ``name`` ended at ``t_end``: its stored times before t_end, then t_end."""
    spec = cc.scene(config, name)
    snapshots = [t for t in spec.store.snapshots or () if t < t_end] or None
    short = dataclasses.replace(spec, t_end=t_end, store=dataclasses.replace(spec.store, snapshots=snapshots))
    assert list(short.times) == [t for t in spec.times if t < t_end] + [t_end]
    return short


def test_iter_dps_blocks_are_bitwise_one_run():
    """DpS (dfnls) computed in blocks of 7 output times, carrying the DOP853 state, equals one call
    bitwise: A, the three drifts, the running maxima and the number of steps."""
    rng = np.random.default_rng(3)
    A0 = 0.3 * (rng.normal(size=24) + 1j * rng.normal(size=24))
    tau = np.linspace(0.0, 20.0, 61)
    one = integrate_dps(A0, tau, alpha=1.5)
    blocks = list(iter_dps(A0, tau, 7, alpha=1.5))
    assert len(blocks) == 9
    assert np.array_equal(np.concatenate([b.A for b in blocks]), one.A)
    for k in ("l2_drift", "energy_drift", "P_drift"):
        assert np.array_equal(np.concatenate([getattr(b, k) for b in blocks]), getattr(one, k)), k
    assert blocks[-1].max_l2_drift == one.max_l2_drift and blocks[-1].max_energy_drift == one.max_energy_drift
    assert sum(b.n_steps for b in blocks) == one.n_steps


@pytest.mark.parametrize("name, t_end", [("tw-weak", 30.0), ("breather-small", 60.0), ("loc1-pair", 120.0),
                                         ("loc1-packet", 60.0), ("fini", 50.0)])
def test_streamed_job_writes_the_in_memory_values(config, tmp_path, name, t_end):
    """Every variable of the four files, in blocks of 37 stored times, bitwise that of the in-memory
    job (travelling wave, breather, pair, packet, free ends); every attribute but how it ran equal."""
    spec = short_spec(config, name, t_end)
    hom = None
    if isinstance(spec.initial, Breather):
        h = spec.initial.homoclinic
        hom = stages.homoclinic_solution(cc.homoclinic(config, h), h)
    init = stages.initial_data(spec, name, hom)
    a = {k: tmp_path / f"a-{k}.nc" for k in PARTS}
    b = {k: tmp_path / "b" / f"{k}.nc" for k in PARTS}
    run_chain([("initial", lambda done: init), ("exact", lambda done: stages.exact_run(spec, init, name)),
               ("dps", lambda done: stages.dps_run(spec, init, name)),
               ("metrics", lambda done: stages.metrics(spec, done["exact"], done["dps"], name))], a)
    s = streamed.simulate_streamed(spec, init, name, b, chunk_bytes=streamed.BLOCK_ARRAYS * 8 * spec.N * 37)
    assert s["rows_per_block"] == 37 and s["blocks"] == -(-len(spec.times) // 37) > 1
    for part in PARTS:
        A, B = io.open_dataset(a[part]), io.open_dataset(b[part])   # checksums verified on both
        assert sorted(A.variables) == sorted(B.variables), part
        for v in A.variables:
            assert np.array_equal(A[v].values, B[v].values, equal_nan=A[v].dtype.kind == "f"), (part, v)
            assert A[v].attrs.keys() == B[v].attrs.keys(), (part, v)
            assert all(np.array_equal(np.asarray(A[v].attrs[k]), np.asarray(B[v].attrs[k])) for k in A[v].attrs)
        for key, value in A.attrs.items():
            if key not in HOW:
                assert np.array_equal(np.asarray(value), np.asarray(B.attrs[key])), (part, key)
    assert sorted(os.listdir(tmp_path / "b")) == sorted([f"{k}.nc" for k in PARTS] + [f".{k}.nc.digest" for k in PARTS])


def test_failed_streamed_job_leaves_nothing(config, tmp_path):
    """An energy drift above max_energy_drift, found after the last block: StageFailure, and none of
    the four files (nor a temporary one) in the folder."""
    spec = dataclasses.replace(short_spec(config, "tw-weak", 20.0), max_energy_drift=1e-300)
    init = stages.initial_data(spec, "tw-weak")
    outs = {k: tmp_path / f"{k}.nc" for k in PARTS}
    with pytest.raises(StageFailure, match="energy drift"):
        streamed.simulate_streamed(spec, init, "tw-weak", outs, chunk_bytes=streamed.BLOCK_ARRAYS * 8 * 64 * 10)
    assert os.listdir(tmp_path) == []


def test_a_large_store_streams_with_bounded_memory(config):
    """fft106 (N = 200) stored every 0.004 (a ~2 GB store) and every 0.0004 (~20 GB): both stream,
    within the default memory budget, with estimates a few hundred MB apart; the disk budget still
    refuses the 200 GB store of every 0.01 up to t = 99000, and N = 1e9 is refused on memory."""
    def est(every, t_end=543.7, N=200):
        spec = dataclasses.replace(cc.scene(config, "fft106"), N=N, t_end=t_end, store=Store(every=every))
        return budget.spec_estimate(spec, "fft106")

    two, twenty = est(0.004), est(0.0004)
    assert two.streamed and twenty.streamed and not est(0.01).streamed
    assert 1.5e9 < two.disk_bytes < 2.5e9
    limit = budget.Budget().memory_gb * budget.GB
    assert two.memory_bytes < 1e9 and twenty.memory_bytes < limit
    assert twenty.memory_bytes - two.memory_bytes < 0.5e9
    assert est(0.01, t_end=99000.0).disk_bytes > budget.Budget().disk_gb * budget.GB
    assert est(0.01, N=int(1e9)).memory_bytes > limit


def test_large_file_opened_lazily_after_verification(config, tmp_path, monkeypatch):
    """Above io.LAZY_ABOVE_BYTES a reader gets the file verified block by block and opened lazily:
    same values, nothing loaded until selected; a damaged large file still stops it in one line."""
    spec = short_spec(config, "tw-weak", 10.0)
    init = stages.initial_data(spec, "tw-weak")
    ex = stages.exact_run(spec, init, "tw-weak")
    path = tmp_path / "exact.nc"
    io.write_netcdf(ex, path)
    monkeypatch.setattr(io, "LAZY_ABOVE_BYTES", 1000)
    lazy = io.open_dataset(path)
    assert not lazy["x"].variable._in_memory
    assert np.array_equal(lazy["x"].values, ex["x"].values)
    lazy.close()
    data = bytearray(path.read_bytes())
    data[len(data) // 2: len(data) // 2 + 4096] = os.urandom(4096)
    path.write_bytes(bytes(data))
    with pytest.raises(io.DamagedOutput, match="exact.nc: damaged"):
        io.open_dataset(path)
