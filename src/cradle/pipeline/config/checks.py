"""The checks no key expresses alone (each class's ``check``), run on the typed entries that passed."""
from __future__ import annotations

import dataclasses
from typing import Any

from cradle.analyses.protocol import FULL, REDUCED, form_spec, own_keys
from cradle.scenes.spec import ENTRY_SECTIONS, Context, Where
from cradle.specs.parse import BAD
from cradle.specs.values import ConfigError, Errors, did_you_mean

from .sections import SECTIONS


def with_all(spec: Any, names: dict) -> Any:
    """``spec`` with each key named after a section of entries given as ``all`` its entries' ``names``."""
    every = {f.name: list(names.get(f.name, ())) for f in dataclasses.fields(spec)
             if f.name in SECTIONS and getattr(spec, f.name) == "all"}
    return dataclasses.replace(spec, **every) if every else spec


def check_forms(spec: Any, where: Where, context: Context, out: Errors) -> None:
    """The check of an analysis's spec in each form, the reduced one reporting only the keys it gives."""
    if not isinstance(getattr(spec, "reduced", None), dict):   # one form
        spec.check(where, context, out)
        return
    form_spec(spec, FULL).check(where, context, out)
    keys = own_keys(spec)
    if keys:
        at = where + ["reduced"]
        form_spec(spec, REDUCED).check(at, context, out.only(at, keys))


def check(parts: dict, config: dict, out: Errors) -> None:
    """The checks of every entry that passed (``parts``: :func:`.validate.read`'s), in the order of the file;
    then every scene an analysis reads is a ``scenes:`` entry. A scene is checked once ``defaults:`` passed."""
    from cradle.analyses.registry import ANALYSES

    given = {section: tuple(config[section]) if isinstance(config.get(section), dict) else ()
             for section in ENTRY_SECTIONS}
    scenes = {} if parts["defaults"] is BAD else parts["scenes"]
    context = Context(given=given, scenes=scenes, homoclinic=parts["homoclinic"])
    folded: dict[str, str] = {}   # a name's results folder is one on a case-insensitive file system
    for section in ENTRY_SECTIONS:   # a name is one entry across the three: a figure reads them all
        for name in given[section]:
            first = folded.setdefault(str(name).casefold(), name)
            if context.names[name] != section:
                out.add([section, name], f"name {name!r} is also used by {context.names[name]}.{name} (map, "
                                         f"homoclinic and scenes names must be unique)")
            elif first != name:
                out.add([section, name], f"name {name!r} differs from {context.names[first]}.{first} only in case "
                                         f"(their files would be one on a case-insensitive file system: macOS, "
                                         f"Windows)")
    for section in ENTRY_SECTIONS:
        for name, entry in (scenes if section == "scenes" else parts[section]).items():
            entry.check([section, name], context, out)
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
    """The key path inside an analysis's section of the first place ``name`` is given, or None."""
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
    """Every scene analysis ``name`` reads in each form is a ``scenes:`` entry, said at the key naming it."""
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
