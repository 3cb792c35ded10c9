"""Provenance of every output: which code, which parameters, which libraries, which command.

:func:`provenance` returns flat netCDF global attributes (names are letters,
digits and underscores, values strings or integers, as CF wants), added by
:func:`cradle.data.io.make_dataset` to every file:

``cradle_version``
    the installed package version;
``git_commit``, ``git_dirty``
    ``git rev-parse HEAD`` of the source tree the package was imported from,
    and 1 if tracked files differ from that commit (0 if not); absent when the
    package is not a git checkout (an installed wheel, a source tarball);
``parameters``, ``params_sha256``
    the canonical JSON (sorted keys, no spaces) of the parameters that produced the file (a spec's
    :func:`cradle.specs.declare.plain`), from which the spec can be rebuilt and checked, and its sha256
    (:func:`params_hash`), when given: two files with the same hash were computed from the same spec;
``software_versions``
    ``python=3.11.7 numpy=... scipy=... numba=... xarray=... netCDF4=...``;
``command``
    ``snakemake rule exact (scene=tw-weak)`` inside a Snakemake job,
    otherwise the command line (``sys.argv``), or what :func:`set_command`
    was told;
``cradle_kind``, ``cradle_name``
    what the file is (:func:`identity`): its kind in the results layout (``exact``, ``dps``, ``initial``,
    ``metrics``, ``homoclinic``, ``map``, ``analysis``, ``analysis-batch``) and the name of its scene, entry,
    analysis or batch, set by the writer that knows them (:func:`identify`); with ``params_sha256`` they are
    what a reader compares with what the config resolves to now (:mod:`cradle.pipeline.identity`).
"""
from __future__ import annotations

import hashlib
import json
import math
import platform
import subprocess
import sys
from functools import cache
from importlib.metadata import PackageNotFoundError, version as _version
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

if TYPE_CHECKING:
    import xarray as xr

try:
    VERSION = _version("cradle")
except PackageNotFoundError:  # running from a source tree that is not installed
    VERSION = "0.0.0+unknown"

__all__ = ["VERSION", "PACKAGES", "KEYS", "IDENTITY_KEYS", "canonical_json", "params_hash", "git_info",
           "software_versions", "command", "set_command", "provenance", "identity", "identify"]

#: the libraries whose versions can change a result
PACKAGES = ("numpy", "scipy", "numba", "xarray", "netCDF4")

#: the global attributes naming what a file is: its kind in the results layout and its name
IDENTITY_KEYS = ("cradle_kind", "cradle_name")
#: every global attribute this module may write (an inherited one is dropped before new ones are set)
KEYS = ("cradle_version", "git_commit", "git_dirty", "parameters", "params_sha256", "software_versions",
        "command") + IDENTITY_KEYS

_COMMAND: str | None = None


def _jsonable(value: Any) -> Any:
    """numpy scalars and arrays, paths, sets -> plain JSON values (for :func:`canonical_json`)."""
    if hasattr(value, "tolist"):  # numpy scalar or array
        return value.tolist()
    if isinstance(value, (set, frozenset)):
        return sorted(value, key=repr)
    if isinstance(value, Path):
        return str(value)
    raise TypeError(f"cannot hash a parameter of type {type(value).__name__}: {value!r}")


def _normalise(value: Any) -> Any:
    """Keys as strings, inf/nan as text (JSON has neither non-string keys nor non-finite numbers)."""
    if isinstance(value, dict):
        return {str(k): _normalise(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_normalise(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return repr(value)
    return value


def canonical_json(params: Any) -> str:
    """The canonical JSON of ``params``: sorted keys, no whitespace, numpy values as plain numbers."""
    plain = json.loads(json.dumps(params, default=_jsonable))
    return json.dumps(_normalise(plain), sort_keys=True, separators=(",", ":"), ensure_ascii=True,
                      allow_nan=False)


def params_hash(params: Any) -> str:
    """sha256 (hex) of :func:`canonical_json` of ``params`` (a resolved config entry)."""
    return hashlib.sha256(canonical_json(params).encode("ascii")).hexdigest()


def _git(args: list[str], cwd: str | Path) -> str | None:
    try:
        out = subprocess.run(["git", *args], cwd=cwd, capture_output=True, text=True, timeout=10)
    except (OSError, subprocess.SubprocessError):
        return None
    return out.stdout.strip() if out.returncode == 0 else None


@cache
def git_info(path: str | None = None) -> dict:
    """``{"git_commit": sha, "git_dirty": 0|1}`` for the git checkout holding ``path``; {} if there is none.

    ``path`` defaults to this package's folder. The file must be tracked by
    that repository (a package installed into a virtualenv that happens to
    sit inside some other git work tree is not attributed to its commit).
    """
    here = Path(path) if path else Path(__file__).resolve().parent
    cwd = here if here.is_dir() else here.parent
    if not cwd.is_dir():
        return {}
    commit = _git(["rev-parse", "--verify", "--quiet", "HEAD"], cwd)
    if not commit:
        return {}
    target = here / "__init__.py" if here.is_dir() else here
    if _git(["ls-files", "--error-unmatch", "--", str(target)], cwd) is None:
        return {}
    status = _git(["status", "--porcelain", "--untracked-files=no"], cwd)
    return {"git_commit": commit, "git_dirty": int(bool(status))}


@cache
def software_versions() -> str:
    """``python=X numpy=Y ...`` for :data:`PACKAGES` that are installed."""
    parts = [f"python={platform.python_version()}"]
    for name in PACKAGES:
        try:
            parts.append(f"{name}={_version(name)}")
        except PackageNotFoundError:
            pass
    return " ".join(parts)


def set_command(text: str | None) -> None:
    """Record the command that produces the outputs of this process (None: back to automatic)."""
    global _COMMAND
    _COMMAND = text


def _snakemake_job() -> str | None:
    """``snakemake rule NAME (wildcards)`` when running inside a Snakemake ``script:`` job."""
    sm = getattr(sys.modules.get("__main__"), "snakemake", None)
    rule = getattr(sm, "rule", None)
    if sm is None or not rule:
        return None
    try:
        wc = ", ".join(f"{k}={v}" for k, v in dict(sm.wildcards.items()).items())
    except Exception:  # noqa: BLE001 - a wildcards object we do not know: the rule name suffices
        wc = ""
    return f"snakemake rule {rule}" + (f" ({wc})" if wc else "")


def command() -> str:
    """The command behind this process's outputs (see the module docstring)."""
    if _COMMAND:
        return _COMMAND
    job = _snakemake_job()
    if job:
        return job
    argv = list(sys.argv) or ["python"]
    argv[0] = Path(argv[0]).name or "python"
    return " ".join(argv)


def provenance(params: Any = None) -> dict:
    """The provenance attributes (see the module docstring); ``parameters`` and ``params_sha256`` only with
    ``params``."""
    attrs = {"cradle_version": VERSION}
    attrs.update(git_info())
    if params is not None:
        attrs["parameters"] = canonical_json(params)
        attrs["params_sha256"] = params_hash(params)
    attrs["software_versions"] = software_versions()
    attrs["command"] = command()
    return attrs


def identity(kind: str, name: str) -> dict:
    """The attributes naming a file: ``{"cradle_kind": kind, "cradle_name": name}`` (see the module docstring)."""
    return dict(zip(IDENTITY_KEYS, (kind, name), strict=True))


#: what :func:`identify` names and returns: a Dataset or a DataTree
_Stamped = TypeVar("_Stamped", "xr.Dataset", "xr.DataTree")


def identify(obj: _Stamped, kind: str, name: str, params: Any = None) -> _Stamped:
    """Name ``obj`` (a Dataset, or a DataTree: its root) as ``kind`` ``name`` (:func:`identity`), in place, and
    return it; with ``params``, also record their hash where its writer recorded none (a batch that stores
    measurements only)."""
    obj.attrs.update(identity(kind, name))
    if params is not None and "params_sha256" not in obj.attrs:
        obj.attrs.update({"parameters": canonical_json(params), "params_sha256": params_hash(params)})
    return obj


# ------------------------------------------------------------------ lock file

def _requirement_names(dist: str, extras: tuple[str, ...] = ()) -> list[str]:
    """Names of the requirements of installed distribution ``dist`` (with ``extras``), markers evaluated."""
    from importlib.metadata import requires

    from packaging.requirements import Requirement

    names = []
    for text in requires(dist) or []:
        req = Requirement(text)
        envs = [{"extra": e} for e in extras] or [{"extra": ""}]
        if req.marker is None or any(req.marker.evaluate(env) for env in envs):
            names.append(req.name if not req.extras else f"{req.name}[{','.join(sorted(req.extras))}]")
    return names


def dependency_tree(root: str = "cradle", extras: tuple[str, ...] = ("workflow",)) -> dict[str, str]:
    """``{name: installed version}`` of every distribution ``root[extras]`` needs, transitively (not root)."""
    from packaging.utils import canonicalize_name

    seen: dict[str, str] = {}
    todo = [(root, tuple(extras))]
    while todo:
        name, ext = todo.pop()
        for req in _requirement_names(name, ext):
            base, _, rest = req.partition("[")
            sub = tuple(rest.rstrip("]").split(",")) if rest else ()
            try:
                ver = _version(base)
            except PackageNotFoundError:
                continue  # an optional dependency that is not installed
            key = canonicalize_name(base)
            if key not in seen or sub:
                if key not in seen:
                    seen[key] = f"{base}=={ver}"
                todo.append((base, sub))
    return dict(sorted(seen.items()))


def lock_text(extras: tuple[str, ...] = ("workflow",)) -> str:
    """requirements-lock.txt: the installed versions of cradle's dependency tree, like a filtered ``pip freeze``."""
    head = (f"# cradle {VERSION} dependency tree (extras: {', '.join(extras) or 'none'}), "
            f"python {platform.python_version()}\n"
            "# regenerate: python -m cradle.data.provenance lock > requirements-lock.txt\n"
            "# install exactly these: pip install -r requirements-lock.txt -e .\n")
    return head + "".join(f"{line}\n" for line in dependency_tree("cradle", extras).values())


if __name__ == "__main__":
    import argparse

    _p = argparse.ArgumentParser(prog="python -m cradle.data.provenance", description="provenance of this installation")
    _p.add_argument("what", choices=("show", "lock"),
                    help="show: the attributes outputs get; lock: requirements-lock.txt")
    _p.add_argument("--extras", default="workflow", help="comma-separated extras of cradle to lock (default: workflow)")
    _a = _p.parse_args()
    if _a.what == "lock":
        sys.stdout.write(lock_text(tuple(e for e in _a.extras.split(",") if e)))
    else:
        for _k, _v in provenance().items():
            print(f"{_k}: {_v}")
