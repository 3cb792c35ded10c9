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
from .breather_interactions import BreatherInteractions
from .floquet import Floquet
from .mi_statistics import MIStatistics
from cradle.specs.values import ConfigError, angle_expr, parse_angle, store_times


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


def resolved_theorem1(config: dict) -> dict:
    """``beyond.theorem1`` resolved (:meth:`.beyond.Theorem1.resolve`)."""
    cfg = _validated(config)
    return Theorem1.resolve(cfg, resolved_scene)


def resolved_mi_diagram(config: dict) -> dict:
    """``beyond.mi_diagram`` resolved (:meth:`.beyond.MIDiagram.resolve`)."""
    return MIDiagram.resolve(_validated(config))


def resolved_mi_statistics(config: dict, variant: str) -> dict:
    """``beyond.mi_statistics.<variant>`` with the shared keys and the inherited defaults merged in."""
    return MIStatistics.resolve(_validated(config), variant)


def resolved_floquet(config: dict, form: str = "full") -> dict:
    """``beyond.floquet`` of one form (full, or reduced: what ``all`` builds) with angles in radians and
    ``convergence`` completed."""
    return Floquet.resolve(_validated(config), form)


def resolved_breathers(config: dict, form: str = "full") -> dict:
    """``beyond.breathers`` of one form (full, or reduced: what ``all`` builds)."""
    return Breathers.resolve(_validated(config), form)


def resolved_breather_interactions(config: dict, form: str = "full") -> dict:
    """``beyond.breather_interactions`` of one form (full, or reduced: what ``all`` builds)."""
    return BreatherInteractions.resolve(_validated(config), form)


def analysis_spec(config: dict, name: str, form: str):
    """The typed spec of analysis ``name`` (:mod:`cradle.analyses.registry`) in one form, from the validated
    config's section ``beyond.<name>``; a key named after a section of entries (scenes, homoclinic, map) given
    as ``all`` becomes the names of every entry of that section (the claims table reads them all)."""
    from cradle.analyses.registry import ANALYSES, form_spec
    from cradle.specs.declare import from_plain

    from .sections import SECTIONS

    a = ANALYSES[name]
    cfg = _validated(config)
    section = {key: (list(cfg.get(key) or {}) if key in SECTIONS and value == "all" else value)
               for key, value in cfg["beyond"][a.name].items()}
    return form_spec(from_plain(a.spec, section, where=f"beyond.{a.name}"), form)
