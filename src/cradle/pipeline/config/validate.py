"""Validating config.yaml: one pass over the declarations builds the typed config, then the checks across keys.

The Snakefile calls :func:`validate` right after loading the config (so after any ``--config`` overrides);
``python -m cradle.pipeline.config [config.yaml]`` does the same from the command line. Every bad input is
reported before any work starts, one line per problem, naming the key path and the value::

    config error: scenes.tw-weak.N = 1: must be >= 2

:func:`typed` reads every section against its declaration (:func:`cradle.specs.parse.parse`): a scene
resolved against ``defaults:`` (alpha, max_energy_drift, its integrators' keys over those of ``defaults``) and
its SI values in (nc)'s units, a homoclinic or map entry with its alpha. Then the jobs' budget
(:mod:`cradle.pipeline.budget`) and the checks no key expresses alone (:mod:`.checks`) run on the entries
that passed. The typed config is remembered for the last few configs: the Snakefile resolves one entry per
job from it.
"""
from __future__ import annotations

import dataclasses
import json
import pickle

from cradle.scenes.spec import Defaults, HomoclinicEntry, MapEntry, Scene, in_nc_units
from cradle.specs.declare import plain
from cradle.specs.parse import BAD, Found, entries, fields_of, given_fields, parse
from cradle.specs.values import ConfigError, Errors, copied, show

from . import checks
from .beyond import Beyond
from .sections import KNOWN_FIGURES, SECTIONS, Config, Figure

#: the sections :func:`read` reads apart from the others: with ``defaults:``, entry by entry
_OWN = ("defaults", "map", "homoclinic", "scenes", "figures", "beyond")

#: the typed configs of the last few configs, by their canonical JSON (:func:`_key`), with their plain values
_TYPED: dict[str, Config] = {}
_PLAIN: dict[int, dict] = {}


def _key(config) -> str | None:
    """The cache key of a config (its canonical JSON), or None if it cannot be serialised or is too large to be
    worth remembering (a config of a huge list is refused anyway: its JSON would cost more than validating it)."""
    if len(pickle.dumps(config, protocol=pickle.HIGHEST_PROTOCOL)) > 1 << 20:
        return None
    try:
        return json.dumps(config, sort_keys=True, default=repr)
    except (TypeError, ValueError):
        return None


def _remember(key: str | None, made: Config) -> Config:
    if key is not None:
        if len(_TYPED) >= 8:
            _TYPED.pop(next(iter(_TYPED)))
        _TYPED[key] = made
    return made


#: what :func:`remembered` made of the entries of recent configs, by (class, key path, pickle of value and base)
_MADE: dict[tuple, tuple] = {}


def remembered(cls, value, path: tuple, found: Found, base=None):
    """:func:`cradle.specs.parse.parse`, remembered: a config validated again with one entry changed (the
    Snakefile's --config overrides, the config fuzz) reads that entry only. What it makes is frozen."""
    try:
        key = (cls, path, pickle.dumps((value, base), protocol=pickle.HIGHEST_PROTOCOL))
    except Exception:  # noqa: BLE001 -- a value pickle refuses is read every time
        return parse(cls, value, path, found, base)
    if key not in _MADE:
        mine = Found()
        _MADE[key] = (parse(cls, value, path, mine, base), mine.lines, mine.finite)
        if len(_MADE) > 4096:
            _MADE.pop(next(iter(_MADE)))
    made, lines, finite = _MADE[key]
    found.lines += lines
    found.finite += finite
    return made


def _base(defaults) -> dict:
    """What an entry leaves out and ``defaults:`` gives: alpha, the integrators, the energy drift bound."""
    if defaults is BAD:
        return {}
    return {"alpha": defaults.alpha, "exact": defaults.exact, "dps": defaults.dps,
            "max_energy_drift": defaults.max_energy_drift}


def read(config: dict) -> tuple[dict, Found]:
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
    found = Found()
    # the sections read below (with what they take from defaults:) left to their defaults here
    parts = given_fields(Config, {key: value for key, value in config.items() if key not in _OWN}, (), found)
    defaults = remembered(Defaults, config["defaults"], ("defaults",), found) if "defaults" in config \
        else Defaults()
    base = _base(defaults)
    parts["defaults"] = defaults
    for section, cls in (("map", MapEntry), ("homoclinic", HomoclinicEntry), ("scenes", Scene)):
        if section in config:
            made = entries(cls, config[section], (section,), found, base={"alpha": base.get("alpha")}
                           if cls is not Scene else base, one=remembered)
            parts[section] = {} if made is BAD else made
    if "scenes" in config:
        parts["scenes"] = _in_nc_units(parts["scenes"], found)
    if "figures" in config:
        made = entries(Figure, config["figures"], ("figures",), found, labels=KNOWN_FIGURES, one=remembered)
        parts["figures"] = {} if made is BAD else made
    parts["beyond"] = {f.name: getattr(parts["beyond"], f.name) for f in dataclasses.fields(Beyond)}
    if "beyond" in config:   # each analysis as an entry: one with problems left out
        parts["beyond"] = _analyses(config["beyond"], found, parts["beyond"])
    return parts, found


def _in_nc_units(scenes: dict, found: Found) -> dict:
    """Each scene in (nc)'s units (:func:`in_nc_units`); one whose converted values break their declarations (an
    SI value that is too large in (nc)'s units) left out, each problem said at the scene."""
    out = {}
    for name, scene in scenes.items():
        try:
            out[name] = in_nc_units(scene)
        except ConfigError as err:
            for line in err.errors:
                found.add(("scenes", name), f"in (nc)'s units, {line.removeprefix('config error: ')}")
    return out


def _analyses(given, found: Found, defaults: dict) -> dict:
    """Each section of ``beyond:`` read as its analysis's spec class (field name -> spec; one with problems
    left out)."""
    if not isinstance(given, dict):
        return {} if given_fields(Beyond, given, ("beyond",), found) is BAD else defaults
    fields = {f.key: f for f in fields_of(Beyond)}
    for key in given:
        if key not in fields:
            given_fields(Beyond, {key: given[key]}, ("beyond",), found)   # says so
    out = dict(defaults)
    for key, f in fields.items():
        if key in given:
            out[f.name] = remembered(f.tp, given[key], ("beyond", key), found, f.make())
    return {name: spec for name, spec in out.items() if spec is not BAD}


def typed(config: dict) -> Config:
    """The validated config as a frozen :class:`.sections.Config` (every entry typed, scenes resolved)."""
    key = _key(config)
    if key in _TYPED:
        return _TYPED[key]
    parts, found = read(config)
    out = found.report(Errors())
    made = None if out.lines else Config(**{**parts, "beyond": Beyond(**parts["beyond"])})
    from cradle.pipeline import budget

    # every job's estimated memory, output and time within budget before the physical checks build stored-time
    # arrays: all jobs when every entry parsed, else the scenes that did (the budget's defaults if it is bad)
    if made is not None:
        budget.check(made)
    else:
        budget.check_scenes(parts.get("scenes") or {}, parts.get("budget"))
    checks.check(parts, config, out)
    out.raise_any()
    assert made is not None
    values = _PLAIN.setdefault(id(made), plain(made, canonical=False))
    if len(_PLAIN) > 8:
        _PLAIN.pop(next(iter(_PLAIN)))
    _remember(_key(values), made)
    return _remember(key, made)


def validate(config: dict) -> dict:
    """``config`` validated, with every default filled in and every scene resolved (:func:`typed`), as plain
    values in the order of the declarations: what the Snakefile's ``config`` holds. Raises
    :class:`ConfigError` listing every problem found, one line each."""
    made = typed(config)
    values = _PLAIN.get(id(made))
    return copied(values) if values is not None else plain(made, canonical=False)


def assume_validated(config: dict) -> dict:
    """``config``, taken as validated (a Snakemake job's copy of the config its Snakefile validated:
    workflow/rules/common.smk): an entry of it is then read alone (:func:`entry`), not the whole config."""
    _TRUSTED.add(_key(config))
    return config


_TRUSTED: set[str | None] = set()


def entry(config: dict, section: str, name: str):
    """Entry ``name`` of ``section`` (scenes, homoclinic, map) of ``config``, typed and resolved; a config taken
    as validated (:func:`assume_validated`) is read for that entry alone."""
    key = _key(config)
    made = _TYPED.get(key) if key is not None else None
    if made is None and key in _TRUSTED and name in (config.get(section) or {}):
        found = Found()
        defaults = parse(Defaults, config.get("defaults", {}), ("defaults",), found)
        cls = {"scenes": Scene, "homoclinic": HomoclinicEntry, "map": MapEntry}[section]
        base = _base(defaults) if cls is Scene else {"alpha": defaults.alpha}
        one = parse(cls, config[section][name], (section, name), found, base)
        found.report(Errors()).raise_any()
        return in_nc_units(one) if cls is Scene else one
    entries_ = getattr(made if made is not None else typed(config), section)
    if name not in entries_:
        raise ConfigError(f"config error: {section}.{name}: no {section} entry of that name ({section} entries: "
                          f"{', '.join(entries_) or 'none'})")
    return entries_[name]
