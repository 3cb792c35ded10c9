"""The typed config declarations (cradle.pipeline.config): the committed schema is the generated one,
one default per setting, and the reliability checks of the validation layer (duplicate keys,
non-finite values reported once)."""
import copy
import dataclasses
import hashlib
import json
import math
from pathlib import Path

import pytest
import yaml

from cradle.analyses import breather_interactions, mi_statistics
from cradle.pipeline import config as cc
from cradle.pipeline.config import (
    beyond,
    breathers,
    dps_validity,
    floquet,
    movies,
    sections,
)
from cradle.scenes import spec as scenes
from cradle.specs.declare import plain

ROOT = Path(__file__).resolve().parents[2]
CONFIG = ROOT / "config.yaml"

# sha256 of every resolved parameter of config.yaml (see _everything_resolved). The move of the config
# into typed declarations changed none of them; a deliberate change of config.yaml or of a resolved_*
# function changes this hash: check the difference, then update it. (Updated once since: the new
# keys beyond.floquet.reduced and work_precision.reduced, the reduced forms `all` builds; every other
# value unchanged. Then issue 14: the new section beyond.breathers and its reduced form. Then issue 13: the new
# section beyond.breather_interactions, and the loc1 scenes set to the readings of docs/loc1-readings.md:
# loc1-pair site-centred copies 6 apart in phase, loc1-packet a cos^2 envelope. Then issue 16: the section
# movies: (no resolved scene changed). Then issue 15: the new section beyond.dps_validity; every other value
# unchanged. Then issue 21: the key beyond.mi_growth renamed beyond.mi-growth, its spec typed (plain() of it is
# the old dict; with the old key the hash is the old a61c41d8...). Then beyond.mi_statistics and
# beyond.breather_interactions renamed beyond.mi-statistics and beyond.breather-interactions, their specs typed,
# mi-statistics' full sweep at the top of its section (its `full:` gone) and its alpha its own (1.5, was null =
# defaults.alpha): plain() of each form is the old resolved dict, but for mi-statistics' key `variant` (the form).)
RESOLVED_SHA256 = "30a5b010c4a32c56775dffd704f14d7aaaa5d09672df843a28de89d4e90f1172"


@pytest.fixture(scope="module")
def raw():
    return yaml.safe_load(CONFIG.read_text())


def _everything_resolved(config) -> dict:
    """Every resolved entry and analysis spec of a config: what the jobs compute from."""
    cfg = cc.validate(config)
    return {
        "validated": cfg,
        "scenes": {n: cc.resolved_scene(cfg, n) for n in cfg["scenes"]},
        "homoclinic": {n: cc.resolved_homoclinic(cfg, n) for n in cfg["homoclinic"]},
        "map": {n: cc.resolved_map(cfg, n) for n in cfg["map"]},
        "theorem1": cc.resolved_theorem1(cfg),
        "mi_diagram": cc.resolved_mi_diagram(cfg),
        "mi_growth": plain(cc.analysis_spec(cfg, "mi-growth", "full")),
        "mi_statistics": {v: plain(cc.analysis_spec(cfg, "mi-statistics", v)) for v in ("reduced", "full")},
        "floquet": cc.resolved_floquet(cfg),
        "floquet_reduced": cc.resolved_floquet(cfg, "reduced"),
        "breathers": cc.resolved_breathers(cfg),
        "breathers_reduced": cc.resolved_breathers(cfg, "reduced"),
        "breather_interactions": {f: plain(cc.analysis_spec(cfg, "breather-interactions", f))
                                  for f in ("reduced", "full")},
        "dps_validity": cc.resolved_dps_validity(cfg),
        "dps_validity_reduced": cc.resolved_dps_validity(cfg, "reduced"),
        "work_precision": {n: cc.resolved_work_precision(cfg, n) for n in cfg["work_precision"]["scenes"]},
        "work_precision_reduced": {n: cc.resolved_work_precision(cfg, n, "reduced")
                                   for n in cfg["work_precision"]["reduced"]["scenes"]},
    }


# ------------------------------------------------------------------ declarations and the generated schema

def test_committed_schema_is_the_generated_one():
    """Regenerate with `python -m cradle.pipeline.config --write-schema` after changing a declaration."""
    committed = cc.schema_path().read_text(encoding="utf-8")
    assert json.loads(committed) == cc.generated_schema()
    assert committed == json.dumps(cc.generated_schema(), indent=2, ensure_ascii=False) + "\n"


def test_write_schema_writes_the_generated_text(tmp_path):
    out = cc.write_schema(tmp_path / "s.json")
    assert out.read_text(encoding="utf-8") == cc.schema_path().read_text(encoding="utf-8")


def test_declarations_are_frozen_and_every_field_described():
    classes = [c for m in (scenes, sections, beyond, floquet, breathers, mi_statistics, breather_interactions,
                           movies, dps_validity) for c in vars(m).values()
               if isinstance(c, type) and hasattr(c, "__schema_doc__")]
    assert len(classes) >= 20
    for cls in classes:
        obj_fields = dataclasses.fields(cls)
        assert cls.__dataclass_params__.frozen, cls
        assert cls.__schema_doc__, cls
        for f in obj_fields:
            assert f.metadata["doc"], f"{cls.__name__}.{f.name} has no description"


def test_one_default_per_setting_api_schema_and_config_agree(raw):
    """The integrators' defaults in the API, the declarations (hence the schema) and config.yaml."""
    import inspect

    from cradle.integrators import integrate_dps, integrate_lattice

    lattice = inspect.signature(integrate_lattice).parameters["method"].default
    dps = inspect.signature(integrate_dps).parameters["method"].default
    assert lattice == scenes.ExactIntegrator().method == raw["defaults"]["exact"]["method"] == "srkn6c"
    assert dps == scenes.DpsIntegrator().method == raw["defaults"]["dps"]["method"] == "dop853_numba"
    d = cc.schema()["properties"]["defaults"]["properties"]
    assert d["exact"]["properties"]["method"]["default"] == lattice
    assert d["dps"]["properties"]["method"]["default"] == dps


def test_removing_the_defaults_section_changes_nothing(raw):
    """config.yaml's `defaults:` restates the declared defaults: without it, every resolved parameter of
    every scene, entry and analysis is the same."""
    bare = copy.deepcopy(raw)
    del bare["defaults"]
    assert _everything_resolved(bare) == _everything_resolved(raw)


def test_resolved_parameters_of_config_yaml_unchanged(raw):
    text = json.dumps(_everything_resolved(raw), sort_keys=True, separators=(",", ":"))
    assert hashlib.sha256(text.encode()).hexdigest() == RESOLVED_SHA256


def test_a_scene_override_of_the_integrator_is_not_filled_with_declared_defaults(raw):
    """A scene's `exact:` is merged over defaults.exact: a key it does not give comes from there, even
    when defaults.exact differs from the declared default."""
    cfg = copy.deepcopy(raw)
    cfg["defaults"]["exact"]["rtol"] = 1e-8
    cfg["scenes"]["tw-weak"]["exact"] = {"method": "dop853"}
    assert cc.resolved_scene(cfg, "tw-weak")["exact"] == {"method": "dop853", "dt_factor": None, "rtol": 1e-8}


# ------------------------------------------------------------------ reliability of the validation layer

def test_duplicate_yaml_key_is_refused_with_its_line(tmp_path, capsys):
    text = CONFIG.read_text().replace("  alpha: 1.5 ", "  alpha: 1.5\n  alpha: 2.0 ", 1)
    p = tmp_path / "dup.yaml"
    p.write_text(text)
    line = 1 + text.splitlines().index("  alpha: 2.0 " + text.split("  alpha: 2.0 ", 1)[1].splitlines()[0])
    with pytest.raises(cc.ConfigError, match=rf"line {line}: key 'alpha' given twice.*first on line {line - 1}"):
        cc.load(p)
    assert cc.main([str(p)]) == 1
    assert f"line {line}: key 'alpha' given twice" in capsys.readouterr().err


def test_same_key_in_different_mappings_is_fine(tmp_path):
    p = tmp_path / "ok.yaml"
    p.write_text("map:\n  a: {box: 1.0, iterations: 2, starts: [[0.0, 0.1]]}\n"
                 "  b: {box: 1.0, iterations: 2, starts: [[0.0, 0.1]]}\n")
    assert set(cc.load(p)["map"]) == {"a", "b"}


def _lines(cfg):
    with pytest.raises(cc.ConfigError) as info:
        cc.validate(cfg)
    return info.value.errors


def test_nan_alpha_is_reported_once(raw):
    """A nan alpha is not != the alpha of the homoclinic entries: one line, where it is written."""
    cfg = copy.deepcopy(raw)
    cfg["defaults"]["alpha"] = math.nan
    assert _lines(cfg) == ["config error: defaults.alpha = nan: must be a finite number"]
    cfg = copy.deepcopy(raw)
    cfg["scenes"]["breather-small"]["alpha"] = "nan"   # as from --config
    assert _lines(cfg) == ["config error: scenes.breather-small.alpha = nan: must be a finite number"]


@pytest.mark.parametrize("where,value", [
    (("scenes", "tw-weak", "t_end"), math.inf), (("scenes", "tw-weak", "t_end"), math.nan),
    (("scenes", "tw-weak", "store", "every"), math.inf), (("scenes", "tw-weak", "store", "snapshots", 0), math.nan),
    (("work_precision", "scenes", "tw-weak", "t_end"), math.inf), (("figures", "plot4-5", "times", 0), math.nan),
    (("beyond", "mi-statistics", "t_end"), "inf"),
])
def test_non_finite_times_are_refused_once(raw, where, value):
    cfg = copy.deepcopy(raw)
    node = cfg
    for k in where[:-1]:
        node = node[k]
    node[where[-1]] = value
    lines = _lines(cfg)
    assert len(lines) == 1, lines
    head = ".".join(map(str, where)) if isinstance(where[-1], str) else \
        ".".join(map(str, where[:-1])) + f"[{where[-1]}]"
    assert lines[0].startswith(f"config error: {head} = ") and lines[0].endswith("must be a finite number")


def test_config_yaml_beyond_restates_the_defaults_as_its_comment_says(raw):
    """config.yaml says that under `beyond:` only theorem1.scenes and mi_growth.scenes differ from the
    declared defaults, and that work_precision's compare_every, repeat_time and reference restate them."""
    declared = cc.validate({"map": {"m": {"box": 1.0, "iterations": 2, "starts": [[0.0, 0.1]]}}})
    given = copy.deepcopy(raw["beyond"])
    for section in ("theorem1", "mi-growth"):
        assert given[section].pop("scenes")
    for section, values in given.items():
        for key, value in values.items():
            assert declared["beyond"][section][key] == value, f"beyond.{section}.{key}"
    for key in ("compare_every", "repeat_time", "reference"):
        assert raw["work_precision"][key] == declared["work_precision"][key], key


def test_typed_config_is_frozen_and_picks_the_kind_of_each_initial_condition(raw):
    c = cc.typed(raw)
    assert isinstance(c, sections.Config) and isinstance(c.defaults.exact, scenes.ExactIntegrator)
    kinds = {name: type(s.initial) for name, s in c.scenes.items()}
    assert kinds["tw-weak"] is scenes.Travelling and kinds["breather-small"] is scenes.Breather
    assert kinds["loc1-packet"] is scenes.Packet and kinds["loc1-pair"] is scenes.Pair
    assert c.scenes["tw-weak-noise"].initial.noise == scenes.Noise(kind="uniform", amplitude=0.5, seed=20110605)
    assert c.map["traj2-8"].line.from_ == [0.2, -0.1] and c.beyond.mi_statistics.q_over_pi.count == 21
    with pytest.raises(dataclasses.FrozenInstanceError):
        c.defaults.alpha = 2.0


@pytest.mark.parametrize("section,key,value,words", [
    ("theorem1", "q", ["pi/5", "-pi/2"], "beyond.theorem1.q[1] = '-pi/2': must be in (0, pi]"),
    ("theorem1", "a_max", 1e-9, "beyond.theorem1.a_max = 1e-09: must exceed a_min = 1e-08"),
    ("theorem1", "grid_log2", 10, "beyond.theorem1.grid_log2 = 10: 2^grid_log2 must be >= 8 x"),
    ("mi_diagram", "check_pairs", [[70, 10], [250, 3]], "beyond.mi_diagram.check_pairs[1] = [250, 3]: need 0 <"),
    ("mi_diagram", "check_pairs", [[10, 150]], "beyond.mi_diagram.check_pairs[0] = [10, 150]: stable for alpha"),
    ("floquet", "q_max", "0.3pi", "beyond.floquet.q_max = '0.3pi': must exceed q_min = '0.4pi'"),
    ("floquet", "small_q", ["3pi/5", "pi"], "beyond.floquet.small_q[1] = 'pi': must be in (0, pi)"),
    ("mi-statistics", "reduced", {"N": [201]}, "beyond.mi-statistics.reduced.N[0] = 201: must be even"),
])
def test_analysis_checks_are_one_line_at_validation(raw, section, key, value, words):
    """The checks the analysis modules used to make when their target was built, now made with the
    rest of the config: one line naming the key and the value."""
    cfg = copy.deepcopy(raw)
    cfg["beyond"][section][key] = value
    lines = _lines(cfg)
    assert len(lines) == 1 and words in lines[0], lines


def test_analysis_scene_names_are_checked_when_resolved(raw):
    """Names of scenes are checked when the analysis is resolved, so a config with fewer scenes (a
    test's) still validates."""
    cfg = copy.deepcopy(raw)
    cfg["beyond"]["theorem1"]["scenes"] = ["tw-weak", "fini"]
    with pytest.raises(cc.ConfigError, match=r"beyond\.theorem1\.scenes\[1\] = 'fini': not a travelling-wave"):
        cc.resolved_theorem1(cfg)
    cfg["beyond"]["theorem1"]["scenes"] = ["tw-wek"]
    with pytest.raises(cc.ConfigError, match=r"scenes\[0\] = 'tw-wek': unknown scene.*did you mean 'tw-weak'"):
        cc.resolved_theorem1(cfg)
    cfg["beyond"]["mi-growth"]["scenes"] = []
    with pytest.raises(cc.ConfigError, match=r"beyond\.mi-growth\.scenes is empty"):
        cc.analysis_reads(cfg, "mi-growth", "full")
    with pytest.raises(cc.ConfigError, match=r"beyond\.mi-statistics: unknown form 'tiny' \(forms: reduced, full\)"):
        cc.analysis_spec(raw, "mi-statistics", "tiny")
