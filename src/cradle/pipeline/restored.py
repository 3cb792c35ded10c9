"""Outputs a failed job gave back keep their old modification time, so nothing downstream reruns.

A rule whose outputs are flagged ``update()`` (every expensive one: docs/recovery.md) does not lose
them when its job fails: the job writes to a temporary file and renames it over the target only on
success (:func:`cradle.data.io.write_netcdf`), and Snakemake copies its backup back in place. That copy
(``shutil.copy``) gives the file a new modification time, so the next ``snakemake`` would redraw every
reader of a file whose content never changed. :func:`snapshot` (the Snakefile's ``onstart``) records the
identity of every file under ``results/``; :func:`restore_times` (its ``onerror``) sets the old time back
on each file that is still the same file (same inode: written in place by the restore, never renamed
over by a finished job) with the same size and a new time.
"""
from __future__ import annotations

import os

#: path -> (inode, size, modification time in ns)
Snapshot = dict[str, tuple[int, int, int]]


def snapshot(root: str | os.PathLike) -> Snapshot:
    """The inode, size and modification time of every file under ``root`` (none if it does not exist)."""
    out: Snapshot = {}
    for folder, _dirs, files in os.walk(os.fspath(root)):
        for name in files:
            path = os.path.join(folder, name)
            try:
                st = os.stat(path)
            except OSError:   # removed meanwhile
                continue
            out[path] = (st.st_ino, st.st_size, st.st_mtime_ns)
    return out


def restore_times(before: Snapshot) -> list[str]:
    """Set back the modification time of each file of ``before`` that is the same file with the same size
    but a new time (given back by Snakemake after its job failed); returns those paths."""
    restored = []
    for path, (ino, size, mtime) in before.items():
        try:
            st = os.stat(path)
        except OSError:
            continue
        if st.st_ino == ino and st.st_size == size and st.st_mtime_ns != mtime:
            os.utime(path, ns=(st.st_atime_ns, mtime))
            restored.append(path)
    return restored

