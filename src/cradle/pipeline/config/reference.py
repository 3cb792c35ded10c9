"""The JSON Schema of config.yaml and its markdown reference, generated from the declarations: for editors
and readers only, never consulted when a config is validated (:mod:`.validate` reads the declarations).

config.yaml states what the paper's scenes need and what differs from the defaults; every key, its type,
bounds, default and meaning is in docs/config-reference.md, generated from the same declarations as the
schema (``python -m cradle.pipeline.config --write-schema`` and ``--write-reference`` rewrite the files; a
test checks both are current).
"""
from __future__ import annotations

import json
from importlib import resources
from pathlib import Path

from cradle.specs import schema as spec
from cradle.specs.values import CONFIG_MAX_VALUES, DEFAULT_MAX_ITEMS, DEFAULT_MAX_LENGTH

REFERENCE_FILE = Path("docs") / "config-reference.md"
SCHEMA_FILE = "config.schema.json"


def generated_schema() -> dict:
    """The JSON Schema of config.yaml, generated from the declarations (:class:`.sections.Config`)."""
    from .sections import Config

    return spec.generate(Config, title="cradle configuration")


def schema_path() -> Path:
    """The committed schema file (src/cradle/pipeline/config.schema.json)."""
    return Path(str(resources.files("cradle.pipeline").joinpath(SCHEMA_FILE)))


def write_schema(path: str | Path | None = None) -> Path:
    """Write the generated schema to ``path`` (default: the committed file)."""
    return spec.write(generated_schema(), Path(path) if path else schema_path())


def write_reference() -> Path:
    """Write docs/config-reference.md (relative to the working directory, the checkout)."""
    REFERENCE_FILE.write_text(reference(generated_schema()) + "\n", encoding="utf-8")
    return REFERENCE_FILE

_BOUNDS = (("minimum", ">= {}"), ("exclusiveMinimum", "> {}"), ("maximum", "<= {}"), ("exclusiveMaximum", "< {}"),
           ("minItems", "at least {} items"), ("maxItems", "at most {} items"), ("maxLength", "at most {} characters"))


def _resolve(node: dict, defs: dict) -> dict:
    """A node with its local $ref merged in (the node's own keywords win)."""
    if "$ref" not in node:
        return node
    target = _resolve(defs[node["$ref"].rsplit("/", 1)[-1]], defs)
    out = {**target, **{k: v for k, v in node.items() if k != "$ref"}}
    if "properties" in node and "properties" in target:   # a partial override: each key's own words win
        out["properties"] = {k: {**target["properties"].get(k, {}), **v} for k, v in node["properties"].items()}
    return out


def _type(node: dict, defs: dict) -> str:
    if "enum" in node:
        return ", ".join(f"`{v}`" for v in node["enum"])
    if "const" in node:
        return f"`{node['const']}`"
    if "anyOf" in node:
        return " or ".join(_type(_resolve(n, defs), defs) for n in node["anyOf"] if isinstance(n, dict))
    if node.get("pattern") and node.get("type") == "string":
        return "string (an angle such as 'pi/5')" if "pi" in node["pattern"] else "string (a name)"
    kind = node.get("type", "")
    kinds = [kind] if isinstance(kind, str) else list(kind)
    if "array" in kinds and isinstance(node.get("items"), dict):
        return f"list of {_type(_resolve(node['items'], defs), defs) or 'values'}"
    return " or ".join(kinds)


def _cell(text: object) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def _rows(node: dict, path: str, defs: dict, out: list, seen: set) -> None:
    node = _resolve(node, defs)
    props = dict(node.get("properties") or {})
    kinds = [b.get("if", {}).get("properties", {}).get("kind", {}).get("const") for b in node.get("allOf", [])]
    for then in (b.get("then", {}) for b in node.get("allOf", [])):   # the kinds of a discriminated union
        props.update({k: v for k, v in _resolve(then, defs).get("properties", {}).items() if k != "kind"})
    if any(kinds):
        props["kind"] = {**props.get("kind", {}), "enum": [k for k in kinds if k]}
    for key, sub in props.items():
        sub = _resolve(sub, defs)
        where = f"{path}.{key}" if path else key
        bounds = ", ".join(fmt.format(sub[k]) for k, fmt in _BOUNDS if k in sub)
        default = f"`{json.dumps(sub['default'])}`" if "default" in sub and not isinstance(sub["default"], dict) \
            else ""
        out.append(f"| `{where}` | {_cell(_type(sub, defs))} | {_cell(bounds)} | {_cell(default)} | "
                   f"{_cell(sub.get('description', ''))} |")
        extra = sub.get("additionalProperties")
        if isinstance(extra, dict) and (extra.get("properties") or "$ref" in extra) and where not in seen:
            seen.add(where)
            _rows(extra, f"{where}.<name>", defs, out, seen)
        if sub.get("properties") or sub.get("allOf"):
            _rows(sub, where, defs, out, seen)


def reference(schema: dict) -> str:
    """The markdown reference of a generated config schema."""
    out = ["# config.yaml reference", "",
           "Generated from the declarations by `python -m cradle.pipeline.config --write-reference`; do not edit.",
           "Every key of config.yaml, its type, bounds, default (when the key may be left out) and meaning; a key",
           "left out of config.yaml takes its default. `<name>` stands for an entry's name. A list without a",
           f"maximum here has at most {DEFAULT_MAX_ITEMS} items, a string at most {DEFAULT_MAX_LENGTH} characters; the "
           f"file holds at most {CONFIG_MAX_VALUES} values", "(an alias counted as the values it stands for).", ""]
    defs = schema.get("$defs", {})
    for key, node in schema["properties"].items():
        out += [f"## `{key}`", "", _cell(_resolve(node, defs).get("description", "")), "",
                "| key | type | bounds | default | meaning |", "|---|---|---|---|---|"]
        rows: list[str] = []
        _rows({"properties": {key: node}}, "", defs, rows, set())
        out += rows + [""]
    return "\n".join(out)
