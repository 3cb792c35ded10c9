"""The fully resolved, JSON-serialisable parameters of one entry or analysis of a validated config.

What each Snakemake job and analysis computes from: defaults merged in, angles
in radians (their text kept next to them), stored times listed. Each function
validates the config first (remembered, so a job's repeated calls cost one
validation).
"""
from __future__ import annotations

import copy

from .beyond import MIDiagram, Theorem1
from .breathers import Breathers
from .dps_validity import DpsValidity
from .floquet import Floquet
from .sections import WorkPrecision
from cradle.specs.values import ConfigError, angle_expr, did_you_mean, parse_angle, store_times


def _validated(config: dict) -> dict:
    from .validate import _validated as validated

    return validated(config)


def _merged(base, override):
    """Deep merge of two mappings (override wins)."""
    out = copy.deepcopy(base) if isinstance(base, dict) else {}
    for k, v in (override or {}).items():
        out[k] = _merged(out.get(k), v) if isinstance(v, dict) and isinstance(out.get(k), dict) else copy.deepcopy(v)
    return out


def _entry(cfg, section, name):
    entries = cfg.get(section) or {}
    if name not in entries:
        known = ", ".join(entries) or "none"
        raise ConfigError(f"config error: {section}.{name}: no {section} entry of that name ({section} entries: "
                          f"{known})")
    return copy.deepcopy(entries[name])


def resolved_scene(config: dict, name: str) -> dict:
    """The fully resolved parameters of scene ``name`` (a plain, JSON-serialisable dict).

    Defaults merged in (alpha, exact, dps, max_energy_drift), ``initial.q`` in
    radians with the original text kept as ``initial.q_expr``, everything else
    as given, plus ``times``: the stored times (:func:`store_times`).
    """
    cfg = _validated(config)
    scene = _entry(cfg, "scenes", name)
    d = cfg["defaults"]
    out = {"name": name}
    out.update(scene)
    out["alpha"] = float(scene.get("alpha", d["alpha"]))
    out["exact"] = _merged(d["exact"], scene.get("exact"))
    out["dps"] = _merged(d["dps"], scene.get("dps"))
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


def resolved_work_precision(config: dict, name: str, form: str = "full") -> dict:
    """The parameters of work-precision scene ``name``: ``alpha``, ``N``, ``bc`` from the ``scenes:``
    entry of the same name (whose initial data are used), the rest from ``work_precision``."""
    cfg = _validated(config)
    entries = cfg["work_precision"]["scenes"]
    if name not in entries:
        raise ConfigError(f"config error: work_precision.scenes.{name}: no entry of that name "
                          f"(entries: {', '.join(entries) or 'none'})")
    return WorkPrecision.resolve(cfg, name, resolved_scene(cfg, name), form)


def resolved_theorem1(config: dict) -> dict:
    """``beyond.theorem1`` resolved (:meth:`.beyond.Theorem1.resolve`)."""
    cfg = _validated(config)
    return Theorem1.resolve(cfg, resolved_scene)


def resolved_mi_diagram(config: dict) -> dict:
    """``beyond.mi_diagram`` resolved (:meth:`.beyond.MIDiagram.resolve`)."""
    return MIDiagram.resolve(_validated(config))


def resolved_floquet(config: dict, form: str = "full") -> dict:
    """``beyond.floquet`` of one form (full, or reduced: what ``all`` builds) with angles in radians and
    ``convergence`` completed."""
    return Floquet.resolve(_validated(config), form)


def resolved_breathers(config: dict, form: str = "full") -> dict:
    """``beyond.breathers`` of one form (full, or reduced: what ``all`` builds)."""
    return Breathers.resolve(_validated(config), form)


def resolved_dps_validity(config: dict, form: str = "full") -> dict:
    """``beyond.dps_validity`` of one form (full, or reduced: what ``all`` builds), T sorted."""
    return DpsValidity.resolve(_validated(config), form)


def analysis_spec(config: dict, name: str, form: str):
    """The typed spec of analysis ``name`` (:mod:`cradle.analyses.registry`) in one form, from the validated
    config's section ``beyond.<name>``."""
    from cradle.analyses.registry import ANALYSES, form_spec
    from cradle.specs.declare import from_plain

    a = ANALYSES[name]
    if form not in a.forms:
        raise ConfigError(f"config error: beyond.{a.name}: unknown form {form!r} (forms: {', '.join(a.forms)})")
    return form_spec(from_plain(a.spec, _validated(config)["beyond"][a.name], where=f"beyond.{a.name}"), form)


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
