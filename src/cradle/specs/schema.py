"""The JSON Schema (draft 2020-12) of a declared class, generated from its declarations (:mod:`.declare`).

For editors and readers only: nothing validates against it at run time (:mod:`.parse` reads the declarations
themselves). ``python -m cradle.pipeline.config --write-schema`` rewrites the committed
``src/cradle/pipeline/config.schema.json``; a test keeps it in step.
"""
from __future__ import annotations

import dataclasses
import json
import types
import typing
from pathlib import Path
from typing import Any

from .declare import REQUIRED
from .parse import reduced_defaults
from .shared import SHARED

SCHEMA_DRAFT = "https://json-schema.org/draft/2020-12/schema"

#: discriminated unions on ``kind`` that fields refer to with ``ref=`` (the kinds of initial condition):
#: name -> (description, description of ``kind``, kind -> declared class); :func:`register_union` adds one
UNIONS: dict[str, tuple[str, str, dict]] = {}


def register_union(name: str, doc: str, kind_doc: str, kinds: dict) -> None:
    """Declare the union ``name`` (a ``$defs`` entry of every generated schema) of the declared ``kinds``."""
    UNIONS[name] = (doc, kind_doc, dict(kinds))


def _hints(cls: Any) -> dict:
    """The resolved annotations of a declared class."""
    return typing.get_type_hints(cls)


def _key(f: dataclasses.Field) -> str:
    """The config key of a field (its name unless declared with ``key=``)."""
    return f.metadata.get("key") or f.name


def _default_of(f: dataclasses.Field) -> Any:
    """The declared default of a field (a fresh copy of a list or a mapping), or REQUIRED."""
    if f.default is not dataclasses.MISSING:
        return f.default
    if f.default_factory is not dataclasses.MISSING:
        return f.default_factory()
    return REQUIRED


def _ref(name: str) -> dict:
    return {"$ref": f"#/$defs/{name}"}


def _is_declared(tp: Any) -> bool:
    return isinstance(tp, type) and hasattr(tp, "__schema_doc__")


def _json_default(value: Any) -> Any:
    """A declared default as JSON (tuples as lists, declared instances as mappings)."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {_key(f): _json_default(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if isinstance(value, (list, tuple)):
        return [_json_default(v) for v in value]
    if isinstance(value, dict):
        return {k: _json_default(v) for k, v in value.items()}
    return value


def _type_of(tp: Any, defs: dict) -> dict:
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


def _field_schema(f: dataclasses.Field, tp: Any, defs: dict, with_defaults: bool, default: Any) -> dict:
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


def object_schema(cls: Any, defs: dict, *, defaults: dict | None = None) -> dict:
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
        if f.name == "reduced" and hints[f.name] is dict:
            props[_key(f)] = _reduced_schema(cls, f, defs)
            continue
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


def _reduced_schema(cls: Any, field: dataclasses.Field, defs: dict) -> dict:
    """The ``reduced:`` key of an analysis: the keys of its class, each with its reduced default if declared."""
    hints, reduced = _hints(cls), reduced_defaults(cls)
    props = {_key(f): _field_schema(f, hints[f.name], defs, f.name in reduced, reduced.get(f.name, REQUIRED))
             for f in dataclasses.fields(cls) if f.name != "reduced"}
    return {"description": field.metadata["doc"], "type": "object", "additionalProperties": False,
            "properties": props}


def union_schema(doc: str, kind_doc: str, kinds: dict, defs: dict) -> dict:
    """A discriminated union on ``kind``: ``kinds`` maps each kind to its declared class."""
    return {
        "description": doc, "type": "object", "required": ["kind"],
        "properties": {"kind": {"description": kind_doc, "type": "string", "enum": list(kinds)}},
        "allOf": [{"if": {"type": "object", "required": ["kind"], "properties": {"kind": {"const": k}}},
                   "then": object_schema(c, defs)} for k, c in kinds.items()],
    }


def generate(root: Any, *, title: str, extra_defs: dict | None = None) -> dict:
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


def _refs(node: Any) -> set[str]:
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
