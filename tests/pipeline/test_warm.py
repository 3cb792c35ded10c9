"""The warm process (cradle.pipeline.warm): a job handed to it runs in a forked child with the job's own
streams, directory, environment and script, and its process exits with the child's status; a job it should
not fork (another environment, a module changed on disk since it was imported) runs in its own process; a
job whose process is killed has its child stopped."""
from __future__ import annotations

import os
import re
import signal
import socket
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from cradle.pipeline import warm

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="abstract Unix sockets: Linux only")

SRC = Path(__file__).resolve().parents[2] / "src"
#: the first lines of every workflow script
FORWARD = "from cradle.pipeline.warm import forward\nforward(globals())\n"


def _env(**extra) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in (warm.ENV_VAR, warm.STARTED_VAR, warm.DECLINED_VAR)}
    env.update({var: "1" for var in warm.THREAD_VARS}, PYTHONPATH=str(SRC), **extra)
    return env


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    """A warm process for this test's parent (the pytest process), its scripts folder importing json."""
    scripts = tmp_path_factory.mktemp("scripts")
    (scripts / "one.py").write_text("import json\n")
    name = f"cradle-warm-test-{os.getpid()}-{os.urandom(4).hex()}"
    proc = subprocess.Popen([sys.executable, "-m", "cradle.pipeline.warm", name, str(os.getpid()), str(scripts)],
                            env=_env(), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    deadline = time.monotonic() + 120
    while True:   # its socket appears once its imports are done
        probe = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        try:
            probe.connect("\0" + name)
            probe.close()
            break
        except OSError:
            probe.close()
            assert proc.poll() is None and time.monotonic() < deadline, "the warm process did not start"
            time.sleep(0.1)
    yield name, proc
    proc.terminate()
    proc.wait(10)


def _job(tmp_path: Path, body: str, name: str, **env) -> subprocess.CompletedProcess:
    """Run a job script (forward() first, then ``body``) as its own process, handed to the server ``name``."""
    script = tmp_path / "job.py"
    script.write_text(FORWARD + textwrap.dedent(body))
    return subprocess.run([sys.executable, str(script), "arg1"], cwd=tmp_path, capture_output=True, text=True,
                          env=_env(**{warm.ENV_VAR: name}, **env), timeout=60)


def test_a_job_runs_in_a_forked_child_with_its_streams_directory_environment_and_status(server, tmp_path):
    name, proc = server
    done = _job(tmp_path, """
        import os, sys
        print("out", os.getppid(), os.getcwd(), sys.argv[1], os.environ.get("JOB_VALUE"), flush=True)
        print("err", file=sys.stderr)
        sys.exit(3)
    """, name, JOB_VALUE="seven")
    assert done.returncode == 3
    words = done.stdout.split()
    assert words[0] == "out" and int(words[1]) == proc.pid   # the warm process is its parent
    assert words[2:] == [str(tmp_path), "arg1", "seven"]
    assert done.stderr.strip() == "err"


def test_an_uncaught_exception_is_reported_and_fails_the_job(server, tmp_path):
    done = _job(tmp_path, "raise ValueError('the reason')\n", server[0])
    assert done.returncode == 1
    assert "ValueError: the reason" in done.stderr


def test_start_up_counts_from_the_jobs_own_process(server, tmp_path):
    done = _job(tmp_path, """
        import os
        from cradle.pipeline.runner import process_age
        print(os.environ["CRADLE_JOB_STARTED"], process_age())
    """, server[0])
    assert done.returncode == 0, done.stderr
    started, age = map(float, done.stdout.split())
    assert started > 0 and 0 < age < 60


def test_another_import_time_environment_runs_in_its_own_process(server, tmp_path):
    done = _job(tmp_path, """
        import os
        print(os.getppid(), os.environ.get("CRADLE_WARM_DECLINED"))
    """, server[0], NUMBA_OPT="1")
    assert done.returncode == 0, done.stderr
    parent, why = done.stdout.split(" ", 1)
    assert int(parent) != server[1].pid
    assert why.strip() == "environment differs in NUMBA_OPT"


def test_no_warm_process_runs_the_job_in_its_own_process(tmp_path):
    done = _job(tmp_path, "import os\nprint(os.environ.get('CRADLE_WARM_DECLINED'))\n", "cradle-warm-nobody-here")
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "the warm process was not up yet"


def test_a_module_changed_since_it_was_imported_is_declined(tmp_path):
    module = tmp_path / "mod.py"
    module.write_text("x = 1\n")
    server = object.__new__(warm.Server)
    server.env = warm._import_time_env(_env())
    server.modules = {str(module): module.stat().st_mtime_ns}
    request = {"python": sys.executable, "env": _env(), "cradle": os.path.realpath(warm._cradle_origin())}
    assert server._declines(request) is None
    os.utime(module, ns=(module.stat().st_atime_ns, module.stat().st_mtime_ns + 1))
    assert server._declines(request) == f"{module} changed since it was imported"
    assert server._declines({**request, "python": "/another/python"}).startswith("another interpreter")


def test_a_killed_job_has_its_child_stopped(server, tmp_path):
    """Killing the job's process (as Snakemake ends a job) interrupts its child: a KeyboardInterrupt inside it,
    as for an orphaned job (cradle.pipeline.orphan)."""
    marker = tmp_path / "child.pid"
    script = tmp_path / "job.py"
    script.write_text(FORWARD + textwrap.dedent(f"""
        import os, time
        from cradle.pipeline.orphan import watch_parent
        watch_parent()   # as every job does (cradle.pipeline.runner.setup_logging): SIGUSR1 interrupts it
        open({str(marker)!r}, "w").write(str(os.getpid()))
        try:
            time.sleep(60)
        except KeyboardInterrupt:
            open({str(marker)!r} + ".interrupted", "w").write("yes")
            raise
    """))
    job = subprocess.Popen([sys.executable, str(script)], cwd=tmp_path, env=_env(**{warm.ENV_VAR: server[0]}))
    deadline = time.monotonic() + 60
    while not marker.exists() or not marker.read_text():
        assert time.monotonic() < deadline and job.poll() is None
        time.sleep(0.05)
    child = int(marker.read_text())
    assert child != job.pid
    job.send_signal(signal.SIGKILL)
    job.wait()
    deadline = time.monotonic() + warm.GRACE_S + 10
    while Path(f"/proc/{child}").exists():
        assert time.monotonic() < deadline, "the child of a killed job is still running"
        time.sleep(0.05)
    assert (tmp_path / "child.pid.interrupted").read_text() == "yes"


def test_the_scripts_imports_are_read_from_the_scripts():
    folder = Path(__file__).resolve().parents[2] / "workflow" / "scripts"
    names = warm.script_imports(str(folder))
    assert "cradle.pipeline.scene_job" in names and "cradle.figures" in names
    assert "cradle.pipeline.warm" not in names


def test_a_forked_job_logs_its_own_peak_memory_and_cpu(server, tmp_path):
    """Snakemake's benchmark of a forked job measures the process that waited: the child logs its own peak
    (read by benchmarks/estimates.py), at least the pages of the modules it runs with."""
    log = tmp_path / "job.log"
    done = _job(tmp_path, f"""
        import logging
        logging.basicConfig(filename={str(log)!r}, level=logging.INFO, format="%(message)s")
        block = bytes(range(256)) * (400 * 2**20 // 256)   # 400 MB written by this job
    """, server[0])
    assert done.returncode == 0, done.stderr
    line = log.read_text().strip().splitlines()[-1]
    peak, cpu = re.fullmatch(r"forked job: peak resident memory (\d+) MB, CPU ([\d.]+) s \(user \+ system\)",
                             line).groups()
    assert int(peak) >= 400 and float(cpu) > 0
