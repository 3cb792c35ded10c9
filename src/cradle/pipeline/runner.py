"""Run one stage and write its output safely (used by workflow scripts and the command line).

* the output is written atomically (:func:`cradle.data.io.write_netcdf`): a failed
  or interrupted run leaves nothing at the target path;
* a :class:`StageFailure` (raised by :mod:`cradle.scenes.stages`) keeps what was computed under
  ``results/failed/...`` with the reason as the ``failure`` attribute, then
  the error propagates (the rule fails with the message);
* progress and timing go to the log file (and to the terminal);
* a damaged, truncated or missing input stops the job with one line naming the file and its
  rebuild command (:class:`cradle.data.io.DamagedOutput`), not a traceback; so does an output that
  does not fit on its file system (:class:`cradle.data.io.DiskFull`: the path, the bytes needed and free).
* a job whose parent (Snakemake) is killed stops too (:mod:`cradle.pipeline.orphan`).
"""
from __future__ import annotations

import logging
import os
import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from types import TracebackType
from typing import TYPE_CHECKING, Any, TypeVar

from cradle.data.io import write_netcdf
from cradle.pipeline.orphan import orphaned, watch_parent
from cradle.pipeline.warm import DECLINED_VAR, STARTED_VAR, process_started
from cradle.scenes.failure import StageFailure

if TYPE_CHECKING:
    import xarray as xr

    from cradle.pipeline.budget import Estimate

#: what a stage computes: a Dataset, or a DataTree of groups
Output = TypeVar("Output", "xr.Dataset", "xr.DataTree")

log = logging.getLogger("cradle")


def process_age() -> float | None:
    """Seconds since this process started (Linux /proc), or None where that is not available.

    Called first thing in a job, it is the job's start-up cost: interpreter,
    Snakemake's script preamble and the imports (benchmarks/rebuild.py adds them up). A job forked
    from the warm process (:mod:`cradle.pipeline.warm`) counts from the start of its own process,
    which handed it over.
    """
    try:
        started = float(os.environ[STARTED_VAR]) if STARTED_VAR in os.environ else process_started()
        if started is None:
            return None
        with open("/proc/uptime") as f:
            uptime = float(f.read().split()[0])
        return uptime - started
    except (OSError, ValueError, IndexError):
        return None


_STARTUP_LOGGED = False  # only the first log of a process says how long its start-up took


def setup_logging(log_path: str | None = None) -> None:
    """Log to ``log_path`` (if given) and to stderr, one line per message; the first call in a
    process starts with the process start-up time (see :func:`process_age`) and the watch on its
    parent (:func:`cradle.pipeline.orphan.watch_parent`)."""
    handlers: list[logging.Handler] = [logging.StreamHandler(sys.stderr)]
    if log_path:
        Path(log_path).parent.mkdir(parents=True, exist_ok=True)
        handlers.append(logging.FileHandler(log_path, mode="w"))
    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(message)s", handlers=handlers, force=True)
    sys.excepthook = _one_line_excepthook
    watch_parent()
    global _STARTUP_LOGGED
    age = None if _STARTUP_LOGGED else process_age()
    if age is not None:
        how = ("forked from the warm process" if STARTED_VAR in os.environ else
               f"own process: {os.environ[DECLINED_VAR]}" if DECLINED_VAR in os.environ else "own process")
        log.info("process start-up (interpreter, imports): %.2f s (%s)", age, how)
        _STARTUP_LOGGED = True


def one_line_errors() -> None:
    """Report a missing, damaged or wrong input in one line (:func:`_one_line_excepthook`) before logging is
    set up: a job that reads an input before its first stage starts."""
    sys.excepthook = _one_line_excepthook


def _one_line_excepthook(exc_type: type[BaseException], exc: BaseException, tb: TracebackType | None) -> None:
    """A job stopped by a missing, damaged or truncated input says so in one line (log and stderr),
    naming the file and the command that rebuilds it, instead of a traceback through the readers; a
    job whose output does not fit on the disk names the path, the bytes it needed and those free."""
    from cradle.data.io import DamagedOutput, DiskFull

    if issubclass(exc_type, DiskFull):
        log.error("output error: %s", " ".join(str(exc).split()))
    elif issubclass(exc_type, (DamagedOutput, FileNotFoundError)):
        log.error("input error: %s", " ".join(str(exc).split()))
    elif issubclass(exc_type, KeyboardInterrupt) and orphaned():
        pass   # stopped for its lost parent: said in one line already
    else:
        sys.__excepthook__(exc_type, exc, tb)


def failed_path(out: str | Path) -> Path:
    """Where a failed run's partial output goes: results/X/Y.nc -> results/failed/X/Y.nc."""
    out = Path(out)
    parts = out.parts
    if "results" in parts:
        i = parts.index("results")
        return Path(*parts[: i + 1], "failed", *parts[i + 1:])
    return out.with_name(f"failed-{out.name}")


class Progress:
    """A progress callback: logs simulated time reached, rate and ETA, at most every ``every`` seconds.

    ``estimate`` (an :class:`cradle.pipeline.budget.Estimate`), when given, is logged before the
    first progress line, so a long run says up front what it will cost; ``t0`` is the simulated
    time the run starts from (a continued run starts after 0).
    """

    def __init__(self, label: str, every: float = 2.0, estimate: Estimate | None = None, t0: float = 0.0) -> None:
        self.label, self.every, self.estimate, self.t0 = label, every, estimate, t0
        self.start = self.last = time.perf_counter()
        self.announced = False
        self.expected = f", estimated {_eta(estimate.seconds)} in all" if estimate is not None else ""

    def __call__(self, t_reached: float, t_final: float) -> None:
        now = time.perf_counter()
        if self.estimate is not None and not self.announced:
            log.info("%s: %s", self.label, self.estimate.describe())
            self.announced = True
        if now - self.last >= self.every or t_reached >= t_final:
            self.last = now
            rate = (t_reached - self.t0) / max(now - self.start, 1e-9)
            eta = f"ETA {_eta((t_final - t_reached) / rate)}" if rate > 0 and t_reached < t_final else "done"
            log.info("%s: t = %.6g / %.6g (%.1f%%), %.3g time units per second, %s%s",
                     self.label, t_reached, t_final, 100.0 * t_reached / t_final, rate, eta, self.expected)


def _eta(seconds: float) -> str:
    """Remaining seconds as '42 s', '3.5 min', '2.1 h' or '4.2 days'."""
    for unit, size in (("days", 86400.0), ("h", 3600.0), ("min", 60.0)):
        if seconds >= size:
            return f"{seconds / size:.2g} {unit}"
    return f"{seconds:.0f} s"


def _keep_failed(ds: xr.Dataset | xr.DataTree, out: str | Path, reason: str) -> str:
    """Write ``ds`` under results/failed/ (not at ``out``) with ``reason`` as its ``failure`` attribute."""
    path = failed_path(out)
    ds.attrs["failure"] = reason
    write_netcdf(ds, path)
    return str(path)


def run(compute: Callable[[], Output], out: str | Path, log_path: str | None = None, label: str = "") -> Output:
    """Call ``compute()`` (returning a Dataset, or a DataTree of groups) and write it to ``out``; see
    module docstring."""
    setup_logging(log_path)
    t0 = time.perf_counter()
    log.info("%s: start -> %s", label, out)
    try:
        ds = compute()
    except StageFailure as err:
        if err.partial is not None:
            path = _keep_failed(err.partial, out, str(err))
            log.error("%s: FAILED: %s (partial output kept in %s)", label, err, path)
        else:
            log.error("%s: FAILED: %s", label, err)
        raise
    write_netcdf(ds, out)
    log.info("%s: done in %.2f s -> %s", label, time.perf_counter() - t0, out)
    return ds


def run_chain(steps: Sequence[tuple[str, Callable[[dict], xr.Dataset | xr.DataTree]]], outs: dict,
              log_path: str | None = None, label: str = "") -> dict:
    """Run dependent stages in one process and write each to ``outs[key]``.

    ``steps`` is a list of ``(key, compute)``; ``compute(done)`` gets the
    Datasets of the earlier steps by key. Every output is written (atomically)
    only after all steps succeeded, so a failure leaves none of them at its
    target path: Snakemake reruns the whole job. If a step fails, the earlier
    steps' results are kept under ``results/failed/`` next to the failed
    step's partial output, each with the reason as its ``failure`` attribute.
    """
    setup_logging(log_path)
    t0 = time.perf_counter()
    done: dict[str, Any] = {}
    for key, compute in steps:
        t1 = time.perf_counter()
        log.info("%s %s: start", key, label)
        try:
            done[key] = compute(done)
        except StageFailure as err:
            kept = [_keep_failed(ds, outs[prev], f"not written: the later step '{key}' failed: {err}")
                    for prev, ds in done.items()]
            if err.partial is not None:
                kept.append(_keep_failed(err.partial, outs[key], str(err)))
            log.error("%s %s: FAILED: %s (kept for diagnosis: %s)", key, label, err, ", ".join(kept) or "nothing")
            raise
        log.info("%s %s: done in %.2f s", key, label, time.perf_counter() - t1)
    for key, ds in done.items():
        write_netcdf(ds, outs[key])
    log.info("%s: all done in %.2f s -> %s", label, time.perf_counter() - t0, ", ".join(map(str, outs.values())))
    return done
