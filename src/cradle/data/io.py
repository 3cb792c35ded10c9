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
it (:class:`DamagedOutput`, docs/recovery.md). A variable that cannot carry the
filter (0-d, strings, empty) carries a recorded SHA-256 of its values instead
(:mod:`cradle.data.checksums`), computed from the written file and checked by
every reader here. Every writer also records the digest of the whole file (values and attributes) in a
sidecar, which every reader compares (:mod:`cradle.data.digests`): an edit that HDF5's own checksums follow
is refused too. A write that fails on a full file system is one line
(:class:`DiskFull`); a killed write leaves a temporary file named after its
process, which :func:`remove_stale_temporaries` deletes once that process is
gone (:mod:`cradle.data.temporaries`).

A file holding several tables is a tree of netCDF groups (:class:`xarray.DataTree`, read by
``xarray.open_datatree``): :func:`make_tree` builds it from the declarations of its analysis
(``variables=``, one dict per group), the global attributes and provenance on the root group;
:func:`write_datatree` writes it atomically with a checksum on every variable of every group, and
:func:`open_tree` reads and verifies every group's values as :func:`open_dataset` does.
"""
from __future__ import annotations

import datetime as _dt
import errno
import os
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np
import xarray as xr

from cradle.data import checksums, digests
from cradle.data.provenance import KEYS as _PROVENANCE_KEYS, VERSION, identity as _identity, provenance
from cradle.data.temporaries import remove_stale_temporaries, stale_temporaries, temporary_beside
from cradle.data.variables import Var, declared

if TYPE_CHECKING:
    import netCDF4

_T = TypeVar("_T")

__all__ = ["DamagedOutput", "DiskFull", "make_dataset", "make_tree", "open_dataset", "open_tree",
           "remove_stale_temporaries", "stale_temporaries", "verify_file", "write_datatree", "write_netcdf",
           "write_text"]

REFERENCE = (
    "G. James, Nonlinear waves in Newton's cradle and the discrete p-Schroedinger "
    "equation, Math. Models Methods Appl. Sci. 21 (2011) 2335-2377"
)


def _attr_value(value: Any) -> int | float | str | np.integer | np.floating | np.ndarray:
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


def _lookup(name: str, variables: dict | None) -> Var:
    """The declaration of ``name``: in ``variables`` (an analysis's own) if given, else the global one."""
    if variables is None:
        return declared(name)
    try:
        return variables[name]
    except KeyError:
        raise KeyError(f"variable {name!r} is not declared in the analysis's VARIABLES") from None


def _var_attrs(var: Var) -> dict:
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


def make_dataset(data: dict, coords: dict | None = None, attrs: dict | None = None, title: str = "", params: Any = None,
                 variables: dict | None = None, identity: tuple[str, str] | None = None) -> xr.Dataset:
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
               params: Any = None, identity: tuple[str, str] | None = None) -> xr.DataTree:
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
    bits. A 0-d, string or empty variable cannot carry a filter: the writers record its checksum as
    an attribute instead (:func:`cradle.data.checksums.stamp`)."""
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


#: set (to anything but 0 or empty) in the environment, every writer also digests the finished file as a reader
#: does and raises :class:`DigestDisagrees` if the two differ: the test suite sets it (tests/conftest.py), so every
#: file any test writes shows that what the writer digests from memory is what every reader reads back
SELF_CHECK_ENV = "CRADLE_DIGEST_SELF_CHECK"


class DigestDisagrees(AssertionError):
    """A writer's digest of what it handed over differs from the digest of the file read back (a bug)."""


def _stamped(tmp: str, known: dict[str, str], handed: tuple[dict[str, str], dict[str, list[str]]]) -> dict[str, str]:
    """Record the checksum of every variable of the written file ``tmp`` that has no Fletcher-32
    filter (:func:`cradle.data.checksums.stamp`): computed from the stored values, so a checksum
    attribute copied from a Dataset read earlier is replaced, never kept. Returns the finished file's
    :func:`cradle.data.digests.items` (``known``: the values digested from memory, :func:`stored_digests`;
    ``handed``: the attributes digested as handed over and the global ones' names, :func:`stored_attributes`),
    computed on the same handle:
    opening an HDF5 file costs as much as digesting a 10 MB one."""
    import netCDF4

    with netCDF4.Dataset(tmp, "a") as nc:
        checksums.stamp(nc)
        parts = digests.items(nc, known=known, handed=handed[0], names=handed[1])
        if os.environ.get(SELF_CHECK_ENV, "0") not in ("", "0"):
            read = digests.items(nc)
            if read != parts:
                differ = sorted(k for k in set(read) | set(parts) if read.get(k) != parts.get(k))
                raise DigestDisagrees(f"{tmp}: the writer's digest differs from the file's at {', '.join(differ)}")
        return parts


def stored_attributes(ds: xr.Dataset, prefix: str = "") -> tuple[dict[str, str], dict[str, list[str]]]:
    """What ``ds`` hands to netCDF4 as attributes: xarray's own encoding of its coordinates
    (``xarray.conventions.encode_dataset_coordinates``, the first step of ``to_netcdf``, which adds the
    ``coordinates`` lists), then (1) the digests (:func:`cradle.data.digests.stored_attribute`) of the global
    attributes and of those of every integer or float variable (xarray's later encoding rewrites others' attributes:
    a time's units, a boolean's dtype, a string's fill value), keyed as :func:`cradle.data.digests.items`
    (``@name``, ``var@name``, a group's prefixed), and (2) the names of the global attributes, by ``prefix``.
    Every other value, and which attributes each variable holds, is read from the file."""
    from xarray import conventions

    variables, attrs = conventions.encode_dataset_coordinates(ds)
    digest = digests.stored_attribute
    out = {f"{prefix}@{key}": digest(key, value) for key, value in attrs.items()}
    for name, var in variables.items():
        if var.dtype.kind in "fiu":
            out.update({f"{prefix}{name}@{key}": digest(key, value) for key, value in var.attrs.items()})
    return {k: d for k, d in out.items() if d is not None}, {prefix: [str(k) for k in attrs]}


def stored_digests(ds: xr.Dataset, encoding: dict, prefix: str = "") -> dict[str, str]:
    """The digests of the values ``ds`` stores with ``encoding`` (:func:`encoding_of`), from memory, for the
    variables whose stored bytes are their values as they are (integers and floats given an encoding of their
    own: no fill value, scale or type of xarray's applied); the others are digested from the written file
    (:func:`cradle.data.digests.record`). Keys as :func:`cradle.data.digests.items` (``group/name``)."""
    out = {}
    for name, var in ds.variables.items():
        if name in encoding and var.dtype.kind in "fiu" and var.ndim > 0:
            out[f"{prefix}{name}"] = digests.array_digest(np.asarray(var.values))
    return out


def write_netcdf(ds: xr.Dataset | xr.DataTree, path: str | os.PathLike) -> Path:
    """Write ``ds`` to ``path`` atomically (temporary file, then rename), every variable checksummed
    (:func:`encoding_of`, and :func:`_stamped` for the variables a filter cannot protect). A
    :class:`xarray.DataTree` is written by :func:`write_datatree`."""
    if isinstance(ds, xr.DataTree):
        return write_datatree(ds, path)

    encoding = encoding_of(ds)
    parts: dict[str, str] = {}

    def write(tmp: str) -> None:
        ds.to_netcdf(tmp, encoding=encoding, engine="netcdf4")
        parts.update(_stamped(tmp, stored_digests(ds, encoding), stored_attributes(ds)))

    return _atomic(Path(path), write, needs=int(ds.nbytes), digest=parts)


def write_datatree(tree: xr.DataTree, path: str | os.PathLike) -> Path:
    """Write a tree of groups to ``path`` atomically, every variable of every group checksummed
    (:func:`encoding_of` per group, :func:`_stamped`); ``xarray.open_datatree`` (and :func:`open_tree`)
    reads it."""
    encoding = {node.path: encoding_of(node.to_dataset(inherit=False)) for node in tree.subtree}

    parts: dict[str, str] = {}

    def write(tmp: str) -> None:
        tree.to_netcdf(tmp, encoding=encoding, engine="netcdf4")
        known: dict[str, str] = {}
        handed: tuple[dict[str, str], dict[str, list[str]]] = ({}, {})
        for node in tree.subtree:
            prefix = node.path.strip("/") + "/" if node.path != "/" else ""
            own = node.to_dataset(inherit=False)
            known.update(stored_digests(own, encoding[node.path], prefix))
            attrs, names = stored_attributes(own, prefix)
            handed[0].update(attrs)
            handed[1].update(names)
        parts.update(_stamped(tmp, known, handed))

    needs = sum(int(node.to_dataset(inherit=False).nbytes) for node in tree.subtree)
    return _atomic(Path(path), write, needs=needs, digest=parts)


def write_text(text: str, path: str | os.PathLike) -> Path:
    """Write a text file atomically (temporary file, then rename)."""
    return _atomic(Path(path), lambda tmp: Path(tmp).write_text(text), needs=len(text.encode()))


class DiskFull(OSError):
    """A write that failed because its file system is full. The message is one line naming the file,
    about how many bytes it needed and how many are free."""


#: a write that fails with less than this free beyond what the file still needed is taken for a full
#: disk: HDF5 reports a full disk as "NetCDF: HDF error", without the errno
SPACE_MARGIN_BYTES = 16 * 2**20


def _size(n: float) -> str:
    """Bytes as '512 B', '3.2 kB', '290 MB', '1.4 GB'."""
    for unit, scale in (("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if n >= scale:
            return f"{n / scale:.3g} {unit}"
    return f"{int(n)} B"


def disk_full(path: Path, tmp: str | None, needs: int, err: BaseException) -> DiskFull | None:
    """The :class:`DiskFull` error for a write of ``path`` (to ``tmp``, about ``needs`` bytes; 0 when
    unknown, a file written in blocks) that failed with ``err``, if the file system is full: errno
    ENOSPC, or an HDF5/netCDF error while less than the rest of the file plus
    :data:`SPACE_MARGIN_BYTES` is free; else None."""
    if not isinstance(err, (OSError, RuntimeError)):
        return None
    try:
        written = os.path.getsize(tmp) if tmp is not None else 0
    except OSError:
        written = 0
    try:
        st = os.statvfs(path.parent)
        free: int | None = st.f_bavail * st.f_frsize
    except (OSError, AttributeError):  # no statvfs (not POSIX) or no folder
        free = None
    rest = max(needs - written, 0)
    if getattr(err, "errno", None) != errno.ENOSPC and (free is None or free >= rest + SPACE_MARGIN_BYTES):
        return None
    where = f"{_size(free)} free" if free is not None else "free space unknown"
    need = f"about {_size(needs)}" if needs > written else f"more than {_size(written)}"  # a file written in blocks
    full = DiskFull(f"{path}: no space left on the file system: the file needs {need}, {where} "
                    f"in {path.parent} ({_size(written)} written before the write failed: {_why(err)}); "
                    f"free space there (or write the results elsewhere) and rerun")
    full.errno = errno.ENOSPC
    return full


def _atomic(path: Path, write: Callable[[str], object], needs: int = 0, digest: dict[str, str] | None = None) -> Path:
    """Call ``write(tmp)`` on a temporary file beside ``path`` (named after this process:
    :func:`cradle.data.temporaries.temporary_beside`), then rename it to ``path``; with ``digest`` (the
    :func:`cradle.data.digests.items` of the finished netCDF file, which ``write`` fills in), the digest is
    recorded beside ``path`` first (:func:`cradle.data.digests.record`).

    An interrupted or failed write leaves nothing at ``path`` (and no temporary file); a write that
    fails on a full file system raises :class:`DiskFull` (``needs``: about how many bytes the file takes).
    """
    tmp = None
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = temporary_beside(path)
        write(tmp)
        os.chmod(tmp, _umask_mode())
        if digest is not None:  # before the rename: a write killed between the two leaves the old file, 'previous'
            digests.record(path, parts=digest)
        os.replace(tmp, path)
    except BaseException as err:
        full = disk_full(path, tmp, needs, err)
        if tmp is not None and os.path.exists(tmp):
            os.remove(tmp)
        if full is not None:
            raise full from None
        raise
    return path


class DamagedOutput(RuntimeError):
    """An output that cannot be trusted: not netCDF, truncated, or failing its checksums.

    The message is one line naming the file, what is wrong and the command that rebuilds it."""


_SIGNATURES = (b"\x89HDF\r\n\x1a\n", b"CDF\x01", b"CDF\x02", b"CDF\x05")


def rebuild_hint(path: str | os.PathLike) -> str:
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


def _is_netcdf(path: str | os.PathLike) -> bool:
    """True if the file starts with a netCDF classic or HDF5 (netCDF-4) signature."""
    with open(path, "rb") as f:
        head = f.read(8)
    return any(head.startswith(sig) for sig in _SIGNATURES)


def _checked(path: str | os.PathLike, read: Callable[[Path], _T]) -> _T:
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
    except DamagedOutput:
        raise
    except (checksums.ChecksumMismatch, digests.ContentMismatch) as err:
        raise DamagedOutput(f"{path}: {err}; {rebuild_hint(path)}") from None
    except (OSError, RuntimeError, ValueError, KeyError, IndexError) as err:
        raise DamagedOutput(f"{path}: damaged or truncated, cannot be read ({_why(err)}); "
                            f"{rebuild_hint(path)}") from None


def check_is_netcdf(path: str | os.PathLike) -> Path:
    """``path`` as a Path if it names a netCDF file (by its signature; its values are not read): else
    FileNotFoundError or one :class:`DamagedOutput` line naming it (a folder, another kind of file)."""
    path = Path(path)
    if path.is_dir():
        raise DamagedOutput(f"{path}: a folder, not a netCDF file")
    return _checked(path, lambda p: p)


#: files larger than this are verified block by block and opened lazily by :func:`open_dataset`
LAZY_ABOVE_BYTES = 512 * 2**20


def _verified(nc: netCDF4.Dataset, path: str | os.PathLike) -> bool:
    """Check the open ``nc`` (the file at ``path``): every recorded checksum (:mod:`cradle.data.checksums`), then
    every value read (HDF5 checks each Fletcher-32 checksum) and, with every attribute, compared with the
    digest recorded beside the file (:func:`cradle.data.digests.compare`). False when no digest is recorded."""
    checksums.check_recorded(nc)
    return digests.compare(path, digests.items(nc))


def open_dataset(path: str | os.PathLike) -> xr.Dataset:
    """Open a cradle output fully into memory (the file is closed on return), verified.

    Every variable is read (so HDF5 checks every chunk's Fletcher-32 checksum), every recorded
    checksum compared (:mod:`cradle.data.checksums`; the attribute is dropped from what is returned), and
    values and attributes compared with the digest recorded beside the file (:mod:`cradle.data.digests`).
    A missing file raises FileNotFoundError; a file that is not netCDF, is truncated or fails a
    checksum raises :class:`DamagedOutput` with one line naming the file (and the variable, for a
    recorded checksum) and the command that rebuilds it.

    A file larger than :data:`LAZY_ABOVE_BYTES` (a large store, :mod:`cradle.scenes.streamed`)
    is verified block by block (:func:`verify_file`) and returned opened lazily: what the reader
    selects is read when used (HDF5 checks those chunks again), so its memory is what it uses.
    """
    def read(p: Path) -> xr.Dataset:
        if Path(p).stat().st_size > LAZY_ABOVE_BYTES:
            verify_file(p)
            ds = xr.open_dataset(p, engine="netcdf4")
        else:  # one handle for both: HDF5 may crash when a file with strings is open twice at once
            store = xr.backends.NetCDF4DataStore.open(p)
            try:
                _verified(store.ds, p)
                with xr.open_dataset(store) as lazy:
                    ds = lazy.load()
            finally:
                store.close()
        checksums.drop(ds.variables.values())
        return ds

    return _checked(path, read)


def open_tree(path: str | os.PathLike) -> xr.DataTree:
    """Open a cradle output as a tree of groups, fully into memory (the file is closed on return),
    verified: every variable of every group is read, so HDF5 checks every checksum, and every recorded
    checksum is compared. A flat file is a tree with a root group only. Errors as :func:`open_dataset`."""
    def read(p: Path) -> xr.DataTree:
        import netCDF4

        with netCDF4.Dataset(p) as nc:
            _verified(nc, p)
        tree = xr.open_datatree(p, engine="netcdf4")
        try:
            tree.load()
        finally:
            tree.close()
        for node in tree.subtree:
            checksums.drop(node.variables.values())
        return tree

    return _checked(path, read)


def verify_file(path: str | os.PathLike, block_bytes: int = 64 * 2**20, digest: bool = True) -> list[str]:
    """Read every value of a netCDF file, ``block_bytes`` at a time (bounded memory whatever its
    size), so that HDF5 checks every Fletcher-32 checksum, compare every recorded checksum
    (:mod:`cradle.data.checksums`), in every group, and compare values and attributes with the digest
    recorded beside the file (:mod:`cradle.data.digests`; not with ``digest=False``: a file known to be another
    entry's, whose sidecar is that of the file the path held). Returns the variables stored with neither
    checksum (written before checksums; an empty variable holds nothing to protect and is not listed);
    raises FileNotFoundError or :class:`DamagedOutput` (one line)."""
    import netCDF4

    def bare(group: netCDF4.Dataset, prefix: str = "") -> list[str]:
        out = [prefix + name for name, var in group.variables.items()
               if checksums.ATTR not in var.ncattrs() and var.size and not checksums.has_filter(var)]
        for gname, sub in group.groups.items():
            out += bare(sub, f"{prefix}{gname}/")
        return out

    def read(p: Path) -> list[str]:
        with netCDF4.Dataset(p) as nc:
            for name, var in checksums.variables(nc):
                checksums.check(var, name, block_bytes)
            if digest:
                digests.compare(p, digests.items(nc, block_bytes=block_bytes))  # reads every value once
            else:
                for _, var in checksums.variables(nc):   # every value read all the same: HDF5 checks its chunks
                    digests.values_digest(var, block_bytes)
            return bare(nc)

    return _checked(path, read)
