"""The checks the schema cannot express, run on the typed objects of the entries the schema passed.

After the schema pass and the default fill (:func:`.validate.validate`), :func:`check` builds every
entry whose key path has no schema error as its declared class (:func:`cradle.specs.declare.build`; a
scene resolved against ``defaults:``, a homoclinic entry with its alpha filled from there) and runs its
``check(where, context, out)`` (:mod:`cradle.scenes.spec`), in the order of the file: map,
homoclinic and scene entries, the sections of ``beyond:`` (one per analysis), figures; then every scene an
analysis reads, in each of its forms, must be a ``scenes:`` entry (what planning the analysis's jobs would
otherwise refuse). An entry with a schema error is skipped: its errors are said, and its check could not
trust its types. A scene is checked only when ``defaults:`` passed too (it is resolved against them).
"""
from __future__ import annotations

import pickle

from cradle.scenes.spec import ENTRY_SECTIONS, Checked, Context, HomoclinicEntry, MapEntry, Where, resolved
from cradle.specs.declare import build
from cradle.specs.values import ConfigError, Errors, did_you_mean

from .beyond import SPECS
from .sections import SECTIONS, Figure

#: typed objects built from the entries of recent configs, by (what is built, the pickle of what it is built
#: from): a config validated again with one entry changed (the Snakefile's --config overrides, the config fuzz)
#: builds that entry only. The objects are frozen; their cached properties (a scene's stored times) come along
_BUILT: dict[tuple, object] = {}


def _memo(what, make, *values):
    """``make(*values)``, remembered by ``what`` and the values' pickle (equal only for values of the same types,
    keys and order, from which building gives the same object)."""
    try:
        key = (what, pickle.dumps(values, protocol=pickle.HIGHEST_PROTOCOL))
    except Exception:  # noqa: BLE001 -- a value pickle refuses is built every time
        return make(*values)
    made = _BUILT.get(key)
    if made is None:
        made = make(*values)
        if len(_BUILT) >= 4096:
            _BUILT.pop(next(iter(_BUILT)))
        _BUILT[key] = made
    return made


def _built(cls, value):
    """``build(cls, value)``, remembered (:func:`_memo`)."""
    return _memo(cls, build, cls, value)


def _passed(cfg: dict, section: str, out: Errors) -> dict[str, dict]:
    """The entries of a name-keyed section without schema errors (none if the section itself is wrong)."""
    entries = cfg.get(section)
    if not isinstance(entries, dict) or out.has([section]):
        return {}
    return {name: entry for name, entry in entries.items() if not out.within([section, name])}


def _unique(given: dict[str, tuple[str, ...]], out: Errors) -> None:
    """A name is one entry across map, homoclinic and scenes (a figure's `scenes:` list reads all three)."""
    names: dict[str, str] = {}
    for section in ENTRY_SECTIONS:
        for name in given[section]:
            if name in names:
                out.add([section, name], f"name {name!r} is also used by {names[name]}.{name} (map, homoclinic "
                                         f"and scenes names must be unique)")
            else:
                names[name] = section


def check(cfg: dict, out: Errors) -> None:
    """The checks of every entry the schema passed, on its typed object (``cfg``: schema-filled; ``out``:
    holds the schema's problems, which tell the entries to skip, and gets these)."""
    # built first, while ``out`` holds the schema's problems only
    defaults = None if out.within(["defaults"]) else cfg["defaults"]
    homoclinic = {name: _built(HomoclinicEntry, entry if defaults is None else
                               {**entry, "alpha": float(entry.get("alpha", defaults["alpha"]))})
                  for name, entry in _passed(cfg, "homoclinic", out).items()}
    scenes = {} if defaults is None else {name: _memo(resolved, resolved, entry, defaults)
                                          for name, entry in _passed(cfg, "scenes", out).items()}
    entries: list[tuple[Where, Checked]] = [(["map", name], _built(MapEntry, entry))
                                            for name, entry in _passed(cfg, "map", out).items()]
    entries += [(["homoclinic", name], h) for name, h in homoclinic.items()]
    entries += [(["scenes", name], s) for name, s in scenes.items()]
    beyond = cfg.get("beyond")
    if isinstance(beyond, dict) and not out.has(["beyond"]):
        entries += [(["beyond", key], _built(cls, beyond[key])) for key, cls in SPECS.items()
                    if hasattr(cls, "check") and not out.within(["beyond", key])]
    entries += [(["figures", label], _built(Figure, fig)) for label, fig in _passed(cfg, "figures", out).items()]

    given = {section: tuple(cfg[section]) if isinstance(cfg.get(section), dict) else () for section in ENTRY_SECTIONS}
    context = Context(given=given, scenes=scenes, homoclinic=homoclinic)
    _unique(given, out)
    for where, entry in entries:
        entry.check(where, context, out)
    if isinstance(beyond, dict) and not out.has(["beyond"]):
        _reads(cfg, context, out)


def _found(node, name: str) -> list | None:
    """The key path, inside an analysis's section, of the first place ``name`` is given (a list item or a
    mapping's key), or None."""
    if isinstance(node, dict) and name in node:
        return [name]
    if isinstance(node, dict):
        items: list = list(node.items())
    elif isinstance(node, list):
        items = list(enumerate(node))
    else:
        return None
    for key, value in items:
        if value == name:
            return [key]
        below = _found(value, name)
        if below is not None:
            return [key, *below]
    return None


def _scenes_read(name: str, section: dict) -> tuple[str, ...]:
    """The scenes analysis ``name`` reads in each of its forms, in order, from its section (schema-valid, a key
    given as "all" expanded); a form that needs what only its target gives (a scene to measure) is said when
    it is planned, not here."""
    from cradle.analyses.protocol import form_spec
    from cradle.analyses.registry import ANALYSES

    a = ANALYSES[name]
    spec = build(a.spec, section)
    names = []
    for form in a.forms:
        try:
            reads = a.reads_of(form_spec(spec, form))
        except ConfigError:
            continue
        names += [scene for read in reads.values() if (scene := dict(read.names).get("scene")) is not None]
    return tuple(names)


def _reads(cfg: dict, context: Context, out: Errors) -> None:
    """Every scene an analysis reads, in each of its forms, is a ``scenes:`` entry: said here, at the key that
    names it, rather than as a failure when its jobs are planned (sections with errors are skipped)."""
    from cradle.analyses.registry import ANALYSES

    scenes = context.given["scenes"]
    for a in ANALYSES.values():
        where = ["beyond", a.name]
        if out.within(where):
            continue
        # as cradle.pipeline.config.analysis_spec: a section key given as "all" is every entry of that section
        section = {key: (list(context.given[key]) if key in SECTIONS and value == "all" else value)
                   for key, value in cfg["beyond"][a.name].items()}
        for name in _memo(_scenes_read, _scenes_read, a.name, section):
            if name not in scenes:
                at = _found(cfg["beyond"][a.name], name)
                out.add(where + (at or []), f"unknown scene: no `scenes:` entry of that name"
                                            f"{did_you_mean(name, scenes)}", name)
