"""Config schema and physical validation (config.yaml).

The Snakefile calls :func:`validate` right after loading the config (so after
any ``--config`` overrides); ``python -m cradle.pipeline.config [config.yaml]`` does
the same from the command line. Every bad input is reported before any work
starts, one line per problem, naming the key path and the value::

    config error: scenes.tw-weak.N = 1: must be >= 2

Two layers:

1. the JSON Schema ``config.schema.json`` (draft 2020-12): keys, types,
   bounds, enums; its errors are rewritten as one readable line each;
2. physical checks the schema cannot express: q in (-pi, pi], q N / (2 pi)
   an integer on a ring, exactly one of a and omega_tw, breathers naming an
   existing homoclinic entry with the same N and bc, packets and pairs that
   fit the chain, increasing snapshots
   within [0, t_end], names unique across sections, figures reading existing
   entries and stored times, ...

:func:`validate` returns a deep copy with the schema defaults filled in;
:func:`resolved_scene`, :func:`resolved_homoclinic` and :func:`resolved_map`
give the fully resolved, JSON-serialisable parameters of one entry.
"""
from __future__ import annotations

import copy
import difflib
import json
import math
import re
import sys
from functools import lru_cache
from importlib import resources
from pathlib import Path

import yaml
from jsonschema import Draft202012Validator

from cradle.pipeline import budget

__all__ = [
    "ConfigError", "KNOWN_FIGURES", "SCHEMA_FILE", "ANGLE_PATTERN", "schema", "parse_angle", "validate",
    "store_times", "resolved_scene", "resolved_homoclinic", "resolved_map", "load", "main",
]

def _known_figures() -> tuple[str, ...]:
    from cradle.figures import DATASET_FIGURES, FIGURES, OTHER_FIGURES

    return (*FIGURES, *DATASET_FIGURES, *OTHER_FIGURES)


KNOWN_FIGURES = _known_figures()

SECTIONS = ("map", "homoclinic", "scenes")  # the name spaces a figure's `scenes:` list reads from

SCHEMA_FILE = "config.schema.json"

# Angles: a number, or [sign] [coefficient [*]] pi [/ denominator], e.g. pi, pi/5, 4pi/5, -52pi/100, 4*pi/5.
_NUM = r"(\d+(\.\d*)?|\.\d+)"
ANGLE_PATTERN = (
    r"^\s*[-+]?\s*((" + _NUM + r"\s*\*?\s*)?pi(\s*/\s*" + _NUM + r")?|" + _NUM + r"([eE][-+]?\d+)?)\s*$"
)
_ANGLE_RE = re.compile(ANGLE_PATTERN)
_ANGLE_HINT = "a number (radians) or a multiple of pi like 'pi', 'pi/5', '4pi/5', '-52pi/100', '4*pi/5'"

TIME_TOL = 1e-9          # two times closer than this are the same time
INTEGER_TOL = 1e-9       # q N / (2 pi) must be this close to an integer on a ring
MAX_STORED_TIMES = 10_000_000  # a guard against typos such as every: 1.0e-7

# Extra words appended to schema messages for some keys, by (last key, schema keyword).
_HINTS = {
    ("alpha", "exclusiveMinimum"): " (Hertz exponent of (vhertz))",
    ("omega_tw", "exclusiveMinimum"): " (a is derived from (freq), omega_tw = 1 + (2/tau0) a^(alpha-1) |sin(q/2)|^(alpha+1))",
    ("omega_sw", "exclusiveMinimum"): " (mu = (omega_sw - 1) 2^alpha tau0 must be > 0)",
}


class ConfigError(ValueError):
    """A config that fails the schema or the physical checks.

    ``str(err)`` is one line per problem; ``err.errors`` is the list of lines.
    """

    def __init__(self, errors):
        if isinstance(errors, str):
            errors = [errors]
        self.errors = list(errors)
        super().__init__("\n".join(self.errors))


# --------------------------------------------------------------------------- schema

@lru_cache(maxsize=1)
def _schema_text() -> str:
    return resources.files("cradle.pipeline").joinpath(SCHEMA_FILE).read_text(encoding="utf-8")


def schema() -> dict:
    """The JSON Schema of config.yaml (a fresh copy)."""
    return json.loads(_schema_text())


@lru_cache(maxsize=1)
def _validator() -> Draft202012Validator:
    s = schema()
    Draft202012Validator.check_schema(s)
    return Draft202012Validator(s)


def _resolve(node: dict) -> dict:
    """Follow a local "$ref" ("#/$defs/...") of the schema."""
    ref = node["$ref"]
    if not ref.startswith("#/"):
        raise ValueError(f"only local $ref are supported, got {ref!r}")
    target = _validator().schema
    for part in ref[2:].split("/"):
        target = target[part]
    return target


def _fill(node, instance):
    """Fill schema defaults into ``instance`` (mutated and returned), following
    $ref, allOf, if/then/else, anyOf/oneOf (first matching branch), properties,
    additionalProperties and items. Robust to instances of the wrong type.
    Integer-valued floats of "integer" keys become ints (N: 50.0 -> 50)."""
    if not isinstance(node, dict):
        return instance
    v = _validator()
    if "$ref" in node:
        instance = _fill(_resolve(node), instance)
    for sub in node.get("allOf", ()):
        instance = _fill(sub, instance)
    if "if" in node:
        branch = node.get("then") if v.evolve(schema=node["if"]).is_valid(instance) else node.get("else")
        instance = _fill(branch, instance)
    for key in ("anyOf", "oneOf"):
        for sub in node.get(key, ()):
            if v.evolve(schema=sub).is_valid(instance):
                instance = _fill(sub, instance)
                break
    if isinstance(instance, dict):
        props = node.get("properties", {})
        for key, sub in props.items():
            if key not in instance and isinstance(sub, dict) and "default" in sub:
                instance[key] = copy.deepcopy(sub["default"])
        extra = node.get("additionalProperties")
        for key in list(instance):
            if key in props:
                instance[key] = _fill(props[key], instance[key])
            elif isinstance(extra, dict):
                instance[key] = _fill(extra, instance[key])
    elif isinstance(instance, list) and isinstance(node.get("items"), dict):
        for i, item in enumerate(instance):
            instance[i] = _fill(node["items"], item)
    if node.get("type") == "integer" and isinstance(instance, float) and instance.is_integer():
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
    if "$ref" in node:
        instance = _coerce(_resolve(node), instance)
    for sub in node.get("allOf", ()):
        instance = _coerce(sub, instance)
    if "if" in node:
        branch = node.get("then") if _validator().evolve(schema=node["if"]).is_valid(instance) else node.get("else")
        instance = _coerce(branch, instance)
    if isinstance(instance, dict):
        props = node.get("properties", {})
        extra = node.get("additionalProperties")
        for key in list(instance):
            sub = props.get(key, extra if isinstance(extra, dict) else None)
            if sub is not None:
                instance[key] = _coerce(sub, instance[key])
    elif isinstance(instance, list) and isinstance(node.get("items"), dict):
        for i, item in enumerate(instance):
            instance[i] = _coerce(node["items"], item)
    elif isinstance(instance, str) and "type" in node:
        types = [node["type"]] if isinstance(node["type"], str) else list(node["type"])
        if "string" not in types:
            instance = _scalar_from_string(instance, types)
    return instance


# --------------------------------------------------------------------------- messages

def _path(parts) -> str:
    out = ""
    for p in parts:
        out += f"[{p}]" if isinstance(p, int) else (f".{p}" if out else str(p))
    return out or "config"


def _show(value) -> str:
    """A short, unambiguous rendering of a value (strings quoted)."""
    if isinstance(value, float):
        text = repr(value)
    elif isinstance(value, (dict, list)):
        try:
            text = json.dumps(value, separators=(", ", ": "), default=str)
        except (TypeError, ValueError):
            text = repr(value)
    else:
        text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


def _number(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool)


_TYPE_WORDS = {"integer": "an integer", "number": "a number", "string": "a string", "object": "a mapping",
               "array": "a list", "boolean": "true or false", "null": "null"}


def _type_words(types) -> str:
    types = [types] if isinstance(types, str) else list(types)
    return " or ".join(_TYPE_WORDS.get(t, t) for t in types)


def _fmt_bound(x) -> str:
    return repr(x) if isinstance(x, float) and not float(x).is_integer() else str(int(x)) if _number(x) else str(x)


class _Errors:
    """Problems by key path, in order; at most one kind of complaint per path."""

    def __init__(self):
        self.lines: list[str] = []
        self.paths: set[str] = set()

    def add(self, path, what: str, value=..., *, force: bool = False):
        p = path if isinstance(path, str) else _path(path)
        if p in self.paths and not force:
            return
        self.paths.add(p)
        head = p if value is ... else f"{p} = {_show(value)}"
        line = f"config error: {head}: {what}"
        if line not in self.lines:
            self.lines.append(line)

    def has(self, path) -> bool:
        return (path if isinstance(path, str) else _path(path)) in self.paths


def _schema_messages(err, out: _Errors):
    """One readable line per jsonschema error (recursing into anyOf/oneOf)."""
    path = list(err.absolute_path)
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
            if not any(s.validator == "type" and list(s.absolute_path) == path for s in errs):
                for s in errs:
                    _schema_messages(s, out)
                return
        types = [s.validator_value for s in subs if s.validator == "type" and list(s.absolute_path) == path]
        flat = []
        for t in types:
            flat += [t] if isinstance(t, str) else list(t)
        if err.schema.get("anyOf") == _validator().schema["$defs"]["angle"]["anyOf"]:
            out.add(path, f"must be {_ANGLE_HINT}", inst)
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
            out.add(path, f"must be {_ANGLE_HINT}", inst)
        else:
            out.add(path, "must use letters, digits, '-' and '_' and start with a letter or digit", inst)
    else:  # a keyword this module does not word specially
        out.add(path, err.message, inst)


# --------------------------------------------------------------------------- angles and times

def parse_angle(value) -> float:
    """An angle in radians from a number or a string 'pi', 'pi/5', '4pi/5', '-52pi/100', '4*pi/5', '0.3'."""
    if _number(value):
        x = float(value)
    elif isinstance(value, str) and _ANGLE_RE.match(value) and "\n" not in value:
        s = re.sub(r"\s+", "", value)
        sign = -1.0 if s.startswith("-") else 1.0
        s = s.lstrip("+-")
        if "pi" in s:
            coef, _, denom = s.partition("pi")
            coef = coef.rstrip("*")
            c = float(coef) if coef else 1.0
            d = float(denom[1:]) if denom else 1.0
            if d == 0.0:
                raise ConfigError(f"cannot read {value!r} as an angle: division by zero")
            x = sign * c * math.pi / d
        else:
            x = sign * float(s)
    else:
        raise ConfigError(f"cannot read {value!r} as an angle: expected {_ANGLE_HINT}")
    if not math.isfinite(x):
        raise ConfigError(f"cannot read {value!r} as an angle: not finite")
    return x


def _grid_size(store: dict, t_end: float) -> int:
    every = store.get("every")
    n = len(store.get("snapshots") or ()) + 2
    if every:
        n += int(math.floor(t_end / every * (1.0 + 1e-12) + TIME_TOL)) + 1
    return n


def store_times(store: dict, t_end: float) -> list[float]:
    """The sorted times a scene stores: 0, the grid k*every on [0, t_end], t_end and the snapshots.

    Times are rounded to 1e-9; times closer than 1e-9 (e.g. a snapshot on the
    grid) are one time. 0 and t_end are always included.
    """
    import numpy as np

    t_end = float(t_end)
    parts = [np.array([0.0, t_end]), np.asarray(store.get("snapshots") or [], dtype=float)]
    every = store.get("every")
    if every:
        every = float(every)
        n = int(math.floor(t_end / every * (1.0 + 1e-12) + TIME_TOL))
        grid = np.arange(n + 1) * every
        parts.append(grid[grid <= t_end + TIME_TOL])
    t = np.sort(np.concatenate(parts))
    keep = np.ones(t.size, dtype=bool)
    keep[1:] = np.diff(t) > TIME_TOL  # a time within TIME_TOL of the previous one is the same time
    t = np.round(t[keep], 9)
    t[0] = 0.0
    if abs(t[-1] - t_end) <= TIME_TOL:
        t[-1] = round(t_end, 9)
    return t.tolist()


# --------------------------------------------------------------------------- physical checks

def _finite(node, path, out: _Errors):
    if isinstance(node, dict):
        for k, v in node.items():
            _finite(v, path + [k], out)
    elif isinstance(node, list):
        for i, v in enumerate(node):
            _finite(v, path + [i], out)
    elif isinstance(node, float) and not math.isfinite(node):
        out.add(path, "must be a finite number", node)


def _entries(cfg, section) -> dict:
    sec = cfg.get(section)
    return {k: v for k, v in sec.items() if isinstance(v, dict)} if isinstance(sec, dict) else {}


def _alpha_of(cfg, entry) -> float | None:
    a = entry.get("alpha")
    if a is None and isinstance(cfg.get("defaults"), dict):
        a = cfg["defaults"].get("alpha")
    return float(a) if _number(a) else None


def _check_alpha(value, path, out):
    if _number(value) and not value > 1:
        out.add(path, "must be > 1 (Hertz exponent of (vhertz))", value)


def _check_N(value, path, out):
    if _number(value) and value < 2:
        out.add(path, "must be >= 2", value)


def _check_travelling(ini, N, bc, alpha, path, out):
    q_raw = ini.get("q")
    q = None
    if q_raw is not None:
        try:
            q = parse_angle(q_raw)
        except ConfigError as err:
            out.add(path + ["q"], "not an angle: " + str(err).split("as an angle: ", 1)[-1], q_raw)
    if q is not None:
        if not (-math.pi + 1e-12 < q <= math.pi + 1e-12):
            out.add(path + ["q"], f"must be in (-pi, pi], got q = {q:.10g} rad", q_raw)
        elif bc == "periodic" and isinstance(N, int) and N >= 2:
            m = q * N / (2.0 * math.pi)
            if abs(m - round(m)) > INTEGER_TOL:
                out.add(path + ["q"], f"with periodic ends q N/(2 pi) must be an integer (the wave must fit the "
                                      f"ring), got q N/(2 pi) = {m:.10g} (N = {N})", q_raw)
    a, om = ini.get("a"), ini.get("omega_tw")
    if a is not None and om is not None:
        out.add(path, f"give exactly one of a and omega_tw, got both (a = {_show(a)}, omega_tw = {_show(om)})")
    elif a is None and om is None:
        out.add(path, "give exactly one of a and omega_tw, got neither")
    elif om is not None and _number(om):
        if not om > 1:
            out.add(path + ["omega_tw"], "must be > 1 to derive a from (freq) (omega_tw = 1 + (2/tau0) "
                                         "a^(alpha-1) |sin(q/2)|^(alpha+1))", om)
        elif q is not None and abs(math.sin(q / 2.0)) < 1e-12:
            out.add(path + ["q"], "must not be 0 with omega_tw: (freq) gives omega_tw = 1 for every a when "
                                  "q = 0; give a instead of omega_tw", q_raw)
        elif alpha is not None and alpha > 1 and q is not None:
            from cradle.models import dps  # the amplitude must come out finite and positive
            try:
                a_derived = dps.amplitude_from_omega(float(om), q, alpha)
            except (ValueError, OverflowError, ZeroDivisionError) as err:
                out.add(path + ["omega_tw"], f"cannot derive a from (freq): {err}", om)
            else:
                if not (math.isfinite(a_derived) and a_derived > 0):
                    out.add(path + ["omega_tw"], f"(freq) gives a = {a_derived!r}, not a finite amplitude > 0", om)


def _check_breather(ini, scene, cfg, alpha, path, scene_path, out):
    om, amp = ini.get("omega_sw"), ini.get("amplitude")
    if om is not None and amp is not None:
        out.add(path, f"give exactly one of omega_sw and amplitude, got both "
                      f"(omega_sw = {_show(om)}, amplitude = {_show(amp)})")
    elif om is None and amp is None:
        out.add(path, "give exactly one of omega_sw and amplitude, got neither")
    if _number(om) and not om > 1:
        out.add(path + ["omega_sw"], "must be > 1 (mu = (omega_sw - 1) 2^alpha tau0 must be > 0)", om)
    N = scene.get("N")
    site = ini.get("site")
    if _number(site) and isinstance(N, int) and not 0 <= site < N:
        out.add(path + ["site"], f"must be a bead index in [0, N-1] = [0, {N - 1}]", site)
    name = ini.get("homoclinic")
    if not isinstance(name, str):
        return
    homs = _entries(cfg, "homoclinic")
    if name not in homs:
        known = ", ".join(homs) or "none"
        out.add(path + ["homoclinic"], f"no homoclinic entry of that name (homoclinic entries: {known})", name)
        return
    h = homs[name]
    for key in ("N", "bc"):
        if scene.get(key) is not None and h.get(key) is not None and scene.get(key) != h.get(key):
            out.add(scene_path + [key], f"must equal homoclinic.{name}.{key} = {_show(h.get(key))} "
                                        f"(the breather is built from that solution)", scene.get(key))
    h_alpha = _alpha_of(cfg, h)
    if alpha is not None and h_alpha is not None and alpha != h_alpha:
        out.add(scene_path + ["alpha"], f"must equal the alpha of homoclinic.{name} ({h_alpha!r}): the breather "
                                        f"is built from that solution", alpha)


def _check_packet(ini, N, path, out):
    """kind packet (loc1, left): the envelope must fit the chain and be centred on it."""
    if not isinstance(N, int) or N < 2:
        return
    width, centre = ini.get("width"), ini.get("centre")
    if _number(width) and width > N:
        out.add(path + ["width"], f"must be <= N = {N} (the envelope must fit the chain)", width)
    if _number(centre) and not 0 <= centre <= N - 1:
        out.add(path + ["centre"], f"must be in [0, N-1] = [0, {N - 1}]", centre)


def _check_pair(ini, N, path, out):
    """kind pair (loc1, right): the two copies must be distinct and the centre a site."""
    if not isinstance(N, int) or N < 2:
        return
    sep, centre = ini.get("separation"), ini.get("centre")
    if _number(sep) and not 1 <= sep < N:
        out.add(path + ["separation"], f"must be in [1, N-1] = [1, {N - 1}]", sep)
    if _number(centre) and not 0 <= centre < N:
        out.add(path + ["centre"], f"must be a site index in [0, N-1] = [0, {N - 1}]", centre)


def _check_scene(name, scene, cfg, out):
    path = ["scenes", name]
    N, bc = scene.get("N"), scene.get("bc", "periodic")
    _check_N(N, path + ["N"], out)
    if "alpha" in scene:
        _check_alpha(scene["alpha"], path + ["alpha"], out)
    alpha = _alpha_of(cfg, scene)
    t_end = scene.get("t_end")
    if _number(t_end) and not t_end > 0:
        out.add(path + ["t_end"], "must be > 0", t_end)
    t_ok = _number(t_end) and t_end > 0 and math.isfinite(t_end)
    store = scene.get("store")
    if isinstance(store, dict):
        snaps = store.get("snapshots")
        if isinstance(snaps, list):
            prev = None
            for i, t in enumerate(snaps):
                if not _number(t):
                    continue
                p = path + ["store", "snapshots", i]
                if t < 0:
                    out.add(p, "must be >= 0", t)
                elif t_ok and t > t_end + TIME_TOL:
                    out.add(p, f"must be <= t_end = {_show(t_end)}", t)
                elif prev is not None and not t > prev:
                    out.add(p, f"must be > the previous snapshot {_show(prev)} (snapshots must be strictly "
                               f"increasing)", t)
                prev = t
        every = store.get("every")
        if _number(every) and not every > 0:
            out.add(path + ["store", "every"], "must be > 0", every)
        elif t_ok and _number(every) and math.isfinite(every):
            n = _grid_size(store, t_end)
            if n > MAX_STORED_TIMES:
                out.add(path + ["store", "every"], f"stores ~{n} times on [0, t_end = {_show(t_end)}], more than "
                                                   f"{MAX_STORED_TIMES}", every)
    ini = scene.get("initial")
    if isinstance(ini, dict):
        if ini.get("kind") == "travelling":
            _check_travelling(ini, N, bc, alpha, path + ["initial"], out)
        elif ini.get("kind") == "breather":
            _check_breather(ini, scene, cfg, alpha, path + ["initial"], path, out)
        elif ini.get("kind") == "packet":
            _check_packet(ini, N, path + ["initial"], out)
        elif ini.get("kind") == "pair":
            _check_pair(ini, N, path + ["initial"], out)


def _physical(cfg: dict, out: _Errors):
    _finite(cfg, [], out)
    d = cfg.get("defaults")
    if isinstance(d, dict):
        _check_alpha(d.get("alpha"), ["defaults", "alpha"], out)
    # unique names across the sections a figure reads from
    seen: dict[str, str] = {}
    for section in SECTIONS:
        sec = cfg.get(section)
        if not isinstance(sec, dict):
            continue
        for name in sec:
            if name in seen:
                out.add([section, name], f"name {name!r} is also used by {seen[name]}.{name} (map, homoclinic "
                                         f"and scenes names must be unique)")
            else:
                seen[name] = section
    for name, entry in _entries(cfg, "map").items():
        if "alpha" in entry:
            _check_alpha(entry["alpha"], ["map", name, "alpha"], out)
        box, starts = entry.get("box"), entry.get("starts")
        points = [(["map", name, "starts", i], u) for i, u in enumerate(starts if isinstance(starts, list) else [])]
        line = entry.get("line")
        if isinstance(line, dict):
            points += [(["map", name, "line", end], line.get(end)) for end in ("from", "to")]
        if _number(box):
            for key, u in points:
                if isinstance(u, list) and all(_number(x) for x in u) and u and max(abs(x) for x in u) > box:
                    out.add(key, f"must lie in the box ||U||_inf <= box = {_show(box)}", u)
    for name, entry in _entries(cfg, "homoclinic").items():
        path = ["homoclinic", name]
        N = entry.get("N")
        _check_N(N, path + ["N"], out)
        if "alpha" in entry:
            _check_alpha(entry["alpha"], path + ["alpha"], out)
        c = entry.get("centre")
        if _number(c) and isinstance(N, int) and not 0 <= c < N:
            out.add(path + ["centre"], f"must be a site index in [0, N-1] = [0, {N - 1}]", c)
        sep = entry.get("separation")
        if entry.get("guess") == "double" and _number(sep) and isinstance(N, int) and not 1 <= sep < N:
            out.add(path + ["separation"], f"must be in [1, N-1] = [1, {N - 1}]", sep)
    for name, scene in _entries(cfg, "scenes").items():
        _check_scene(name, scene, cfg, out)
    _check_work_precision(cfg, out)
    _check_mi(cfg, out)
    figures = cfg.get("figures")
    if isinstance(figures, dict):
        scenes = _entries(cfg, "scenes")
        for label, fig in figures.items():
            if label not in KNOWN_FIGURES:
                out.add(["figures", label], f"unknown figure label {label!r} (known labels: "
                                            f"{', '.join(KNOWN_FIGURES)})")
            if not isinstance(fig, dict):
                continue
            names = fig.get("scenes")
            if not isinstance(names, list):
                continue
            for i, n in enumerate(names):
                if isinstance(n, str) and n not in seen:
                    near = difflib.get_close_matches(n, list(seen), n=1)
                    did = f"; did you mean {near[0]!r}?" if near else ""
                    out.add(["figures", label, "scenes", i], f"unknown scene: no map, homoclinic or scene entry of "
                                                             f"that name{did}", n)
            read = [n for n in names if isinstance(n, str) and n in scenes]
            times = fig.get("times")
            if not read or not isinstance(times, list):
                continue
            stored = []
            for n in read:
                s = scenes[n]
                if isinstance(s.get("store"), dict) and _number(s.get("t_end")) and s["t_end"] > 0 \
                        and not out.has(["scenes", n, "store", "every"]) and math.isfinite(s["t_end"]):
                    try:
                        stored += store_times(s["store"], s["t_end"])
                    except (TypeError, ValueError):
                        stored = None
                        break
                else:
                    stored = None
                    break
            if stored is None:
                continue
            import numpy as np
            stored = np.asarray(stored)
            for i, t in enumerate(times):
                if _number(t) and math.isfinite(t) and not np.any(np.abs(stored - t) <= TIME_TOL):
                    out.add(["figures", label, "times", i], f"not a stored time of {', '.join(read)} "
                                                            f"(add it to a store.snapshots list)", t)


def _check_work_precision(cfg: dict, out: _Errors):
    """work_precision.scenes name `scenes:` entries (their initial data are measured)."""
    wp = cfg.get("work_precision")
    if not isinstance(wp, dict) or not isinstance(wp.get("scenes"), dict):
        return
    scenes = _entries(cfg, "scenes")
    for name in wp["scenes"]:
        if name not in scenes:
            near = difflib.get_close_matches(name, list(scenes), n=1)
            did = f"; did you mean {near[0]!r}?" if near else ""
            out.add(["work_precision", "scenes", name], f"unknown scene: no `scenes:` entry of that name{did}")


def _check_mi(cfg: dict, out: _Errors):
    """beyond.mi_growth.scenes: periodic travelling-wave scenes (names are checked by
    cradle.analyses.migrowth.resolved_spec, so that a config with fewer scenes still validates);
    beyond.mi_statistics.<variant>: every q of the
    grid on every ring's wavenumber grid (q N / (2 pi) an integer), N even, start < stop, chunks <= count."""
    b = cfg.get("beyond")
    if not isinstance(b, dict):
        return
    mg = b.get("mi_growth")
    scenes = _entries(cfg, "scenes")
    if isinstance(mg, dict) and isinstance(mg.get("scenes"), list):
        for i, name in enumerate(mg["scenes"]):
            path = ["beyond", "mi_growth", "scenes", i]
            if name not in scenes:   # checked by cradle.analyses.migrowth.resolved_spec, when the target is built
                continue
            sc = scenes[name]
            ini = sc.get("initial") if isinstance(sc.get("initial"), dict) else {}
            if ini.get("kind") != "travelling" or sc.get("bc") != "periodic":
                out.add(path, "must be a travelling-wave scene on a periodic ring (initial.kind travelling, "
                              "bc periodic)", name)
    ms = b.get("mi_statistics")
    if not isinstance(ms, dict):
        return
    for variant in ("reduced", "full"):
        v = ms.get(variant)
        if not isinstance(v, dict):
            continue
        base = ["beyond", "mi_statistics", variant]
        g = v.get("q_over_pi")
        if not isinstance(g, dict) or not all(_number(g.get(k)) for k in ("start", "stop", "count")):
            continue
        if not g["start"] < g["stop"]:
            out.add(base + ["q_over_pi"], "need start < stop", g)
            continue
        count = int(g["count"])
        vals = [g["start"] + i * (g["stop"] - g["start"]) / (count - 1) for i in range(count)]
        if _number(v.get("chunks")) and v["chunks"] > count:
            out.add(base + ["chunks"], f"more batches than q values (count = {count})", v["chunks"])
        for j, N in enumerate(v.get("N") or []):
            if not isinstance(N, int):
                continue
            if N % 2:
                out.add(base + ["N", j], "must be even (Gamma* of the spatial DFT)", N)
                continue
            for x in vals:
                m = x * N / 2.0
                if abs(m - round(m)) > INTEGER_TOL:
                    out.add(base + ["q_over_pi"], f"q = {x:.10g} pi gives q N/(2 pi) = {m:.10g} for N = {N}: with "
                                                  f"periodic ends it must be an integer (choose start, stop, count "
                                                  f"so that the step is a multiple of 2/N)", g)
                    break


# --------------------------------------------------------------------------- public API

def validate(config: dict) -> dict:
    """A validated deep copy of ``config`` with the schema defaults filled in.

    Strings where a number, integer, boolean or null is expected are read as
    such first (``--config`` overrides arrive as strings), so ``N: "50"`` is
    50 but ``N: "fifty"`` is an error.

    Raises :class:`ConfigError` listing every problem found, one line each.
    """
    if config is None:
        config = {}
    if not isinstance(config, dict):
        raise ConfigError(f"config error: config = {_show(config)}: must be a mapping")
    cfg = _coerce(_validator().schema, copy.deepcopy(dict(config)))
    out = _Errors()
    for err in sorted(_validator().iter_errors(cfg), key=lambda e: [str(p) for p in e.absolute_path]):
        _schema_messages(err, out)
    cfg = _fill(_validator().schema, cfg)
    if not out.lines:  # every job's estimated memory, output and time within budget, before the physical
        budget.check(cfg)  # checks build stored-time arrays (cradle.pipeline.budget)
    _physical(cfg, out)
    if out.lines:
        raise ConfigError(out.lines)
    # a validated config validates to itself (tested): remember it, so that the resolved_* calls
    # the Snakefile makes with it, once per job, do not validate it again
    _remember(_key(cfg), copy.deepcopy(cfg))
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


def _validated(config: dict) -> dict:
    """validate(config), remembered for the last few configs (the Snakefile resolves one entry per job)."""
    key = _key(config)
    if key is None:
        return validate(config)
    if key not in _VALIDATED:
        _remember(key, validate(config))
    return _VALIDATED[key]


def _merged(base, override):
    """Deep merge of two mappings (override wins)."""
    out = copy.deepcopy(base) if isinstance(base, dict) else {}
    for k, v in (override or {}).items():
        out[k] = _merged(out.get(k), v) if isinstance(v, dict) and isinstance(out.get(k), dict) else copy.deepcopy(v)
    return out


def _entry(cfg, section, name):
    entries = cfg.get(section) or {}
    if name not in entries:
        known = ", ".join(entries) or "none"
        raise ConfigError(f"config error: {section}.{name}: no {section} entry of that name ({section} entries: "
                          f"{known})")
    return copy.deepcopy(entries[name])


def resolved_scene(config: dict, name: str) -> dict:
    """The fully resolved parameters of scene ``name`` (a plain, JSON-serialisable dict).

    Defaults merged in (alpha, exact, dps, max_energy_drift), ``initial.q`` in
    radians with the original text kept as ``initial.q_expr``, everything else
    as given, plus ``times``: the stored times (:func:`store_times`).
    """
    cfg = _validated(config)
    scene = _entry(cfg, "scenes", name)
    d = cfg["defaults"]
    out = {"name": name}
    out.update(scene)
    out["alpha"] = float(scene.get("alpha", d["alpha"]))
    out["exact"] = _merged(d["exact"], scene.get("exact"))
    out["dps"] = _merged(d["dps"], scene.get("dps"))
    out["max_energy_drift"] = float(scene.get("max_energy_drift", d["max_energy_drift"]))
    ini = out["initial"]
    if ini["kind"] == "travelling":
        q = ini["q"]
        ini["q_expr"] = q if isinstance(q, str) else repr(float(q))
        ini["q"] = parse_angle(q)
    out["times"] = store_times(scene["store"], scene["t_end"])
    return out


def resolved_homoclinic(config: dict, name: str) -> dict:
    """The fully resolved parameters of homoclinic entry ``name`` (alpha filled from defaults)."""
    cfg = _validated(config)
    entry = _entry(cfg, "homoclinic", name)
    return {"name": name, **entry, "alpha": float(entry.get("alpha", cfg["defaults"]["alpha"]))}


def resolved_map(config: dict, name: str) -> dict:
    """The fully resolved parameters of map entry ``name`` (alpha filled from defaults)."""
    cfg = _validated(config)
    entry = _entry(cfg, "map", name)
    return {"name": name, **entry, "alpha": float(entry.get("alpha", cfg["defaults"]["alpha"]))}


def load(path) -> dict:
    """Read a YAML config file and :func:`validate` it."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise ConfigError(f"config error: cannot read {str(path)!r}: {err.strerror}") from None
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as err:
        raise ConfigError(f"config error: {path}: not valid YAML: {' '.join(str(err).split())}") from None
    return validate(data)


def main(argv=None) -> int:
    """``python -m cradle.pipeline.config [config.yaml] [--scene|--homoclinic|--map NAME]``.

    Validates the config (exit status 1 and one line per problem on stderr if
    it is bad); with a NAME, prints that entry's resolved parameters as JSON.
    """
    import argparse

    parser = argparse.ArgumentParser(prog="python -m cradle.pipeline.config", description=main.__doc__.splitlines()[0])
    parser.add_argument("config", nargs="?", default="config.yaml")
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--scene", metavar="NAME")
    group.add_argument("--homoclinic", metavar="NAME")
    group.add_argument("--map", metavar="NAME")
    args = parser.parse_args(argv)
    try:
        cfg = load(args.config)
        if args.scene:
            print(json.dumps(resolved_scene(cfg, args.scene), indent=1))
        elif args.homoclinic:
            print(json.dumps(resolved_homoclinic(cfg, args.homoclinic), indent=1))
        elif args.map:
            print(json.dumps(resolved_map(cfg, args.map), indent=1))
        else:
            counts = ", ".join(f"{len(cfg.get(s) or {})} {s}" for s in (*SECTIONS, "figures"))
            print(f"{args.config}: OK ({counts})")
    except ConfigError as err:
        print(err, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
