"""Declarations of the typed config, :func:`declared` classes of :func:`param` fields, and their plain form
(docs/developing.md "Specs")."""
from __future__ import annotations

import dataclasses
import json
import types
import typing
from collections.abc import Callable
from typing import Any, TypeVar

from .parse import BAD, BUILDING, Field, _deref, fields_of, given_fields, parse, reduced_defaults
from .shared import SHARED
from .values import NAME_PATTERN, ConfigError, Errors, canonical_angle

__all__ = ["NAME_PATTERN", "NULL", "REQUIRED", "SHARED", "declared", "from_plain", "param", "plain",
           "reduced_defaults", "schema_doc"]

T = TypeVar("T")

ANGLE = _deref({"$ref": "#/$defs/angle"})

REQUIRED = dataclasses.MISSING  # a key without default: the config must give it
_ATOM_TYPES = frozenset({float, int, str})

#: the default of a key whose default is null (filled in as None), unlike an optional key
NULL: Any = type("Null", (), {"__repr__": lambda self: "NULL"})()


def param(default: Any = REQUIRED, doc: str = "", *, ref: str | None = None, fill: dict | None = None,
          key: str | None = None, reduced: Any = REQUIRED, **keywords: Any) -> Any:
    """A config key: ``default`` (REQUIRED, None: optional, NULL: null, or a value), description ``doc``, shared
    type ``ref``, JSON-Schema ``keywords``; ``fill``: the descriptions of a partial class's keys in this place;
    ``key``: the config key when not a Python name; ``reduced``: its value in an analysis's reduced form."""
    meta = {"key": key, "doc": doc, "ref": ref, "keywords": keywords, "fill": fill, "required": default is REQUIRED,
            "null_default": default is NULL}
    if reduced is not REQUIRED:
        meta["reduced"] = json.dumps(reduced) if isinstance(reduced, (list, dict)) else reduced
    if default is NULL:
        default = None
    if isinstance(default, (list, dict)):
        frozen = json.dumps(default)
        return dataclasses.field(default_factory=lambda: json.loads(frozen), metadata=meta)
    return dataclasses.field(default=default, metadata=meta)


# `param` is no field specifier: it takes its default by position, which a type checker reads as none
@typing.dataclass_transform(kw_only_default=True, frozen_default=True)
def declared(name: str | None = None, *, doc: str, partial: bool = False, any_of: list | None = None,
             extra: dict | None = None) -> Callable[[T], T]:
    """Class decorator: a frozen dataclass declaring one object of the config, ``$defs`` key ``name`` (None:
    inline); ``partial``: an override of inherited settings; ``any_of``: alternatives of required keys."""
    def wrap(cls: Any) -> Any:
        documented = cls.__dict__.get("__doc__") is not None
        if any(isinstance(f, dataclasses.Field) and "reduced" in f.metadata for f in vars(cls).values()):
            # the overrides of the reduced form, each key checked as its field (cradle.specs.parse)
            cls.__annotations__["reduced"] = "dict"   # None in a form (cradle.analyses.protocol.form_spec)
            cls.reduced = param({}, REDUCED_DOC)
        # keyword-only: fields are declared in the order of the config's keys, required or not
        cls = dataclasses.dataclass(frozen=True, kw_only=True)(cls)
        if not documented:  # help() shows the description, not the signature dataclass puts there
            cls.__doc__ = doc
        cls.__schema_name__ = name
        cls.__schema_doc__ = doc
        cls.__schema_partial__ = partial
        cls.__schema_any_of__ = any_of
        cls.__schema_extra__ = extra or {}
        return cls
    return wrap


REDUCED_DOC = ("The reduced form `snakemake all` builds (results/<name>/<name>.nc, results/figures/<name>.*): "
               "these keys replace those of the full form, `snakemake <name>_full` (results/<name>/full/); a key "
               "left out takes its declared reduced value, else the full form's.")


def schema_doc(cls: Any) -> str:
    """The description :func:`declared` gave the class ``cls``."""
    return cls.__schema_doc__


def plain(value: Any, canonical: bool = True) -> Any:
    """A spec (or any value holding specs) as plain JSON values, canonical by value with sorted keys (what
    ``params:`` carry and a file stores); ``canonical=False``: as given, in the order declared."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        # an optional key left out (None, where null is not a value of its own) stays out
        items = [(f.key, _by_value(f, plain(getattr(value, f.name), canonical)) if canonical
                  else plain(getattr(value, f.name), canonical)) for f in fields_of(type(value))
                 if getattr(value, f.name) is not None or f.nullable]
        return dict(sorted(items) if canonical else items)
    if isinstance(value, (list, tuple)):
        if _ATOM_TYPES.issuperset(map(type, value)):   # one pass in C
            return list(value)   # a per-bead list of numbers: nothing below to make plain
        return [plain(v, canonical) for v in value]
    if isinstance(value, dict):
        items = [(str(k), plain(v, canonical)) for k, v in value.items()]
        return dict(sorted(items) if canonical else items)
    return value


def _by_value(f: Field, value: Any) -> Any:
    """A field's plain value in its one form: angles canonical, numbers typed as declared."""
    if f.ref in ("angle", "angleString"):
        return canonical_angle(value)
    if f.node.get("items") == ANGLE and isinstance(value, list):
        return [canonical_angle(v) for v in value]
    return _typed(f.tp, value)


def _typed(tp: Any, value: Any) -> Any:
    """``value`` with every number of the annotation ``tp`` as its declared type."""
    origin, args = typing.get_origin(tp), typing.get_args(tp)
    if origin in (typing.Union, types.UnionType):
        numbers = [a for a in args if a in (float, int)]
        return _typed(numbers[0], value) if len(numbers) == 1 and isinstance(value, (int, float)) else value
    if origin in (list, tuple) and isinstance(value, list):
        inner = args[0] if args and (origin is list or (len(args) == 2 and args[1] is Ellipsis)) else None
        return [_typed(inner, v) for v in value] if inner is not None else value
    if isinstance(value, bool):
        return value
    if tp is float and isinstance(value, int):
        return float(value)
    if tp is int and isinstance(value, float) and value.is_integer():
        return int(value)
    return value




def check_fields(obj: Any, where: str, skip: tuple[str, ...] = ()) -> None:
    """What a public declared class's ``__post_init__`` calls: an instance built directly refused in one line
    per bad field, a value stored as the pass reads it; ``skip``: keys the caller checks itself."""
    cls: Any = type(obj)
    if BUILDING.get() is cls:   # made by the validation pass of values it has just read
        return
    found = Errors()
    values = {f.key: plain(getattr(obj, f.name), canonical=False) for f in fields_of(cls)
              if getattr(obj, f.name) is not None or f.nullable}
    got = given_fields(cls, values, (where,), found)
    kept = [p for p in found.held if not (len(p[1]) > 1 and p[1][1] in skip)]
    found.held = kept
    if len(found) or got is BAD:
        raise ConfigError(found.said().lines)
    for name, value in got.items():
        if name not in skip:
            object.__setattr__(obj, name, value)


def from_plain(cls: type[T], mapping: Any, where: str | None = None) -> T:
    """A validated instance of ``cls`` from plain values; a ConfigError line per problem names ``where``."""
    found = Errors()
    made = parse(cls, mapping, (where or cls.__name__,), found)
    if found or made is BAD:
        raise ConfigError(found.said().lines)
    return made
