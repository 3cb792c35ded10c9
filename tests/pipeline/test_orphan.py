"""A job whose Snakemake is killed (``kill -9``: no signal reaches the job) stops by itself within seconds
(cradle.pipeline.orphan), and the atomic write it was in removes its temporary file."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src"

#: the job: logs through the runner (which starts the watch), then writes a file slowly (atomically)
JOB = r"""
import sys, time
from pathlib import Path
from cradle.data.io import _atomic
from cradle.pipeline.runner import setup_logging

folder = Path(sys.argv[1])
setup_logging(str(folder / "job.log"))

def slow(tmp):
    Path(tmp).write_text("partial")
    (folder / "writing").touch()
    for _ in range(600):
        time.sleep(0.1)

_atomic(folder / "out.txt", slow)
"""

#: its parent (Snakemake's place): starts the job, says its process id, and waits
PARENT = r"""
import os, subprocess, sys, time
env = dict(os.environ)
if sys.argv[2] == "snakemake":
    env["CRADLE_SNAKEMAKE_PID"] = str(os.getpid())
job = subprocess.Popen([sys.executable, "-c", sys.argv[3], sys.argv[1]], env=env,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
print(job.pid, flush=True)
time.sleep(600)
"""


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    with open(f"/proc/{pid}/stat") as f:   # a zombie waiting for init to reap it has stopped
        return f.read().rsplit(")", 1)[1].split()[0] != "Z"


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads /proc (Linux)")
@pytest.mark.parametrize("how", ["snakemake", "parent"])
def test_a_job_stops_when_its_parent_is_killed(tmp_path, how):
    """``snakemake``: the job knows its Snakemake ($CRADLE_SNAKEMAKE_PID); ``parent``: outside the
    workflow, the parent it started with."""
    env = dict(os.environ, PYTHONPATH=str(SRC))
    parent = subprocess.Popen([sys.executable, "-c", PARENT, str(tmp_path), how, JOB], env=env,
                              stdout=subprocess.PIPE, text=True)
    try:
        assert parent.stdout is not None
        job = int(parent.stdout.readline())
        deadline = time.monotonic() + 120
        while not (tmp_path / "writing").exists():
            assert time.monotonic() < deadline and _alive(job), "the job did not start writing"
            time.sleep(0.1)
    finally:
        os.kill(parent.pid, signal.SIGKILL)
        parent.wait()
    killed = time.monotonic()
    while _alive(job) and time.monotonic() - killed < 30:
        time.sleep(0.1)
    stopped = time.monotonic() - killed
    if _alive(job):
        os.kill(job, signal.SIGKILL)
    assert stopped < 5, f"the orphaned job ran {stopped:.1f} s after its parent was killed"
    lines = (tmp_path / "job.log").read_text().splitlines()
    assert f"parent process {parent.pid} is gone" in lines[-1] and "Traceback" not in "\n".join(lines)
    assert not (tmp_path / "out.txt").exists()
    assert not list(tmp_path.glob(".out.txt.*.tmp")), "the atomic write left its temporary file"
