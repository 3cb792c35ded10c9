"""A recorded checksum for every stored variable HDF5 cannot checksum itself.

HDF5's Fletcher-32 filter (:func:`cradle.data.io.encoding_of`) needs chunked storage, which a 0-d
variable, a string variable (variable-length strings, or characters) and an empty variable cannot
have. Each variable of a written file that carries no Fletcher-32 filter carries instead the
attribute ``checksum_sha256`` (:data:`ATTR`): the hex SHA-256 of its values as stored, in the
canonical byte form of :func:`digest`. :func:`stamp` records it (the writers call it on the finished
temporary file, so it is always computed from the stored values, never copied from a Dataset's
attributes), :func:`check` compares it; :mod:`cradle.data.io` turns a mismatch into one
:class:`cradle.data.io.DamagedOutput` line.

The functions work on the variables of an open ``netCDF4.Dataset`` (every group), read raw: no
mask, no scaling, no characters joined into strings, so the bytes hashed are the bytes stored.
"""
from __future__ import annotations

import hashlib
from collections.abc import Callable, Iterable, Iterator
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

if TYPE_CHECKING:
    import netCDF4
    import xarray as xr

class Hash(Protocol):
    """A running hash (``hashlib.sha256()``, ``xxhash.xxh3_128()``)."""

    def update(self, data: Any, /) -> None: ...  # a buffer: bytes, or an array's (no stub spells both)

    def hexdigest(self) -> str: ...


#: the variable attribute holding the recorded checksum
ATTR = "checksum_sha256"


class ChecksumMismatch(ValueError):
    """A variable's stored values do not match its recorded checksum (``name``: its path in the file)."""

    def __init__(self, name: str, scalar: bool) -> None:
        self.name = name
        super().__init__(f"{name}: stored value does not match its checksum" if scalar else
                         f"{name}: stored values do not match their checksum")


def _raw(var: netCDF4.Variable, index: Any) -> np.ndarray:
    var.set_auto_maskandscale(False)
    var.set_auto_chartostring(False)
    return np.asarray(var[index])


def array_digest(values: np.ndarray, new: Callable[[bytes], Hash] = hashlib.sha256) -> str:
    """:func:`digest` of a fixed-size numeric array in memory, the values a file will store: the same bytes."""
    h = new(f"{np.dtype(values.dtype).newbyteorder('<').str}|{','.join(map(str, values.shape))}\n".encode())
    _update(h, values)
    return h.hexdigest()


def _update(h: Hash, block: np.ndarray) -> None:
    """Add one C-order block of values: fixed-size values as little-endian bytes, strings as UTF-8
    each preceded by its length in bytes (8 bytes, little-endian), so no two lists of strings share
    a byte form."""
    if block.dtype.kind == "O":
        for item in block.ravel():
            text = item if isinstance(item, bytes) else str(item).encode("utf-8")
            h.update(len(text).to_bytes(8, "little"))
            h.update(text)
    else:
        h.update(np.ascontiguousarray(block, dtype=block.dtype.newbyteorder("<")))  # its buffer: no copy


def _kind(var: netCDF4.Variable) -> str:
    """The dtype in the header: ``str`` for variable-length strings, else numpy's little-endian code."""
    dtype = var.dtype
    if dtype is str or getattr(dtype, "kind", "") == "O":
        return "str"
    return np.dtype(dtype).newbyteorder("<").str


def digest(var: netCDF4.Variable, block_bytes: int = 64 * 2**20, new: Callable[[bytes], Hash] = hashlib.sha256) -> str:
    """The hex SHA-256 (or the hash ``new`` makes) of ``var``'s stored values (a ``netCDF4.Variable``), read
    ``block_bytes`` at a time.

    Canonical byte form: the header ``"<dtype>|<shape>\\n"`` (dtype ``str`` for variable-length strings,
    else numpy's little-endian code such as ``<f8``, ``|i1``, ``|S1``; shape as comma-separated sizes,
    empty for a 0-d variable), then the values in C order (see :func:`_update`)."""
    h = new(f"{_kind(var)}|{','.join(map(str, var.shape))}\n".encode())
    if var.ndim == 0:
        _update(h, _raw(var, ...))
        return h.hexdigest()
    row = int(np.prod(var.shape[1:], dtype=np.int64)) * max(getattr(var.dtype, "itemsize", 64), 1)
    step = max(1, block_bytes // max(row, 1))
    for i in range(0, var.shape[0], step):
        _update(h, _raw(var, slice(i, i + step)))
    return h.hexdigest()


def has_filter(var: netCDF4.Variable) -> bool:
    """True if HDF5 checks ``var`` itself (a Fletcher-32 filter)."""
    return bool((var.filters() or {}).get("fletcher32"))


def variables(group: netCDF4.Dataset, prefix: str = "") -> Iterator[tuple[str, netCDF4.Variable]]:
    """(path, variable) for every variable of ``group`` and its subgroups."""
    for name, var in group.variables.items():
        yield prefix + name, var
    for gname, sub in group.groups.items():
        yield from variables(sub, f"{prefix}{gname}/")


def stamp(nc: netCDF4.Dataset) -> None:
    """Record :data:`ATTR` on every variable of the open, writable ``nc`` (every group) that has no
    Fletcher-32 filter, and drop it from those that have one (a stale copy)."""
    for _, var in variables(nc):
        if has_filter(var):
            if ATTR in var.ncattrs():
                var.delncattr(ATTR)
        else:
            var.setncattr(ATTR, digest(var))


def check(var: netCDF4.Variable, name: str, block_bytes: int = 64 * 2**20) -> None:
    """Raise :class:`ChecksumMismatch` if ``var`` carries :data:`ATTR` and its values do not match."""
    if ATTR in var.ncattrs() and digest(var, block_bytes) != str(var.getncattr(ATTR)):
        raise ChecksumMismatch(name, var.ndim == 0)


def check_recorded(nc: netCDF4.Dataset) -> None:
    """:func:`check` every variable of ``nc`` (every group) that carries a recorded checksum."""
    for name, var in variables(nc):
        check(var, name)


def drop(variables: Iterable[xr.Variable]) -> None:
    """Remove :data:`ATTR` from the attributes of the xarray ``variables`` read from a verified file: it
    describes the file, so a Dataset edited and written again with plain xarray carries no stale one."""
    for var in variables:
        var.attrs.pop(ATTR, None)
