"""The resolved parameters of one entry or analysis of a validated config.

What each Snakemake job and analysis computes from, defaults merged in. A scene,
homoclinic or map entry is a typed, frozen instance (:func:`scene`,
:func:`homoclinic`, :func:`map_entry`; :mod:`cradle.scenes.spec`); the analyses
still read plain, JSON-serialisable dicts (:func:`resolved_scene` and the other
``resolved_*``: angles in radians with their text kept next to them, stored
times listed). Each function validates the config first (remembered, so a job's
repeated calls cost one validation).
"""
from __future__ import annotations

from typing import Any

from cradle.scenes.spec import HomoclinicEntry, MapEntry, Scene, resolved
from cradle.specs.declare import build
from cradle.specs.values import ConfigError, angle_expr, copied, did_you_mean, merged, parse_angle, store_times


def _validated(config: dict) -> dict:
    from .validate import _validated as validated

    return validated(config)


def _entry(cfg, section, name):
    entries = cfg.get(section) or {}
    if name not in entries:
        known = ", ".join(entries) or "none"
        raise ConfigError(f"config error: {section}.{name}: no {section} entry of that name ({section} entries: "
                          f"{known})")
    return copied(entries[name])


def scene_of(cfg: dict, name: str) -> Scene:
    """Scene ``name`` of a schema-filled config (defaults filled in, not necessarily checked further:
    the budget estimates it during validation), resolved: ``alpha`` and ``max_energy_drift`` from
    defaults unless the scene gives them, ``exact`` and ``dps`` the scene's keys merged over
    ``defaults.exact`` / ``defaults.dps``."""
    return resolved(_entry(cfg, "scenes", name), cfg["defaults"])


def scene(config: dict, name: str) -> Scene:
    """Scene ``name`` of ``config``, validated and resolved (:func:`scene_of`)."""
    return scene_of(_validated(config), name)


def homoclinic(config: dict, name: str) -> HomoclinicEntry:
    """Homoclinic entry ``name`` of ``config``, validated, its ``alpha`` filled from defaults."""
    cfg = _validated(config)
    entry = _entry(cfg, "homoclinic", name)
    return build(HomoclinicEntry, {**entry, "alpha": float(entry.get("alpha", cfg["defaults"]["alpha"]))})


def map_entry(config: dict, name: str) -> MapEntry:
    """Map entry ``name`` of ``config``, validated, its ``alpha`` filled from defaults."""
    cfg = _validated(config)
    entry = _entry(cfg, "map", name)
    return build(MapEntry, {**entry, "alpha": float(entry.get("alpha", cfg["defaults"]["alpha"]))})


def resolved_scene(config: dict, name: str) -> dict:
    """The fully resolved parameters of scene ``name`` (a plain, JSON-serialisable dict).

    Defaults merged in (alpha, exact, dps, max_energy_drift), ``initial.q`` in
    radians with the original text kept as ``initial.q_expr``, everything else
    as given, plus ``times``: the stored times (:func:`store_times`).
    """
    cfg = _validated(config)
    scene = _entry(cfg, "scenes", name)
    d = cfg["defaults"]
    out: dict[str, Any] = {"name": name}
    out.update(scene)
    out["alpha"] = float(scene.get("alpha", d["alpha"]))
    out["exact"] = merged(d["exact"], scene.get("exact"))
    out["dps"] = merged(d["dps"], scene.get("dps"))
    out["max_energy_drift"] = float(scene.get("max_energy_drift", d["max_energy_drift"]))
    ini = out["initial"]
    if ini["kind"] == "travelling":
        q = ini["q"]
        ini["q_expr"] = angle_expr(q)
        ini["q"] = parse_angle(q)
    out["times"] = store_times(scene["store"], scene["t_end"])
    return out


def resolved_homoclinic(config: dict, name: str) -> dict:
    """The fully resolved parameters of homoclinic entry ``name`` (alpha filled from defaults)."""
    cfg = _validated(config)
    entry = _entry(cfg, "homoclinic", name)
    return {"name": name, **entry, "alpha": float(entry.get("alpha", cfg["defaults"]["alpha"]))}


def resolved_map(config: dict, name: str) -> dict:
    """The fully resolved parameters of map entry ``name`` (alpha filled from defaults)."""
    cfg = _validated(config)
    entry = _entry(cfg, "map", name)
    return {"name": name, **entry, "alpha": float(entry.get("alpha", cfg["defaults"]["alpha"]))}




def typed(config: dict):
    """The validated config as a frozen :class:`.sections.Config` (scenes, entries, analyses as typed
    instances; each initial condition an instance of its kind's class)."""
    from cradle.specs import declare as spec

    from .sections import Config

    return spec.build(Config, _validated(config))






def analysis_spec(config: dict, name: str, form: str):
    """The typed spec of analysis ``name`` (:mod:`cradle.analyses.registry`) in one form, from the validated
    config's section ``beyond.<name>``; a key named after a section of entries (scenes, homoclinic, map) given
    as ``all`` becomes the names of every entry of that section (the claims table reads them all)."""
    from cradle.analyses.registry import ANALYSES, form_spec
    from cradle.specs.declare import from_plain

    from .sections import SECTIONS

    a = ANALYSES[name]
    if form not in a.forms:
        raise ConfigError(f"config error: beyond.{a.name}: unknown form {form!r} (forms: {', '.join(a.forms)})")
    cfg = _validated(config)
    # `all` in name order: moving a block of config.yaml changes nothing the analysis reads
    section = {key: (sorted(cfg.get(key) or {}) if key in SECTIONS and value == "all" else value)
               for key, value in cfg["beyond"][a.name].items()}
    return form_spec(from_plain(a.spec, section, where=f"beyond.{a.name}"), form)


def analysis_reads(config: dict, name: str, form: str) -> dict:
    """What analysis ``name`` reads in one form (:meth:`cradle.analyses.protocol.Analysis.reads_of`): name ->
    :class:`~cradle.analyses.protocol.Read`; every scene it names must be a ``scenes:`` entry."""
    from cradle.analyses.registry import ANALYSES

    cfg = _validated(config)
    reads = ANALYSES[name].reads_of(analysis_spec(cfg, name, form))
    for read in reads.values():
        scene = dict(read.names).get("scene")
        if scene is not None and scene not in cfg["scenes"]:
            raise ConfigError(f"config error: beyond.{name}: reads scene {scene!r}: no `scenes:` entry of that "
                              f"name{did_you_mean(scene, cfg['scenes'])}")
    return reads
