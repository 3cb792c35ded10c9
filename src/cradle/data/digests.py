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
from pathlib import Path

import numpy as np
import xxhash

from cradle.data import checksums
from cradle.data.temporaries import temporary_beside

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


def _attribute(value) -> str:
    """The SHA-256 of one attribute's value: its type, shape and bytes (a string as UTF-8)."""
    if isinstance(value, str):
        body = b"str|" + value.encode("utf-8")
    elif isinstance(value, bytes):
        body = b"bytes|" + value
    else:
        arr = np.asarray(value)
        arr = arr.astype(arr.dtype.newbyteorder("<"), copy=False) if arr.dtype.kind in "fiuc" else arr
        body = f"{arr.dtype.str}|{','.join(map(str, arr.shape))}|".encode() + arr.tobytes()
    return hashlib.sha256(body).hexdigest()


def values_digest(var, block_bytes: int = 64 * 2**20) -> str:
    """The digest of a ``netCDF4.Variable``'s stored values: :func:`cradle.data.checksums.digest`'s byte form, hashed
    with XXH3-128 (a 128-bit hash for telling accidental changes apart, several times faster than SHA-256)."""
    return checksums.digest(var, block_bytes, new=xxhash.xxh3_128)


def array_digest(values: np.ndarray) -> str:
    """:func:`values_digest` of the numeric array a writer is about to store, from memory (no read back)."""
    return checksums.array_digest(values, new=xxhash.xxh3_128)


def items(nc, prefix: str = "", block_bytes: int = 64 * 2**20, known: dict[str, str] | None = None) -> dict[str, str]:
    """Every thing a reader uses of the open ``netCDF4.Dataset`` ``nc`` (and its groups), each with its digest:
    ``@name`` a global attribute, ``dim:name`` a dimension's size, ``var`` a variable's values (read raw, so
    HDF5 checks every Fletcher-32 checksum on the way), ``var@name`` a variable's attribute; a group's prefixed
    by its path (``waves/omega``); values read ``block_bytes`` at a time, except those whose digest ``known`` gives
(:func:`array_digest` of what the writer stored, by the same keys)."""
    out = {f"{prefix}@{k}": _attribute(v) for k, v in nc.__dict__.items()}   # all read at once
    for name, dim in nc.dimensions.items():
        out[f"{prefix}dim:{name}"] = hashlib.sha256(f"{len(dim)}|{dim.isunlimited()}".encode()).hexdigest()
    for name, var in nc.variables.items():
        dims = hashlib.sha256(",".join(var.dimensions).encode()).hexdigest()
        stored = (known or {}).get(f"{prefix}{name}") or values_digest(var, block_bytes)
        out[f"{prefix}{name}"] = hashlib.sha256(f"{stored}|{dims}".encode()).hexdigest()
        out.update({f"{prefix}{name}@{k}": _attribute(v) for k, v in var.__dict__.items()})
    for gname, group in nc.groups.items():
        out.update(items(group, f"{prefix}{gname}/", block_bytes, known))
    return out


def whole(parts: dict[str, str]) -> str:
    """The digest of a whole file: the SHA-256 of its :func:`items`, sorted."""
    return hashlib.sha256(json.dumps(parts, sort_keys=True).encode()).hexdigest()


def read_record(path) -> dict | None:
    """The sidecar of ``path`` as recorded, or None when there is none (or it is not one of ours)."""
    try:
        record = json.loads(sidecar(path).read_text())
    except (OSError, ValueError):
        return None
    return record if isinstance(record, dict) and record.get("format") == FORMAT else None


def record(path, source=None, known: dict[str, str] | None = None, parts: dict[str, str] | None = None) -> Path:
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
    text = json.dumps({"format": FORMAT, "file": Path(path).name, "sha256": whole(parts), "previous": previous,
                       "items": parts}, sort_keys=True)
    return _write_sidecar(path, text)


def _write_sidecar(path, text: str) -> Path:
    """Write ``text`` as the record beside ``path``, atomically (a temporary renamed into place)."""
    target = sidecar(path)
    tmp = temporary_beside(target)
    try:
        Path(tmp).write_text(text)
        os.chmod(tmp, 0o644)
        os.replace(tmp, target)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    return target


def discard(path) -> None:
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


def compare(path, parts: dict[str, str], most: int = 3) -> bool:
    """Compare the :func:`items` ``parts`` of the file at ``path`` with its sidecar: True when they match (or match
    the file it replaced), False when there is no sidecar; else raise :class:`ContentMismatch` naming what differs."""
    rec = read_record(path)
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


def _file_sha256(path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(2**20), b""):
            h.update(block)
    return h.hexdigest()


def record_owner(path, owner: str) -> Path:
    """Record beside a file that is not netCDF (a movie) what wrote it, ``owner``, with the digest of its bytes:
    what lets that command replace it later (:func:`cradle.pipeline.destinations.check`)."""
    return _write_sidecar(path, json.dumps({"format": FORMAT, "file": Path(path).name, "owner": owner,
                                            "bytes_sha256": _file_sha256(path)}, sort_keys=True))


def read_owner(path) -> str | None:
    """What wrote the file at ``path`` by its record (:func:`record_owner`), if the file is still those bytes."""
    rec = read_record(path)
    if rec is None or "owner" not in rec or rec.get("bytes_sha256") != _file_sha256(path):
        return None
    return str(rec["owner"])
