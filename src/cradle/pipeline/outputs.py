"""The workflow's outputs opened by name: a scene's exact and DpS runs as one Dataset, the files a paper
figure reads."""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import xarray as xr

from cradle.data.io import open_dataset
from cradle.pipeline import layout

SHARED = ("x", "force")  # variables both models store on the same (t, n) grid


def open_scene(scene: str, root: str | os.PathLike = "results", metrics: bool = True) -> xr.Dataset:
    """The exact and DpS runs of ``scene`` as one Dataset, read from ``root``/sim/``scene``/{exact,dps}.nc.

    ``x`` and ``force`` get a ``model`` dimension (``exact``, ``dps``); the
    other variables keep their names (``v``, ``energy`` of the lattice;
    ``A_re``, ``A_im``, the drifts and the ``tau`` coordinate of the DpS
    run), plus ``E`` and the spectra of ``root``/metrics/``scene``.nc when
    it exists (and ``metrics`` is true). Global attributes equal in both runs
    are kept as they are; the others are prefixed ``exact_`` or ``dps_``
    (``exact_energy_drift``, ``dps_integrator``, ...)::

        ds = cradle.open_scene("tw-weak")
        (ds.x.sel(model="exact") - ds.x.sel(model="dps")).sel(t=621.95).plot()
    """
    root = Path(root)
    paths = {m: Path(p) for m, p in layout.scene_paths(scene, root, ("exact", "dps")).items()}
    missing = [str(p) for p in paths.values() if not p.exists()]
    if missing:
        raise FileNotFoundError(f"scene {scene!r}: no {' and no '.join(missing)} (run `cradle run {scene} "
                                f"--out {root}` or `snakemake {' '.join(missing)}`)")
    runs = {m: open_dataset(p) for m, p in paths.items()}
    if not np.array_equal(runs["exact"]["t"].values, runs["dps"]["t"].values):
        raise ValueError(f"scene {scene!r}: exact and dps runs are stored at different times (rerun one)")
    model = xr.DataArray(["exact", "dps"], dims="model", name="model",
                         attrs={"long_name": "model: exact lattice (nc) or DpS approximation (dfnls)/(ansatz)"})
    shared = xr.concat([runs[m][list(SHARED)].drop_vars("tau", errors="ignore") for m in ("exact", "dps")],
                       dim=model, combine_attrs="drop_conflicts")
    for name in SHARED:
        shared[name].attrs = dict(runs["exact"][name].attrs)
    rest = [runs[m].drop_vars(list(SHARED)) for m in ("exact", "dps")]
    parts = [shared, *rest]
    mpath = Path(layout.path("metrics", root, scene=scene))
    if metrics and mpath.exists():
        parts.append(open_dataset(mpath))
    ds = xr.merge(parts, compat="override", join="exact", combine_attrs="override")
    ex, ap = runs["exact"].attrs, runs["dps"].attrs
    attrs = {}
    for key in list(ex) + [k for k in ap if k not in ex]:
        if key in ex and key in ap and _same(ex[key], ap[key]):
            attrs[key] = ex[key]
        else:
            if key in ex:
                attrs[f"exact_{key}"] = ex[key]
            if key in ap:
                attrs[f"dps_{key}"] = ap[key]
    attrs["title"] = f"exact and DpS runs of scene '{scene}'"
    ds.attrs = attrs
    return ds


def _same(a, b) -> bool:
    try:
        return bool(np.array_equal(np.asarray(a), np.asarray(b)))
    except Exception:  # noqa: BLE001
        return False


def load_inputs(scenes: dict, root) -> dict:
    """Open the netCDF files of a figure's scenes.

    ``scenes`` maps each name to its config section (map, homoclinic,
    scenes). Map and homoclinic names give one Dataset; a scene gives
    ``{"exact": ..., "dps": ..., "metrics": ...}``. Every file is verified as it is read
    (:func:`cradle.data.io.open_dataset`): a damaged or truncated one stops the figure with one
    line naming it and its rebuild command, before anything is drawn or written.
    """
    data: dict[str, xr.Dataset | dict[str, xr.Dataset]] = {}
    for name, kind in scenes.items():
        if kind in ("map", "homoclinic"):
            data[name] = open_dataset(layout.path(kind, root, name=name))
        else:
            data[name] = {part: open_dataset(path)
                          for part, path in layout.scene_paths(name, root, layout.RUN_PARTS).items()}
    return data
