"""The typed config declarations (cradle.pipeline.config): the committed schema is the generated one,
one default per setting, and the reliability checks of the validation layer (duplicate keys,
non-finite values reported once)."""
import copy
import dataclasses
import json
import math
from pathlib import Path

import pytest
import yaml

from cradle.analyses import (
    breather_interactions,
    breathers_spec,
    dps_validity,
    floquet_spec,
    mi_statistics,
    paper_checks,
    work_precision,
)
from cradle.analyses.registry import FULL, REDUCED
from cradle.pipeline import config as cc
from cradle.pipeline.config import movies, sections
from cradle.pipeline.config.reference import generated_schema, schema_path, write_schema
from cradle.scenes import spec as scenes
from cradle.specs.declare import from_plain, plain, plain as spec_plain

ROOT = Path(__file__).resolve().parents[2]
CONFIG = ROOT / "config.yaml"

@pytest.fixture(scope="module")
def raw():
    return yaml.safe_load(CONFIG.read_text())


def _everything_resolved(config) -> dict:
    """The plain values of every entry and of each form of every analysis of a config: what the jobs compute
    from, their params and their files' parameters."""
    from cradle.analyses.registry import ANALYSES

    cfg = cc.validate(config)
    out = {f"{section}/{name}": plain(fn(cfg, name)) for section, fn in
           (("scenes", cc.scene), ("homoclinic", cc.homoclinic), ("map", cc.map_entry)) for name in cfg[section]}
    out.update({f"beyond/{a.name}/{form}": plain(cc.analysis_spec(cfg, a.name, form))
                for a in ANALYSES.values() for form in a.forms})
    return out


# ------------------------------------------------------------------ declarations and the generated schema

def test_committed_schema_is_the_generated_one():
    """Regenerate with `python -m cradle.pipeline.config --write-schema` after changing a declaration."""
    committed = schema_path().read_text(encoding="utf-8")
    assert json.loads(committed) == generated_schema()
    assert committed == json.dumps(generated_schema(), indent=2, ensure_ascii=False) + "\n"


def test_the_schema_is_a_valid_json_schema():
    """The generated schema is valid under JSON Schema 2020-12's meta-schema (checked here once, not by every
    validation)."""
    from jsonschema import Draft202012Validator

    Draft202012Validator.check_schema(generated_schema())


def test_write_schema_writes_the_generated_text(tmp_path):
    out = write_schema(tmp_path / "s.json")
    assert out.read_text(encoding="utf-8") == schema_path().read_text(encoding="utf-8")


def test_declarations_are_frozen_and_every_field_described():
    modules = (scenes, sections, floquet_spec, breathers_spec, mi_statistics, breather_interactions, movies,
               dps_validity, work_precision, paper_checks)
    classes = [c for m in modules for c in vars(m).values()
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
    filled = cc.validate(raw)["defaults"]   # config.yaml leaves them to the declarations
    assert lattice == scenes.ExactIntegrator().method == filled["exact"]["method"] == "srkn6c"
    assert dps == scenes.DpsIntegrator().method == filled["dps"]["method"] == "dop853_numba"
    d = generated_schema()["properties"]["defaults"]["properties"]
    assert d["exact"]["properties"]["method"]["default"] == lattice
    assert d["dps"]["properties"]["method"]["default"] == dps


def test_restating_the_declared_defaults_changes_nothing(raw):
    """Writing the declared defaults out (`defaults:`, as config.yaml did before it stated only what differs)
    changes no resolved parameter of any scene, entry or analysis."""
    full = copy.deepcopy(raw)
    full["defaults"] = {"alpha": 1.5, "exact": {"method": "srkn6c", "dt_factor": None, "rtol": 1e-10},
                        "dps": {"method": "dop853_numba", "rtol": 1e-10}, "max_energy_drift": 1e-6}
    assert _everything_resolved(full) == _everything_resolved(raw)


def test_a_scene_s_plain_values_are_its_resolved_keys(raw):
    """What the simulate rule's params carry and its files store: every key of the scene, its defaults filled
    in (alpha, the integrators, max_energy_drift), numbers as their declared type, the store as written (not the
    stored times), sorted."""
    assert plain(cc.scene(raw, "tw-weak")) == {
        "N": 50, "alpha": 1.5, "bc": "periodic", "dps": {"method": "dop853_numba", "rtol": 1e-10},
        "exact": {"dt_factor": None, "method": "srkn6c", "rtol": 1e-10},
        "initial": {"kind": "travelling", "omega_tw": 1.01, "phi": 0.0, "q": "pi/5"}, "max_energy_drift": 1e-6,
        "store": {"every": 0.1, "snapshots": [333.7, 621.95]}, "t_end": 621.95}
    assert plain(cc.homoclinic(raw, "double")) == {"N": 50, "alpha": 1.5, "amplitude": 0.1, "bc": "periodic",
                                                   "guess": "double", "mu": 1.0, "separation": 9}


def test_a_reduced_form_is_the_full_one_with_its_overrides(raw):
    """Each analysis's reduced form differs from its full form exactly in the keys its declaration gives a
    reduced value and those config.yaml gives under `reduced:`; neither form keeps the overrides."""
    from cradle.analyses.registry import ANALYSES
    from cradle.specs.declare import reduced_defaults

    for a in ANALYSES.values():
        if REDUCED not in a.forms:
            continue
        full, reduced = (plain(cc.analysis_spec(raw, a.name, form)) for form in (FULL, REDUCED))
        overrides = {**reduced_defaults(a.spec), **raw["beyond"].get(a.name, {}).get("reduced", {})}
        assert "reduced" not in full and "reduced" not in reduced, a.name
        assert {k: v for k, v in reduced.items() if k not in overrides} == \
            {k: v for k, v in full.items() if k not in overrides}, a.name
        assert set(overrides) <= set(reduced), a.name


def test_a_key_given_as_all_names_every_entry_in_name_order(raw):
    spec = cc.analysis_spec(raw, "paper-checks", FULL)
    assert spec.scenes == sorted(raw["scenes"]) and spec.homoclinic == sorted(raw["homoclinic"])


def test_a_scene_override_of_the_integrator_is_not_filled_with_declared_defaults(raw):
    """A scene's `exact:` is merged over defaults.exact: a key it does not give comes from there, even
    when defaults.exact differs from the declared default."""
    cfg = copy.deepcopy(raw)
    cfg.setdefault("defaults", {}).setdefault("exact", {})["rtol"] = 1e-8
    cfg["scenes"]["tw-weak"]["exact"] = {"method": "dop853"}
    assert cc.scene(cfg, "tw-weak").exact == scenes.ExactIntegrator(method="dop853", dt_factor=None, rtol=1e-8)


# ------------------------------------------------------------------ typed, resolved entries

def test_every_scene_resolves_to_a_typed_scene_equal_to_its_plain_values(raw):
    """cc.scene: defaults filled (alpha, max_energy_drift numbers, complete integrators), and plain ->
    from_plain gives the same scene back (what a rule passes to its script)."""
    for name in raw["scenes"]:
        s = cc.scene(raw, name)
        assert isinstance(s, scenes.Scene) and isinstance(s.alpha, float) and isinstance(s.max_energy_drift, float)
        assert isinstance(s.exact, scenes.ExactIntegrator) and isinstance(s.dps, scenes.DpsIntegrator)
        assert s.times[0] == 0.0 and s.times[-1] == round(s.t_end, 9), name
        values = spec_plain(s)
        assert "times" not in values and json.loads(json.dumps(values)) == values
        back = from_plain(scenes.Scene, values)
        assert back == s and back.times == s.times


def test_typed_homoclinic_and_map_entries_have_alpha_filled(raw):
    for name in raw["homoclinic"]:
        h = cc.homoclinic(raw, name)
        assert isinstance(h, scenes.HomoclinicEntry) and from_plain(scenes.HomoclinicEntry, spec_plain(h)) == h
        assert h.alpha == 1.5
    for name in raw["map"]:
        m = cc.map_entry(raw, name)
        assert isinstance(m, scenes.MapEntry) and from_plain(scenes.MapEntry, spec_plain(m)) == m
        assert m.alpha == 1.5
    assert cc.homoclinic(raw, "double").alpha == 1.5 and cc.map_entry(raw, "traj2-8").line.count == 40


def test_plain_values_of_a_scene_ignore_the_order_of_config_keys(raw):
    """A rule's params are the sorted plain values: reordering config.yaml reruns nothing."""
    cfg = copy.deepcopy(raw)
    cfg["scenes"] = {n: dict(reversed(list(s.items()))) for n, s in cfg["scenes"].items()}
    cfg["scenes"]["tw-weak"]["initial"] = dict(reversed(list(cfg["scenes"]["tw-weak"]["initial"].items())))
    for name in raw["scenes"]:
        assert json.dumps(spec_plain(cc.scene(cfg, name))) == json.dumps(spec_plain(cc.scene(raw, name))), name


def test_typed_entries_refuse_unknown_names_and_bad_plain_values(raw):
    for fn in (cc.scene, cc.homoclinic, cc.map_entry):
        with pytest.raises(cc.ConfigError, match="nosuch"):
            fn(raw, "nosuch")
    values = {**spec_plain(cc.scene(raw, "tw-weak")), "N": 1}
    with pytest.raises(cc.ConfigError, match=r"^config error: Scene\.N = 1: "):
        from_plain(scenes.Scene, values)


# ------------------------------------------------------------------ reliability of the validation layer

def test_duplicate_yaml_key_is_refused_with_its_line(tmp_path, capsys):
    text = CONFIG.read_text().replace("    N: 50 ", "    N: 50\n    N: 60 ", 1)
    p = tmp_path / "dup.yaml"
    p.write_text(text)
    line = 1 + text.splitlines().index("    N: 60 " + text.split("    N: 60 ", 1)[1].splitlines()[0])
    with pytest.raises(cc.ConfigError, match=rf"line {line}: key 'N' given twice.*first on line {line - 1}"):
        cc.load(p)
    assert cc.main([str(p)]) == 1
    assert f"line {line}: key 'N' given twice" in capsys.readouterr().err


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
    cfg.setdefault("defaults", {})["alpha"] = math.nan
    assert _lines(cfg) == ["config error: defaults.alpha = nan: must be a finite number"]
    cfg = copy.deepcopy(raw)
    cfg["scenes"]["breather-small"]["alpha"] = "nan"   # as from --config
    assert _lines(cfg) == ["config error: scenes.breather-small.alpha = nan: must be a finite number"]


@pytest.mark.parametrize("where,value", [
    (("scenes", "tw-weak", "t_end"), math.inf), (("scenes", "tw-weak", "t_end"), math.nan),
    (("scenes", "tw-weak", "store", "every"), math.inf), (("scenes", "tw-weak", "store", "snapshots", 0), math.nan),
    (("beyond", "work-precision", "scenes", "tw-weak", "t_end"), math.inf),
    (("figures", "plot4-5", "times", 0), math.nan),
    (("beyond", "mi-statistics", "t_end"), "inf"),
])
def test_non_finite_times_are_refused_once(raw, where, value):
    cfg = copy.deepcopy(raw)
    node = cfg
    for k in where[:-1]:
        node = node.setdefault(k, {}) if isinstance(k, str) else node[k]   # a section config.yaml leaves out
    node[where[-1]] = value
    lines = _lines(cfg)
    assert len(lines) == 1, lines
    head = ".".join(map(str, where)) if isinstance(where[-1], str) else \
        ".".join(map(str, where[:-1])) + f"[{where[-1]}]"
    assert lines[0].startswith(f"config error: {head} = ") and lines[0].endswith("must be a finite number")


def test_config_yaml_states_only_what_differs_from_the_defaults(raw):
    """config.yaml writes under `beyond:` and `movies:` only values that differ from the declared defaults
    (docs/config-reference.md has the rest); `defaults:` is left to its declarations."""
    declared = cc.validate({"map": {"m": {"box": 1.0, "iterations": 2, "starts": [[0.0, 0.1]]}}})
    assert "defaults" not in raw
    for section, values in raw["beyond"].items():
        for key, value in values.items():   # a key without a declared default (desk-toy's cradle) differs from it
            assert declared["beyond"][section].get(key) != value, f"beyond.{section}.{key} restates its default"
    for key, value in raw["movies"].items():
        assert declared["movies"][key] != value, f"movies.{key} restates its default"


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
    ("mi-diagram", "check_pairs", [[70, 10], [250, 3]], "beyond.mi-diagram.check_pairs[1] = [250, 3]: need 0 <"),
    ("mi-diagram", "check_pairs", [[10, 150]], "beyond.mi-diagram.check_pairs[0] = [10, 150]: stable for alpha"),
    ("theorem1", "scenes", ["tw-weak", "fini"], "beyond.theorem1.scenes[1] = 'fini': not a travelling-wave scene"),
    ("floquet", "q_max", "0.3pi", "beyond.floquet.q_max = '0.3pi': must exceed q_min = '0.4pi'"),
    ("floquet", "small_q", ["3pi/5", "pi"], "beyond.floquet.small_q[1] = 'pi': must be in (0, pi)"),
    ("mi-statistics", "reduced", {"N": [201]}, "beyond.mi-statistics.reduced.N[0] = 201: must be even"),
    # the reduced form reports the keys it replaces, once; what it keeps of the full form is said there only
    ("floquet", "reduced", {"small_q": ["pi"]}, "beyond.floquet.reduced.small_q[0] = 'pi': must be in (0, pi)"),
    ("floquet", "ring_k", 20, "beyond.floquet.ring_k = 20: need 0 < ring_k < ring_N = 20"),
    ("breathers", "reduced", {"omegas": [1.2, 1.1]}, "beyond.breathers.reduced.omegas = [1.2, 1.1]: must be strictly"),
])
def test_analysis_checks_are_one_line_at_validation(raw, section, key, value, words):
    """The checks the analysis modules used to make when their target was built, now made with the
    rest of the config: one line naming the key and the value."""
    cfg = copy.deepcopy(raw)
    cfg["beyond"].setdefault(section, {})[key] = value
    lines = _lines(cfg)
    assert len(lines) == 1 and words in lines[0], lines


def test_an_entry_with_a_schema_error_is_not_checked_further(raw):
    """The checks run on the typed objects of the entries the schema passed: a bad value is one line, with no
    line about what follows from it (mi-growth does not call fft344 'not a travelling wave' for a misspelt
    kind, the breathers do not compare their N with homoclinic.bond.N = 0.3, figure fft344 does not look for
    its times in a store that is not a list) and no traceback (a q grid of 1e9 points is not built)."""
    cfg = copy.deepcopy(raw)
    cfg["scenes"]["tw-weak"]["store"]["snapshots"] = 3
    cfg["scenes"]["fft344"]["initial"]["kind"] = "travelling-wave"
    cfg["homoclinic"]["bond"]["N"] = 0.3
    cfg["beyond"].setdefault("mi-statistics", {})["q_over_pi"] = {"start": 0.45, "stop": 0.65, "count": 1e9}
    assert _lines(cfg) == [
        "config error: beyond.mi-statistics.q_over_pi.count = 1000000000.0: must be <= 1000",
        "config error: homoclinic.bond.N = 0.3: must be an integer",
        "config error: scenes.fft344.initial.kind = 'travelling-wave': must be one of travelling, breather, packet, "
        "pair, kick",
        "config error: scenes.tw-weak.store.snapshots = 3: must be a list"]


def test_analysis_scene_names_are_checked_at_validation(raw):
    """A scene an analysis reads that is no `scenes:` entry is refused when the config is validated, at the key
    that names it, with the nearest name (not when its jobs are planned); what only its target needs (a scene
    to measure) is said when the target is planned."""
    cfg = copy.deepcopy(raw)
    cfg["beyond"].setdefault("theorem1", {})["scenes"] = ["tw-wek"]
    with pytest.raises(cc.ConfigError) as info:
        cc.validate(cfg)
    assert str(info.value) == ("config error: beyond.theorem1.scenes[0] = 'tw-wek': unknown scene: no `scenes:` "
                               "entry of that name; did you mean 'tw-weak'?")
    cfg = copy.deepcopy(raw)
    cfg["beyond"]["mi-growth"]["scenes"] = []
    with pytest.raises(cc.ConfigError, match=r"beyond\.mi-growth\.scenes is empty"):
        cc.analysis_reads(cfg, "mi-growth", "full")
    with pytest.raises(cc.ConfigError, match=r"beyond\.mi-statistics: unknown form 'tiny' \(forms: reduced, full\)"):
        cc.analysis_spec(raw, "mi-statistics", "tiny")
