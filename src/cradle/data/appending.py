"""netCDF files written block by block along ``t``, in bounded memory, renamed into place at the end.

:class:`Appender` creates the file from a first block (an :class:`xarray.Dataset` with every
variable, each checksummed as :func:`cradle.data.io.encoding_of` does) with ``t`` unlimited,
appends later blocks row by row, can overwrite the values of variables without ``t`` (known only
at the end) and the global attributes, records the checksums of the variables a filter cannot protect
(:func:`cradle.data.checksums.stamp`) and renames the temporary file to its target on
:meth:`Appender.commit`: an interrupted run leaves nothing at the target. Used by
:mod:`cradle.pipeline.extend` (long exact runs) and :mod:`cradle.scenes.streamed` (a scene's
job whose store exceeds memory).
"""
from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import xarray as xr

from cradle.data import checksums, digests
from cradle.data.io import _attr_value, _umask_mode, disk_full, encoding_of
from cradle.data.temporaries import temporary_beside

#: memory per block of stored states
DEFAULT_CHUNK_BYTES = 64 * 2**20
#: HDF5 chunk cache per variable while appending (netCDF-C's default, 64 MiB, is held per variable)
CHUNK_CACHE_BYTES = 4 * 2**20


def chunk_rows(N: int, chunk_bytes: int = DEFAULT_CHUNK_BYTES, arrays: int = 3) -> int:
    """Stored times per block: ``arrays`` float64 arrays of N values per stored time within
    ``chunk_bytes``; at least 1."""
    return max(1, int(chunk_bytes // (arrays * 8 * max(int(N), 1))))


class Appender:
    """A netCDF file with an unlimited ``t``, written under a temporary name, renamed on :meth:`commit`."""

    def __init__(self, path: str | os.PathLike, first: xr.Dataset) -> None:
        import netCDF4

        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.tmp = temporary_beside(self.path)
        try:
            with self._space():
                first.to_netcdf(self.tmp, engine="netcdf4", unlimited_dims=["t"], encoding=encoding_of(first))
            self.nc = netCDF4.Dataset(self.tmp, "a")
        except BaseException:
            os.remove(self.tmp)
            raise
        for var in self.nc.variables.values():   # HDF5 would otherwise cache up to 64 MiB per variable
            var.set_var_chunk_cache(size=CHUNK_CACHE_BYTES, nelems=61)
        self.rows = first.sizes["t"]
        #: the variables on t (appended) and the others (set once, :meth:`set_values`)
        self.on_t = [k for k in list(first.coords) + list(first.data_vars) if "t" in first[k].dims]

    @contextlib.contextmanager
    def _space(self) -> Iterator[None]:
        """A write that fails on a full file system raises :class:`cradle.data.io.DiskFull` (one line)."""
        try:
            yield
        except (OSError, RuntimeError) as err:
            full = disk_full(self.path, self.tmp, 0, err)
            if full is None:
                raise
            raise full from None

    def append(self, t: np.ndarray, fields: dict) -> None:
        """Append the rows of stored times ``t``: ``fields`` maps each variable on t (but t) to its rows."""
        n0, n1 = self.rows, self.rows + len(t)
        with self._space():
            self.nc.variables["t"][n0:n1] = np.asarray(t)
            for name, arr in fields.items():
                self.nc.variables[name][n0:n1, ...] = arr
        self.rows = n1

    def append_block(self, ds: xr.Dataset) -> None:
        """Append every variable on t of ``ds`` (a block built as the first one)."""
        self.append(ds["t"].values, {k: ds[k].values for k in self.on_t if k != "t"})

    def set_values(self, values: dict) -> None:
        """Overwrite variables without t (their final values, known at the end of the run)."""
        for name, arr in values.items():
            self.nc.variables[name][...] = np.asarray(arr)

    def set_attrs(self, attrs: dict) -> None:
        for k, v in attrs.items():
            self.nc.setncattr(k, _attr_value(v))

    def commit(self) -> None:
        with self._space():
            checksums.stamp(self.nc)  # the values without t are final now
            parts = digests.items(self.nc)   # every value read back: the store is not in memory
            self.nc.close()
        os.chmod(self.tmp, _umask_mode())
        digests.record(self.path, parts=parts)  # before the rename, as cradle.data.io.write_netcdf does
        os.replace(self.tmp, self.path)

    def abort(self) -> None:
        try:
            self.nc.close()
        except Exception:  # noqa: BLE001
            pass
        if os.path.exists(self.tmp):
            os.remove(self.tmp)
