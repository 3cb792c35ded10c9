"""The resolved config as plain JSON, to compare two checkouts across a refactoring of the config code.

The plain form of every scene, homoclinic and map entry, figure and analysis spec (each form, with what it
reads) that a config resolves to, with each number's type. Those values are what the jobs' ``params:`` carry,
so equal dumps of two checkouts mean the same jobs::

    python benchmarks/config_dump.py > before.json      # in the old checkout
    python benchmarks/config_dump.py | diff before.json -

Not a test: a committed dump of the whole config would have to be rewritten for every new key or analysis.
"""
import json
import sys
from pathlib import Path

from cradle.analyses.registry import ANALYSES
from cradle.pipeline import config as cc
from cradle.specs.declare import plain

ROOT = Path(__file__).resolve().parents[1]


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


if __name__ == "__main__":
    config_path = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "config.yaml"
    sys.stdout.write(json.dumps(dump(config_path), indent=1, sort_keys=True) + "\n")
