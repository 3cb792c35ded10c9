"""The workflow's outputs opened by name: a scene's exact and DpS runs as one Dataset, the files a paper
figure reads; each checked to be the file the config expects (:mod:`cradle.pipeline.identity`)."""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import xarray as xr

from cradle.data.io import open_dataset
from cradle.data.si import in_si
from cradle.pipeline import layout
from cradle.pipeline.identity import Expectations, WrongOutput

SHARED = ("x", "force")  # variables both models store on the same (t, n) grid


def open_scene(scene: str, root: str | os.PathLike = "results", metrics: bool = True, check: bool = True,
               config: str | os.PathLike | dict | None = None, units: str = "nc") -> xr.Dataset:
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

    Each file must be the one ``config`` expects (:mod:`cradle.pipeline.identity`): this scene's, made
    from the parameters the config resolves to now; else :class:`~cradle.pipeline.identity.WrongOutput`,
    one line naming the file, what it holds and what was expected. ``config``: a config file or mapping;
    by default the ``config.yaml`` beside ``root`` (in ``root``'s parent folder), and when there is none
    nothing is checked. ``check=False`` opens whatever is there. ``units="si"``: a scene of a real cradle
    (``cradle:``) with its times, displacements, velocities, forces and energies in SI (:func:`cradle.data.si.in_si`).
    """
    if units not in ("nc", "si"):
        raise ValueError(f"units = {units!r}: must be nc or si")
    root = Path(root)
    paths = {m: Path(p) for m, p in layout.scene_paths(scene, root, ("exact", "dps")).items()}
    missing = [str(p) for p in paths.values() if not p.exists()]
    if missing:
        raise FileNotFoundError(f"scene {scene!r}: no {' and no '.join(missing)} (run `cradle run {scene} "
                                f"--out {root}` or `snakemake {' '.join(missing)}`)")
    expect = _expectations(root, config) if check else None
    runs = {m: _opened(p, expect) for m, p in paths.items()}
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
        parts.append(_opened(mpath, expect))
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
    return in_si(ds) if units == "si" else ds


def _same(a: object, b: object) -> bool:
    try:
        return bool(np.array_equal(np.asarray(a), np.asarray(b)))
    except Exception:  # noqa: BLE001
        return False


def _expectations(root: Path, config: dict | str | os.PathLike | None) -> Expectations | None:
    """What ``config`` (a mapping, a file, or None: ``root``'s parent's config.yaml if there is one) expects
    under ``root``; None when there is no config to check against."""
    from cradle.pipeline.config import read_yaml

    if config is None:
        config = root.parent / "config.yaml"
        if not config.is_file():
            return None
    if isinstance(config, dict):
        return Expectations(config, root, source="the config")
    return Expectations(read_yaml(config), root, source=str(config))


def _opened(path: str | Path, expect: Expectations | None) -> xr.Dataset:
    """:func:`open_dataset`, then refused unless it is the file ``expect`` expects (None: not checked)."""
    if expect is not None:  # attributes only, first: another entry's whole file says so, not "edited"
        line = expect.check_file(path)
        if line is not None:
            raise WrongOutput(line)
    ds = open_dataset(path)
    if expect is not None:
        expect.check(path, ds)
    return ds


def load_inputs(scenes: dict, root: str | Path, config: dict | None = None, source: str = "the config") -> dict:
    """Open the netCDF files of a figure's scenes.

    ``scenes`` maps each name to its config section (map, homoclinic,
    scenes). Map and homoclinic names give one Dataset; a scene gives
    ``{"exact": ..., "dps": ..., "metrics": ...}``. Every file is verified as it is read
    (:func:`cradle.data.io.open_dataset`): a damaged or truncated one stops the figure with one
    line naming it and its rebuild command, before anything is drawn or written. With ``config`` (the
    workflow's, named ``source`` in messages), every file must also be the one it expects
    (:mod:`cradle.pipeline.identity`: its scene or entry, made from the parameters it resolves to now).
    """
    expect = None if config is None else Expectations(config, root, source)
    data: dict[str, xr.Dataset | dict[str, xr.Dataset]] = {}
    for name, kind in scenes.items():
        if kind in ("map", "homoclinic"):
            data[name] = _opened(layout.path(kind, root, name=name), expect)
        else:
            data[name] = {part: _opened(path, expect)
                          for part, path in layout.scene_paths(name, root, layout.RUN_PARTS).items()}
    return data
