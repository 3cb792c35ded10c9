"""The record of a written file's content, kept beside it: what an edit through any library cannot update.

HDF5 recomputes a chunk's Fletcher-32 checksum when a value is written, and a global attribute carries no
checksum at all, so an edit made with netCDF4 (``d["x"][0] *= 3``, ``d.a = 1.0``) leaves a file whose own
checksums all pass. The writers (:mod:`cradle.data.io`, :mod:`cradle.data.appending`, :mod:`cradle.pipeline.extend`)
therefore record, in a sidecar ``.NAME.digest`` beside ``NAME`` (:func:`sidecar`), a digest of every variable's
stored values (:func:`values_digest`, raw bytes), of every attribute (global and per variable) and of every
dimension, in every group; every reader compares the file with it (:func:`compare`) and
refuses a difference in one line naming the file, what differs and the rebuild.

The sidecar is written (atomically) before its file is renamed into place and names the digests of the files the
path held before (``previous``, the last :data:`HISTORY`), so the file as it was before the rename (a write killed
between the two renames, or a failed Snakemake job's backup put back) is accepted too. A file without a sidecar
(written before digests existed, or copied without it) is read, and reported by ``cradle verify`` as not fully
protected.

Threat model (docs/recovery.md): accidental edits and damage, not someone who rewrites the sidecar too.
"""
from __future__ import annotations

import hashlib
import json
import os
import struct
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import xxhash

if TYPE_CHECKING:
    import netCDF4

from cradle.data import checksums
from cradle.data.temporaries import open_beside

#: the format of a sidecar; a sidecar of another format is ignored as unknown
FORMAT = "cradle-digest-2"
#: how many digests of the files a path held before are accepted (``previous``): a failed Snakemake job puts its
#: backup back, possibly after several failed reruns
HISTORY = 4


class ContentMismatch(ValueError):
    """A file whose content differs from its recorded digest; the message names what differs (no file name)."""


def sidecar(path: str | os.PathLike) -> Path:
    """Where the digest of ``path`` is recorded: ``.NAME.digest`` beside ``NAME`` (hidden, like the temporaries)."""
    path = Path(path)
    return path.with_name(f".{path.name}.digest")


def _attribute(value: Any) -> str:
    """The SHA-256 of one attribute's value: its type, shape and bytes (a string as UTF-8)."""
    if isinstance(value, str):
        body = b"str|" + value.encode("utf-8")
    elif type(value) in (float, np.float64):   # what the general case below gives, without making an array
        body = b"<f8||" + struct.pack("<d", value)
    elif type(value) in (int, np.int64) and -2**63 <= value < 2**63:
        body = b"<i8||" + struct.pack("<q", value)
    elif isinstance(value, bytes):
        body = b"bytes|" + value
    else:
        arr = np.asarray(value)
        arr = arr.astype(arr.dtype.newbyteorder("<"), copy=False) if arr.dtype.kind in "fiuc" else arr
        body = f"{arr.dtype.str}|{','.join(map(str, arr.shape))}|".encode() + arr.tobytes()
    return hashlib.sha256(body).hexdigest()


#: attributes never digested from what the writer hands over, always read back from the file: those xarray or
#: netCDF4 set or rewrite themselves as they encode a variable (a fill value, packing, a time's calendar, a
#: boolean's dtype) and the checksum :func:`cradle.data.checksums.stamp` records on the written file
READ_BACK = frozenset({"scale_factor", "add_offset", "missing_value", "valid_range", "valid_min",
                       "valid_max", "calendar", "dtype", checksums.ATTR})


_SCALARS = (float, int, np.float64, np.int64, np.float32, np.int32)


def stored_attribute(name: str, value: Any) -> str | None:
    """:func:`_attribute` of what netCDF4 reads back of the attribute ``name = value`` a writer hands it, for the
    values whose round trip is known (docs/recovery.md, "Cost"); None for any other, which is read back instead.

    A string without NUL (netCDF stores text up to its first NUL) reads back as itself; a number (an int, a
    float, a numpy integer or float) as the numpy scalar of its type; a 1-D list or array of numbers as the array
    of its numpy type, except that one element reads back as that element. Which attributes of which variables a
    writer may give this way: :func:`cradle.data.io.stored_attributes`."""
    if name[:1] == "_" or name in READ_BACK:
        return None
    kind = type(value)
    if kind is str:
        return None if "\x00" in value else hashlib.sha256(b"str|" + value.encode("utf-8")).hexdigest()
    if kind in _SCALARS:   # read back as the numpy scalar of its type (bool is not int's type)
        return _attribute(value)
    if isinstance(value, str):
        return None if "\x00" in value else _attribute(value)
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating, list,
                                                                      tuple, np.ndarray)):
        return None
    if isinstance(value, (list, tuple)) and not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                    for v in value):
        return None
    arr = np.asarray(value)
    if arr.ndim > 1 or arr.dtype.kind not in "iuf" or arr.dtype.itemsize < 4 and arr.dtype.kind == "f":
        return None
    return _attribute(arr[0] if arr.shape == (1,) else arr)


def values_digest(var: netCDF4.Variable, block_bytes: int = 64 * 2**20) -> str:
    """The digest of a ``netCDF4.Variable``'s stored values: :func:`cradle.data.checksums.digest`'s byte form, hashed
    with XXH3-128 (a 128-bit hash for telling accidental changes apart, several times faster than SHA-256)."""
    return checksums.digest(var, block_bytes, new=xxhash.xxh3_128)


def array_digest(values: np.ndarray) -> str:
    """:func:`values_digest` of the numeric array a writer is about to store, from memory (no read back)."""
    return checksums.array_digest(values, new=xxhash.xxh3_128)


def items(nc: netCDF4.Dataset, prefix: str = "", block_bytes: int = 64 * 2**20,
          known: dict[str, str] | None = None, handed: dict[str, str] | None = None,
          names: dict[str, list[str]] | None = None) -> dict[str, str]:
    """Every thing a reader uses of the open ``netCDF4.Dataset`` ``nc`` (and its groups), each with its digest:
    ``@name`` a global attribute, ``dim:name`` a dimension's size, ``var`` a variable's values (read raw, so
    HDF5 checks every Fletcher-32 checksum on the way), ``var@name`` a variable's attribute; a group's prefixed
    by its path (``waves/omega``); values read ``block_bytes`` at a time, except those whose digest ``known`` gives
    (:func:`array_digest` of what the writer stored, by the same keys), attributes read except those whose digest
    ``handed`` gives (:func:`stored_attribute` of what the writer handed to netCDF4, by the same keys). Which
    attributes there are: the file's own lists, except the global attributes of a group whose ``names`` (by its
    prefix) gives them (the writer's, all it handed over: listing a new file's global attributes makes HDF5 read
    them all)."""
    known, handed, names = known or {}, handed or {}, names or {}
    out = {}
    for k in names.get(prefix, None) or nc.ncattrs():
        key = f"{prefix}@{k}"
        out[key] = handed.get(key) or _attribute(nc.getncattr(k))
    for name, dim in nc.dimensions.items():
        out[f"{prefix}dim:{name}"] = hashlib.sha256(f"{len(dim)}|{dim.isunlimited()}".encode()).hexdigest()
    for name, var in nc.variables.items():
        dims = hashlib.sha256(",".join(var.dimensions).encode()).hexdigest()
        stored = known.get(f"{prefix}{name}") or values_digest(var, block_bytes)
        out[f"{prefix}{name}"] = hashlib.sha256(f"{stored}|{dims}".encode()).hexdigest()
        for k in var.ncattrs():
            key = f"{prefix}{name}@{k}"
            out[key] = handed.get(key) or _attribute(var.getncattr(k))
    for gname, group in nc.groups.items():
        out.update(items(group, f"{prefix}{gname}/", block_bytes, known, handed, names))
    return out


def whole(parts: dict[str, str]) -> str:
    """The digest of a whole file: the SHA-256 of its :func:`items`, sorted."""
    return hashlib.sha256(json.dumps(parts, sort_keys=True).encode()).hexdigest()


def _record_text(name: str, parts: dict[str, str], previous: list[str]) -> str:
    """``json.dumps`` of the record (``sort_keys``: file, format, items, previous, sha256), its items serialised
    once for both the text and :func:`whole`."""
    listed = json.dumps(parts, sort_keys=True)
    sha = hashlib.sha256(listed.encode()).hexdigest()
    return (f'{{"file": {json.dumps(name)}, "format": {json.dumps(FORMAT)}, "items": {listed}, '
            f'"previous": {json.dumps(previous)}, "sha256": {json.dumps(sha)}}}')


def read_record(path: str | os.PathLike, strict: bool = False) -> dict | None:
    """The sidecar of ``path`` as recorded, or None when there is none; one that is there but is not a record of
    ours (unreadable, not JSON, another format, without its digests) is None too, or with ``strict``
    :class:`ContentMismatch`: a damaged record cannot vouch for the file."""
    try:
        with open(sidecar(path), "rb") as fh:
            raw = fh.read()
    except FileNotFoundError:
        return None
    except OSError as err:
        if strict:
            raise ContentMismatch(f"its digest record {sidecar(path).name} cannot be read ({err.strerror}): "
                                  "whether the file was edited cannot be told") from None
        return None
    try:
        record = json.loads(raw)
    except ValueError:
        record = None
    if isinstance(record, dict) and record.get("format") == FORMAT and (
            not strict or (isinstance(record.get("sha256"), str) and isinstance(record.get("items"), dict))):
        return record
    if strict:
        raise ContentMismatch(f"its digest record {sidecar(path).name} is damaged (not a digest record of this "
                              "project's files): whether the file was edited cannot be told")
    return None


def record(path: str | os.PathLike, source: str | os.PathLike | None = None, known: dict[str, str] | None = None,
           parts: dict[str, str] | None = None) -> Path:
    """Write the sidecar of ``path`` from the file ``source`` (default ``path``; a writer's finished temporary file),
    atomically, naming the digests recorded before as ``previous``. Call it before renaming ``source`` to ``path``.
    ``known``: the values' digests the writer computed from memory (:func:`items`); ``parts``: the :func:`items` of
    the file, computed by a writer that still had it open (then the file is not opened again)."""
    if parts is None:
        import netCDF4

        with netCDF4.Dataset(source or path) as nc:
            parts = items(nc, known=known)
    old = read_record(path) or {}
    before = old.get("previous")
    before = [before] if isinstance(before, str) else before if isinstance(before, list) else []
    previous = [d for d in [old.get("sha256"), *before] if isinstance(d, str)][:HISTORY]
    return _write_sidecar(path, _record_text(Path(path).name, parts, previous))


def _write_sidecar(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` as the record beside ``path``, atomically: a temporary beside it
    (:func:`cradle.data.temporaries.open_beside`, mode 0644) renamed into place."""
    target = sidecar(path)
    fd, tmp = open_beside(target, 0o644)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(text.encode())
        os.replace(tmp, target)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    return target


def discard(path: str | os.PathLike) -> None:
    """Remove the sidecar of ``path`` (a temporary file renamed or deleted), if there is one."""
    try:
        sidecar(path).unlink()
    except FileNotFoundError:
        pass


def _named(key: str) -> str:
    """How a message calls one item: ``global attribute a``, ``variable x``, ``attribute units of variable x``."""
    group, _, key = key.rpartition("/")
    where = f" of group {group}" if group else ""
    if key.startswith("@"):
        return f"{'global ' if not group else ''}attribute {key[1:]}{where}"
    if key.startswith("dim:"):
        return f"dimension {key[4:]}{where}"
    if "@" in key:
        var, _, attr = key.partition("@")
        return f"attribute {attr} of variable {var}{where}"
    return f"variable {key}{where}"


def compare(path: str | os.PathLike, parts: dict[str, str], most: int = 3) -> bool:
    """Compare the :func:`items` ``parts`` of the file at ``path`` with its sidecar: True when they match (or match
    the file it replaced), False when there is no sidecar; else raise :class:`ContentMismatch` naming what differs."""
    rec = read_record(path, strict=True)
    if rec is None:
        return False
    before = rec.get("previous")
    if whole(parts) == rec.get("sha256") or whole(parts) in (before if isinstance(before, list) else [before]):
        return True
    want = rec.get("items") or {}
    keys = sorted(set(parts) | set(want))
    changed = [_named(k) + (" added" if k not in want else " removed" if k not in parts else " changed")
               for k in keys if parts.get(k) != want.get(k)]
    shown = ", ".join(changed[:most]) + (f" and {len(changed) - most} more" if len(changed) > most else "")
    raise ContentMismatch(f"edited since it was written: {shown or 'its content changed'} (against the digest "
                          f"recorded in {sidecar(path).name})")


def _file_sha256(path: str | os.PathLike) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(2**20), b""):
            h.update(block)
    return h.hexdigest()


def record_owner(path: str | os.PathLike, owner: str) -> Path:
    """Record beside a file that is not netCDF (a movie) what wrote it, ``owner``, with the digest of its bytes:
    what lets that command replace it later (:func:`cradle.pipeline.destinations.check`)."""
    return _write_sidecar(path, json.dumps({"format": FORMAT, "file": Path(path).name, "owner": owner,
                                            "bytes_sha256": _file_sha256(path)}, sort_keys=True))


def read_owner(path: str | os.PathLike) -> str | None:
    """What wrote the file at ``path`` by its record (:func:`record_owner`), if the file is still those bytes."""
    rec = read_record(path)
    if rec is None or "owner" not in rec or rec.get("bytes_sha256") != _file_sha256(path):
        return None
    return str(rec["owner"])
