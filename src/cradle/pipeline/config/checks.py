"""The checks no key expresses alone, run on the typed entries that passed :func:`.validate.read`.

Each declared class with such checks has a method ``check(where, context, out)`` (:mod:`cradle.scenes.spec`);
:func:`check` runs them in the order of the file: map, homoclinic and scene entries, the sections of
``beyond:`` (an analysis with a reduced form checked in each form: :func:`check_forms`), figures; then every
scene an analysis reads, in each of its forms, must be a ``scenes:`` entry. An entry with a problem of its own
keys is not checked further: its problems are said, and its check could not trust its types. A scene is
checked only when ``defaults:`` passed too (it is resolved against them).
"""
from __future__ import annotations

import dataclasses
from typing import Any

from cradle.analyses.protocol import FULL, REDUCED, form_spec, own_keys
from cradle.scenes.spec import ENTRY_SECTIONS, Checked, Context, Where
from cradle.specs.parse import BAD
from cradle.specs.values import ConfigError, Errors, did_you_mean

from .sections import SECTIONS


def with_all(spec: Any, names: dict) -> Any:
    """``spec`` with each of its keys named after a section of entries (scenes, homoclinic, map) given as
    ``all`` replaced by the names of that section's entries (``names``: section -> names)."""
    every = {f.name: list(names.get(f.name, ())) for f in dataclasses.fields(spec)
             if f.name in SECTIONS and getattr(spec, f.name) == "all"}
    return dataclasses.replace(spec, **every) if every else spec


def check_forms(spec: Any, where: Where, context: Context, out: Errors) -> None:
    """The check of an analysis's spec in each of its forms: the full one at ``where``, the reduced one (if the
    spec has one) at ``where + ["reduced"]``, reporting only the keys the reduced form gives (:func:`own_keys`)."""
    if not isinstance(getattr(spec, "reduced", None), dict):   # one form
        spec.check(where, context, out)
        return
    form_spec(spec, FULL).check(where, context, out)
    keys = own_keys(spec)
    if keys:
        at = where + ["reduced"]
        form_spec(spec, REDUCED).check(at, context, out.only(at, keys))


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


def check(parts: dict, config: dict, out: Errors) -> None:
    """The checks of every entry that passed (``parts``: :func:`.validate.read`'s; ``config``: the mapping
    read, for the names it gives)."""
    from cradle.analyses.registry import ANALYSES

    given = {section: tuple(config[section]) if isinstance(config.get(section), dict) else ()
             for section in ENTRY_SECTIONS}
    scenes = {} if parts["defaults"] is BAD else parts["scenes"]
    context = Context(given=given, scenes=scenes, homoclinic=parts["homoclinic"])
    entries: list[tuple[Where, Checked]] = [(["map", name], m) for name, m in parts["map"].items()]
    entries += [(["homoclinic", name], h) for name, h in parts["homoclinic"].items()]
    entries += [(["scenes", name], s) for name, s in scenes.items()]
    _unique(given, out)
    for where, entry in entries:
        entry.check(where, context, out)
    specs = {a.name: parts["beyond"][a.module] for a in ANALYSES.values() if a.module in parts["beyond"]}
    for name, spec in specs.items():
        if hasattr(spec, "check"):
            check_forms(spec, ["beyond", name], context, out)
    for label, figure in parts["figures"].items():
        figure.check(["figures", label], context, out)
    for name, spec in specs.items():
        if not out.within(["beyond", name]):
            _reads(name, with_all(spec, given), context, out)


def _found(node: Any, name: str) -> list | None:
    """The key path, inside an analysis's section, of the first place ``name`` is given (a list item or a
    mapping's key), or None."""
    if isinstance(node, dict) and name in node:
        return [name]
    items = list(node.items()) if isinstance(node, dict) else list(enumerate(node)) if isinstance(node, list) \
        else []
    for key, value in items:
        below = [key] if value == name else _found(value, name)
        if below is not None:
            return below if value == name else [key, *below]
    return None


def _reads(name: str, spec: Any, context: Context, out: Errors) -> None:
    """Every scene analysis ``name`` reads, in each of its forms, is a ``scenes:`` entry: said here, at the key
    that names it, rather than as a failure when its jobs are planned; a form that needs what only its target
    gives (a scene to measure) is said when it is planned."""
    from cradle.analyses.registry import ANALYSES
    from cradle.specs.declare import plain

    a, scenes = ANALYSES[name], context.given["scenes"]
    for form in a.forms:
        try:
            reads = a.reads_of(form_spec(spec, form))
        except ConfigError:
            continue
        for read in reads.values():
            scene = dict(read.names).get("scene")
            if scene is not None and scene not in scenes:
                at = _found(plain(spec, canonical=False), scene)
                out.add(["beyond", name, *(at or [])], f"unknown scene: no `scenes:` entry of that name"
                                                        f"{did_you_mean(scene, scenes)}", scene)
