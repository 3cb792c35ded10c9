"""The checks the schema cannot express, run on the typed objects of the entries the schema passed.

After the schema pass and the default fill (:func:`.validate.validate`), :func:`check` builds every
entry whose key path has no schema error as its declared class (:func:`cradle.specs.declare.build`; a
scene resolved against ``defaults:``, a homoclinic entry with its alpha filled from there) and runs its
``check(where, context, out)`` (:mod:`cradle.scenes.spec`), in the order of the file: map,
homoclinic and scene entries, the sections of ``beyond:`` (one per analysis), figures. An entry with a
schema error is skipped: its errors are said, and its check could not trust its types. A scene is
checked only when ``defaults:`` passed too (it is resolved against them).
"""
from __future__ import annotations

from cradle.scenes.spec import ENTRY_SECTIONS, Checked, Context, HomoclinicEntry, MapEntry, Where, resolved
from cradle.specs.declare import build
from cradle.specs.values import Errors

from .beyond import SPECS
from .sections import Figure


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
    homoclinic = {name: build(HomoclinicEntry, entry if defaults is None else
                              {**entry, "alpha": float(entry.get("alpha", defaults["alpha"]))})
                  for name, entry in _passed(cfg, "homoclinic", out).items()}
    scenes = {} if defaults is None else {name: resolved(entry, defaults)
                                          for name, entry in _passed(cfg, "scenes", out).items()}
    entries: list[tuple[Where, Checked]] = [(["map", name], build(MapEntry, entry))
                                            for name, entry in _passed(cfg, "map", out).items()]
    entries += [(["homoclinic", name], h) for name, h in homoclinic.items()]
    entries += [(["scenes", name], s) for name, s in scenes.items()]
    beyond = cfg.get("beyond")
    if isinstance(beyond, dict) and not out.has(["beyond"]):
        entries += [(["beyond", key], build(cls, beyond[key])) for key, cls in SPECS.items()
                    if hasattr(cls, "check") and not out.within(["beyond", key])]
    entries += [(["figures", label], build(Figure, fig)) for label, fig in _passed(cfg, "figures", out).items()]

    given = {section: tuple(cfg[section]) if isinstance(cfg.get(section), dict) else () for section in ENTRY_SECTIONS}
    context = Context(given=given, scenes=scenes, homoclinic=homoclinic)
    _unique(given, out)
    for where, entry in entries:
        entry.check(where, context, out)
