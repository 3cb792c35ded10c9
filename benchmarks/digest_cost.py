"""What the digest beside every output costs (cradle.data.digests): to digest the largest files of a build against
the time to write them, and what the comparison adds to a reader.

For each of the ``COUNT`` largest netCDF files without groups (a file of groups is a tree, which this does not
write) of a results folder (default ``results``, a finished build), in this
process, ``REPEATS`` times each, alternating:

* write: :func:`cradle.data.io.write_netcdf` of it, what every job calls (a temporary file beside the target,
  ``to_netcdf`` with the checksummed encoding, the recorded checksums of the scalars and strings, the rename),
  into a temporary folder, less its digest:
* digest: the time spent in that same call in what the digest adds to the write, each timed where the writer calls
  it: :func:`cradle.data.io.stored_digests` (the numeric arrays hashed from memory),
  :func:`cradle.data.io.stored_attributes` (the attributes hashed as handed to netCDF4),
  :func:`cradle.data.digests.items` on the handle the writer opens anyway to record the checksums of its scalars
  and strings (the other values read raw and hashed, the attributes not digested as handed), and
  :func:`cradle.data.digests.record` (the sidecar written);
* read: :func:`cradle.data.io.open_dataset` of it, the reader's whole work, and in it the comparison with the
  sidecar (:func:`cradle.data.digests.items` and ``compare``), the reader's added work.

CPU time of this process (``time.process_time``: the machine is shared), the median of the repeats (``REPEATS``,
default 31: a median the odd disturbed repeat does not move); digest / write is the median of the repeats' own
ratios, beside their interquartile range. Writes the table between its markers in docs/recovery.md::

    python benchmarks/digest_cost.py [RESULTS]
"""
from __future__ import annotations

import contextlib
import datetime as dt
import os
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path

from doctable import git_commit, publish

ROOT = Path(__file__).resolve().parents[1]
RESULTS = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "results"
COUNT = int(os.environ.get("COUNT", 3))
REPEATS = int(os.environ.get("REPEATS", 31))
TARGET = 0.10   # the digest's cost, at most this fraction of the write's


def cpu(fn) -> float:
    t0 = time.process_time()
    fn()
    return time.process_time() - t0


@contextlib.contextmanager
def digest_timed(spent: list[float]):
    """Within it, the CPU seconds :func:`cradle.data.io.write_netcdf` spends in the digest's four steps are added
    to ``spent[0]`` (each step wrapped where the writer looks it up: ``io.stored_digests``, ``io.stored_attributes``,
    ``digests.items``, ``digests.record``)."""
    from cradle.data import digests, io

    def timed(fn):
        def inner(*args, **kwargs):
            t0 = time.process_time()
            try:
                return fn(*args, **kwargs)
            finally:
                spent[0] += time.process_time() - t0
        return inner

    saved = io.stored_digests, io.stored_attributes, digests.items, digests.record
    io.stored_digests, io.stored_attributes, digests.items, digests.record = map(timed, saved)
    try:
        yield
    finally:
        io.stored_digests, io.stored_attributes, digests.items, digests.record = saved


def measure(path: Path, scratch: Path) -> dict:
    """Median CPU seconds of write, digest, read and the reader's comparison for the file ``path``."""
    import netCDF4

    from cradle.data import digests
    from cradle.data.io import open_dataset, write_netcdf

    ds = open_dataset(path)   # also proves the file is intact before it is timed
    out = scratch / path.name
    times: dict[str, list[float]] = {"write": [], "digest": [], "read": [], "compare": [], "ratio": []}

    def compare():
        with netCDF4.Dataset(out) as nc:
            digests.compare(out, digests.items(nc))

    for _ in range(REPEATS):
        for old in (out, digests.sidecar(out)):   # each write a first one (no earlier record read)
            old.unlink(missing_ok=True)
        spent = [0.0]
        with digest_timed(spent):
            whole = cpu(lambda: write_netcdf(ds, out))
        times["write"].append(whole - spent[0])
        times["digest"].append(spent[0])
        times["ratio"].append(spent[0] / (whole - spent[0]))
        times["read"].append(cpu(lambda: open_dataset(out)))
        times["compare"].append(cpu(compare))
    q1, _, q3 = statistics.quantiles(times["ratio"], n=4)
    return {k: statistics.median(v) for k, v in times.items()} | {"bytes": path.stat().st_size, "q1": q1, "q3": q3}


def table(rows: dict[Path, dict]) -> str:
    commit = git_commit()
    load = os.getloadavg()[0]
    stamp = dt.datetime.now(dt.UTC).strftime("%Y-%m-%d %H:%M UTC")
    lines = [f"`python benchmarks/digest_cost.py` at commit {commit}, {stamp}, the {len(rows)} largest files of "
             f"{RESULTS.name}/ (a `snakemake -j2 all` build); CPU time of one process, median of {REPEATS} repeats "
             f"(load average {load:.1f}: the 2 cores are shared)", "",
             "| file | size [MB] | write [ms] | digest [ms] | digest / write | (interquartile) | read, verified [ms] | "
             "of which the comparison [ms] |",
             "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for path, r in rows.items():
        lines.append(f"| `{path.relative_to(RESULTS).as_posix()}` | {r['bytes'] / 1e6:.1f} | {r['write'] * 1e3:.0f} | "
                     f"{r['digest'] * 1e3:.1f} | **{r['ratio'] * 100:.1f} %** | {r['q1'] * 100:.1f}-"
                     f"{r['q3'] * 100:.1f} % | {r['read'] * 1e3:.0f} | {r['compare'] * 1e3:.0f} |")
    worst = max(r["ratio"] for r in rows.values())
    lines += ["", f"Largest digest / write: {worst * 100:.1f} % (target: under {TARGET * 100:.0f} %)."]
    return "\n".join(lines)


def main() -> int:
    import netCDF4

    def flat(p: Path) -> bool:   # a file of groups (a tree) is written otherwise: open_dataset reads its root only
        with netCDF4.Dataset(p) as nc:
            return not nc.groups

    files = sorted((p for p in RESULTS.rglob("*.nc") if "failed" not in p.parts and not p.name.startswith(".")
                    and flat(p)), key=lambda p: p.stat().st_size, reverse=True)[:COUNT]
    if not files:
        raise SystemExit(f"no netCDF file under {RESULTS}: build first (snakemake -j2 all)")
    scratch = Path(tempfile.mkdtemp(prefix="digest-cost-"))
    try:
        rows = {p: measure(p, scratch) for p in files}
    finally:
        shutil.rmtree(scratch)
    text = table(rows)
    print(text)
    publish("recovery.md", "digest-cost", text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
