"""The one validation pass: plain values in, the typed objects of their declarations out, each problem one
line (docs/developing.md "Specs")."""
from __future__ import annotations

import contextvars
import dataclasses
import functools
import json
import math
import re
import types
import typing
from collections.abc import Callable
from typing import Any, NamedTuple

from .shared import SHARED
from .values import (
    ANGLE_HINT,
    ANGLE_PATTERN,
    DEFAULT_MAX_ITEMS,
    DEFAULT_MAX_LENGTH,
    NAME_MAX_LENGTH,
    T_END_WHY,
    TYPE_WORDS,
    Errors,
    bound_text,
    did_you_mean,
    number,
)

#: what :func:`parse` returns for a value it refused
BAD: Any = type("Bad", (), {"__repr__": lambda self: "BAD"})()

#: words a message adds to a bound, by (last key of the path, keyword)
HINTS = {("alpha", "exclusiveMinimum"): " (Hertz exponent of (vhertz))",
         ("omega_tw", "exclusiveMinimum"): " (a is derived from (freq), omega_tw = 1 + (2/tau0) a^(alpha-1) "
                                           "|sin(q/2)|^(alpha+1))",
         ("omega_sw", "exclusiveMinimum"): " (mu = (omega_sw - 1) 2^alpha tau0 must be > 0)",
         **{(key, "minimum"): " (a floor the integrator can honour, about 1e2 machine epsilons or more: below, a "
                              "step's error estimate is rounding noise and the steps shrink until they underflow)"
            for key in ("rtol", "dps_rtol", "check_rtol")},
         ("atol", "minimum"): " (the error norm squares state / atol, which overflows float64 below it)",
         ("max_energy_drift", "minimum"): " (H is computed in double precision: a relative drift below about 1e2 "
                                          "machine epsilons is its rounding alone, so a smaller bound fails every "
                                          "run)",
         ("dt_factor", "minimum"): " (the step dt_factor 2 pi / omega_max is then about 1e2 spacings of doubles at "
                                   "the longest t_end or more: below, t + dt is rounding noise)",
         ("t_end", "maximum"): f" ({T_END_WHY})"}
_BOUNDS = {"minimum": (">=", lambda x, b: x >= b), "exclusiveMinimum": (">", lambda x, b: x > b),
           "maximum": ("<=", lambda x, b: x <= b), "exclusiveMaximum": ("<", lambda x, b: x < b)}
_JSON_TYPES = {"integer": lambda v: number(v) and float(v).is_integer() if isinstance(v, float) else number(v),
               "number": number, "string": lambda v: isinstance(v, str), "boolean": lambda v: isinstance(v, bool),
               "null": lambda v: v is None, "array": lambda v: isinstance(v, (list, tuple)),
               "object": lambda v: isinstance(v, dict)}
_PLAIN_NUMBER = frozenset({"type", "description", *_BOUNDS})
#: the class :func:`build_object` is making of values just read: its own ``check_fields`` skips them
BUILDING: contextvars.ContextVar[type | None] = contextvars.ContextVar("building", default=None)
_NUMBER_TYPES = frozenset({int, float})
#: an integer of more bits is beyond the largest double (about 1.8e308): no config value
_DOUBLE_BITS = 1024
#: the problems of a list's items said before the rest is left unread
MAX_ITEM_PROBLEMS = 10
_INT_RE = re.compile(r"^[-+]?\d+$")
_FLOAT_RE = re.compile(r"^[-+]?(\d+(\.\d*)?|\.\d+)([eE][-+]?\d+)?$|^[-+]?(inf|nan)$", re.IGNORECASE)


def _from_string(text: str, kinds: list[str]) -> Any:
    """``text`` read as a value of one of the JSON ``kinds``, or the text itself."""
    s = text.strip()
    if "null" in kinds and s in ("null", "Null", "NULL", "~", ""):
        return None
    if "boolean" in kinds and s in ("true", "True", "TRUE", "false", "False", "FALSE"):
        return s.lower() == "true"
    if ("integer" in kinds or "number" in kinds) and _INT_RE.match(s):
        return int(s) if len(s) <= 400 else float(s)   # past 308 digits no double: inf, said as not finite
    if "number" in kinds and _FLOAT_RE.match(s):
        return float(s)
    if "integer" in kinds and _FLOAT_RE.match(s) and float(s).is_integer():
        return int(float(s))
    return text


def _finite(value: Any, path: tuple, found: Errors) -> bool:
    """Whether every float in ``value`` is finite (each other one held at its key)."""
    if isinstance(value, float) and not math.isfinite(value):
        found.finite.append((path, path, "must be a finite number", value, False))
        return False
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > _DOUBLE_BITS:
        found.finite.append((path, path, "must be a number a double holds (|x| < 1.8e308)", value, False))
        return False
    if isinstance(value, list) and _all_numbers(value) and _all_finite(value):
        return True   # a long list of numbers in one pass, not a call per item
    items = value.items() if isinstance(value, dict) else enumerate(value) if isinstance(value, list) else ()
    return all([_finite(v, (*path, k), found) for k, v in items])


def _all_finite(value: list) -> bool:
    try:
        return all(map(math.isfinite, value))
    except OverflowError:   # an integer beyond every double: said item by item
        return False


def _all_numbers(value: list | tuple) -> bool:
    return _NUMBER_TYPES.issuperset(map(type, value))   # in C; a bool's type is not int


def leaf(node: dict, value: Any, path: tuple, found: Errors, coerce: bool = True) -> Any:
    """``value`` checked against the JSON-Schema keywords of ``node``, or :data:`BAD`; ``coerce``: a string where
    none is expected read as the number, boolean or null it spells (``--config`` values)."""
    kinds = node.get("type")
    kinds = [kinds] if isinstance(kinds, str) else kinds or []
    if coerce and isinstance(value, str) and kinds and "string" not in kinds:
        value = _from_string(value, kinds)
    if isinstance(value, (list, tuple)) and len(value) > node.get("maxItems", DEFAULT_MAX_ITEMS):
        # said before its items are walked: a list of a million values is refused at once
        n = node.get("maxItems", DEFAULT_MAX_ITEMS)
        found.hold(path, f"must have at most {n} items" if "array" in kinds else
                  f"must be {' or '.join(TYPE_WORDS[k] for k in kinds)}" if kinds else
                  f"must not be a list of {len(value)} items", value)
        return BAD
    if not _finite(value, path, found):
        return BAD
    if "anyOf" in node:
        return _any_of(node, value, path, found)
    if kinds and not any(_JSON_TYPES[k](value) for k in kinds):
        found.hold(path, f"must be {' or '.join(TYPE_WORDS[k] for k in kinds)}", value)
        return BAD
    n, last = len(found), str(path[-1]) if path else ""
    if "enum" in node and not any(value == e and isinstance(value, bool) == isinstance(e, bool) for e in node["enum"]):
        found.hold(path, f"must be one of {', '.join(map(str, node['enum']))}", value)
    if "const" in node and value != node["const"]:
        found.hold(path, f"must be {node['const']!r}", value)
    if number(value):
        for key in [k for k in node if k in _BOUNDS]:   # in the order declared: the first one said
            word, ok = _BOUNDS[key]
            if not ok(value, node[key]):
                found.hold(path, f"must be {word} {bound_text(node[key])}{HINTS.get((last, key), '')}", value)
        step = node.get("multipleOf")
        if step and not float(value / step).is_integer():
            found.hold(path, f"{value!r} is not a multiple of {step!r}", value)
    if isinstance(value, str) and len(value) > node.get("maxLength", DEFAULT_MAX_LENGTH):
        found.hold(path, f"must be at most {node.get('maxLength', DEFAULT_MAX_LENGTH)} characters long", value)
    elif isinstance(value, str) and "pattern" in node and not re.search(node["pattern"], value):
        angle = last == "q" or node["pattern"] == ANGLE_PATTERN
        found.hold(path, f"must be {ANGLE_HINT}" if angle else
                  "must use letters, digits, '-' and '_' and start with a letter or digit", value)
    if isinstance(value, (list, tuple)):
        value = _items(node, list(value), path, found)
    if isinstance(value, dict) and "properties" in node:
        value = _mapping(node, value, path, found)
    if len(found) > n or value is BAD:
        return BAD
    return int(value) if "integer" in kinds and isinstance(value, float) else value   # 50.0 is the integer 50


def _items(node: dict, value: list, path: tuple, found: Errors) -> Any:
    lo, hi = node.get("minItems"), node.get("maxItems", DEFAULT_MAX_ITEMS)
    if lo is not None and lo == hi and len(value) != lo:
        found.hold(path, f"must have exactly {lo} items", value)
    elif lo is not None and len(value) < lo:
        found.hold(path, "must not be empty" if lo == 1 else f"must have at least {lo} items", value)
    if node.get("uniqueItems") and len({_same(v) for v in value}) < len(value):
        found.hold(path, "must not repeat a name", value)
    if isinstance(node.get("items"), dict) and not _at_once(node["items"], value):
        out, before = [], len(found)
        for i, v in enumerate(value):
            out.append(leaf(node["items"], v, (*path, i), found))
            if len(found) - before >= MAX_ITEM_PROBLEMS:   # a long list of wrong items: its first ones said
                return BAD
        return BAD if any(v is BAD for v in out) else out
    return value


def _same(item: Any) -> Any:
    """What tells a repeated item: a number or a string by type and value; anything else only itself."""
    return (type(item), item) if isinstance(item, (str, int, float)) or item is None else id(item)


def _at_once(node: dict, value: list) -> bool:
    """Whether the list ``value`` passes ``node`` (a bounded number, or an enum alone) in one pass (a per-bead
    list); False: read it item by item, which words each problem."""
    if node.get("type") == "string" and set(node) <= {"type", "enum", "description"} and "enum" in node:
        names = frozenset(node["enum"])
        return all(type(v) is str and v in names for v in value)
    if node.get("type") != "number" or not set(node) <= _PLAIN_NUMBER or not value:
        return False
    if not _all_numbers(value):   # finite already: leaf checked it before the items
        return False
    lo, hi = min(value), max(value)
    return all(ok(lo if key.endswith("inimum") else hi, node[key]) for key, (_, ok) in _BOUNDS.items() if key in node)


def _mapping(node: dict, value: dict, path: tuple, found: Errors) -> Any:
    """A mapping checked against ``properties``, ``required`` and ``additionalProperties``."""
    props = node["properties"]
    for key in node.get("required", ()):
        if key not in value:
            found.hold((*path, key), "missing (required key)", at=path)
    out = {}
    for key, v in value.items():
        if key in props:
            out[key] = leaf(props[key], v, (*path, key), found)
        elif node.get("additionalProperties") is False:
            found.hold((*path, key), f"unknown key (allowed: {', '.join(props)}){did_you_mean(key, props)}", v,
                      at=path)
    return BAD if any(v is BAD for v in out.values()) else {**value, **out}


def _any_of(node: dict, value: Any, path: tuple, found: Errors) -> Any:
    """The first branch of ``anyOf`` that takes ``value``; else the problems of the first whose type fits."""
    tried = []
    for sub in node["anyOf"]:
        mine = Errors()
        got = leaf(sub, value, path, mine, coerce=False)
        if not mine:
            return got
        kinds = sub.get("type")
        tried.append(([kinds] if isinstance(kinds, str) else kinds or [], mine))
    for kinds, mine in tried:
        if any(_JSON_TYPES[k](value) for k in kinds):
            found.held += mine.held
            return BAD
    if any(sub.get("pattern") == ANGLE_PATTERN for sub in node["anyOf"]):
        found.hold(path, f"must be {ANGLE_HINT}", value)
    else:
        found.hold(path, f"must be {' or '.join(dict.fromkeys(TYPE_WORDS[k] for kinds, _ in tried for k in kinds))}",
                  value)
    return BAD


class Field(NamedTuple):
    """What the pass reads of one declared field (``node``: its keywords, shared types merged in)."""
    name: str
    key: str
    tp: Any
    node: dict
    required: bool
    make: Any
    reduced: Any
    ref: str | None
    nullable: bool
    nested: bool


def declared_class(tp: Any) -> bool:
    return isinstance(tp, type) and hasattr(tp, "__schema_doc__")


@functools.cache
def fields_of(cls: type) -> tuple[Field, ...]:
    """The :class:`Field` of each field of the declared class ``cls``."""
    hints = typing.get_type_hints(cls)
    out = []
    for f in dataclasses.fields(cls):
        meta, tp = f.metadata, hints[f.name]
        node = _deref({"$ref": f"#/$defs/{meta['ref']}"} if meta["ref"] else _annotation_node(tp))
        node.update(_deref(meta["keywords"]))
        make = f.default_factory if f.default_factory is not dataclasses.MISSING else \
            (lambda d=f.default: None if d is dataclasses.MISSING else d)
        # null is a value of its own where declared as the default, or where the default is not None
        nullable = meta["null_default"] or (type(None) in typing.get_args(tp) and make() is not None)
        nested = declared_class(tp) or typing.get_origin(tp) is dict or any(map(declared_class, typing.get_args(tp)))
        out.append(Field(f.name, meta["key"] or f.name, tp, node, meta["required"], make, meta.get("reduced"),
                         meta["ref"], nullable, nested))
    return tuple(out)


def _deref(node: Any) -> Any:
    """``node`` with every ``$ref`` to a shared type merged in, its own keywords winning."""
    if isinstance(node, list):
        return [_deref(v) for v in node]
    if not isinstance(node, dict):
        return node
    shared = SHARED.get(str(node.get("$ref", "")).rsplit("/", 1)[-1])
    out = {key: _deref(v) for key, v in node.items() if key != "$ref" or shared is None}
    return out if shared is None else {**_deref(shared), **out}


def _annotation_node(tp: Any) -> dict:
    """The JSON type of a scalar or list annotation; {} for the others."""
    origin, args = typing.get_origin(tp), typing.get_args(tp)
    if origin in (typing.Union, types.UnionType):
        inner = [a for a in args if a is not type(None)]
        node = _annotation_node(inner[0]) if len(inner) == 1 else {}
        if "type" in node and len(args) == 2:
            node["type"] = [node["type"], "null"]
        return node
    if origin in (list, tuple):
        return {"type": "array"}
    names = {float: "number", int: "integer", str: "string", bool: "boolean"}
    return {"type": names[tp]} if tp in names else {}


def parse(tp: Any, value: Any, path: tuple, found: Errors, base: Any = None) -> Any:
    """``value`` as the annotation ``tp``, or :data:`BAD`; ``base``: what a declared class's absent keys take
    instead of their defaults (a scene's integrators: those of ``defaults:``)."""
    origin, args = typing.get_origin(tp), typing.get_args(tp)
    if origin in (typing.Union, types.UnionType) and any(declared_class(a) for a in args):
        return _union([a for a in args if declared_class(a)], value, path, found)
    if origin is dict:
        return entries(args[1], value, path, found)
    if declared_class(tp):
        return build_object(tp, value, path, found, base)
    return leaf(_annotation_node(tp), value, path, found)


def _not_mapping(value: Any, path: tuple, found: Errors) -> bool:
    if isinstance(value, dict):
        return False
    long = isinstance(value, (list, tuple)) and len(value) > DEFAULT_MAX_ITEMS   # its items not walked
    if long or _finite(value, path, found):
        found.hold(path, "must be a mapping", value)
    return True


def _union(classes: list, value: Any, path: tuple, found: Errors) -> Any:
    """One of ``classes``, picked by its ``kind`` constant."""
    if _not_mapping(value, path, found):
        return BAD
    kinds = {next(f.node["const"] for f in fields_of(c) if f.name == "kind"): c for c in classes}
    kind = value.get("kind")
    if "kind" not in value or not isinstance(kind, str) or kind not in kinds:
        if "kind" not in value:
            found.hold((*path, "kind"), "missing (required key)", at=path)
        else:
            found.hold((*path, "kind"), f"must be one of {', '.join(kinds)}" if isinstance(kind, str) else
                      "must be a string", kind)
        _finite(value, path, found)
        return BAD
    return build_object(kinds[kind], value, path, found)


def entries(cls: type, value: Any, path: tuple, found: Errors, labels: tuple | None = None,
            base: Any = None, one: Callable[..., Any] | None = None) -> Any:
    """Entry names -> instances of ``cls``, one with problems left out; ``labels``: the names allowed."""
    if _not_mapping(value, path, found):
        return BAD
    out = {}
    for name, entry in value.items():
        if labels is not None and name not in labels:
            found.hold((*path, name), f"unknown figure label {name!r} (known labels: {', '.join(labels)})", at=path)
        elif labels is None and not (isinstance(name, str) and re.search(SHARED["name"]["pattern"], name)):
            found.hold((*path, name), f"bad name {name!r}: names use letters, digits, '-' and '_' and start with a "
                                     f"letter or digit", at=path, force=True)
        elif labels is None and len(name) > NAME_MAX_LENGTH:
            found.hold((*path, name[:20] + "..."), f"bad name of {len(name)} characters: at most {NAME_MAX_LENGTH} "
                                                  f"(names are part of file names)", at=path, force=True)
        made = (one or parse)(cls, entry, (*path, name), found, base)
        if made is not BAD:
            out[name] = made
    return out


def given_fields(cls: Any, value: Any, path: tuple, found: Errors, base: Any = None, full: Any = None) -> Any:
    """field name -> value of ``cls`` from the mapping ``value``, absent keys from ``base`` or their defaults;
    ``full``: ``value`` is a ``reduced:`` section over the full form's values ``full`` (its keys only)."""
    if _not_mapping(value, path, found):
        return BAD
    fields = [f for f in fields_of(cls) if full is None or (f.name, f.tp) != ("reduced", dict)]
    by_key = {f.key: f for f in fields}
    bases = base if full is None else {**full, **reduced_defaults(cls)}
    bases = {} if bases is None else bases if isinstance(bases, dict) else vars(bases)
    out: dict[str, Any] = {}
    for key, v in value.items():
        f = by_key.get(key)
        if f is None:
            allowed = list(by_key)
            found.hold((*path, key), f"unknown key (allowed: {', '.join(allowed)}){did_you_mean(key, allowed)}", v,
                       at=path)
            if full is None:
                _finite(v, (*path, key), found)
        elif (f.name, f.tp) != ("reduced", dict):   # read below, over the full form's values
            inner = bases.get(f.name)
            out[f.name] = _field(f, v, (*path, key), found, inner if inner is not None else f.make())
    if full is not None:
        return BAD if any(v is BAD for v in out.values()) else out
    for f in fields:
        if f.name not in out:
            inner = bases.get(f.name)
            if f.required and inner is None:
                found.hold((*path, f.key), "missing (required key)", at=path)
            out[f.name] = inner if inner is not None else f.make()
    if "reduced" in value and any((f.name, f.tp) == ("reduced", dict) for f in fields):
        out["reduced"] = given_fields(cls, value["reduced"], (*path, "reduced"), found, full=out)
    groups = cls.__schema_any_of__
    if groups and not any(all(k in value for k in g) for g in groups):
        found.hold(path, f"needs at least one of {', '.join(k for g in groups for k in g)}", value)
    return out


def reduced_defaults(cls: type) -> dict[str, Any]:
    """field name -> its declared ``reduced=`` value."""
    out = {}
    for f in fields_of(cls):
        if f.reduced is not None:
            value = json.loads(f.reduced) if isinstance(f.reduced, str) and f.reduced[:1] in "[{" else f.reduced
            out[f.name] = _reduced_objects(cls, f.name) if isinstance(value, dict) else value
    return out


@functools.cache
def _reduced_objects(cls: type, name: str) -> Any:
    """The declared reduced mapping of field ``name`` read as its objects (once)."""
    f = next(f for f in fields_of(cls) if f.name == name)
    return _field(f, json.loads(f.reduced), (cls.__name__, "reduced", f.key), Errors())


def _field(f: Field, value: Any, path: tuple, found: Errors, base: Any = None) -> Any:
    """The value of field ``f``: against its keywords, or as its annotation declares it, or both."""
    if f.nested and "properties" not in f.node:
        return parse(f.tp, value, path, found, base)
    value = leaf(f.node, value, path, found)
    return parse(f.tp, value, path, found, base) if f.nested and value is not BAD else value


def build_object(cls: type, value: Any, path: tuple, found: Errors, base: Any = None) -> Any:
    """An instance of ``cls`` from the mapping ``value``, or :data:`BAD`."""
    n = len(found)
    got = given_fields(cls, value, path, found, base)
    if got is BAD or len(found) > n:
        return BAD
    token = BUILDING.set(cls)
    try:
        return cls(**got)
    finally:
        BUILDING.reset(token)
