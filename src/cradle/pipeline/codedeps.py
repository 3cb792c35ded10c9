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
without numpy or matplotlib.

A rule's inputs are not the source files themselves but one stamp file per module
(:func:`code_stamps`): the :func:`fingerprint` of the module's code, rewritten only
when that changes. An edit to a comment or a docstring leaves the stamp, and so every
job, alone; an edit to the code moves it, and the jobs whose code reaches the module
rerun (Snakemake compares an input's time, then its checksum).
"""
from __future__ import annotations

import ast
import hashlib
import os
from collections import deque
from collections.abc import Iterator
from functools import cache
from pathlib import Path

PACKAGE = "cradle"

#: where :func:`code_stamps` writes the stamps, relative to the workflow's working directory
STAMPS = Path(".snakemake") / "cradle-code"


def _module_file(src: Path, name: str) -> Path | None:
    """src/cradle/a/b.py or src/cradle/a/b/__init__.py for ``cradle.a.b``; None if neither."""
    base = os.path.join(src, *name.split("."))   # strings: this runs some 10,000 times per Snakefile read
    for path in (base + ".py", os.path.join(base, "__init__.py")):
        if os.path.isfile(path):
            return Path(path)
    return None


def _version(path: str | Path) -> tuple[Path, int, int]:
    """``path`` with the time and size of its current version: what the caches here are keyed by."""
    st = os.stat(path)
    return Path(path), st.st_mtime_ns, st.st_size


@cache
def _parsed(path: Path, mtime_ns: int, size: int) -> ast.Module:
    return ast.parse(path.read_text(), str(path))


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
    key = _version(path)
    if key not in _FINGERPRINTS:
        # the shared tree, stripped in place once (stripped twice, a string after a docstring would go
        # too); the import scan finds the same imports in it
        _FINGERPRINTS[key] = hashlib.sha256(ast.dump(_without_docstrings(_parsed(*key))).encode()).hexdigest()
    return _FINGERPRINTS[key]


_FINGERPRINTS: dict[tuple[Path, int, int], str] = {}


def _stamp(path: str, name: str, stamps: Path) -> str:
    """The stamp ``name`` of one source file, written (atomically) only when its fingerprint changed."""
    stamp = stamps / f"{name}.sha256"
    text = f"{fingerprint(path)}  {path}\n"
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
    """A rule's code inputs: the stamp of each script among ``entries`` and of every source file
    :func:`code_files` finds, under ``stamps`` (``cradle.models.dps.sha256``,
    ``workflow.scripts.simulate.sha256``), sorted."""
    def name(path: str, root: Path) -> str:
        return Path(path).relative_to(root).with_suffix("").as_posix().replace("/", ".")

    scripts = [str(e) for e in entries if str(e).endswith(".py")]
    return sorted({_stamp(f, name(f, Path()), Path(stamps)) for f in scripts}
                  | {_stamp(f, name(f, Path(src)), Path(stamps)) for f in code_files(*entries, src=src)})


def stamp_all(src: str | Path = "src", scripts: str | Path = "workflow/scripts", stamps: str | Path = STAMPS) -> int:
    """Bring the stamp of every module under ``src``/cradle and every script under ``scripts`` up to date;
    returns how many there are. The Snakefile calls it when it is read, before Snakemake takes its
    inventory of the files on disk: a stamp first written later, by an input function while the DAG is
    built, would be missing from that inventory and reported as a missing input."""
    src, scripts = Path(src), Path(scripts)
    n = 0
    for root, prefix in ((src, src), (scripts, Path())):
        base = root / PACKAGE if root == src else root
        for path in sorted(base.rglob("*.py")):
            name = path.relative_to(prefix).with_suffix("").as_posix().replace("/", ".")
            _stamp(str(path), name, Path(stamps))
            n += 1
    return n


def _imports(path: Path, package: str | None) -> tuple[str, ...]:
    """Every module name the file at ``path`` may import (relative ones resolved in ``package``);
    ``from X import y`` gives both X and X.y (y may be a submodule)."""
    return _imports_of(*_version(path), package)


@cache
def _imports_of(path: Path, mtime_ns: int, size: int, package: str | None) -> tuple[str, ...]:
    found = []
    for node in _statements(_parsed(path, mtime_ns, size)):
        if isinstance(node, ast.Import):
            found += [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                if package is None:
                    continue
                head = package.split(".")
                head = head[: len(head) - node.level + 1]
                base = ".".join(head + ([node.module] if node.module else []))
            else:
                base = node.module or ""
            found.append(base)
            found += [f"{base}.{alias.name}" for alias in node.names if alias.name != "*"]
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
