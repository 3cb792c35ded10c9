"""The temporary files of atomic writes, and the ones a killed writer left behind.

Every atomic writer (:func:`cradle.data.io.write_netcdf`, :class:`cradle.data.appending.Appender`,
the figures) writes to ``.NAME.pid-PID@HOST.XXXXXXXX.tmp`` beside its target ``NAME`` (hidden, so no
reader takes it for an output) and renames it when complete. A write killed before the rename leaves
that file behind; the process id and host in its name tell whether its writer is still running:
:func:`stale_temporaries` lists those whose writer is gone, :func:`remove_stale_temporaries` deletes
them. A temporary of an older version (``.NAME.XXXXXXXX.tmp``, no process id) or of another host
(a shared file system) is stale once unmodified for ``older_than_s`` seconds.
"""
from __future__ import annotations

import os
import re
import socket
import tempfile
import time
from pathlib import Path

#: a temporary file of an atomic write: ``.NAME.`` then, since temporaries name their writer,
#: ``pid-PID@HOST.``, then mkstemp's random part and ``.tmp`` (a figure's: ``.tmp.png``, ``.tmp.pdf``)
PATTERN = re.compile(r"^\.(?P<name>.+?)\.(?:pid-(?P<pid>\d+)@(?P<host>[A-Za-z0-9-]*)\.)?"
                     r"(?P<random>[A-Za-z0-9_]+)\.tmp(?:\.[A-Za-z0-9]+)?$")
#: a temporary unmodified this long whose writer cannot be asked (no process id, another host)
STALE_AFTER_S = 3600.0


def _host() -> str:
    return re.sub(r"[^A-Za-z0-9-]", "-", socket.gethostname().split(".")[0])


_HOST = _host()


def temporary_beside(path: Path, suffix: str = ".tmp") -> str:
    """Create an empty temporary file beside ``path`` named after it and this process (see module)."""
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.pid-{os.getpid()}@{_host()}.", suffix=suffix, dir=path.parent)
    os.close(fd)
    return tmp


def open_beside(path: Path, mode: int, suffix: str = ".tmp") -> tuple[int, str]:
    """:func:`temporary_beside`'s file (the same name, its random part from ``os.urandom``), created and left open
    for writing: (its file descriptor, its path), with permissions ``mode`` whatever the umask (a small file written
    at once: one open, no second one by name)."""
    head = os.path.join(path.parent, f".{path.name}.pid-{os.getpid()}@{_HOST}.")
    for _ in range(100):
        tmp = f"{head}{os.urandom(6).hex()}{suffix}"
        try:
            fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0), mode)
        except FileExistsError:
            continue
        try:
            os.fchmod(fd, mode)
        except BaseException:
            os.close(fd)
            os.remove(tmp)
            raise
        return fd, tmp
    raise FileExistsError(f"no free temporary name beside {path}")


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process: alive
        return True
    return True


def _is_stale(path: Path, match: re.Match, older_than_s: float, now: float) -> bool:
    if match["pid"] is not None and match["host"] == _host():
        return not _alive(int(match["pid"]))
    try:
        return now - path.stat().st_mtime > older_than_s
    except FileNotFoundError:  # renamed or removed meanwhile: its writer finished
        return False


def stale_temporaries(folder: str | os.PathLike, older_than_s: float = STALE_AFTER_S) -> list[Path]:
    """The temporary files of atomic writes under ``folder`` (recursively) left by a writer that is
    gone: its process id on this host is not running, or, without a process id of this host, the file
    has not been modified for ``older_than_s`` seconds."""
    folder, now = Path(folder), time.time()
    found = []
    for root, _dirs, files in os.walk(folder):
        for name in files:
            m = PATTERN.match(name)
            if m is not None and _is_stale(Path(root, name), m, older_than_s, now):
                found.append(Path(root, name))
    return sorted(found)


def remove_stale_temporaries(folder: str | os.PathLike, older_than_s: float = STALE_AFTER_S) -> list[Path]:
    """Delete the :func:`stale_temporaries` under ``folder``; returns the files removed (the workflow
    calls it when it starts, so a killed run leaves no debris)."""
    removed = []
    for path in stale_temporaries(folder, older_than_s):
        try:
            path.unlink()
        except FileNotFoundError:
            continue
        removed.append(path)
    return removed
