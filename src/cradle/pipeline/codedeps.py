"""Which source files a job runs: the transitive ``cradle`` imports of its entry points.

A rule's code inputs are derived, never listed by hand: :func:`code_files`
parses the entry points (a workflow script, a module name) with :mod:`ast`,
follows every import of a ``cradle`` module -- at module level or inside a
function, absolute or relative -- and returns the source file of each module
reached, with the ``__init__.py`` of every package on the way (Python runs
them on import). So an edit to any module reruns exactly the jobs whose code
can reach it: a change to :mod:`cradle.data.provenance` (imported by the
netCDF writer and reader) reruns everything, a change to a figure helper only
the figures drawn with it.

Only the source text is read: nothing is imported, so the Snakefile can plan
without numpy or matplotlib. Each file is parsed once per version: :func:`stamp_all`
keeps its fingerprint and import statements in ``.snakemake/cradle-code.index.json``,
keyed by the file's inode, size and times (its change time moves with every write), so a
later read of the Snakefile parses only what was written since.

A rule's input is not the source files themselves but one stamp file for the code it
runs (:func:`code_stamps`): the :func:`fingerprint` of each module's code it reaches,
rewritten only when one of them changes. An edit to a comment or a docstring leaves the
stamps, and so every job, alone; an edit to the code moves the stamps that name the
module, and the jobs whose code reaches it rerun (Snakemake compares an input's time,
then its checksum). Every stamp is written when the Snakefile is read, before Snakemake
takes its inventory of the files (the rules ask for them then, or the Snakefile does:
workflow/rules/common.smk).
"""
from __future__ import annotations

import ast
import hashlib
import json
import os
import sys
import time
from collections import deque
from collections.abc import Iterator
from pathlib import Path

PACKAGE = "cradle"

#: where :func:`code_stamps` writes the stamps, relative to the workflow's working directory
STAMPS = Path(".snakemake") / "cradle-code"
#: the folder, under the stamps, of each job's code stamp (:func:`code_stamps`)
JOBS = "jobs"


#: (src, module name) -> its file or None, found once per read of the Snakefile (:func:`stamp_all` empties it)
_FOUND: dict[tuple[str, str], Path | None] = {}


def _module_file(src: Path, name: str) -> Path | None:
    """src/cradle/a/b.py or src/cradle/a/b/__init__.py for ``cradle.a.b``; None if neither."""
    key = (str(src), name)
    if key in _FOUND:   # asked some 15,000 times per Snakefile read, for a few hundred names
        return _FOUND[key]
    base = os.path.join(src, *name.split("."))
    found = next((Path(p) for p in (base + ".py", os.path.join(base, "__init__.py")) if os.path.isfile(p)), None)
    _FOUND[key] = found
    return found


#: the node types that hold statements: a def, a class or an import is a statement, found only in their bodies
_BLOCKS = (ast.stmt, ast.excepthandler, ast.match_case)


def _statements(tree: ast.Module) -> Iterator[ast.AST]:
    """The module and every statement of ``tree`` (with the except and case clauses that hold some), in the
    order of :func:`ast.walk`, without visiting the expressions, which hold no statement."""
    todo = deque([tree])
    while todo:
        node = todo.popleft()
        for field in node._fields:
            value = getattr(node, field, None)
            if isinstance(value, list) and value and isinstance(value[0], _BLOCKS):
                todo.extend(value)
        yield node


def _without_docstrings(tree: ast.Module) -> ast.Module:
    """``tree`` with the docstring of the module and of every class and function removed (in place)."""
    for node in _statements(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
                    and isinstance(body[0].value.value, str):
                node.body = body[1:] or [ast.Pass()]
    return tree


def fingerprint(path: str | Path) -> str:
    """sha256 of the code of the Python file at ``path``: its syntax tree without docstrings, positions
    or comments (the parser drops those), so only an edit that changes what runs changes it."""
    return _facts(path)[0]


#: an import statement of a file: ("import", 0, None, names) or ("from", level, module, names)
_Record = tuple[str, int, str | None, tuple[str, ...]]

#: what is known of each file read, by absolute path: the :func:`_identity` of the version read, its
#: fingerprint and its import statements (loaded from and saved to the index of :func:`stamp_all`)
_KNOWN: dict[str, tuple[tuple[int, ...], str, tuple[_Record, ...]]] = {}


def _identity(st: os.stat_result) -> tuple[int, ...]:
    """A version of a file: its device, inode, size, modification and change times. Every write changes
    the change time (which no program can set), so a file with the same identity has the same text."""
    return st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns, st.st_ctime_ns


def _facts(path: str | Path) -> tuple[str, tuple[_Record, ...]]:
    """The fingerprint and the import statements of the file at ``path``, parsed once per version."""
    absolute = os.path.abspath(path)
    identity = _identity(os.stat(absolute))   # before the text is read: a later write gives a new identity
    known = _KNOWN.get(absolute)
    if known is None or known[0] != identity:
        tree = ast.parse(Path(absolute).read_text(), str(path))
        records = tuple(("import", 0, None, tuple(a.name for a in node.names)) if isinstance(node, ast.Import)
                        else ("from", node.level, node.module, tuple(a.name for a in node.names))
                        for node in _statements(tree) if isinstance(node, (ast.Import, ast.ImportFrom)))
        code = hashlib.sha256(ast.dump(_without_docstrings(tree)).encode()).hexdigest()
        known = _KNOWN[absolute] = identity, code, records
    return known[1], known[2]


def _index_file(stamps: Path) -> Path:
    """Where :func:`stamp_all` keeps what it knows of each file, beside the stamps folder."""
    return stamps.with_name(f"{stamps.name}.index.json")


#: a file changed this recently is not saved to the index: its change time may not yet tell its next
#: write from this one (file times advance by the kernel's clock tick, some milliseconds)
RECENT_NS = 2 * 10**9


def _load_index(stamps: Path) -> None:
    """Add the facts saved by earlier runs (of this Python: the fingerprint is the dump of its syntax tree)."""
    try:
        saved = json.loads(_index_file(stamps).read_text())
    except (OSError, ValueError):
        return
    if not isinstance(saved, dict) or saved.get("python") != sys.version:
        return
    for path, (identity, code, records) in saved.get("files", {}).items():
        if path not in _KNOWN:
            _KNOWN[path] = tuple(identity), code, tuple((k, level, module, tuple(names))
                                                        for k, level, module, names in records)


def _save_index(stamps: Path, paths: list[str]) -> None:
    """Save the facts of ``paths`` (atomically: another Snakemake may save at once; either file is whole)."""
    now = time.time_ns()
    files = {p: _KNOWN[p] for p in map(os.path.abspath, paths)
             if p in _KNOWN and _KNOWN[p][0][4] < now - RECENT_NS}
    index = _index_file(stamps)
    tmp = index.with_name(f".{index.name}.{os.getpid()}.tmp")
    try:
        tmp.write_text(json.dumps({"python": sys.version, "files": files}))
        os.replace(tmp, index)
    except OSError:   # only a cache: the next run parses again
        tmp.unlink(missing_ok=True)


def _stamp(path: str, name: str, stamps: Path) -> str:
    """The stamp ``name`` of one source file, written (atomically) only when its fingerprint changed."""
    return _write_if_changed(stamps / f"{name}.sha256", f"{fingerprint(path)}  {path}\n")


def _write_if_changed(stamp: Path, text: str) -> str:
    """``text`` at ``stamp``, written (atomically) only when it differs from what is there."""
    try:
        if stamp.read_text() == text:
            return str(stamp)
    except OSError:
        pass
    stamp.parent.mkdir(parents=True, exist_ok=True)
    tmp = stamp.with_name(f".{stamp.name}.{os.getpid()}.tmp")
    tmp.write_text(text)
    os.replace(tmp, stamp)   # another Snakemake (a cluster job) may write the same stamp at once
    return str(stamp)


def code_stamps(*entries: str | Path, src: str | Path = "src", stamps: str | Path = STAMPS) -> list[str]:
    """A rule's code input: one stamp for the code its ``entries`` reach, ``stamps/jobs/<entries>.sha256``
    (``workflow.scripts.figure+cradle.figures.maps.sha256``), a line per file -- each script among
    ``entries`` and every source file :func:`code_files` finds -- with its :func:`fingerprint`; rewritten
    only when one of them changes, or the set of files does.

    One file, not one per module: Snakemake looks at every input of every job ready to run each time it
    picks the next (their sizes, for its greedy scheduler), and eighty code inputs a job made that a large
    part of a build's time."""
    scripts = [str(e) for e in entries if str(e).endswith(".py")]
    files = sorted(set(scripts) | set(code_files(*entries, src=src)))
    key = "+".join(Path(str(e)).with_suffix("").as_posix().replace("/", ".") if str(e).endswith(".py") else str(e)
                   for e in entries)
    text = "".join(f"{fingerprint(f)}  {f}\n" for f in files)
    return [_write_if_changed(Path(stamps) / JOBS / f"{key}.sha256", text)]


def stamped_files(stamp: str | Path) -> list[str]:
    """The source files a job's code stamp (:func:`code_stamps`) names."""
    return [line.split("  ", 1)[1] for line in Path(stamp).read_text().splitlines() if "  " in line]


def stamp_all(src: str | Path = "src", scripts: str | Path = "workflow/scripts", stamps: str | Path = STAMPS) -> int:
    """Bring the stamp of every module under ``src``/cradle and every script under ``scripts`` up to date;
    returns how many there are. The Snakefile calls it when it is read, before Snakemake takes its
    inventory of the files on disk: a stamp first written later, by an input function while the DAG is
    built, would be missing from that inventory and reported as a missing input."""
    src, scripts, stamps = Path(src), Path(scripts), Path(stamps)
    _FOUND.clear()   # modules may have been added or removed since the last read (a test's tree, a long process)
    # what earlier runs found in the files whose version is unchanged: parsing every module on every read
    # of the Snakefile (every cluster job reads it) cost more than the rest of the stamping
    _load_index(stamps)
    done = []
    for root, prefix in ((src, src), (scripts, Path())):
        base = root / PACKAGE if root == src else root
        for path in sorted(base.rglob("*.py")):
            name = path.relative_to(prefix).with_suffix("").as_posix().replace("/", ".")
            _stamp(str(path), name, stamps)
            done.append(str(path))
    _save_index(stamps, done)
    return len(done)


def _imports(path: Path, package: str | None) -> tuple[str, ...]:
    """Every module name the file at ``path`` may import (relative ones resolved in ``package``);
    ``from X import y`` gives both X and X.y (y may be a submodule)."""
    found: list[str] = []
    for kind, level, module, names in _facts(path)[1]:
        if kind == "import":
            found += names
            continue
        if level:
            if package is None:
                continue
            head = package.split(".")
            head = head[: len(head) - level + 1]
            base = ".".join(head + ([module] if module else []))
        else:
            base = module or ""
        found.append(base)
        found += [f"{base}.{name}" for name in names if name != "*"]
    return tuple(n for n in found if n == PACKAGE or n.startswith(PACKAGE + "."))


def _with_parents(name: str) -> list[str]:
    parts = name.split(".")
    return [".".join(parts[: i + 1]) for i in range(len(parts))]


def code_files(*entries: str | Path, src: str | Path = "src") -> list[str]:
    """Source files of every ``cradle`` module the entry points can import, transitively.

    ``entries`` are dotted module names (``cradle.figures.maps``) or paths to
    scripts outside the package (``workflow/scripts/figure.py``). ``src`` is
    the folder that holds the ``cradle`` package; paths are returned as
    ``src``-relative strings joined to ``src`` (what Snakemake compares),
    sorted, each once.
    """
    src = Path(src)
    todo: list[tuple[Path, str | None]] = []
    found: dict[str, Path] = {}
    not_modules: set[str] = set()   # names of functions and constants: looked up once

    def visit(name: str) -> None:
        for full in _with_parents(name):
            if full in found or full in not_modules:
                continue
            path = _module_file(src, full)
            if path is None:  # a function or constant of the package, not a module
                not_modules.add(full)
                continue
            found[full] = path
            # a module's package is its folder; so is an __init__.py's (relative imports resolve the same way)
            todo.append((path, full if path.name == "__init__.py" else full.rpartition(".")[0]))

    for entry in entries:
        if isinstance(entry, Path) or str(entry).endswith(".py"):
            for name in _imports(Path(entry), None):
                visit(name)
        else:
            if _module_file(src, str(entry)) is None:
                raise ValueError(f"no module {entry!r} under {src}")
            visit(str(entry))
    while todo:
        path, package = todo.pop()
        for name in _imports(path, package):
            visit(name)
    return sorted(str(path) for path in found.values())
