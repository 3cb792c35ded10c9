"""Validating config.yaml (one pass builds the typed config, then the budget and the checks across keys) and
resolving one entry or analysis of it (docs/developing.md "Specs")."""
from __future__ import annotations

import json
import pickle
from typing import Any

from cradle.analyses.protocol import Read
from cradle.scenes.spec import Defaults, HomoclinicEntry, MapEntry, Scene, in_nc_units
from cradle.specs.declare import plain
from cradle.specs.parse import BAD, entries, fields_of, given_fields, parse
from cradle.specs.values import ConfigError, Errors, show

from . import checks
from .sections import KNOWN_FIGURES, SECTIONS, Beyond, Config, Figure

#: the sections of entries resolved against ``defaults:``
ENTRIES: dict[str, type] = {"map": MapEntry, "homoclinic": HomoclinicEntry, "scenes": Scene}
#: the typed configs of the last few configs, by their canonical JSON (:func:`_key`)
_TYPED: dict[str | None, Config] = {}
#: the configs taken as validated (:func:`assume_validated`)
_TRUSTED: set[str | None] = set()
#: what :func:`remembered` made of recent entries, by (class, key path, pickle of value and base)
_MADE: dict[tuple, tuple] = {}
_REMEMBER_BYTES = 1 << 20   # config.yaml's entries pickle to a few kB


def _key(config: Any) -> str | None:
    """The canonical JSON of a config, or None if it has none or is too large to remember."""
    if len(pickle.dumps(config, protocol=pickle.HIGHEST_PROTOCOL)) > _REMEMBER_BYTES:
        return None
    try:
        return json.dumps(config, sort_keys=True, default=repr)
    except (TypeError, ValueError):
        return None


def _base(defaults: Any, cls: type) -> dict[str, Any]:
    """What an entry of class ``cls`` leaves out and ``defaults:`` gives."""
    keys = ("alpha", "exact", "dps", "max_energy_drift") if cls is Scene else ("alpha",)
    return {} if defaults is BAD else {key: getattr(defaults, key) for key in keys}


def remembered(cls: Any, value: Any, path: tuple, found: Errors, base: Any = None) -> Any:
    """:func:`cradle.specs.parse.parse` of one entry, remembered: a config validated again with one entry changed
    (``--config`` overrides, the config fuzz) reads that entry only."""
    try:
        key = (cls, path, pickle.dumps((value, base), protocol=pickle.HIGHEST_PROTOCOL))
    except Exception:  # noqa: BLE001 -- a value pickle refuses is read every time
        return parse(cls, value, path, found, base)
    if len(key[2]) > _REMEMBER_BYTES:   # a huge entry is read, not kept
        return parse(cls, value, path, found, base)
    if key not in _MADE:
        mine = Errors()
        _MADE[key] = (parse(cls, value, path, mine, base), mine.held, mine.finite)
        if len(_MADE) > 4096:
            _MADE.pop(next(iter(_MADE)))
    made, held, finite = _MADE[key]
    found.held += held
    found.finite += finite
    return made


def read(config: Any) -> tuple[dict[str, Any], Errors]:
    """Every section of ``config`` typed (field name of :class:`.sections.Config` -> value; an entry with
    problems left out), and the problems found."""
    config = {} if config is None else config   # an empty YAML file
    if not isinstance(config, dict):
        raise ConfigError(f"config error: config = {show(config)}: must be a mapping")
    if not any(config.get(section) for section in SECTIONS):   # an empty file, or the wrong one
        raise ConfigError(f"config error: config: no {', '.join(SECTIONS)} entries, nothing to build (keys given: "
                          f"{', '.join(map(str, config)) or 'none'})")
    found = Errors()
    apart = ("defaults", *ENTRIES, "figures", "beyond")   # read entry by entry below
    parts = given_fields(Config, {key: value for key, value in config.items() if key not in apart}, (), found)
    defaults = parts["defaults"] = remembered(Defaults, config.get("defaults", {}), ("defaults",), found)
    for section, cls in ENTRIES.items():
        made = entries(cls, config.get(section, {}), (section,), found, base=_base(defaults, cls), one=remembered)
        parts[section] = {} if made is BAD else made
    parts["scenes"] = _in_nc_units(parts["scenes"], found)
    made = entries(Figure, config.get("figures", {}), ("figures",), found, labels=KNOWN_FIGURES, one=remembered)
    parts["figures"] = {} if made is BAD else made
    # each analysis as an entry (one with problems left out); given_fields says what else is wrong
    beyond, known = config.get("beyond", {}), {f.key: f for f in fields_of(Beyond)}
    mapping = isinstance(beyond, dict)
    given_fields(Beyond, {k: v for k, v in beyond.items() if k not in known} if mapping else beyond, ("beyond",), found)
    made = {f.name: remembered(f.tp, beyond[key], ("beyond", key), found, f.make()) if key in beyond else f.make()
            for key, f in known.items()} if mapping else {}
    parts["beyond"] = {name: spec for name, spec in made.items() if spec is not BAD}
    return parts, found


def _in_nc_units(scenes: dict, found: Errors) -> dict:
    """Each scene in (nc)'s units; one whose converted values break their declarations or whose cradle is
    impossible (:meth:`~cradle.scenes.spec.Scene.check_cradle`) left out, its problems said."""
    out = {}
    for name, scene in scenes.items():
        try:
            out[name] = in_nc_units(scene)
        except ConfigError as err:
            for line in err.errors:
                found.hold(("scenes", name), f"in (nc)'s units, {line.removeprefix('config error: ')}")
            continue
        mine = Errors()
        out[name].check_cradle(["scenes", name], mine)
        if mine.lines:   # its budget's estimate would be meaningless
            found.lines += mine.lines
            found.paths |= mine.paths
            del out[name]
    return out


def typed(config: Any) -> Config:
    """The validated config as a frozen :class:`.sections.Config` (every entry typed, scenes resolved)."""
    key = _key(config)
    if key is not None and key in _TYPED:
        return _TYPED[key]
    parts, found = read(config)
    out = found.said()
    made = None if out.lines else Config(**{**parts, "beyond": Beyond(**parts["beyond"])})
    from cradle.pipeline import budget

    # the budget before the checks build stored-time arrays: all jobs, else the scenes that parsed
    if made is not None:
        unestimated = budget.check(made)
    else:
        unestimated = budget.check_scenes(parts.get("scenes") or {}, parts.get("budget"))
    checks.check(parts, config, out)
    if not out.lines:   # refused, never run unbudgeted (beside other problems, often their consequence: not said)
        for key, line in unestimated.items():
            out.add(key, line.removeprefix(f"{key}: "))
    out.raise_any()
    assert made is not None
    if key is not None:
        if len(_TYPED) >= 8:
            _TYPED.pop(next(iter(_TYPED)))
        _TYPED[key] = made
    return made


def validate(config: Any) -> dict[str, Any]:
    """``config`` validated, defaults filled in, scenes resolved, as plain values in the order of the
    declarations: what the Snakefile's ``config`` holds. Raises :class:`ConfigError`, one line per problem."""
    return plain(typed(config), canonical=False)


def assume_validated(config: dict[str, Any]) -> dict[str, Any]:
    """``config`` taken as validated (a job's copy of its Snakefile's config): an entry is then read alone."""
    _TRUSTED.add(_key(config))
    return config


def entry(config: dict[str, Any], section: str, name: str) -> Any:
    """Entry ``name`` of ``section`` (scenes, homoclinic, map) of ``config``, typed and resolved against
    ``defaults:`` (a scene in (nc)'s units)."""
    key = _key(config)
    if key in _TRUSTED and key not in _TYPED and name in (config.get(section) or {}):
        found, cls = Errors(), ENTRIES[section]
        defaults = parse(Defaults, config.get("defaults", {}), ("defaults",), found)
        one = parse(cls, config[section][name], (section, name), found, _base(defaults, cls))
        found.said().raise_any()
        return in_nc_units(one) if cls is Scene else one
    made = getattr(typed(config), section)
    if name not in made:
        raise ConfigError(f"config error: {section}.{name}: no {section} entry of that name ({section} entries: "
                          f"{', '.join(made) or 'none'})")
    return made[name]


def scene(config: dict[str, Any], name: str) -> Scene:
    return entry(config, "scenes", name)


def homoclinic(config: dict[str, Any], name: str) -> HomoclinicEntry:
    return entry(config, "homoclinic", name)


def map_entry(config: dict[str, Any], name: str) -> MapEntry:
    return entry(config, "map", name)


def analysis_spec(config: dict[str, Any], name: str, form: str) -> Any:
    """The typed spec of analysis ``name`` in one form, a key naming a section of entries given as ``all``
    the names of its entries, sorted."""
    from cradle.analyses.registry import ANALYSES, form_spec

    a = ANALYSES[name]
    if form not in a.forms:
        raise ConfigError(f"config error: beyond.{a.name}: unknown form {form!r} (forms: {', '.join(a.forms)})")
    cfg = typed(config)
    names = {section: sorted(getattr(cfg, section)) for section in SECTIONS}
    return form_spec(checks.with_all(getattr(cfg.beyond, a.module), names), form)


def analysis_reads(config: dict[str, Any], name: str, form: str) -> dict[str, Read]:
    """What analysis ``name`` reads in one form: name -> :class:`~cradle.analyses.protocol.Read`."""
    from cradle.analyses.registry import ANALYSES

    return ANALYSES[name].reads_of(analysis_spec(config, name, form))
