"""The resolved config is unchanged by a refactoring of the config code: the plain form of every scene,
homoclinic and map entry, figure and analysis spec (each form, with what it reads) that config.yaml resolves to,
with each number's type, equals the dump committed in tests/specs/fixtures/config_dump.json. Those values are
what the jobs' ``params:`` carry, so equal dumps mean bitwise equal outputs. A deliberate change of a resolved
value rewrites the dump: ``python tests/specs/test_config_dump.py > tests/specs/fixtures/config_dump.json``."""
import json
import sys
from pathlib import Path

from cradle.analyses.registry import ANALYSES, FULL, form_spec
from cradle.pipeline import config as cc
from cradle.scenes.spec import HomoclinicEntry, MapEntry, Scene
from cradle.specs.declare import from_plain, plain

ROOT = Path(__file__).resolve().parents[2]
DUMP = Path(__file__).parent / "fixtures" / "config_dump.json"


def typed_json(x):
    """``x`` as JSON that keeps an int and a float apart (``1`` and ``1.0`` are different parameters)."""
    if isinstance(x, dict):
        return {str(k): typed_json(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [typed_json(v) for v in x]
    if x is None or isinstance(x, (bool, str)):
        return x
    if isinstance(x, int):
        return {"int": x}
    if isinstance(x, float):
        return {"float": repr(x)}
    return {"other": repr(x)}


def dump(path=ROOT / "config.yaml") -> dict:
    """Every resolved entry and analysis form of the config at ``path``, as plain values."""
    raw = cc.read_yaml(path)
    config = cc.validate(raw)
    out: dict = {"scenes": {}, "homoclinic": {}, "map": {}, "figures": {}, "analyses": {}}
    for name in raw.get("scenes", {}):
        out["scenes"][name] = plain(cc.scene(raw, name))
    for name in raw.get("homoclinic", {}):
        out["homoclinic"][name] = plain(cc.homoclinic(raw, name))
    for name in raw.get("map", {}):
        out["map"][name] = plain(cc.map_entry(raw, name))
    for label, figure in config["figures"].items():
        out["figures"][label] = plain(figure)
    for a in ANALYSES.values():
        for form in a.forms:
            spec = cc.analysis_spec(raw, a.name, form)
            reads = cc.analysis_reads(raw, a.name, form)
            out["analyses"][f"{a.name}/{form}"] = {
                "spec": plain(spec), "class": type(spec).__name__,
                "reads": {k: [r.kind, [list(n) for n in r.names]] for k, r in reads.items()}}
    out["movies"] = plain(dict(config["movies"]))
    out["budget"] = plain(config["budget"])
    return typed_json(out)


def test_config_yaml_resolves_as_dumped():
    assert dump() == json.loads(DUMP.read_text(encoding="utf-8"))


def test_a_job_rebuilds_its_spec_from_its_plain_values():
    """What a job does with its ``params:`` (workflow/scripts): the same plain values back."""
    raw = cc.read_yaml(ROOT / "config.yaml")
    for section, cls, resolve in (("scenes", Scene, cc.scene), ("homoclinic", HomoclinicEntry, cc.homoclinic),
                                  ("map", MapEntry, cc.map_entry)):
        for name in raw[section]:
            spec = resolve(raw, name)
            assert from_plain(cls, plain(spec)) == spec
    for a in ANALYSES.values():
        for form in a.forms:
            spec = cc.analysis_spec(raw, a.name, form)
            # rebuilt, a spec takes its declared overrides again: its full form is the form it was
            assert plain(form_spec(from_plain(type(spec), plain(spec)), FULL)) == plain(spec)


if __name__ == "__main__":
    sys.stdout.write(json.dumps(dump(), indent=1, sort_keys=True) + "\n")
