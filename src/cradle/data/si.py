"""A scene's file in SI units: the variables of (nc) times the SI value of their unit, which a scene of a real
cradle stores (``scale_time_s``, ``scale_length_m``, ...: :func:`cradle.scenes.stages.physical_attrs`, from
:func:`cradle.models.physical.scales`).

Only the variables whose quantity is a plain multiple of one scale are converted (:data:`QUANTITIES`): times,
displacements, velocities, forces and energies of the lattice. The DpS amplitudes A_n and the slow time tau are
left in (nc)'s units: their SI value also depends on eps of (ansatz).
"""
from __future__ import annotations

import xarray as xr

#: quantity -> (the global attribute holding the SI value of one unit of it, its CF units)
SCALES = {"time": ("scale_time_s", "s"), "displacement": ("scale_length_m", "m"),
          "velocity": ("scale_velocity_m_s", "m s-1"), "force": ("scale_force_N", "N"),
          "energy": ("scale_energy_J", "J")}

#: the variables converted, by quantity
QUANTITIES = {"t": "time", "x": "displacement", "x0": "displacement", "v": "velocity", "v0": "velocity",
              "force": "force", "energy": "energy", "dissipated": "energy"}


def si_long_name(long_name: str) -> str:
    """The long name of a variable of (nc) once in SI: the same quantity, without the word that says it has no
    units ("dimensionless time t of (nc)" -> "time t of (nc)"); the units attribute says which."""
    return " ".join(word for word in str(long_name).split() if word.lower() != "dimensionless")


def has_scales(ds: xr.Dataset) -> bool:
    """Whether ``ds`` holds the scales of a real cradle (a scene with ``cradle:``)."""
    return all(attr in ds.attrs for attr, _ in SCALES.values())


def in_si(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with its times, displacements, velocities, forces and energies in SI (CF units s, m, m s-1, N, J);
    a file without a cradle's scales is refused in one line."""
    if not has_scales(ds):
        raise ValueError(f"{ds.attrs.get('title', 'this dataset')}: no SI scales (scale_time_s, ...): only a scene "
                         "with `cradle:` converts to SI")
    out = ds.copy()
    for name, quantity in QUANTITIES.items():
        if name not in out.variables:
            continue
        attr, units = SCALES[quantity]
        var = out[name]
        converted = var * float(ds.attrs[attr])
        converted.attrs = {**var.attrs, "units": units, "long_name": si_long_name(var.attrs.get("long_name", name)),
                           "si_conversion": f"the value of (nc) times the global attribute {attr}"}
        if name in out.coords:
            out = out.assign_coords({name: converted})
        else:
            out[name] = converted
    out.attrs["units_system"] = "SI"
    return out
