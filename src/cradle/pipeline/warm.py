"""Jobs forked from a warm process: a script job of a local build skips its interpreter's imports.

A job of the workflow spends about a second starting (the interpreter, Snakemake's script preamble,
numpy, xarray, numba, matplotlib) for a second or a few of work. In a local build the Snakefile starts
one *warm process* (:func:`start`, from ``onstart``): it imports what the workflow's scripts import,
once, and then forks one child per job. The job's own process (the script Snakemake starts) calls
:func:`forward` first thing: it hands its standard streams, working directory, environment and script
to the warm process over a Unix socket and exits with the status of the child, which runs the same
script file, preamble included, as the job's process would have (``runpy``). What each job computes
is unchanged; only where its imports were paid.

Whenever in doubt, the job runs in its own process as before (:func:`forward` returns): no warm process
(a dry run, a cluster executor, ``CRADLE_WARM=0``, not Linux), or one that declines the job because a
module it imported has changed on disk since, or because the job's environment differs from the warm
process's in a variable read at import time (numba's, BLAS thread counts, ``PYTHON*``, ``CRADLE_*``).
The warm process exits with its Snakemake (:func:`stop`, or when its parent is gone). A job killed by
Snakemake (its process ended) has its child interrupted like an orphaned job
(:mod:`cradle.pipeline.orphan`: ``SIGUSR1``, then killed after the grace).

Only the standard library is imported here: the job's process must stay light.
"""
from __future__ import annotations

import json
import os
import signal
import socket
import struct
import sys
import time
from collections.abc import Mapping
from typing import Any

#: the environment variable naming the warm process's socket (set by :func:`start` for the jobs)
ENV_VAR = "CRADLE_WARM"
#: values of :data:`ENV_VAR` that mean no warm process (unset, or turned off by the user)
OFF = ("", "0", "off", "no")
#: set in a child forked for a job: the Linux uptime (s) at which the job's own process started, so the
#: job's start-up still counts from there (:func:`cradle.pipeline.runner.process_age`)
STARTED_VAR = "CRADLE_JOB_STARTED"
#: set in a job that runs in its own process although a warm process was there: why
DECLINED_VAR = "CRADLE_WARM_DECLINED"
#: environment variables that act when a module is imported: a job whose values differ is not forked
IMPORT_TIME_PREFIXES = ("NUMBA_", "OMP_", "OPENBLAS_", "MKL_", "GOTO_", "VECLIB_", "NUMEXPR_", "PYTHON",
                        "MPL", "CRADLE_", "LD_")
#: those of them that differ from job to job by design
PER_JOB = (ENV_VAR, STARTED_VAR, DECLINED_VAR)
#: the fewest jobs a build has for a warm process to be started: it costs a few seconds of one core to import
#: what the jobs import, while the first jobs start in their own processes, and each later job saves about one
MIN_JOBS = 6
#: seconds a job waits for the warm process to answer before running in its own process
CONNECT_TIMEOUT_S = 30.0
#: seconds a child has, after its job's process is gone and it was interrupted, before it is killed
GRACE_S = 10.0
#: the thread counts Snakemake sets for each job (snakemake.shell)
THREAD_VARS = ("OMP_NUM_THREADS", "GOTO_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS",
               "VECLIB_MAXIMUM_THREADS", "NUMEXPR_NUM_THREADS")
#: modules every job's script preamble imports (snakemake.script builds it)
PREAMBLE = ("pickle", "snakemake.logging", "snakemake.iocontainers", "snakemake.script")


def process_started() -> float | None:
    """When this process started, in seconds of Linux uptime (None where /proc cannot tell)."""
    try:
        with open("/proc/self/stat") as f:
            ticks = int(f.read().rsplit(")", 1)[1].split()[19])
        return ticks / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError):
        return None


def _import_time_env(env: Mapping[str, str]) -> dict:
    return {k: v for k, v in env.items() if k.startswith(IMPORT_TIME_PREFIXES) and k not in PER_JOB}


# ---------------------------------------------------------------------------------------- the job's side

def forward(script_globals: dict) -> None:
    """Run this job in a child of the warm process and exit with its status; return (to run it here)
    when there is none or it declines. Called first in a workflow script, with ``globals()``."""
    name = os.environ.get(ENV_VAR, "")
    if name in OFF or os.environ.get(STARTED_VAR) or not sys.platform.startswith("linux"):
        return   # no warm process, or already its child
    script = str(script_globals.get("__real_file__") or script_globals.get("__file__"))
    try:
        sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        sock.settimeout(CONNECT_TIMEOUT_S)
        sock.connect("\0" + name)
        cradle = _cradle_origin()
        request = json.dumps({"script": os.path.abspath(script), "argv": sys.argv, "cwd": os.getcwd(),
                              "env": dict(os.environ), "started": process_started(), "pid": os.getpid(),
                              "python": sys.executable, "cradle": cradle}).encode()
        socket.send_fds(sock, [struct.pack("!I", len(request)) + request], [0, 1, 2])
        sock.settimeout(None)
        reader = sock.makefile("r")
        answer = reader.readline().split(" ", 1)
    except OSError:   # no warm process (still starting, or gone): routine, this process runs the job
        os.environ[DECLINED_VAR] = "the warm process was not up yet"
        return
    if answer[0] != "forked":
        os.environ[DECLINED_VAR] = answer[-1].strip() or "no answer"
        sock.close()
        return
    # the child runs the job with this process's streams; this process waits for its status
    status = reader.readline().split()
    code = int(status[1]) if len(status) == 2 and status[0] == "exit" else 1
    sys.stdout.flush()
    sys.stderr.flush()
    if code < 0:   # ended by a signal: end the same way, as Snakemake would have seen it
        signal.signal(-code, signal.SIG_DFL)
        os.kill(os.getpid(), -code)
    os._exit(code)


def _cradle_origin() -> str | None:
    """Where this process would import ``cradle`` from (without importing it)."""
    from importlib.util import find_spec

    spec = find_spec("cradle")
    return os.path.realpath(spec.origin) if spec and spec.origin else None


# ---------------------------------------------------------------------------- the workflow's side (start/stop)

_server: dict = {}


def start(workflow: Any) -> str | None:  # Snakemake's workflow object
    """Start the warm process of a local build (from the Snakefile's ``onstart``); its socket's name goes
    to the jobs in ``$CRADLE_WARM``. None (and no process) for a cluster executor or a job's own Snakemake,
    off Linux, for fewer than :data:`MIN_JOBS` jobs, or with ``CRADLE_WARM=0`` in the environment."""
    import subprocess

    if os.environ.get(ENV_VAR, "") in OFF[1:]:
        return None
    if not sys.platform.startswith("linux") or not getattr(workflow, "local_exec", False) \
            or getattr(workflow, "remote_exec", False) or getattr(workflow, "subprocess_exec", False):
        return None
    try:
        jobs = sum(1 for _ in workflow.dag.needrun_jobs())
    except Exception:   # another Snakemake's inside: assume a build worth it
        jobs = MIN_JOBS
    if jobs < MIN_JOBS:
        return None
    name = f"cradle-warm-{os.getpid()}-{os.urandom(6).hex()}"
    scripts = os.path.join(workflow.basedir, "workflow", "scripts")
    log_path = os.path.join(".snakemake", "log", "cradle-warm.log")
    os.makedirs(os.path.dirname(log_path), exist_ok=True)
    # as Snakemake's shell sets them for a one-thread job (every job of a local build but the few that ask for
    # more threads, which then run in their own process)
    env = dict(os.environ, **{var: "1" for var in THREAD_VARS})
    with open(log_path, "w") as log:
        proc = subprocess.Popen([sys.executable, "-m", "cradle.pipeline.warm", name, str(os.getpid()), scripts],
                                stdin=subprocess.DEVNULL, stdout=log, stderr=log, env=env)
    _server.update(proc=proc, name=name)
    os.environ[ENV_VAR] = name
    return name


def stop() -> None:
    """End the warm process started by :func:`start` (from ``onsuccess`` and ``onerror``)."""
    proc = _server.pop("proc", None)
    os.environ.pop(ENV_VAR, None)
    if proc is not None and proc.poll() is None:
        proc.terminate()
        try:
            proc.wait(5)
        except Exception:
            proc.kill()


# --------------------------------------------------------------------------------------- the warm process

def script_imports(folder: str) -> list[str]:
    """The modules the workflow's scripts in ``folder`` import (their top-level ``import``/``from``)."""
    import ast

    names: list[str] = []
    for entry in sorted(os.listdir(folder)):
        if entry.endswith(".py"):
            with open(os.path.join(folder, entry)) as f:
                tree = ast.parse(f.read())
            for node in tree.body:
                if isinstance(node, ast.Import):
                    names += [a.name for a in node.names]
                elif isinstance(node, ast.ImportFrom) and node.module and not node.level:
                    names.append(node.module)
    return list(dict.fromkeys(n for n in names if n != __name__))


#: imported with the scripts' own imports: what half the jobs (the figures) import lazily
FIRST = ("matplotlib.figure", "matplotlib.backends.backend_agg", "matplotlib.backends.backend_pdf")
#: imported one at a time while no job waits, then every module of cradle: what the jobs import lazily
LATER = ("scipy.linalg", "scipy.integrate", "scipy.optimize", "scipy.special", "scipy.interpolate",
         "scipy.signal", "scipy.fft")


def cradle_modules() -> list[str]:
    """Every module of the cradle package (the figure and analysis modules are imported on first use)."""
    import pkgutil

    import cradle

    return [m.name for m in pkgutil.walk_packages(cradle.__path__, "cradle.")
            if not m.name.endswith("__main__") and m.name != __name__]


class Server:
    """The warm process: imports, then forks a child per request (single-threaded: it forks)."""

    def __init__(self, name: str, parent: int, scripts: str) -> None:
        import selectors

        # Ctrl-C reaches the whole process group: like Snakemake's jobs, the warm process and its children
        # ignore it (Snakemake ends the jobs, whose children are then interrupted: _job_gone)
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        self.parent = parent
        self.children: dict[int, list] = {}   # child pid -> [connection, job pid, when interrupted]
        self.env = _import_time_env(os.environ)
        self.later = [*LATER, *cradle_modules()]
        wake_r, wake_w = os.pipe()
        os.set_blocking(wake_w, False)
        os.set_blocking(wake_r, False)
        self.wake = wake_r
        signal.signal(signal.SIGCHLD, lambda *_: None)
        signal.set_wakeup_fd(wake_w)
        t0 = time.perf_counter()
        for module in (*PREAMBLE, *script_imports(scripts), *FIRST):
            __import__(module)
        self.modules: dict[str, int] = {}
        self._record()
        self._warm_numba()
        # the socket exists once the imports are done: a job that starts before runs in its own process
        # instead of waiting (abstract socket: no file to clean up, no path length limit)
        self.listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.listener.bind("\0" + name)
        self.listener.listen(64)
        self.selector = selectors.DefaultSelector()
        self.selector.register(self.listener, selectors.EVENT_READ, "accept")
        self.selector.register(wake_r, selectors.EVENT_READ, "child")
        self._say(f"ready: {len(self.modules)} modules of cradle imported in {time.perf_counter() - t0:.2f} s")

    @staticmethod
    def _say(text: str) -> None:
        print(time.strftime("%H:%M:%S"), text, file=sys.stderr, flush=True)

    def _record(self) -> None:
        """Add the files of the cradle modules imported since the last call, with their modification times
        (:meth:`_declines` compares them before each fork)."""
        for mod in list(sys.modules.values()):
            path = getattr(mod, "__file__", None)
            if path and path not in self.modules and getattr(mod, "__name__", "").split(".")[0] == "cradle":
                try:
                    self.modules[path] = os.stat(path).st_mtime_ns
                except OSError:
                    pass

    @staticmethod
    def _warm_numba() -> None:
        """numba's first compiled call in a process builds its target context: once, here."""
        try:
            from cradle.integrators._cache import warm_target

            warm_target()
        except Exception:   # a job then pays it itself
            pass

    def serve(self) -> None:
        while True:
            idle = not self.children and not self.later
            events = self.selector.select(timeout=0 if self.later else 1.0)
            for key, _ in events:
                if key.data == "accept":
                    self._accept()
                elif key.data == "child":
                    try:
                        while os.read(self.wake, 512):
                            pass
                    except BlockingIOError:
                        pass
                else:
                    self._job_gone(key.data)
            self._reap()
            self._interrupted()
            if not events and self.later:   # nothing waits: import one more module the jobs will want
                module = self.later.pop(0)
                try:
                    __import__(module)
                except Exception:
                    pass
                self._record()
            if os.getppid() != self.parent and idle:
                self._say("its Snakemake is gone: exiting")
                return

    def _accept(self) -> None:
        import selectors

        conn, _ = self.listener.accept()
        conn.settimeout(10.0)
        try:
            head, fds, _, _ = socket.recv_fds(conn, 1 << 16, 3)
            size = struct.unpack("!I", head[:4])[0]
            body = head[4:]
            while len(body) < size:
                more = conn.recv(size - len(body))
                if not more:
                    raise OSError("request cut short")
                body += more
            request = json.loads(body)
        except (OSError, ValueError, struct.error) as e:
            self._say(f"a request could not be read: {e}")
            conn.close()
            return
        why = self._declines(request) if len(fds) == 3 else "the job's streams did not arrive"
        if why:
            self._say(f"job {request.get('pid')}: declined ({why})")
            self._send(conn, f"declined {why}\n")
            for fd in fds:
                os.close(fd)
            conn.close()
            return
        pid = os.fork()
        if pid == 0:   # the job
            self._run(request, fds, conn)
        for fd in fds:
            os.close(fd)
        conn.settimeout(None)
        self._send(conn, f"forked {pid}\n")
        self.children[pid] = [conn, request.get("pid"), None]
        self.selector.register(conn, selectors.EVENT_READ, pid)

    def _declines(self, request: dict) -> str | None:
        """Why the job should run in its own process, or None."""
        if request.get("python") != sys.executable:
            return f"another interpreter ({request.get('python')})"
        import cradle

        if request.get("cradle") != os.path.realpath(cradle.__file__):
            return f"cradle imported from elsewhere ({request.get('cradle')})"
        env = _import_time_env(request.get("env", {}))
        if env != self.env:
            keys = sorted(k for k in set(env) | set(self.env) if env.get(k) != self.env.get(k))
            return f"environment differs in {', '.join(keys)}"
        for path, mtime in self.modules.items():
            try:
                changed = os.stat(path).st_mtime_ns != mtime
            except OSError:
                changed = True
            if changed:
                return f"{path} changed since it was imported"
        return None

    @staticmethod
    def _send(conn: socket.socket, text: str) -> None:
        try:
            conn.sendall(text.encode())
        except OSError:
            pass

    def _job_gone(self, pid: int) -> None:
        """The job's process closed its end (killed): interrupt its child, as an orphan would be."""
        entry = self.children.get(pid)
        if entry is None or entry[2] is not None:
            return
        self.selector.unregister(entry[0])
        entry[2] = time.monotonic()
        self._say(f"job {entry[1]} is gone: interrupting its child {pid}")
        try:
            os.kill(pid, signal.SIGUSR1)
        except ProcessLookupError:
            pass

    def _interrupted(self) -> None:
        for pid, (_, _, since) in list(self.children.items()):
            if since is not None and time.monotonic() - since > GRACE_S:
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass

    def _reap(self) -> None:
        while self.children:
            try:
                pid, status = os.waitpid(-1, os.WNOHANG)
            except ChildProcessError:
                return
            if pid == 0:
                return
            entry = self.children.pop(pid, None)
            if entry is None:
                continue
            conn, _, since = entry
            if since is None:
                self.selector.unregister(conn)
                self._send(conn, f"exit {os.waitstatus_to_exitcode(status)}\n")
            conn.close()

    def _run(self, request: dict, fds: list, conn: socket.socket) -> None:
        """In the forked child: become the job's process, run its script, exit with its status."""
        import atexit
        import io
        import runpy
        import tempfile

        code = 1
        try:
            signal.set_wakeup_fd(-1)
            signal.signal(signal.SIGCHLD, signal.SIG_DFL)
            self.selector.close()
            self.listener.close()
            os.close(self.wake)
            for other, *_ in self.children.values():
                other.close()
            conn.close()
            for i, fd in enumerate(fds):
                os.dup2(fd, i)
                os.close(fd)
            # fresh streams on the job's descriptors, buffered as a new interpreter's would be
            sys.stdin = io.TextIOWrapper(io.FileIO(0, "r", closefd=False))
            sys.stdout = io.TextIOWrapper(io.FileIO(1, "w", closefd=False), line_buffering=os.isatty(1),
                                          write_through=False)
            sys.stderr = io.TextIOWrapper(io.FileIO(2, "w", closefd=False), line_buffering=True,
                                          errors="backslashreplace")
            os.chdir(request["cwd"])
            os.environ.clear()
            os.environ.update(request["env"])
            # also what tells forward(), run again by the script, that this is the child
            started = request.get("started")
            os.environ[STARTED_VAR] = "unknown" if started is None else repr(started)
            sys.argv = list(request["argv"])
            tempfile.tempdir = None
            runpy.run_path(request["script"], run_name="__main__")
            code = 0
        except SystemExit as e:
            code = e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
            if e.code is not None and not isinstance(e.code, int):
                print(e.code, file=sys.stderr)
        except KeyboardInterrupt:
            sys.excepthook(*sys.exc_info())
            code = -signal.SIGINT
        except BaseException:
            sys.excepthook(*sys.exc_info())
            code = 1
        finally:
            try:
                _log_usage()
                atexit._run_exitfuncs()
                sys.stdout.flush()
                sys.stderr.flush()
            finally:
                if code < 0:
                    signal.signal(-code, signal.SIG_DFL)
                    os.kill(os.getpid(), -code)
                os._exit(code)


def _log_usage() -> None:
    """Log a forked job's peak memory and CPU time: Snakemake's benchmark of the job measures the job's own
    process, which only waited (benchmarks/estimates.py reads this line instead)."""
    import logging
    import resource

    if not logging.getLogger().handlers:   # the job set up no log
        return
    peak = None
    try:
        with open("/proc/self/status") as f:
            peak = next(int(line.split()[1]) / 1024 for line in f if line.startswith("VmHWM:"))
    except (OSError, StopIteration, ValueError):
        pass
    usage = resource.getrusage(resource.RUSAGE_SELF)
    logging.getLogger("cradle").info("forked job: peak resident memory %s MB, CPU %.2f s (user + system)",
                                     "?" if peak is None else f"{peak:.0f}", usage.ru_utime + usage.ru_stime)


def main(argv: list[str] | None = None) -> int:
    name, parent, scripts = (argv or sys.argv[1:])[:3]
    Server(name, int(parent), scripts).serve()
    return 0


if __name__ == "__main__":
    sys.exit(main())
