"""Loading and validating config.yaml: coercion, schema messages, defaults, resolved entries.

The Snakefile calls :func:`validate` right after loading the config (so after
any ``--config`` overrides); ``python -m cradle.pipeline.config [config.yaml]`` does
the same from the command line. Every bad input is reported before any work
starts, one line per problem, naming the key path and the value::

    config error: scenes.tw-weak.N = 1: must be >= 2

Two layers, both declared in :mod:`.sections`, :mod:`cradle.scenes.spec` and :mod:`.beyond`:

1. the JSON Schema generated from the declarations (``config.schema.json``):
   keys, types, bounds, enums; its errors are rewritten as one readable line each;
2. the ``check`` methods of the declared types, run by :func:`.checks.check` on the
   typed object of every entry the schema passed: what the schema cannot express
   (q N / (2 pi) an integer on a ring, a breather built from an existing
   homoclinic entry of the same N and bc, stored times of figures, ...).

:func:`validate` returns a deep copy with the schema defaults filled in;
:func:`.resolve.scene`, :func:`.resolve.homoclinic` and :func:`.resolve.map_entry` give one
entry as a resolved, typed instance, the ``resolved_*`` of the analyses their plain
parameters.
"""
from __future__ import annotations

import difflib
import json
import pickle
import re
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import NamedTuple, cast

from jsonschema import Draft202012Validator
from jsonschema.exceptions import ValidationError
from jsonschema.protocols import Validator

from cradle.specs import declare as spec
from cradle.specs.values import ANGLE_HINT, ANGLE_PATTERN, ConfigError, Errors, copied, number, show

from . import checks, sections
from .sections import SECTIONS

SCHEMA_FILE = "config.schema.json"

# Extra words appended to schema messages for some keys, by (last key, schema keyword).
_HINTS = {
    ("alpha", "exclusiveMinimum"): " (Hertz exponent of (vhertz))",
    ("omega_tw", "exclusiveMinimum"): " (a is derived from (freq), omega_tw = 1 + (2/tau0) a^(alpha-1) "
                                      "|sin(q/2)|^(alpha+1))",
    ("omega_sw", "exclusiveMinimum"): " (mu = (omega_sw - 1) 2^alpha tau0 must be > 0)",
}


# --------------------------------------------------------------------------- schema

def generated_schema() -> dict:
    """The JSON Schema of config.yaml, generated from the declarations (:mod:`.sections`)."""
    return spec.generate(sections.Config, title="cradle configuration")


def schema_path() -> Path:
    """The committed schema file (src/cradle/pipeline/config.schema.json)."""
    return Path(str(resources.files("cradle.pipeline").joinpath(SCHEMA_FILE)))


def write_schema(path=None) -> Path:
    """Write the generated schema to ``path`` (default: the committed file)."""
    return spec.write(generated_schema(), Path(path) if path else schema_path())


@lru_cache(maxsize=1)
def _schema_text() -> str:
    return spec.dump(generated_schema())


def schema() -> dict:
    """The JSON Schema of config.yaml (a fresh copy; equal to the committed file, which a test checks)."""
    return json.loads(_schema_text())


@lru_cache(maxsize=1)
def _validator() -> Draft202012Validator:
    # the schema is generated from the typed specs and checked against JSON Schema's own by a test
    # (tests/pipeline/test_config_typed.py), not on every read of the Snakefile, where it cost a second
    return Draft202012Validator(schema())


def _root() -> dict:
    """The schema the validator checks against (a mapping: the generated schema is never a boolean one)."""
    return cast(dict, _validator().schema)


#: validators of the schema's sub-schemas that pick a branch (if, anyOf), by the node's id: the schema is
#: built once, and building a validator costs more than most checks it makes
_BRANCHES: dict[int, Validator] = {}


def _branch(node: dict) -> Validator:
    """The validator of the sub-schema ``node`` of the schema (its $ref resolved in the whole schema)."""
    v = _BRANCHES.get(id(node))
    if v is None:
        v = _BRANCHES[id(node)] = _validator().evolve(schema=node)
    return v


def _is_valid(node: dict, instance) -> bool:
    """Whether ``instance`` is valid against the sub-schema ``node`` of the schema."""
    kind = _node(node).kind
    if kind is not None:   # the test of a union's branch, the most frequent: answered without jsonschema
        return isinstance(instance, dict) and isinstance(instance.get("kind"), str) and instance["kind"] == kind
    return _branch(node).is_valid(instance)


def _kind_test(node: dict) -> str | None:
    """``k`` when ``node`` is the test of a discriminated union's branch (an object whose ``kind`` is ``k``:
    :func:`cradle.specs.declare.union_schema`), else None."""
    if set(node) != {"type", "required", "properties"} or node["type"] != "object" or node["required"] != ["kind"]:
        return None
    props = node["properties"]
    if set(props) != {"kind"} or set(props["kind"]) != {"const"} or not isinstance(props["kind"]["const"], str):
        return None
    return props["kind"]["const"]


def _resolve(node: dict) -> dict:
    """Follow a local "$ref" ("#/$defs/...") of the schema."""
    ref = node["$ref"]
    if not ref.startswith("#/"):
        raise ValueError(f"only local $ref are supported, got {ref!r}")
    target = _root()
    for part in ref[2:].split("/"):
        target = target[part]
    return target


class _Node(NamedTuple):
    """What :func:`_fill`, :func:`_coerce` and :func:`_is_valid` read of a schema node, read once (by the node's id, as
    :data:`_BRANCHES`): the first two walk the schema along every config, on every validation."""
    ref: dict | None
    all_of: tuple
    test: dict | None
    then: dict | None
    otherwise: dict | None
    groups: tuple   # the branches of anyOf, then those of oneOf (each group given)
    props: dict
    defaults: tuple   # (key, default) of the properties that declare one
    extra: dict | None
    items: dict | None
    integer: bool
    types: tuple | None   # the JSON types a string is read as (:func:`_scalar_from_string`); None: kept a string
    kind: str | None      # the kind a union's branch test asks for (:func:`_kind_test`), else None


_NODES: dict[int, _Node] = {}
#: whether :func:`_fill` leaves every instance of a node as it is (no default, no integer key below it), by id
_INERT: dict[int, bool] = {}


def _node(node: dict) -> _Node:
    n = _NODES.get(id(node))
    if n is None:
        props = node.get("properties", {})
        extra, items, tp = node.get("additionalProperties"), node.get("items"), node.get("type")
        types = None if tp is None else (tp,) if isinstance(tp, str) else tuple(tp)
        n = _NODES[id(node)] = _Node(
            ref=_resolve(node) if "$ref" in node else None, all_of=tuple(node.get("allOf", ())),
            test=node.get("if"), then=node.get("then"), otherwise=node.get("else"),
            groups=tuple(node[k] for k in ("anyOf", "oneOf") if node.get(k)), props=props,
            defaults=tuple((k, sub["default"]) for k, sub in props.items()
                           if isinstance(sub, dict) and "default" in sub),
            extra=extra if isinstance(extra, dict) else None, items=items if isinstance(items, dict) else None,
            integer=tp == "integer", types=None if types is None or "string" in types else types,
            kind=_kind_test(node))
    return n


def _inert(node) -> bool:
    """Whether :func:`_fill` returns every instance of ``node`` unchanged: no default to fill and no integer
    key anywhere below it (most leaves), so that it need not be followed."""
    if not isinstance(node, dict):
        return True
    inert = _INERT.get(id(node))
    if inert is None:
        _INERT[id(node)] = False   # while it is worked out (a node reached again through a $ref)
        n = _node(node)
        below = [n.ref, *n.all_of, n.then, n.otherwise, *(sub for group in n.groups for sub in group),
                 *n.props.values(), n.extra, n.items]
        inert = _INERT[id(node)] = not n.defaults and not n.integer and all(_inert(sub) for sub in below)
    return inert


def _fill(node, instance):
    """Fill schema defaults into ``instance`` (mutated and returned), following
    $ref, allOf, if/then/else, anyOf/oneOf (first matching branch), properties,
    additionalProperties and items. Robust to instances of the wrong type.
    Integer-valued floats of "integer" keys become ints (N: 50.0 -> 50)."""
    if not isinstance(node, dict):
        return instance
    n = _node(node)
    if n.ref is not None:
        instance = _fill(n.ref, instance)
    for sub in n.all_of:
        instance = _fill(sub, instance)
    if n.test is not None:
        instance = _fill(n.then if _is_valid(n.test, instance) else n.otherwise, instance)
    for group in n.groups:   # the first branch that matches in each
        for sub in group:
            if _is_valid(sub, instance):
                instance = _fill(sub, instance)
                break
    if isinstance(instance, dict):
        props = n.props
        for key, default in n.defaults:
            if key not in instance:
                instance[key] = copied(default)
        for key in list(instance):
            sub = props.get(key, n.extra)
            if sub is not None and not _inert(sub):
                instance[key] = _fill(sub, instance[key])
    elif isinstance(instance, list) and n.items is not None:
        for i, item in enumerate(instance):
            instance[i] = _fill(n.items, item)
    if n.integer and isinstance(instance, float) and instance.is_integer():
        instance = int(instance)
    return instance


_INT_RE = re.compile(r"^[-+]?\d+$")
_FLOAT_RE = re.compile(r"^[-+]?(\d+(\.\d*)?|\.\d+)([eE][-+]?\d+)?$|^[-+]?(inf|nan)$", re.IGNORECASE)


def _scalar_from_string(text: str, types):
    """``text`` as a value of one of the JSON ``types`` (not string), or the string itself."""
    s = text.strip()
    if "null" in types and s in ("null", "Null", "NULL", "~", ""):
        return None
    if "boolean" in types and s in ("true", "True", "TRUE", "false", "False", "FALSE"):
        return s.lower() == "true"
    if ("integer" in types or "number" in types) and _INT_RE.match(s):
        return int(s)
    if "number" in types and _FLOAT_RE.match(s):
        return float(s)
    if "integer" in types and _FLOAT_RE.match(s) and float(s).is_integer():
        return int(float(s))
    return text


def _coerce(node, instance):
    """Turn strings into the number / integer / boolean / null their key expects.

    ``snakemake --config key='{nested: {x: 1.5}}'`` parses nested values with
    YAML's BaseLoader, so every nested scalar arrives as a string; PyYAML also
    reads ``1e-10`` (no dot) as a string. Strings that do not read as the
    expected type are left alone for the schema to report.
    """
    if not isinstance(node, dict):
        return instance
    n = _node(node)
    if n.ref is not None:
        instance = _coerce(n.ref, instance)
    for sub in n.all_of:
        instance = _coerce(sub, instance)
    if n.test is not None:
        instance = _coerce(n.then if _is_valid(n.test, instance) else n.otherwise, instance)
    if isinstance(instance, dict):
        props, extra = n.props, n.extra
        for key in list(instance):
            sub = props.get(key, extra)
            if sub is not None:
                instance[key] = _coerce(sub, instance[key])
    elif isinstance(instance, list) and n.items is not None:
        for i, item in enumerate(instance):
            instance[i] = _coerce(n.items, item)
    elif isinstance(instance, str) and n.types is not None:
        instance = _scalar_from_string(instance, n.types)
    return instance


# --------------------------------------------------------------------------- the schema's errors, by part

def _shell(node: dict) -> dict:
    """An object schema that checks the object itself (its type, required and unknown keys, the names of its
    entries) but takes any value for each of its keys: those are validated apart."""
    shell = dict(node)
    if isinstance(node.get("properties"), dict):
        shell["properties"] = {key: {} for key in node["properties"]}
    if isinstance(node.get("additionalProperties"), dict):
        shell["additionalProperties"] = {}
    return shell


@lru_cache(maxsize=1)
def _parts() -> tuple[dict, dict[str, tuple[dict, dict, dict | None]]]:
    """The root's shell, and for each section its shell, the schemas of its keys and that of its entries."""
    root = _root()
    sections = {}
    for section, node in root["properties"].items():
        node = _resolve(node) if "$ref" in node else node
        extra = node.get("additionalProperties")
        sections[section] = (_shell(node), dict(node.get("properties") or {}), extra if isinstance(extra, dict)
                             else None)
    return _shell(root), sections


#: the schema's errors of the parts of recent configs (the root's and the sections' shells; an entry's are
#: those of :func:`_entry`), by (part, its pickle: :func:`_memo_key`)
_PART_ERRORS: dict[tuple, list[ValidationError]] = {}


def _memo_key(key: tuple, value) -> tuple | None:
    """``key`` and the pickle of ``value``, or None if it cannot be pickled: equal only for values of the same
    types, keys and order (1, 1.0 and True apart), for which every step of the validation gives the same."""
    try:
        return (*key, pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL))
    except Exception:  # noqa: BLE001 -- any value pickle refuses is validated without the memo
        return None


def _part_errors(schema: dict, value, key: tuple[str, ...]) -> list[ValidationError]:
    """jsonschema's errors of ``value`` against the sub-schema ``schema`` (paths relative to ``value``)."""
    memo = _memo_key(key, value)
    if memo is not None and memo in _PART_ERRORS:
        return _PART_ERRORS[memo]
    # a copy: the errors keep their instance, which filling in the defaults would change
    errors = list(_branch(schema).iter_errors(copied(value)))
    if memo is not None:
        if len(_PART_ERRORS) >= 4096:
            _PART_ERRORS.pop(next(iter(_PART_ERRORS)))
        _PART_ERRORS[memo] = errors
    return errors


#: the keywords of a shell (:func:`_shell`) whose errors say nothing of the values of its keys: the type, the
#: required, declared and well-named keys (the message of an undeclared key shows its value)
_KEYS_ONLY = frozenset({"$schema", "$defs", "title", "description", "default", "type", "required", "properties",
                        "additionalProperties", "propertyNames"})


def _shell_errors(shell: dict, value, key: tuple[str, ...]) -> list[ValidationError]:
    """:func:`_part_errors` of a shell, found for a mapping on its keys alone (the values replaced by None, which
    the shell takes as any other value) where no error can show a value: the memo then holds one entry per set
    of keys, not one per config."""
    if isinstance(value, dict) and _KEYS_ONLY.issuperset(shell) and (
            shell.get("additionalProperties") is not False or all(k in shell.get("properties", {}) for k in value)):
        return _part_errors(shell, dict.fromkeys(value), key)
    return _part_errors(shell, value, key)


def _schema_errors(cfg: dict, entry_errors: dict | None = None) -> list[tuple[tuple, ValidationError]]:
    """(key path of a part, error) for every error of ``cfg`` against the schema: the same errors as the
    whole schema gives, found part by part (the root, each section, each of its keys or entries); those of
    an entry taken from ``entry_errors`` (by (section, key): :func:`_by_entry`) where it holds them."""
    entry_errors = entry_errors or {}
    root, sections = _parts()
    out: list[tuple[tuple, ValidationError]] = [((), e) for e in _shell_errors(root, cfg, ("",))]
    for section, (shell, props, entries) in sections.items():
        if section not in cfg:
            continue
        value = cfg[section]
        out += [((section,), e) for e in _shell_errors(shell, value, (section,))]
        if not isinstance(value, dict):
            continue
        for key, item in value.items():
            sub = props.get(key, entries)
            known = entry_errors.get((section, key))
            if known is not None:
                out += [((section, key), e) for e in known]
            elif isinstance(sub, dict) and sub:
                out += [((section, key), e) for e in _part_errors(sub, item, (section, "*" if key not in props
                                                                                 else key))]
    return out


class _Entry(NamedTuple):
    """What the validation makes of one entry of a section (a key of ``beyond:``, a scene, ...), which depends
    on that entry alone: memoised by :func:`_entry`, so that a config validated again with one entry changed
    (the Snakefile's --config overrides, the config fuzz) works on that entry only. Never changed once made."""
    coerced: object            # the entry with its strings read (:func:`_coerce`)
    filled: object             # the coerced entry with the schema defaults filled in (:func:`_fill`)
    infinite: tuple            # (key path below the entry, message, value) of each float not finite, in order
    errors: list               # jsonschema's errors of the coerced entry against its schema


_ENTRIES: dict[tuple, _Entry] = {}
#: the default of a key (a section, an analysis) filled in, by the id of the key's node: a config that leaves
#: the key out gets it
_FILLED_DEFAULTS: dict[int, object] = {}


class _Infinite:
    """Takes the lines of :func:`.sections.check_finite` as (key path, message, value), in order."""

    def __init__(self) -> None:
        self.found: list[tuple[list, str, object]] = []

    def add(self, path, what: str, value) -> None:
        self.found.append((path, what, value))


def _infinite(value, path: tuple) -> list[tuple[list, str, object]]:
    found = _Infinite()
    sections.check_finite(value, found, path)
    return found.found


def _make_entry(sub, value, where: tuple) -> _Entry:
    coerced = _coerce(sub, copied(value))
    errors = list(_branch(sub).iter_errors(coerced)) if isinstance(sub, dict) and sub else []
    filled = coerced if sub is None or _inert(sub) else _fill(sub, copied(coerced))
    infinite = tuple((path[len(where):], what, v) for path, what, v in _infinite(coerced, where))
    return _Entry(coerced, filled, infinite, errors)


def _entry(sub, value, where: tuple) -> _Entry:
    """The :class:`_Entry` of ``value``, the entry at ``where`` (section, key) whose schema is ``sub`` (None:
    a key its section does not declare)."""
    memo = _memo_key((id(sub),), value)   # what it holds does not depend on ``where``
    if memo is None:
        return _make_entry(sub, value, where)
    made = _ENTRIES.get(memo)
    if made is None:
        made = _make_entry(sub, value, where)
        if len(_ENTRIES) >= 4096:
            _ENTRIES.pop(next(iter(_ENTRIES)))
        _ENTRIES[memo] = made
    return made


def _plain(node) -> _Node | None:
    """The :class:`_Node` of ``node`` if :func:`_coerce` and :func:`_fill` treat a mapping given for it key by
    key (no $ref, allOf, if, anyOf, oneOf, items or integer type: the root and the sections), else None."""
    if not isinstance(node, dict):
        return None
    n = _node(node)
    plain = n.ref is None and not n.all_of and n.test is None and not n.groups and n.items is None and not n.integer
    return n if plain else None


def _filled_default(node: dict, default):
    """``_fill(node, copied(default))``, ``default`` being that of ``node`` (made once)."""
    made = _FILLED_DEFAULTS.get(id(node))
    if made is None:
        made = _FILLED_DEFAULTS[id(node)] = _fill(node, copied(default))
    return made


def _by_entry(config: dict) -> tuple[dict, dict, list, dict]:
    """What ``_coerce``, ``check_finite`` and ``_fill`` make of ``config`` and the schema's errors of its
    entries, worked out entry by entry (:func:`_entry`): (the coerced config, the filled config, the
    (key path, message, value) of each float that is not finite, in the config's order, and {(section, key): the
    schema's errors of that entry}). Both configs share their entries with the memo: they are only read."""
    root = _root()
    n = _plain(root)
    if n is None:   # not a schema this walks: the whole config at once
        coerced = _coerce(root, copied(config))
        return coerced, _fill(root, copied(coerced)), _infinite(coerced, ()), {}
    coerced, filled, infinite, errors = {}, {}, [], {}
    for section, value in config.items():
        node = n.props.get(section, n.extra)
        s = _plain(node)
        if node is None or s is None or not isinstance(value, dict):   # an unknown key, a section that is not
            coerced[section] = c = _coerce(node, copied(value))         # a mapping: as a whole
            infinite += _infinite(c, (section,))
            filled[section] = c if node is None or _inert(node) else _fill(node, copied(c))
            continue
        coerced[section], filled[section] = {}, {}
        for key, item in value.items():
            sub = s.props.get(key, s.extra)
            e = _entry(sub, item, (section, key))
            coerced[section][key], filled[section][key] = e.coerced, e.filled
            infinite += [([section, key, *path], what, v) for path, what, v in e.infinite]
            errors[section, key] = e.errors
        for key, default in s.defaults:
            if key not in value:
                filled[section][key] = _filled_default(s.props[key], default)
    for section, default in n.defaults:
        if section not in config:
            filled[section] = _filled_default(n.props[section], default)
    return coerced, filled, infinite, errors


# --------------------------------------------------------------------------- messages

_TYPE_WORDS = {"integer": "an integer", "number": "a number", "string": "a string", "object": "a mapping",
               "array": "a list", "boolean": "true or false", "null": "null"}


def _type_words(types) -> str:
    types = [types] if isinstance(types, str) else list(types)
    return " or ".join(_TYPE_WORDS.get(t, t) for t in types)


def _fmt_bound(x) -> str:
    return repr(x) if isinstance(x, float) and not float(x).is_integer() else str(int(x)) if number(x) else str(x)


def _schema_messages(err, out: Errors, prefix: tuple = ()):
    """One readable line per jsonschema error (recursing into anyOf/oneOf); ``prefix``: the key path of the
    part of the config the error's validator was given (:func:`_schema_errors`)."""
    path = [*prefix, *err.absolute_path]
    last = str(path[-1]) if path else ""
    kw = err.validator
    val = err.validator_value
    inst = err.instance
    hint = _HINTS.get((last, kw), "")
    if "propertyNames" in err.schema_path:
        # jsonschema reports the bad name itself as the instance, at the parent's path
        if kw == "enum":
            out.add(path + [inst], f"unknown figure label {inst!r} (known labels: {', '.join(map(str, val))})"
                    if path == ["figures"] else f"must be one of {', '.join(map(str, val))}")
        else:
            out.add(path + [inst], f"bad name {inst!r}: names use letters, digits, '-' and '_' "
                                   f"and start with a letter or digit", force=True)
        return
    if kw == "required":
        for key in val:
            if isinstance(inst, dict) and key not in inst:
                out.add(path + [key], "missing (required key)")
        return
    if kw == "additionalProperties" and val is False:
        allowed = list(err.schema.get("properties", {}))
        for key in inst:
            if key not in allowed:
                near = difflib.get_close_matches(str(key), allowed, n=1)
                did = f"; did you mean {near[0]!r}?" if near else ""
                out.add(path + [key], f"unknown key (allowed: {', '.join(allowed)}){did}", inst[key])
        return
    if kw in ("anyOf", "oneOf"):
        branches: dict[int, list] = {}
        for sub in err.context:
            branches.setdefault(sub.relative_schema_path[0], []).append(sub)
        subs = [s for errs in branches.values() for s in errs]
        if subs and all(s.validator == "required" for s in subs):
            names = [k for s in subs for k in s.validator_value]
            out.add(path, f"needs at least one of {', '.join(names)}", inst)
            return
        # a branch whose type fits the value explains best what is wrong with it
        for errs in branches.values():
            if not any(s.validator == "type" and [*prefix, *s.absolute_path] == path for s in errs):
                for s in errs:
                    _schema_messages(s, out, prefix)
                return
        types = [s.validator_value for s in subs if s.validator == "type" and [*prefix, *s.absolute_path] == path]
        flat = []
        for t in types:
            flat += [t] if isinstance(t, str) else list(t)
        if err.schema.get("anyOf") == _root()["$defs"]["angle"]["anyOf"]:
            out.add(path, f"must be {ANGLE_HINT}", inst)
        else:
            out.add(path, f"must be {_type_words(list(dict.fromkeys(flat)))}", inst)
        return
    if kw == "type":
        out.add(path, f"must be {_type_words(val)}", inst)
    elif kw == "enum":
        out.add(path, f"must be one of {', '.join(map(str, val))}", inst)
    elif kw == "const":
        out.add(path, f"must be {val!r}", inst)
    elif kw == "minimum":
        out.add(path, f"must be >= {_fmt_bound(val)}{hint}", inst)
    elif kw == "exclusiveMinimum":
        out.add(path, f"must be > {_fmt_bound(val)}{hint}", inst)
    elif kw == "maximum":
        out.add(path, f"must be <= {_fmt_bound(val)}{hint}", inst)
    elif kw == "exclusiveMaximum":
        out.add(path, f"must be < {_fmt_bound(val)}{hint}", inst)
    elif kw in ("minItems", "maxItems"):
        lo, hi = err.schema.get("minItems"), err.schema.get("maxItems")
        if lo is not None and lo == hi:
            out.add(path, f"must have exactly {lo} items", inst)
        elif kw == "minItems":
            out.add(path, "must not be empty" if val == 1 else f"must have at least {val} items", inst)
        else:
            out.add(path, f"must have at most {val} items", inst)
    elif kw == "uniqueItems":
        out.add(path, "must not repeat a name", inst)
    elif kw == "pattern":
        if last == "q" or err.schema.get("pattern") == ANGLE_PATTERN:
            out.add(path, f"must be {ANGLE_HINT}", inst)
        else:
            out.add(path, "must use letters, digits, '-' and '_' and start with a letter or digit", inst)
    else:  # a keyword this module does not word specially
        out.add(path, err.message, inst)


# --------------------------------------------------------------------------- public API

def validate(config: dict) -> dict:
    """A validated deep copy of ``config`` with the schema defaults filled in.

    Strings where a number, integer, boolean or null is expected are read as
    such first (``--config`` overrides arrive as strings), so ``N: "50"`` is
    50 but ``N: "fifty"`` is an error.

    Raises :class:`ConfigError` listing every problem found, one line each.
    """
    if config is None:
        config = {}   # an empty YAML file
    if not isinstance(config, dict):
        raise ConfigError(f"config error: config = {show(config)}: must be a mapping")
    if not any(config.get(section) for section in SECTIONS):
        # an empty file, or the wrong one: refused here rather than as a traceback while the DAG is built
        raise ConfigError(f"config error: config: no {', '.join(SECTIONS)} entries, nothing to build (keys given: "
                          f"{', '.join(map(str, config)) or 'none'})")
    coerced, filled, infinite, entry_errors = _by_entry(dict(config))
    out = Errors()
    for path, what, value in infinite:   # sections.check_finite's lines, in its order
        out.add(path, what, value)
    for prefix, err in sorted(_schema_errors(coerced, entry_errors),
                              key=lambda pe: [str(p) for p in (*pe[0], *pe[1].absolute_path)]):
        _schema_messages(err, out, prefix)
    # ``filled`` shares its entries with the memo of :func:`_entry`: the checks only read it, and what is
    # returned is a copy
    cfg = filled
    if not out.lines:  # every job's estimated memory, output and time within budget, before the physical
        from cradle.pipeline import budget  # checks build stored-time arrays (cradle.pipeline.budget)

        budget.check(cfg)
    checks.check(cfg, out)
    if out.lines:
        raise ConfigError(out.lines)
    cfg = copied(cfg)
    # a validated config validates to itself (tested): remember it, so that the resolving calls
    # the Snakefile makes with it, once per job, do not validate it again
    _remember(_key(cfg), copied(cfg))
    return cfg


_VALIDATED: dict[str, dict] = {}


def _key(config) -> str | None:
    """The cache key of a config (its canonical JSON), or None if it cannot be serialised."""
    try:
        return json.dumps(config, sort_keys=True, default=repr)
    except (TypeError, ValueError):
        return None


def _remember(key: str | None, validated: dict) -> None:
    """Keep ``validated`` under ``key``, for the last few configs only."""
    if key is None:
        return
    if len(_VALIDATED) >= 8:
        _VALIDATED.pop(next(iter(_VALIDATED)))
    _VALIDATED[key] = validated


def assume_validated(config: dict) -> dict:
    """``config``, taken as validated without validating it again: a Snakemake job's copy of the config its
    Snakefile validated (workflow/rules/common.smk), which the job resolves entries from to check its inputs
    (:mod:`cradle.pipeline.identity`); validating it again would cost every job a validation."""
    _remember(_key(config), copied(config))
    return config


def _validated(config: dict) -> dict:
    """validate(config), remembered for the last few configs (the Snakefile resolves one entry per job)."""
    key = _key(config)
    if key is None:
        return validate(config)
    if key not in _VALIDATED:
        _remember(key, validate(config))
    return _VALIDATED[key]
