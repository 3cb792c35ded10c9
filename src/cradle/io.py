"""Self-describing netCDF output.

:func:`make_dataset` builds an :class:`xarray.Dataset` whose variables get
their dimensions, ``long_name`` and ``units`` from :mod:`cradle.variables`,
plus the global attributes every file carries (paper reference, code version).
:func:`write_netcdf` writes it atomically: to a temporary file in the target
folder, then ``os.replace``, so an interrupted or failed rule never leaves a
file that Snakemake would take as done.
"""
from __future__ import annotations

import datetime as _dt
import os
import sys
import tempfile
from pathlib import Path

import numpy as np
import xarray as xr

from . import __version__
from .variables import declared

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


def make_dataset(data: dict, coords: dict | None = None, attrs: dict | None = None, title: str = "") -> xr.Dataset:
    """A Dataset from ``{name: array}`` with declared dims, long names and units.

    ``coords`` maps coordinate names to 1-D arrays (also declared). ``attrs``
    become global attributes (every parameter that produced the file).
    """
    coords = coords or {}
    ds = xr.Dataset()
    for name, values in coords.items():
        var = declared(name)
        ds = ds.assign_coords({name: (var.dims, np.asarray(values), {"long_name": var.long_name, "units": var.units})})
    for name, values in data.items():
        var = declared(name)
        ds[name] = xr.Variable(var.dims, np.asarray(values), {"long_name": var.long_name, "units": var.units})
    ds.attrs.update(
        {
            "title": title,
            "Conventions": "CF-1.10",
            "source": f"cradle {__version__}",
            "references": REFERENCE,
            "history": f"{_dt.datetime.now(_dt.timezone.utc).isoformat(timespec='seconds')} "
            f"{' '.join(Path(a).name if i == 0 else a for i, a in enumerate(sys.argv))}",
            "cradle_version": __version__,
        }
    )
    for key, value in (attrs or {}).items():
        ds.attrs[key] = _attr_value(value)
    return ds


def write_netcdf(ds: xr.Dataset, path: str | os.PathLike) -> Path:
    """Write ``ds`` to ``path`` atomically (temporary file, then rename)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    # float coordinates must not get a _FillValue (CF forbids it on coordinates)
    encoding = {name: {"_FillValue": None} for name in list(ds.coords) + list(ds.data_vars)
                if np.issubdtype(ds[name].dtype, np.floating)}
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(fd)
    try:
        ds.to_netcdf(tmp, encoding=encoding, engine="netcdf4")
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    return path


def write_text(text: str, path: str | os.PathLike) -> Path:
    """Write a text file atomically (temporary file, then rename)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w") as fh:
            fh.write(text)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    return path


def open_dataset(path: str | os.PathLike) -> xr.Dataset:
    """Open a cradle output fully into memory (the file is closed on return)."""
    with xr.open_dataset(path) as ds:
        return ds.load()
