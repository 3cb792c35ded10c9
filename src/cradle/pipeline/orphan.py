"""A job whose parent is gone stops: no orphan keeps computing and writing after its Snakemake was killed.

``kill -9`` of Snakemake (or of ``cradle run``'s shell) does not reach the job it started: the job is
re-parented to init (or to a subreaper) and used to run to its end, writing its outputs behind the
back of the next run. :func:`watch_parent` starts a daemon thread that looks, every ``interval``
seconds, whether the Snakemake that started the job is still among its parents (the workflow puts
its process id in ``$CRADLE_SNAKEMAKE_PID``; so a Snakemake killed while the job was still starting
up is noticed too), or, outside the workflow, whether the parent the job started with is still its
parent. When not, the job logs one line and is interrupted in its main thread (``KeyboardInterrupt``,
raised by a handler of ``SIGUSR1``: Snakemake starts its jobs with ``SIGINT`` ignored), so the atomic
writes of
:mod:`cradle.data.io` remove their temporary files as for Ctrl-C. A job busy in compiled code for
longer than ``grace`` seconds (it notices the interrupt only when it returns to Python) is ended
with ``os._exit``; a temporary file it leaves is removed by the workflow's next start.
"""
from __future__ import annotations

import _thread
import logging
import os
import signal
import threading
import time
from collections.abc import Callable
from types import FrameType
from typing import NoReturn

log = logging.getLogger("cradle")

#: the process id of the Snakemake whose job this is (set by the Snakefile, inherited by its jobs)
ENV_VAR = "CRADLE_SNAKEMAKE_PID"
#: how many generations up a job may be from its Snakemake (a shell between them, or none)
DEPTH = 3
#: seconds between two looks at the parent
INTERVAL_S = 1.0
#: seconds an interrupted job has to stop by itself before it is ended
GRACE_S = 10.0

_state: dict[str, object] = {}


def orphaned() -> bool:
    """Whether this process found its parent gone and was told to stop."""
    return bool(_state.get("orphaned"))


def watch_parent(interval: float = INTERVAL_S, grace: float = GRACE_S) -> None:
    """Stop this process when its parent goes away (module docstring); once per process."""
    if _state.get("pid") == os.getpid():   # already watching (a forked child starts its own watch)
        return
    if threading.current_thread() is not threading.main_thread():   # only the main thread sets handlers
        return
    signal.signal(signal.SIGUSR1, _stop)
    _state.update(pid=os.getpid(), orphaned=False)
    threading.Thread(target=_watch, args=(_has_parent(), interval, grace), name="cradle-parent-watch",
                     daemon=True).start()


def _ancestors() -> list[int] | None:
    """The process ids of this process's parent, grandparent, ... (:data:`DEPTH` of them at most), from
    Linux's /proc; None where that cannot be read."""
    out: list[int] = []
    pid = os.getpid()
    for _ in range(DEPTH):
        try:
            with open(f"/proc/{pid}/stat") as f:
                pid = int(f.read().rsplit(")", 1)[1].split()[1])
        except (OSError, ValueError, IndexError):
            return None
        out.append(pid)
        if pid <= 1:
            break
    return out


def _has_parent() -> tuple[Callable[[], bool], int]:
    """A test of whether this process still has the parent it is a job of: its Snakemake among its
    ancestors (``$CRADLE_SNAKEMAKE_PID``, where /proc tells), else the same parent as now."""
    try:
        snakemake = int(os.environ.get(ENV_VAR, ""))
    except ValueError:
        snakemake = None
    if snakemake is not None and _ancestors() is not None:
        return lambda: snakemake in (_ancestors() or [snakemake]), snakemake
    parent = os.getppid()
    return lambda: os.getppid() == parent, parent


def _stop(signum: int, frame: FrameType | None) -> NoReturn:
    raise KeyboardInterrupt("parent process gone")


def _watch(has_parent: tuple[Callable[[], bool], int], interval: float, grace: float) -> None:
    alive, parent = has_parent
    while alive():
        time.sleep(interval)
    _state["orphaned"] = True
    log.error("parent process %d is gone (Snakemake killed?): stopping this job; its outputs are not written",
              parent)
    _thread.interrupt_main(signal.SIGUSR1)
    time.sleep(grace)
    log.error("job did not stop within %.0f s of losing its parent: ending it now", grace)
    logging.shutdown()
    os._exit(1)
