"""Self-describing netCDF output.

:func:`make_dataset` builds an :class:`xarray.Dataset` whose variables get
their dimensions, ``long_name`` and ``units`` from :mod:`cradle.data.variables`,
plus the global attributes every file carries: CF-1.10 ``Conventions``,
``title``, ``history``, ``source``, ``references`` (the paper) and the
provenance of :mod:`cradle.data.provenance` (code version and git commit, hash of
the parameters, library versions, command). :func:`write_netcdf` writes it
atomically: to a temporary file in the target folder, then ``os.replace``, so
an interrupted or failed rule never leaves a file that Snakemake would take
as done. Every variable carries a Fletcher-32 checksum (:func:`encoding_of`),
and :func:`open_dataset` reads every value, so a damaged or truncated file
stops its reader with one line naming the file and the command that rebuilds
it (:class:`DamagedOutput`, docs/recovery.md). :func:`open_scene` opens the
exact and DpS runs of one scene as a single Dataset.

A file holding several tables is a tree of netCDF groups (:class:`xarray.DataTree`, read by
``xarray.open_datatree``): :func:`make_tree` builds it from the declarations of its analysis
(``variables=``, one dict per group), the global attributes and provenance on the root group;
:func:`write_datatree` writes it atomically with a checksum on every variable of every group, and
:func:`open_tree` reads and verifies every group's values as :func:`open_dataset` does.
"""
from __future__ import annotations

import datetime as _dt
import os
import tempfile
from pathlib import Path

import numpy as np
import xarray as xr

from cradle.data.provenance import KEYS as _PROVENANCE_KEYS, VERSION, identity as _identity, provenance
from cradle.data.variables import declared

REFERENCE = (
    "G. James, Nonlinear waves in Newton's cradle and the discrete p-Schroedinger "
    "equation, Math. Models Methods Appl. Sci. 21 (2011) 2335-2377"
)


def _attr_value(value):
    """netCDF attributes hold numbers, strings and 1-D arrays; map the rest."""
    if value is None:
        return "none"
    if isinstance(value, bool):
        return int(value)
    if isinstance(value, (int, float, str, np.integer, np.floating)):
        return value
    if isinstance(value, (list, tuple)) and all(isinstance(v, (int, float)) for v in value):
        return np.asarray(value, dtype=float)
    return str(value)


def _lookup(name: str, variables: dict | None):
    """The declaration of ``name``: in ``variables`` (an analysis's own) if given, else the global one."""
    if variables is None:
        return declared(name)
    try:
        return variables[name]
    except KeyError:
        raise KeyError(f"variable {name!r} is not declared in the analysis's VARIABLES") from None


def _var_attrs(var) -> dict:
    return {"long_name": var.long_name, "units": var.units, **dict(var.attrs)}


def _table(data: dict, coords: dict | None, variables: dict | None) -> xr.Dataset:
    """The variables and coordinates of one table, with their declared dims, long names and units."""
    ds = xr.Dataset()
    for name, values in (coords or {}).items():
        var = _lookup(name, variables)
        ds = ds.assign_coords({name: (var.dims, np.asarray(values), _var_attrs(var))})
    for name, values in data.items():
        var = _lookup(name, variables)
        ds[name] = xr.Variable(var.dims, np.asarray(values), _var_attrs(var))
    return ds


#: global attributes set by :func:`make_dataset` itself; an inherited value (attrs copied from the
#: Dataset of an earlier stage) is replaced, never kept
GLOBAL_KEYS = ("title", "Conventions", "source", "references", "history") + _PROVENANCE_KEYS


def make_dataset(data: dict, coords: dict | None = None, attrs: dict | None = None, title: str = "",
                 params=None, variables: dict | None = None, identity: tuple[str, str] | None = None) -> xr.Dataset:
    """A Dataset from ``{name: array}`` with declared dims, long names and units.

    ``coords`` maps coordinate names to 1-D arrays (also declared). ``attrs``
    become global attributes (every parameter that produced the file).
    ``params`` (the resolved config entry, JSON-serialisable) is hashed into
    ``params_sha256``; the other provenance attributes are always written.
    ``variables`` (name -> :class:`cradle.data.variables.Var`) holds the declarations of an
    analysis's own variables; without it the global :data:`cradle.data.variables.VARIABLES`.
    ``identity`` ``(kind, name)`` names what the file is (``("exact", "tw-weak")``):
    :func:`cradle.data.provenance.identity`, what readers check (:mod:`cradle.pipeline.identity`).
    """
    ds = _table(data, coords, variables)
    prov = provenance(params)
    ds.attrs.update(
        {
            "title": title,
            "Conventions": "CF-1.10",
            "source": f"cradle {VERSION}" + (f" (git {prov['git_commit'][:12]}"
                                                f"{', dirty' if prov.get('git_dirty') else ''})"
                                                if "git_commit" in prov else ""),
            "references": REFERENCE,
            "history": f"{_dt.datetime.now(_dt.UTC).isoformat(timespec='seconds')} {prov['command']}",
        }
    )
    for key, value in (attrs or {}).items():
        if key not in GLOBAL_KEYS:
            ds.attrs[key] = _attr_value(value)
    ds.attrs.update(prov)
    if identity is not None:
        ds.attrs.update(_identity(*identity))
    return ds


def make_tree(groups: dict, variables: dict, attrs: dict | None = None, title: str = "",
               params=None, identity: tuple[str, str] | None = None) -> xr.DataTree:
    """A tree of netCDF groups: ``groups`` maps a group path ("/", "/scenes", ...) to its
    ``(data, coords)``, ``variables`` maps the same paths to their declarations (name -> Var).

    The root group carries the global attributes, provenance and ``identity`` of :func:`make_dataset`; a child
    group carries only its variables (it inherits the root's coordinates in xarray, so a child
    never reuses a name of its parents' coordinates).
    """
    root_data, root_coords = groups.get("/", ({}, {}))
    nodes = {"/": make_dataset(root_data, root_coords, attrs=attrs, title=title, params=params,
                               variables=variables["/"], identity=identity)}
    for path, (data, coords) in groups.items():
        if path != "/":
            nodes[path] = _table(data, coords, variables[path])
    for path, ds in nodes.items():  # xarray would let an inherited coordinate hide a child's variable
        parents = ["/"] + ["/".join(path.split("/")[:i]) for i in range(2, path.count("/") + 1)]
        for parent in (p for p in parents if p in nodes and p != path):
            clash = set(ds.variables) & set(nodes[parent].coords)
            if clash:
                raise ValueError(f"group {path}: {sorted(map(str, clash))} already coordinates of its parent {parent}")
    return xr.DataTree.from_dict(nodes)


def _umask_mode() -> int:
    """0o666 less the process umask: what open() would have given (mkstemp gives 0o600)."""
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


#: bytes per HDF5 chunk of a checksummed variable: whole rows (every bead of a stored time), about
#: this many bytes of them. netCDF-C's default shapes split the rows and made writing a 260 MB
#: exact run several times slower; whole-row chunks also suit the readers, which take rows
CHUNK_BYTES = 4 * 2**20


def encoding_of(ds: xr.Dataset) -> dict:
    """The netCDF encoding of every output: a Fletcher-32 checksum on every variable, checked by
    HDF5 whenever the data is read (:func:`open_dataset` reads it all), and no _FillValue on
    floats (CF forbids it on coordinates). The checksum needs chunked storage: chunks of whole
    rows, :data:`CHUNK_BYTES` at most (one row if a row is larger); the stored values are the same
    bits. A 0-d or string variable cannot carry a filter and is stored without one."""
    encoding = {}
    for name in list(ds.coords) + list(ds.data_vars):
        var = ds[name]
        enc: dict[str, object] = {}
        if np.issubdtype(var.dtype, np.floating):
            enc["_FillValue"] = None
        if var.ndim > 0 and var.dtype.kind in "fiucb" and var.shape[0] > 0:
            enc["fletcher32"] = True
            row = int(np.prod(var.shape[1:], dtype=np.int64)) * var.dtype.itemsize
            enc["chunksizes"] = (max(1, min(var.shape[0], CHUNK_BYTES // max(row, 1))),) + tuple(var.shape[1:])
        if enc:
            encoding[name] = enc
    return encoding


def write_netcdf(ds: xr.Dataset | xr.DataTree, path: str | os.PathLike) -> Path:
    """Write ``ds`` to ``path`` atomically (temporary file, then rename), every variable checksummed
    (:func:`encoding_of`). A :class:`xarray.DataTree` is written by :func:`write_datatree`."""
    if isinstance(ds, xr.DataTree):
        return write_datatree(ds, path)
    return _atomic(Path(path), lambda tmp: ds.to_netcdf(tmp, encoding=encoding_of(ds), engine="netcdf4"))


def write_datatree(tree: xr.DataTree, path: str | os.PathLike) -> Path:
    """Write a tree of groups to ``path`` atomically, every variable of every group checksummed
    (:func:`encoding_of` per group); ``xarray.open_datatree`` (and :func:`open_tree`) reads it."""
    encoding = {node.path: encoding_of(node.to_dataset(inherit=False)) for node in tree.subtree}
    return _atomic(Path(path), lambda tmp: tree.to_netcdf(tmp, encoding=encoding, engine="netcdf4"))


def write_text(text: str, path: str | os.PathLike) -> Path:
    """Write a text file atomically (temporary file, then rename)."""
    return _atomic(Path(path), lambda tmp: Path(tmp).write_text(text))


def _atomic(path: Path, write) -> Path:
    """Call ``write(tmp)`` on a temporary file beside ``path``, then rename it to ``path``.

    An interrupted or failed write leaves nothing at ``path`` (and no temporary file).
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(fd)
    try:
        write(tmp)
        os.chmod(tmp, _umask_mode())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    return path


class DamagedOutput(RuntimeError):
    """An output that cannot be trusted: not netCDF, truncated, or failing its checksums.

    The message is one line naming the file, what is wrong and the command that rebuilds it."""


_SIGNATURES = (b"\x89HDF\r\n\x1a\n", b"CDF\x01", b"CDF\x02", b"CDF\x05")


def rebuild_hint(path) -> str:
    """The command that rebuilds ``path``: Snakemake's for a file under ``results/``, else a rerun."""
    parts = Path(path).parts
    if "results" in parts:
        rel = Path(*parts[parts.index("results"):])
        return f"rebuild it: snakemake --force {rel} (see docs/recovery.md)"
    return "rebuild it: rerun the command that wrote it (see docs/recovery.md)"


def _why(err: BaseException) -> str:
    """The reader's error on one line, without the file name it repeats."""
    import re

    text = re.sub(r"\[Errno -?\d+\] ", "", " ".join(str(err).split()))
    return re.sub(r":? '[^']*'", "", text).strip() or type(err).__name__


def _is_netcdf(path) -> bool:
    """True if the file starts with a netCDF classic or HDF5 (netCDF-4) signature."""
    with open(path, "rb") as f:
        head = f.read(8)
    return any(head.startswith(sig) for sig in _SIGNATURES)


def _checked(path, read):
    """``read(path)``, with a missing file as FileNotFoundError and a file that is not netCDF, is
    truncated or fails a checksum as one :class:`DamagedOutput` line naming it and its rebuild."""
    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such file ({rebuild_hint(path)})")
    if not _is_netcdf(path):
        raise DamagedOutput(f"{path}: not a netCDF file (no netCDF or HDF5 signature in its first bytes)"
                            + (f"; {rebuild_hint(path)}" if "results" in path.parts else ""))
    try:
        return read(path)
    except (OSError, RuntimeError, ValueError, KeyError, IndexError) as err:
        raise DamagedOutput(f"{path}: damaged or truncated, cannot be read ({_why(err)}); "
                            f"{rebuild_hint(path)}") from None


#: files larger than this are verified block by block and opened lazily by :func:`open_dataset`
LAZY_ABOVE_BYTES = 512 * 2**20


def open_dataset(path: str | os.PathLike) -> xr.Dataset:
    """Open a cradle output fully into memory (the file is closed on return), verified.

    Every variable is read (so HDF5 checks every chunk's Fletcher-32 checksum). A missing file
    raises FileNotFoundError; a file that is not netCDF, is truncated or fails a checksum raises
    :class:`DamagedOutput` with one line naming the file and the command that rebuilds it.

    A file larger than :data:`LAZY_ABOVE_BYTES` (a large store, :mod:`cradle.scenes.streamed`)
    is verified block by block (:func:`verify_file`) and returned opened lazily: what the reader
    selects is read when used (HDF5 checks those chunks again), so its memory is what it uses.
    """
    def read(p):
        if Path(p).stat().st_size > LAZY_ABOVE_BYTES:
            verify_file(p)
            return xr.open_dataset(p, engine="netcdf4")
        with xr.open_dataset(p, engine="netcdf4") as ds:
            return ds.load()

    return _checked(path, read)


def open_tree(path: str | os.PathLike) -> xr.DataTree:
    """Open a cradle output as a tree of groups, fully into memory (the file is closed on return),
    verified: every variable of every group is read, so HDF5 checks every checksum. A flat file is
    a tree with a root group only. Errors as :func:`open_dataset`."""
    def read(p):
        tree = xr.open_datatree(p, engine="netcdf4")
        try:
            return tree.load()
        finally:
            tree.close()

    return _checked(path, read)


def verify_file(path: str | os.PathLike, block_bytes: int = 64 * 2**20) -> list[str]:
    """Read every value of a netCDF file, ``block_bytes`` at a time (bounded memory whatever its
    size), so that HDF5 checks every checksum. Returns the variables stored without a checksum
    (written before checksums); raises FileNotFoundError or :class:`DamagedOutput` (one line)."""
    import netCDF4

    def walk(group, prefix, bare):
        for name, var in group.variables.items():
            if var.ndim == 0:
                var[...]
                continue
            if var.size and not (var.filters() or {}).get("fletcher32"):  # an empty variable holds no data
                bare.append(prefix + name)
            row = int(np.prod(var.shape[1:], dtype=np.int64)) * getattr(var.dtype, "itemsize", 1)
            step = max(1, block_bytes // max(row, 1))
            for i in range(0, var.shape[0], step):
                var[i:i + step]
        for gname, sub in group.groups.items():  # every netCDF group of a tree (open_tree)
            walk(sub, f"{prefix}{gname}/", bare)
        return bare

    def read(p):
        with netCDF4.Dataset(p) as nc:
            return walk(nc, "", [])

    return _checked(path, read)
