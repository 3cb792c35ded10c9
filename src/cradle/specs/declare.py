"""Declaration helpers for the typed config, and the JSON Schema generated from the declarations.

Each config section and each kind of initial condition is a frozen dataclass
(:mod:`.sections`, :mod:`.scenes`, :mod:`.beyond`); each field is declared by
:func:`param` with its description, its JSON-Schema keywords (bounds, enum,
pattern, items) and its default, so that a bound or a default is written once.
:func:`generate` turns the declarations into the JSON Schema (draft 2020-12)
committed as ``src/cradle/pipeline/config.schema.json``; ``python -m
cradle.pipeline.config --write-schema`` rewrites that file.

Field annotations give the JSON type: ``float`` is a number, ``int`` an
integer, ``str`` a string, ``bool`` a boolean, ``X | None`` adds null,
``list[...]`` / ``tuple[...]`` an array, ``dict[str, C]`` a mapping from entry
names to ``C``, and a declared dataclass a nested object (a ``$ref`` when the
class is one of the schema's ``$defs``).
"""
from __future__ import annotations

import dataclasses
import functools
import json
import types
import typing
from collections.abc import Callable
from pathlib import Path
from typing import Any

from .values import ANGLE_PATTERN, NAME_PATTERN, ConfigError, canonical_angle, key_path, show

REQUIRED = dataclasses.MISSING  # a key without default: the config must give it

SCHEMA_DRAFT = "https://json-schema.org/draft/2020-12/schema"


class _Null:
    """The default of a key whose default is null (filled in as None), unlike an optional key."""

    def __repr__(self):
        return "NULL"


NULL = _Null()


def param(default=REQUIRED, doc: str = "", *, ref: str | None = None, fill: dict | None = None, key: str | None = None,
          **keywords):
    """A config key: ``default``, its description ``doc``, ``ref`` (a shared type of :data:`SHARED`,
    e.g. "alpha") and JSON-Schema ``keywords`` (minimum, exclusiveMinimum, maximum, enum, items, ...).

    ``default``: REQUIRED (the config must give the key), None (optional, absent unless given), NULL
    (filled in as null) or a value (filled in). A mutable default (list, dict) is copied into every
    instance. ``fill``: for a nested object whose class is a partial override (an integrator), the
    descriptions of its keys in this place, where they get the defaults of the class. ``key``: the
    config key when it is not a Python name (``from``).
    """
    meta = {"key": key, "doc": doc, "ref": ref, "keywords": keywords, "fill": fill, "required": default is REQUIRED,
            "null_default": default is NULL}
    if default is NULL:
        default = None
    if isinstance(default, (list, dict)):
        frozen = json.dumps(default)
        return dataclasses.field(default_factory=lambda: json.loads(frozen), metadata=meta)
    return dataclasses.field(default=default, metadata=meta)


# for a type checker, a declared class is a frozen keyword-only dataclass. `param` is not named a field
# specifier: it takes its default by position, which the checker would read as no default
@typing.dataclass_transform(kw_only_default=True, frozen_default=True)
def declared(name: str | None = None, *, doc: str, partial: bool = False, any_of=None, extra=None):
    """Class decorator: a frozen dataclass declaring one object of the config.

    ``name``: its key under ``$defs`` (None: written inline where it is used); ``doc``: its
    description; ``partial``: an override of settings inherited from elsewhere (its keys get no
    defaults in ``$defs``); ``any_of``: alternatives of required keys (e.g. snapshots or every);
    ``extra``: further schema keywords.
    """
    def wrap(cls):
        documented = cls.__dict__.get("__doc__") is not None
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


def schema_doc(cls: Any) -> str:
    """The description :func:`declared` gave the class ``cls`` (the type checker does not see the attribute
    the decorator sets)."""
    return cls.__schema_doc__


# Shared scalar types ($defs), each bound written here only.

SHARED: dict[str, dict[str, Any]] = {
    "name": {"description": "An entry name: letters, digits, '-' and '_' (it becomes part of file names).",
             "type": "string", "pattern": NAME_PATTERN},
    # at most 10: the paper's exponents are 3/2 (Hertz) to 3; beyond, a^(alpha-1) of (freq) underflows to 0 or
    # overflows for the amplitudes of the experiments, and a huge alpha makes every power overflow
    "alpha": {"description": "Hertz exponent alpha of (vhertz); in (1, 10].", "type": "number", "exclusiveMinimum": 1,
              "maximum": 10},
    # at most 1e7: the 32 state arrays of a run (cradle.pipeline.budget) alone then take 2.6 GB
    "N": {"description": "Number of sites (beads) n = 0..N-1; in [2, 1e7].", "type": "integer", "minimum": 2,
          "maximum": 10_000_000},
    "bc": {"description": "Boundary conditions: periodic (x_N = x_0, a ring) or free (the end beads have one "
                          "neighbour).", "type": "string", "enum": ["periodic", "free"]},
    "rtol": {"description": "Relative tolerance of an adaptive integrator, in (0, 1e-2].", "type": "number",
             "exclusiveMinimum": 0, "maximum": 0.01},
    # at most 1e-2: a run whose energy moved by more than 1 % of H(0) is no solution of (nc), and a larger bound
    # would silently turn the check off
    "maxEnergyDrift": {"description": "Largest accepted relative energy drift max_t |H(t)-H(0)|/H(0) of an exact "
                                      "run; in (0, 1e-2] (a larger bound would turn the check off).",
                       "type": "number", "exclusiveMinimum": 0, "maximum": 0.01},
    "angleString": {"description": "A multiple of pi such as 'pi', 'pi/5', '4pi/5', '-52pi/100', '4*pi/5', or a "
                                   "number written as a string.", "type": "string", "pattern": ANGLE_PATTERN},
    "angle": {"description": "An angle: a number (radians) or a multiple of pi as a string ('pi/5', '4pi/5', "
                             "'-52pi/100', '4*pi/5').", "anyOf": [{"type": "number"}, {"$ref": "#/$defs/angleString"}]},
    # arguments of public functions (cradle.specs.checked) that no config key refers to yet: a schema
    # lists only the shared types its keys use, so these are not in config.schema.json
    "atol": {"description": "Absolute tolerance of an adaptive integrator; > 0.", "type": "number",
             "exclusiveMinimum": 0},
    "dt": {"description": "Time step of a fixed-step splitting; > 0.", "type": "number", "exclusiveMinimum": 0},
    "dt_factor": {"description": "Splitting step as a fraction of the shortest linearised period 2 pi / omega_max; "
                                 "> 0.", "type": "number", "exclusiveMinimum": 0},
    "latticeMethod": {"description": "Integrator of the lattice (nc): a splitting (srkn6c, srkn4c with the "
                                     "contact-onset correction; srkn6, srkn4, strang) or an adaptive method "
                                     "(dop853_numba; scipy's dop853, rk45, lsoda, radau).", "type": "string",
                      "enum": ["srkn6c", "srkn4c", "srkn6", "srkn4", "strang", "dop853_numba", "dop853", "rk45",
                               "lsoda", "radau"]},
    "dpsMethod": {"description": "Integrator of the DpS equation (dfnls): dop853_numba, or scipy's dop853, rk45.",
                  "type": "string", "enum": ["dop853_numba", "dop853", "rk45"]},
    "potential": {"description": "Interaction potential: hertz, V0 of (vhertz), or smooth, |d|^(alpha+1)/(alpha+1) "
                                 "of (meca) with kappa = 1.", "type": "string", "enum": ["hertz", "smooth"]},
}

#: words a message adds to a bound of a shared type, by (type, keyword): what the bound is
BOUND_HINTS = {("alpha", "exclusiveMinimum"): " (Hertz exponent of (vhertz))"}


def _ref(name: str) -> dict:
    return {"$ref": f"#/$defs/{name}"}


@functools.cache
def _hints(cls) -> dict[str, Any]:
    """The resolved annotations of a declared class (resolving them is most of the cost of :func:`build`)."""
    return typing.get_type_hints(cls)


def _is_declared(tp) -> bool:
    return isinstance(tp, type) and hasattr(tp, "__schema_doc__")


def _key(f: dataclasses.Field) -> str:
    """The config key of a field (its name unless declared with ``key=``)."""
    return f.metadata.get("key") or f.name


def _json_default(value):
    """A declared default as JSON (tuples as lists, declared instances as mappings)."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {_key(f): _json_default(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if isinstance(value, (list, tuple)):
        return [_json_default(v) for v in value]
    if isinstance(value, dict):
        return {k: _json_default(v) for k, v in value.items()}
    return value


def _default_of(f: dataclasses.Field):
    if f.default is not dataclasses.MISSING:
        return f.default
    if f.default_factory is not dataclasses.MISSING:
        return f.default_factory()
    return REQUIRED


def _type_of(tp, defs: dict) -> dict:
    """The schema of an annotation (without description)."""
    origin, args = typing.get_origin(tp), typing.get_args(tp)
    if origin in (typing.Union, types.UnionType):
        inner = [a for a in args if a is not type(None)]
        node = _type_of(inner[0], defs) if len(inner) == 1 else {}
        if "type" in node and isinstance(node["type"], str) and len(args) == 2:
            node["type"] = [node["type"], "null"]
        return node
    if origin in (list, tuple):
        return {"type": "array"}
    if origin is dict:
        return {"type": "object", "propertyNames": _ref("name"), "additionalProperties": _type_of(args[1], defs)}
    if _is_declared(tp):
        return object_schema(tp, defs)
    names = {float: "number", int: "integer", str: "string", bool: "boolean"}
    return {"type": names[tp]} if tp in names else {}


def _field_schema(f: dataclasses.Field, tp, defs: dict, with_defaults: bool, default) -> dict:
    meta = f.metadata
    node = {"description": meta["doc"]} if meta["doc"] else {}
    if meta["ref"]:
        node.update(_ref(meta["ref"]))
    elif _is_declared(tp) and not tp.__schema_name__ and default is not None and default is not REQUIRED:
        # an inline nested object: its keys get the defaults of this field's default instance
        node.update(object_schema(tp, defs, defaults=_json_default(default)))
        if meta["doc"]:
            node["description"] = meta["doc"]
        default = {}
    else:
        node.update(_type_of(tp, defs))
    if meta["fill"] is not None:
        # a partial override declared once (an integrator): here its keys get the class defaults
        values = _json_default(default if default is not None else tp())
        node["properties"] = {k: {"description": d, "default": values[k]} for k, d in meta["fill"].items()}
        default = {}
    node.update(meta["keywords"])
    if with_defaults and not meta["required"] and (default is not None or meta["null_default"]):
        node["default"] = _json_default(default)
    return node


def object_schema(cls, defs: dict, *, defaults: dict | None = None) -> dict:
    """The schema of a declared class: a ``$ref`` for a named class (added to ``defs``), else inline.

    ``defaults``: the defaults of the keys of an inline class, when they are not the class's own.
    """
    name = cls.__schema_name__
    if name and name in defs:
        return _ref(name)
    if name:
        defs[name] = {}   # reserved (a class may refer to itself through its fields)
    hints = _hints(cls)
    props, required = {}, []
    for f in dataclasses.fields(cls):
        default = _default_of(f) if defaults is None else defaults.get(_key(f))
        props[_key(f)] = _field_schema(f, hints[f.name], defs, not cls.__schema_partial__, default)
        if f.metadata["required"]:
            required.append(_key(f))
    out = {"description": cls.__schema_doc__, "type": "object", "additionalProperties": False}
    if required:
        out["required"] = required
    if cls.__schema_any_of__:
        out["anyOf"] = [{"required": list(r)} for r in cls.__schema_any_of__]
    out.update(cls.__schema_extra__)
    out["properties"] = props
    if name:
        defs[name] = out
        return _ref(name)
    return out


def union_schema(doc: str, kind_doc: str, kinds: dict, defs: dict) -> dict:
    """A discriminated union on ``kind``: ``kinds`` maps each kind to its declared class."""
    return {
        "description": doc, "type": "object", "required": ["kind"],
        "properties": {"kind": {"description": kind_doc, "type": "string", "enum": list(kinds)}},
        "allOf": [{"if": {"type": "object", "required": ["kind"], "properties": {"kind": {"const": k}}},
                   "then": object_schema(c, defs)} for k, c in kinds.items()],
    }


def build(tp, value):
    """``value`` (a validated, schema-filled mapping or one of its values) as an instance of the
    annotation ``tp``: declared classes become frozen instances, recursively; a union of declared
    classes (the kinds of initial condition) picks the class whose ``kind`` constant matches."""
    make = _builder(tp)
    return value if make is None or value is None else make(value)


@functools.cache
def _builder(tp) -> Callable[[Any], Any] | None:
    """The function :func:`build` applies for annotation ``tp`` to a value that is not None, or None where it
    keeps the value as it is: worked out once per annotation, since configs are built on every validation."""
    origin, args = typing.get_origin(tp), typing.get_args(tp)
    if origin in (typing.Union, types.UnionType):
        kinds = [(next((f.metadata["keywords"].get("const") for f in dataclasses.fields(cls) if f.name == "kind"),
                       None), _class_builder(cls)) for cls in args if _is_declared(cls)]
        if not kinds:
            return None

        def pick(value):
            if isinstance(value, dict):
                for const, make in kinds:
                    if const is None or const == value.get("kind"):
                        return make(value)
            return value
        return pick
    if origin is dict and _is_declared(args[1]):
        entry = _class_builder(args[1])
        return lambda value: {k: None if v is None else entry(v) for k, v in value.items()}
    return _class_builder(tp) if _is_declared(tp) else None


def _class_builder(cls) -> Callable[[dict], Any]:
    """The builder of the declared class ``cls``: each key the mapping gives, built as its field's annotation."""
    hints = _hints(cls)
    fields = [(f.name, _key(f), _builder(hints[f.name])) for f in dataclasses.fields(cls)]

    def make(value):
        return cls(**{name: v if sub is None or v is None else sub(v)
                      for name, key, sub in fields if key in value for v in (value[key],)})
    return make


#: discriminated unions on ``kind`` that fields refer to with ``ref=`` (the kinds of initial condition):
#: name -> (description, description of ``kind``, kind -> declared class); :func:`register_union` adds one
UNIONS: dict[str, tuple[str, str, dict]] = {}


def register_union(name: str, doc: str, kind_doc: str, kinds: dict) -> None:
    """Declare the union ``name`` (a ``$defs`` entry of every generated schema) of the declared ``kinds``."""
    UNIONS[name] = (doc, kind_doc, dict(kinds))


def generate(root, *, title: str, extra_defs=None) -> dict:
    """The JSON Schema of the declared class ``root`` (the whole config, or one spec), shared types and
    the registered unions under $defs."""
    defs = {k: dict(v) for k, v in SHARED.items()}
    for name, (doc, kind_doc, kinds) in UNIONS.items():
        defs[name] = union_schema(doc, kind_doc, kinds, defs)
    for name, make in (extra_defs or {}).items():
        defs[name] = make(defs)
    body = object_schema(root, defs)
    if "$ref" in body:  # a named class: its schema is under $defs
        body = defs[root.__schema_name__]
    out = {"$schema": SCHEMA_DRAFT, "title": title, "description": root.__schema_doc__, "type": "object",
           "additionalProperties": False, "properties": body["properties"], "$defs": _used_shared(defs, body)}
    return out


def _refs(node) -> set[str]:
    """The ``$defs`` names a schema node refers to (``#/$defs/<name>``), anywhere inside it."""
    if isinstance(node, dict):
        ref = node.get("$ref")
        found = {ref[len("#/$defs/"):]} if isinstance(ref, str) and ref.startswith("#/$defs/") else set()
        return found.union(*(_refs(v) for v in node.values()))
    if isinstance(node, list):
        return set().union(*(_refs(v) for v in node))
    return set()


def _used_shared(defs: dict, body: dict) -> dict:
    """``defs`` without the shared types nothing refers to (those only functions' arguments use), in order."""
    keep = set(defs) - set(SHARED)
    todo = [body, *(defs[k] for k in keep)]
    while todo:
        for name in _refs(todo.pop()) - keep:
            keep.add(name)
            todo.append(defs[name])
    return {k: v for k, v in defs.items() if k in keep}


def dump(schema: dict) -> str:
    """The committed text of a schema (stable key order, one trailing newline)."""
    return json.dumps(schema, indent=2, ensure_ascii=False) + "\n"


def write(schema: dict, path: Path) -> Path:
    path.write_text(dump(schema), encoding="utf-8")
    return path


@functools.cache
def _nullable(cls) -> frozenset[str]:
    """The fields of a declared class where null is a value of its own: declared with a NULL default, or
    typed ``X | None`` with a default other than None (``direct_omega: null`` = the most unstable one)."""
    hints = _hints(cls)
    out = set()
    for f in dataclasses.fields(cls):
        optional = type(None) in typing.get_args(hints[f.name])
        if f.metadata.get("null_default") or (optional and _default_of(f) not in (None, REQUIRED)):
            out.add(f.name)
    return frozenset(out)


def plain(value):
    """A spec (or any value holding specs) as plain JSON values: declared instances as mappings of their
    config keys, sorted, tuples as lists. What a rule's ``params:`` carry and a file stores; equal
    specs give equal plain values whatever the order they were written in, and however a value was
    written: a declared number as a float (``100``, ``1e2`` and ``100.0`` alike), an integer as an int,
    an angle in one form (:func:`cradle.specs.values.canonical_angle`). An optional key that is absent
    (None) is left out."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        # an optional key left out (None, where null is not a value of its own) stays out
        cls = type(value)
        nullable, hints = _nullable(cls), _hints(cls)
        return {k: v for k, v in sorted((_key(f), _by_value(f, hints[f.name], plain(getattr(value, f.name))))
                                        for f in dataclasses.fields(value)
                                        if getattr(value, f.name) is not None or f.name in nullable)}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in sorted(value.items())}
    return value


def _by_value(f: dataclasses.Field, tp, value):
    """A field's plain value in its one form by value: angles canonical, numbers typed as declared."""
    items = f.metadata["keywords"].get("items")
    if f.metadata["ref"] in ("angle", "angleString"):
        return canonical_angle(value)
    if items == _ref("angle") and isinstance(value, list):
        return [canonical_angle(v) for v in value]
    return _typed(tp, value)


def _typed(tp, value):
    """``value`` with every number of the annotation ``tp`` as its declared type (an int where a number is
    declared is a float; an integral float where an integer is declared is an int)."""
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


@functools.cache
def _validator_of(cls):
    from jsonschema import Draft202012Validator

    return Draft202012Validator(generate(cls, title=cls.__name__))


def from_plain(cls, mapping, where: str | None = None):
    """A validated instance of the declared class ``cls`` from plain values (:func:`plain`'s output, a
    rule's ``params:``, a file's stored parameters, keyword arguments): every key checked against its
    declaration (type, bounds, enum), then built. Raises :class:`cradle.specs.values.ConfigError`, one
    line per problem naming ``where`` (default: the class name), the key and the value."""
    errors = sorted(_validator_of(cls).iter_errors(mapping), key=lambda e: [str(p) for p in e.absolute_path])
    if errors:
        head = where or cls.__name__
        raise ConfigError([f"config error: {head}{'.' if e.absolute_path else ''}{key_path(list(e.absolute_path))}"
                           f" = {show(e.instance)}: {e.message}" for e in errors])
    return build(cls, mapping)
