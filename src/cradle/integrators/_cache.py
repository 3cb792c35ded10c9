"""Where numba keeps the compiled kernels: one folder per version of their sources.

numba's own cache (``@njit(cache=True)``) checks only the file that defines a
cached function, so a kernel of ``_onset.py`` that inlines or calls a kernel of
``_kernels.py`` keeps loading stale machine code after ``_kernels.py`` changes
(a documented numba limitation). Here numba's cache directory
(``numba.config.CACHE_DIR``) is set to a folder named by a hash of

* the source text of every module of this package that defines kernels
  (``njit`` in its text) and of every ``cradle`` module they import,
  transitively;
* scipy's DOP853 tableau file, whose stage count ``_dop853`` compiles in;
* the versions of Python, numba, llvmlite and numpy.

Any edit of any of these sources selects a new, empty folder (everything is
recompiled once); restoring the text selects the old folder again.

The folders live under a root, the first of:

1. ``$CRADLE_KERNEL_CACHE``;
2. ``$NUMBA_CACHE_DIR/cradle`` if the user set ``NUMBA_CACHE_DIR``;
3. ``$XDG_CACHE_HOME/cradle/numba``;
4. ``~/.cache/cradle/numba``;

and, if that root cannot be written, a folder in the system's temporary
directory (with a warning). Nothing is written next to the sources (a new
folder also deletes the ``.nbi``/``.nbc`` files numba used to leave in
``__pycache__``). Each use touches the folder's modification time;
:func:`prune` then keeps the :data:`KEEP` most recently used folders plus any
used within :data:`GRACE_S`, and removes the rest by renaming each to a
``.trash-*`` name first (atomic, so two processes pruning at once never see a
half-deleted folder) and deleting it afterwards. No locks: a folder removed
under a running process is only a cache miss for it, since numba recreates
its cache path before every save.

A damaged cache file (a truncated or overwritten ``.nbi`` index or ``.nbc`` data file: numba
would stop every kernel that reads it with ``UnpicklingError``, ``EOFError`` or "invalid load
key") is detected where numba reads it (:func:`_guard_loads`): the file is moved aside to
``NAME.damaged``, one line says so in the log, and the kernel is compiled again as on a cache miss.

:func:`activate` must run before numba decorates a kernel (the locator reads
the directory when ``njit(cache=True)`` is applied): each kernel module calls
it after its imports, before its first ``@njit``, so importing
``cradle.integrators`` (which imports them all) activates it.
See docs/compiled-kernels.md.
"""
from __future__ import annotations

import hashlib
import logging
import os
import pickle
import re
import shutil
import sys
import tempfile
import time
import uuid
import warnings
from pathlib import Path
from typing import Any, cast

#: Environment variable naming the root folder of the per-key folders.
ENV_VAR = "CRADLE_KERNEL_CACHE"
#: Folders kept whatever their age: the most recently used ones.
KEEP = 8
#: Folders used within this many seconds are never removed (another process may be using them).
GRACE_S = 3600.0
#: Hex digits of the key that name a folder.
KEY_DIGITS = 16

PACKAGE_DIR = Path(__file__).resolve().parents[1]   # src/cradle
KERNEL_DIR = Path(__file__).resolve().parent         # src/cradle/integrators
INFO_FILE = "cradle-kernel-cache.txt"

_active: dict[str, Any] = {}


def _module_file(name: str) -> Path | None:
    """The source file of module ``name`` of the cradle package, or None if it is not one."""
    parts = name.split(".")
    if parts[0] != PACKAGE_DIR.name:
        return None
    base = PACKAGE_DIR.joinpath(*parts[1:])
    for path in (base.with_suffix(".py"), base / "__init__.py"):
        if path.is_file():
            return path
    return None


def _module_name(path: Path) -> str:
    rel = path.relative_to(PACKAGE_DIR.parent).with_suffix("")
    parts = rel.parts[:-1] if rel.name == "__init__" else rel.parts
    return ".".join(parts)


_IMPORT = re.compile(r"^[ \t]*(?:from[ \t]+(\.*[\w.]*)[ \t]+import[ \t]+(\([^)]*\)|[^\n#;]*)|import[ \t]+([^\n#;]*))",
                     re.MULTILINE)


def _imported_files(path: Path, text: str) -> set[Path]:
    """Files of the cradle modules that ``path`` imports (anywhere in it, relative imports too).

    A regular expression over the lines, not ``ast``: parsing the kernel modules
    would cost more than the rest of :func:`activate`. A docstring line that looks
    like an import can only add a file to the key, never drop one.
    """
    found: set[Path | None] = set()
    package = _module_name(path) if path.name == "__init__.py" else _module_name(path).rpartition(".")[0]
    for m in _IMPORT.finditer(text):
        if m.group(3) is not None:
            found.update(_module_file(item.split()[0]) for item in m.group(3).split(",") if item.split())
            continue
        module = m.group(1)
        level = len(module) - len(module.lstrip("."))
        if level:
            base = package.split(".")[: len(package.split(".")) - level + 1]
            module = ".".join(base + ([module[level:]] if module[level:] else []))
        for item in m.group(2).strip("()").split(","):
            if item.split():
                # ``from pkg import sub``: the submodule if there is one, else what pkg defines
                found.add(_module_file(f"{module}.{item.split()[0]}") or _module_file(module))
    return {path for path in found if path is not None}


def kernel_sources() -> list[Path]:
    """Every module of cradle.integrators (its sub-packages included) defining numba kernels, and the cradle
    modules they import."""
    todo = [p for p in sorted(KERNEL_DIR.rglob("*.py")) if p.name != Path(__file__).name and "njit" in p.read_text()]
    seen: set[Path] = set()
    while todo:
        path = todo.pop()
        if path in seen:
            continue
        seen.add(path)
        todo.extend(_imported_files(path, path.read_text()) - seen)
    return sorted(seen)


def _external_sources() -> list[tuple[str, bytes]]:
    """Files outside cradle whose contents are compiled into the kernels."""
    import importlib.util

    spec = importlib.util.find_spec("scipy")
    assert spec is not None and spec.origin is not None, "scipy is a dependency"
    path = Path(spec.origin).parent / "integrate" / "_ivp" / "dop853_coefficients.py"
    return [("scipy/integrate/_ivp/dop853_coefficients.py", path.read_bytes())]


def cache_key() -> tuple[str, str]:
    """(hex sha256, description) of everything the compiled kernels depend on."""
    import llvmlite
    import numba
    import numpy

    h = hashlib.sha256()
    lines = [f"python {sys.version.split()[0]} {sys.implementation.cache_tag} {getattr(sys, 'abiflags', '')}",
             f"numba {numba.__version__}", f"llvmlite {llvmlite.__version__}", f"numpy {numpy.__version__}"]
    for line in lines:
        h.update(line.encode() + b"\0")
    sources = [(p.relative_to(PACKAGE_DIR.parent).as_posix(), p.read_bytes()) for p in kernel_sources()]
    for name, data in sources + _external_sources():
        h.update(f"{name}\0{len(data)}\0".encode() + data)
        lines.append(f"{name} sha256={hashlib.sha256(data).hexdigest()}")
    return h.hexdigest(), "\n".join(lines) + "\n"


def cache_root() -> Path:
    """The folder holding one folder per key (see the module docstring for the order of choices)."""
    if os.environ.get(ENV_VAR):
        root = Path(os.environ[ENV_VAR]).expanduser()
    elif os.environ.get("NUMBA_CACHE_DIR"):
        root = Path(os.environ["NUMBA_CACHE_DIR"]).expanduser() / "cradle"
    else:
        root = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache").expanduser() / "cradle" / "numba"
    return root.absolute()   # numba would read a relative one against each later working directory


def _prepare(folder: Path, info: str) -> None:
    """Create ``folder`` (with a note of its key) if missing, and mark it used now.

    On creation, also delete the cache files numba used to write next to the
    sources (``__pycache__/*.nbi``, ``*.nbc``): never read any more, and stale.
    """
    folder.mkdir(parents=True, exist_ok=True)
    note = folder / INFO_FILE
    if not note.exists():
        tmp = folder / f".{INFO_FILE}.{uuid.uuid4().hex[:8]}"
        tmp.write_text(info)
        os.replace(tmp, note)
        for old in [*KERNEL_DIR.glob("__pycache__/*.nbi"), *KERNEL_DIR.glob("__pycache__/*.nbc")]:
            try:
                old.unlink()
            except OSError:   # a read-only tree, or another process was first
                pass
    os.utime(folder)


def prune(root: Path, current: Path, keep: int = KEEP, grace_s: float = GRACE_S,
          now: float | None = None) -> list[Path]:
    """Remove the key folders of ``root`` beyond the ``keep`` most recently used, except ``current``
    and those used within ``grace_s`` seconds; return the folders removed.

    Lock-free: each folder is first renamed to a unique ``.trash-*`` name, so of
    two processes pruning at once exactly one takes it (the other's rename
    fails and is ignored); trash left by an interrupted prune is removed too.
    """
    now = time.time() if now is None else now
    folders, trash = [], []
    try:
        entries = list(os.scandir(root))
    except OSError:
        return []
    for entry in entries:
        try:
            if entry.name.startswith(".trash-"):
                trash.append(Path(entry.path))
            elif (len(entry.name) == KEY_DIGITS and all(c in "0123456789abcdef" for c in entry.name)
                  and entry.is_dir(follow_symlinks=False)):
                folders.append((entry.stat(follow_symlinks=False).st_mtime, Path(entry.path)))
        except OSError:   # removed meanwhile
            continue
    folders.sort(key=lambda f: f[0], reverse=True)
    removed = []
    for rank, (mtime, folder) in enumerate(folders):
        if rank < keep or folder == current or now - mtime < grace_s:
            continue
        target = root / f".trash-{folder.name}-{uuid.uuid4().hex[:8]}"
        try:
            os.rename(folder, target)
        except OSError:   # another process took it first
            continue
        removed.append(folder)
        trash.append(target)
    for path in trash:
        shutil.rmtree(path, ignore_errors=True)
    return removed


#: What unpickling a damaged cache file raises (truncated: UnpicklingError or EOFError; overwritten:
#: "invalid load key", or garbage that unpickles into the wrong shape)
_DAMAGE = (pickle.UnpicklingError, EOFError, ValueError, TypeError, IndexError, KeyError, AttributeError,
           ImportError)


def _quarantine(path: str, exc: BaseException) -> None:
    """Move the damaged cache file ``path`` aside (``path.damaged``) and say so in one line."""
    target = f"{path}.damaged"
    try:
        os.replace(path, target)
    except OSError:   # another process moved it first, or the folder is read-only: a miss all the same
        target = "left in place"
    why = " ".join(str(exc).split()) or type(exc).__name__
    logging.getLogger("cradle").warning("compiled-kernel cache: %s is damaged (%s: %s): moved to %s; "
                                        "compiling that kernel again", path, type(exc).__name__, why, target)


def _ours(path: str) -> bool:
    """Whether ``path`` is in this process's cache folder (other numba caches are left to numba)."""
    folder = _active.get("folder")
    return folder is not None and Path(path).resolve().is_relative_to(Path(folder).resolve())


def _guard_loads() -> None:
    """Make numba's reads of this cache's index and data files treat a damaged file as a cache miss
    (:func:`_quarantine`); numba then compiles the kernel and writes a good file in its place."""
    from numba.core import caching

    cls = cast(Any, caching.IndexDataCacheFile)   # its methods are replaced below
    if getattr(cls, "_cradle_guarded", False):
        return
    load_index, load_data = cls._load_index, cls._load_data

    def _load_index(self: Any) -> dict:
        try:
            return load_index(self)
        except _DAMAGE as exc:
            if not _ours(self._index_path):
                raise
            _quarantine(self._index_path, exc)
            return {}

    def _load_data(self: Any, name: str) -> Any:
        try:
            return load_data(self, name)
        except _DAMAGE as exc:
            path = self._data_path(name)
            if not _ours(path):
                raise
            _quarantine(path, exc)
            raise OSError(f"damaged cache file {path}") from None   # numba's load: a missing file, a miss

    cls._load_index = _load_index
    cls._load_data = _load_data
    cls._cradle_guarded = True


def warm_target() -> None:
    """Build numba's compilation target in this process once: the warm process that forks the workflow's
    jobs (:mod:`cradle.pipeline.warm`) does, so that no job's first compiled call pays for it. A throwaway
    function, never cached."""
    import numba

    numba.njit(lambda x: x + 1)(1)


def activate() -> Path:
    """Point numba's cache at this version's folder (created if needed), prune old folders, and
    return the folder. Later calls only set numba's config again (numba re-reads its environment
    variables when it compiles, which would undo the setting if one of them changed)."""
    import numba.core.config as numba_config

    if not _active:
        key, info = cache_key()
        root = cache_root()
        folder = root / key[:KEY_DIGITS]
        try:
            _prepare(folder, info)
        except OSError as exc:
            fallback = Path(tempfile.gettempdir()) / f"cradle-numba-{os.getuid() if hasattr(os, 'getuid') else 0}"
            warnings.warn(f"compiled-kernel cache {root} is not writable ({exc}); using {fallback}",
                          RuntimeWarning, stacklevel=2)
            root, folder = fallback, fallback / key[:KEY_DIGITS]
            _prepare(folder, info)
        prune(root, folder)
        _active.update(root=root, folder=folder, key=key)
        _guard_loads()
    # numba's config module sets its attributes from the environment at run time, unseen by mypy
    cast(Any, numba_config).CACHE_DIR = str(_active["folder"])
    return _active["folder"]
