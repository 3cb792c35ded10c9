"""Validating config.yaml: one pass over the declarations builds the typed config, then the checks across keys.

The Snakefile calls :func:`validate` right after loading the config (so after any ``--config`` overrides);
``python -m cradle.pipeline.config [config.yaml]`` does the same from the command line. Every bad input is
reported before any work starts, one line per problem, naming the key path and the value::

    config error: scenes.tw-weak.N = 1: must be >= 2

:func:`typed` reads every section against its declaration (:func:`cradle.specs.parse.parse`): a scene
resolved against ``defaults:`` (alpha, max_energy_drift, its integrators' keys over those of ``defaults``) and
its SI values in (nc)'s units, a homoclinic or map entry with its alpha. Then the jobs' budget
(:mod:`cradle.pipeline.budget`) and the checks no key expresses alone (:mod:`.checks`) run on the entries
that passed. The typed config of the last few configs is remembered (the Snakefile resolves one entry per job),
and so is each entry's typed object (a config validated again with one entry changed reads that entry only).
"""
from __future__ import annotations

import json
import pickle
from typing import Any

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
#: the configs taken as validated (:func:`assume_validated`), by their canonical JSON
_TRUSTED: set[str | None] = set()
#: what :func:`remembered` made of the entries of recent configs, by (class, key path, pickle of value and base)
_MADE: dict[tuple, tuple] = {}
#: the largest pickle of an entry :func:`remembered` keeps: config.yaml's entries pickle to a few kB; a list of a
#: million values (kept with its problems, held by the cache) would fill memory and slow every garbage collection
_REMEMBER_BYTES = 1 << 20


def _key(config: Any) -> str | None:
    """The canonical JSON of a config, or None if it cannot be serialised or is too large to be worth remembering
    (a config of a huge list is refused anyway: its JSON would cost more than validating it)."""
    if len(pickle.dumps(config, protocol=pickle.HIGHEST_PROTOCOL)) > _REMEMBER_BYTES:
        return None
    try:
        return json.dumps(config, sort_keys=True, default=repr)
    except (TypeError, ValueError):
        return None


def _base(defaults: Any, cls: type) -> dict[str, Any]:
    """What an entry of class ``cls`` leaves out and ``defaults:`` gives: alpha, and for a scene its
    integrators and its energy drift bound."""
    keys = ("alpha", "exact", "dps", "max_energy_drift") if cls is Scene else ("alpha",)
    return {} if defaults is BAD else {key: getattr(defaults, key) for key in keys}


def remembered(cls: Any, value: Any, path: tuple, found: Errors, base: Any = None) -> Any:
    """:func:`cradle.specs.parse.parse` of one entry (or section), remembered: a config validated again with one
    entry changed (the Snakefile's --config overrides, the config fuzz) reads that entry only, and its checks
    see the same frozen objects (a scene's stored times are worked out once)."""
    try:
        key = (cls, path, pickle.dumps((value, base), protocol=pickle.HIGHEST_PROTOCOL))
    except Exception:  # noqa: BLE001 -- a value pickle refuses is read every time
        return parse(cls, value, path, found, base)
    if len(key[2]) > _REMEMBER_BYTES:   # a huge entry (a list of a million values) is read, not kept
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
    """Every section of ``config`` as its typed value (field name of :class:`.sections.Config` -> value; an
    entry with problems left out), and the problems found."""
    if config is None:
        config = {}   # an empty YAML file
    if not isinstance(config, dict):
        raise ConfigError(f"config error: config = {show(config)}: must be a mapping")
    if not any(config.get(section) for section in SECTIONS):
        # an empty file, or the wrong one: refused here rather than as a traceback while the DAG is built
        raise ConfigError(f"config error: config: no {', '.join(SECTIONS)} entries, nothing to build (keys given: "
                          f"{', '.join(map(str, config)) or 'none'})")
    found = Errors()
    # the sections read entry by entry below are left to their defaults here
    apart = ("defaults", *ENTRIES, "figures", "beyond")
    parts = given_fields(Config, {key: value for key, value in config.items() if key not in apart}, (), found)
    defaults = remembered(Defaults, config["defaults"], ("defaults",), found) if "defaults" in config \
        else Defaults()
    parts["defaults"] = defaults
    for section, cls in ENTRIES.items():
        if section in config:
            made = entries(cls, config[section], (section,), found, base=_base(defaults, cls), one=remembered)
            parts[section] = {} if made is BAD else made
    parts["scenes"] = _in_nc_units(parts["scenes"], found)
    if "figures" in config:
        made = entries(Figure, config["figures"], ("figures",), found, labels=KNOWN_FIGURES, one=remembered)
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
    """Each scene in (nc)'s units (:func:`in_nc_units`); one whose converted values break their declarations (an
    SI value that is too large in (nc)'s units) or whose cradle is impossible (a swing beyond its string, another
    exponent than Hertz's: :meth:`~cradle.scenes.spec.Scene.check_cradle`) left out, each problem said at it."""
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
        if mine.lines:   # said here, and the scene left out: its estimate would be meaningless
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

    # every job's estimated memory, output and time within budget before the physical checks build stored-time
    # arrays: all jobs when every entry parsed, else the scenes that did (the largest budget if its own is bad)
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
    """``config`` validated, with every default filled in and every scene resolved (:func:`typed`), as plain
    values in the order of the declarations: what the Snakefile's ``config`` holds. Raises
    :class:`ConfigError` listing every problem found, one line each."""
    return plain(typed(config), canonical=False)


def assume_validated(config: dict[str, Any]) -> dict[str, Any]:
    """``config``, taken as validated (a Snakemake job's copy of the config its Snakefile validated:
    workflow/rules/common.smk): an entry of it is then read alone (:func:`entry`), not the whole config."""
    _TRUSTED.add(_key(config))
    return config


def entry(config: dict[str, Any], section: str, name: str) -> Any:
    """Entry ``name`` of ``section`` (scenes, homoclinic, map) of ``config``, typed and resolved; a config taken
    as validated (:func:`assume_validated`) is read for that entry alone."""
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
