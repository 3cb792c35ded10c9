"""A job rebuilds its typed spec from the plain values of its ``params:`` (workflow/scripts): the same values back,
for every entry and analysis form of config.yaml. (benchmarks/config_dump.py compares two checkouts' resolved
configs across a refactoring.)"""
from pathlib import Path

from cradle.analyses.registry import ANALYSES, FULL, form_spec
from cradle.pipeline import config as cc
from cradle.scenes.spec import HomoclinicEntry, MapEntry, Scene
from cradle.specs.declare import from_plain, plain

ROOT = Path(__file__).resolve().parents[2]


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

