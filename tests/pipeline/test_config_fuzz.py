"""The config fuzz: every leaf of config.yaml and of its generated schema, given each of seven bad values
(negative, zero, string, list, null, 1e300, bool), is either accepted or refused by the validation the
workflow runs, in one line per problem naming the key, never a traceback and never a hang.

A case substitutes one value for one leaf of the parsed config.yaml and runs what the Snakefile runs before
any job starts: :func:`cradle.pipeline.config.validate` (schema, budget estimates, physical checks), then,
when that accepts it, the planning of every analysis in each form (:func:`cradle.pipeline.config.analysis_reads`),
which must then accept it too (what validation passes must not fail at planning). Each case has a watchdog
of :data:`CASE_SECONDS`; the whole fuzz must take under :data:`TOTAL_SECONDS` of CPU time.

The leaves: every key the schema declares (followed into the entries config.yaml gives, and into the defaults
it fills in) and every leaf of config.yaml itself, list items included (the first of each list), one
representative per shape: the entries of a name-keyed section (scenes, map, homoclinic, figures) share their
keys, so each key is fuzzed in the first entry that has it, and for scenes in the first of each kind of
initial condition. A mapping (a section, an entry, a nested object) is fuzzed too, with the values of
:data:`NOT_MAPPINGS` (any number is the same wrong type there). ``CRADLE_FUZZ=all`` fuzzes every entry and
every list item instead (minutes, not part of the 60 s).
"""
from __future__ import annotations

import copy
import faulthandler
import os
import signal
import time
from pathlib import Path

import pytest
import yaml

from cradle.analyses.registry import ANALYSES
from cradle.pipeline import config as cc
from cradle.pipeline.config.reference import generated_schema
from cradle.specs.values import key_path

ROOT = Path(__file__).resolve().parents[2]

#: the seven bad values each leaf is given
VALUES = {"negative": -1, "zero": 0, "string": "fuzz", "list": ["fuzz", 1e300], "null": None, "huge": 1e300,
          "bool": True}
#: those a mapping (a section, an entry, a nested object) is given too: every number is the same wrong type there
NOT_MAPPINGS = ("string", "list", "null", "huge")
CASE_SECONDS = 10
TOTAL_SECONDS = 60
NAMED = ("map", "homoclinic", "scenes", "figures")   # the name-keyed sections of config.yaml


def _resolve(schema: dict, node: dict) -> dict:
    """A schema node with its local ``$ref`` followed (keywords beside the ``$ref`` kept)."""
    while isinstance(node, dict) and "$ref" in node:
        target = schema
        for part in node["$ref"][2:].split("/"):
            target = target[part]
        beside = {k: v for k, v in node.items() if k != "$ref"}
        node = {**target, **beside}
    return node


def _walk(schema: dict, node, path: list, shape: list, inst, out: dict) -> None:
    """Every leaf path under ``node`` -> its shape (objects and mappings count as leaves too: a scalar may
    be given for them), following the entries ``inst`` holds and the kind of a discriminated union. The
    shape names an entry of a mapping by '*' and marks the kind a union's keys belong to, so entries of
    the same shape share it."""
    node = _resolve(schema, node)
    if not isinstance(node, dict):
        return
    for sub in node.get("allOf", ()):
        kind = sub["if"]["properties"]["kind"]["const"] if "if" in sub else None
        if kind is not None and isinstance(inst, dict) and inst.get("kind") == kind:
            _walk(schema, sub["then"], path, shape + [("kind", kind)], inst, out)
    if path:
        out.setdefault(tuple(path), tuple(shape))
    props, extra = node.get("properties"), node.get("additionalProperties")
    if props:
        for key, sub in props.items():
            # a key of an analysis's reduced form has the declaration, hence the shape, of its full form's key
            same = shape if key == "reduced" and len(path) == 2 and path[0] == "beyond" else shape + [key]
            _walk(schema, sub, path + [key], same, inst.get(key) if isinstance(inst, dict) else None, out)
    elif isinstance(extra, dict):
        for name in (inst if isinstance(inst, dict) else ()):
            _walk(schema, extra, path + [name], shape + ["*"], inst[name], out)
    elif isinstance(inst, list) and isinstance(node.get("items"), dict):
        for i, item in enumerate(inst):
            _walk(schema, node["items"], path + [i], shape + [i], item, out)


def _config_leaves(node, path: list, out: list) -> None:
    if path:
        out.append(tuple(path))
    if isinstance(node, dict):
        for key, value in node.items():
            _config_leaves(value, path + [key], out)
    elif isinstance(node, list):
        for i, value in enumerate(node):
            _config_leaves(value, path + [i], out)


def leaves(raw: dict, filled: dict, every: bool = False) -> list[tuple]:
    """The leaf paths to fuzz (see the module docstring): one per shape, where config.yaml (or its defaults)
    gives it when some entry does, the first item of a list; with ``every``, all of them."""
    shapes: dict[tuple, tuple] = {}
    _walk(generated_schema(), generated_schema(), [], [], filled, shapes)
    given: list[tuple] = []
    _config_leaves(raw, [], given)
    for path in given:   # a key of config.yaml the schema does not declare is its own shape
        shapes.setdefault(path, path)
    if every:
        return list(shapes)
    reps: dict[tuple, tuple] = {}
    for path in sorted(shapes, key=lambda p: not _exists(filled, p)):
        if not any(isinstance(p, int) and p > 0 for p in path):
            reps.setdefault(shapes[path], path)
    return list(reps.values())


def _exists(node, path) -> bool:
    for part in path:
        if isinstance(node, dict) and part in node or isinstance(node, list) and isinstance(part, int) \
                and part < len(node):
            node = node[part]
        else:
            return False
    return True


def _get(node, path):
    """The value at ``path``, or None where the config (or its defaults) gives none."""
    return _get(node[path[0]], path[1:]) if path and _exists(node, path[:1]) else (node if not path else None)


def substituted(raw: dict, filled: dict, path: tuple, value) -> dict:
    """``raw`` with ``value`` at ``path``; a parent config.yaml leaves out is taken from the filled config
    (its defaults), so that only the one leaf is bad."""
    cfg = copy.deepcopy(raw)
    node, full = cfg, filled
    for part in path[:-1]:
        full = full.get(part, {}) if isinstance(full, dict) else full[part]
        if isinstance(node, dict) and part not in node:
            node[part] = copy.deepcopy(full)
        node = node[part]
    node[path[-1]] = _copied(value)
    return cfg


_ATOMS = frozenset({int, float, str, bool, type(None)})


def _copied(value):
    """A deep copy of ``value``; a list of plain values in one call (copy.deepcopy walks a list of 1e6 numbers
    item by item: a few tenths of a second of the case's CPU that would be the fuzz's, not the validation's)."""
    return list(value) if isinstance(value, list) and _ATOMS.issuperset(map(type, value)) else copy.deepcopy(value)


class Hang(Exception):
    pass


def cases(filled: dict, paths: list[tuple], values: dict, not_mappings: tuple[str, ...]):
    """Every (path, label, value) of a fuzz: each leaf given each of ``values``; a mapping (a section, an entry,
    an object) only those of ``not_mappings`` (any number is the same wrong type there)."""
    for path in paths:
        mapping = isinstance(_get(filled, path), dict)
        for label, value in values.items():
            if not mapping or label in not_mappings:
                yield path, label, value


def _alarm(signum, frame):
    raise Hang(f"no answer within {CASE_SECONDS} s")


def _names_key(line: str, path: tuple) -> bool:
    """Whether an error line is about the key at ``path``: it names the key, a key below it or the key (or
    entry) it belongs to, or it is about another key and names the entry (a figure's time that the
    scene's new snapshots no longer store)."""
    key = key_path(list(path))
    head = line.removeprefix("config error: ").split(" = ", 1)[0].split(": ", 1)[0]
    if head == key or head.startswith((key + ".", key + "[")) or key.startswith((head + ".", head + "[")):
        return True
    return len(path) > 1 and path[0] in NAMED and str(path[1]) in line


def _plan(cfg: dict, path: tuple) -> None:
    """What the Snakefile resolves when it plans the jobs of the analysis whose section holds ``path``, in each
    form (a value elsewhere renames no scene, so it changes no analysis's reads)."""
    if path[0] == "beyond" and len(path) > 1:
        for form in ANALYSES[path[1]].forms:
            cc.analysis_reads(cfg, path[1], form)


def run_case(raw: dict, filled: dict, path: tuple, value) -> tuple[str, str | None]:
    """("accepted" | "refused", the problem or None) for one case, under the watchdog."""
    cfg = substituted(raw, filled, path, value)
    signal.setitimer(signal.ITIMER_REAL, CASE_SECONDS)
    try:
        try:
            validated = cc.validate(cfg)
        except cc.ConfigError as err:
            lines = str(err).splitlines()
            if lines != err.errors or not all(line.startswith("config error: ") for line in lines):
                return "refused", f"not one line per problem: {str(err)!r}"
            if not any(_names_key(line, path) for line in lines):
                return "refused", f"no line names the key: {lines}"
            return "refused", None
        try:
            _plan(validated, path)
        except cc.ConfigError as err:
            return "accepted", f"validation accepted it, planning refused it: {err}"
        return "accepted", None
    except Hang as err:
        return "hang", str(err)
    except Exception as err:  # noqa: BLE001 -- any other exception is the failure this test looks for
        return "error", f"{type(err).__name__}: {err}"
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)


@pytest.fixture(scope="module")
def raw():
    return yaml.safe_load((ROOT / "config.yaml").read_text())


def test_config_fuzz(raw):
    filled = cc.validate(raw)
    paths = leaves(raw, filled, every=os.environ.get("CRADLE_FUZZ") == "all")
    previous = signal.signal(signal.SIGALRM, _alarm)
    # a hang inside C code (a huge integer power) never returns to the interpreter: dump and exit instead
    faulthandler.dump_traceback_later(CASE_SECONDS + 5, repeat=True, exit=True)
    counts: dict[str, int] = {}
    by_value: dict[tuple[str, str], int] = {}
    failures, slowest = [], (0.0, "")
    start, cpu = time.perf_counter(), time.process_time()
    try:
        for path, label, value in cases(filled, paths, VALUES, NOT_MAPPINGS):
            t0 = time.perf_counter()
            outcome, problem = run_case(raw, filled, path, value)
            took = time.perf_counter() - t0
            faulthandler.dump_traceback_later(CASE_SECONDS + 5, repeat=True, exit=True)
            case = f"{key_path(list(path))} = {label}"
            counts[outcome] = counts.get(outcome, 0) + 1
            by_value[label, outcome] = by_value.get((label, outcome), 0) + 1
            slowest = max(slowest, (took, case))
            if problem is not None:
                failures.append(f"{case}: {outcome}: {problem}")
    finally:
        faulthandler.cancel_dump_traceback_later()
        signal.signal(signal.SIGALRM, previous)
    total, cpu = time.perf_counter() - start, time.process_time() - cpu
    refused = ", ".join(f"{label} {by_value.get((label, 'refused'), 0)}" for label in VALUES)
    print(f"\nconfig fuzz: {len(paths)} leaves (mappings included) x {len(VALUES)} values "
          f"({len(NOT_MAPPINGS)} for a mapping) = {sum(counts.values())} cases "
          f"({', '.join(f'{n} {k}' for k, n in sorted(counts.items()))}) in {total:.1f} s ({cpu:.1f} s of CPU); "
          f"slowest: {slowest[1]} ({slowest[0]:.3f} s); refused by value: "
          f"{refused}")
    assert not failures, f"{len(failures)} failing cases:\n" + "\n".join(failures[:60])
    # the CPU time of this process: on a machine shared with other jobs the wall time is theirs too
    assert cpu < TOTAL_SECONDS or os.environ.get("CRADLE_FUZZ") == "all", f"the fuzz took {cpu:.1f} s of CPU"


@pytest.mark.parametrize("path, words", [
    # the hangs: a check computed 2 ** grid_log2 with the value the schema had refused
    (("beyond", "floquet", "grid_log2"), "must be <= 22"),
    (("beyond", "floquet", "convergence", "grid_log2"), "must be <= 22"),
    (("beyond", "theorem1", "grid_log2"), "must be <= 18"),
    (("beyond", "mi-statistics", "q_over_pi", "count"), "must be <= 1000"),
    (("beyond", "work-precision", "scenes", "tw-weak", "t_end"),
     "must be <= 4194304 (float64 tells stored times 1e-9 apart only below 2^22 = 4194304)"),
    (("homoclinic", "site", "N"), "must be <= 9007199254740992"),
    (("defaults", "max_energy_drift"), "must be <= 0.01"),
])
def test_a_huge_value_is_refused_by_its_bound_alone(raw, path, words):
    """1e300 where a size, an exponent, a count or a tolerance goes: one line, its bound, within a second; the
    checks across entries never see the value (an entry with a schema error is not checked further)."""
    cfg = substituted(raw, cc.validate(raw), path, 1e300)   # (the first validation builds the validators)
    t0 = time.perf_counter()
    with pytest.raises(cc.ConfigError) as err:
        cc.validate(cfg)
    assert str(err.value) == f"config error: {key_path(list(path))} = 1e+300: {words}"
    assert time.perf_counter() - t0 < 1.0
