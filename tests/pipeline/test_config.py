"""Config schema and physical validation (cradle.pipeline.config): every bad input is
caught with a one-line message naming the key path and the value."""
import copy
import json
import math
import time
from pathlib import Path

import pytest
import yaml

from cradle.pipeline import config as cc
from cradle.pipeline.config.reference import generated_schema
from cradle.pipeline.config.validate import _MADE, _TYPED
from cradle.scenes.spec import ExactIntegrator, Noise

ROOT = Path(__file__).resolve().parents[2]
CONFIG = ROOT / "config.yaml"


@pytest.fixture(scope="module")
def raw():
    return yaml.safe_load(CONFIG.read_text())


@pytest.fixture
def cfg(raw):
    return copy.deepcopy(raw)


def errors(cfg):
    """The lines of the ConfigError that validate(cfg) must raise."""
    with pytest.raises(cc.ConfigError) as info:
        cc.validate(cfg)
    lines = str(info.value).splitlines()
    assert lines == info.value.errors
    assert all(line.startswith("config error: ") for line in lines)
    return lines


def one_error(cfg, *parts):
    """validate(cfg) fails with exactly one line, containing every string in ``parts``."""
    lines = errors(cfg)
    assert len(lines) == 1, lines
    for p in parts:
        assert p in lines[0], (p, lines[0])
    return lines[0]


def tw(cfg):
    return cfg["scenes"]["tw-weak"]


BREATHER = {"N": 50, "bc": "periodic", "initial": {"kind": "breather", "homoclinic": "site", "omega_sw": 1.1},
            "t_end": 10.0, "store": {"every": 1.0}}


# ------------------------------------------------------------------ the real config

def test_real_config_validates_and_fills_defaults(raw):
    cfg = cc.load(CONFIG)
    assert cfg["defaults"] == {"alpha": 1.5, "exact": {"method": "srkn6c", "dt_factor": None, "rtol": 1e-10},
                               "dps": {"method": "dop853_numba", "rtol": 1e-10}, "max_energy_drift": 1e-6}
    assert cfg["scenes"]["tw-weak"]["bc"] == "periodic"
    assert cfg["scenes"]["tw-weak"]["initial"]["phi"] == 0.0
    assert cfg["homoclinic"]["site"]["mu"] == 1.0 and cfg["homoclinic"]["site"]["separation"] == 9
    assert raw == yaml.safe_load(CONFIG.read_text())  # validate works on a copy
    assert cc.validate(cfg) == cfg  # idempotent (the Snakefile re-validates resolved configs)
    json.dumps(cfg)


def test_defaults_are_filled_into_a_small_config():
    cfg = cc.validate({"map": {"m": {"box": 1.0, "iterations": 2, "starts": [[0.0, 0.1]]}}})
    assert cfg["defaults"]["alpha"] == 1.5 and cfg["scenes"] == {} and cfg["figures"] == {}
    assert cfg["defaults"]["exact"]["method"] == "srkn6c" and cfg["defaults"]["dps"]["method"] == "dop853_numba"


@pytest.mark.parametrize("empty", [None, {}, {"defaults": {"alpha": 2.0}}, {"figures": {}}])
def test_empty_or_sectionless_config_is_refused_in_one_line(empty):
    """An empty file (None) or one without map, homoclinic or scenes would otherwise validate and fail
    later, as a traceback while Snakemake builds the DAG."""
    assert len(errors(empty)) == 1 and "nothing to build" in errors(empty)[0]


def test_resolved_scene(raw):
    r = cc.scene(raw, "tw-weak")
    assert r.N == 50 and r.alpha == 1.5 and r.bc == "periodic"
    assert r.initial.wavenumber == pytest.approx(math.pi / 5) and r.initial.q_expr == "pi/5"
    assert r.exact == ExactIntegrator(method="srkn6c", dt_factor=None, rtol=1e-10)
    assert (r.dps.method, r.dps.rtol, r.max_energy_drift) == ("dop853_numba", 1e-10, 1e-6)
    assert r.times[0] == 0.0 and r.times[-1] == 621.95 and 333.7 in r.times
    assert len(r.times) == 6221  # 0, 0.1, ..., 621.9 and 621.95
    noisy = cc.scene(raw, "tw-weak-noise")
    assert noisy.initial.noise == Noise(kind="uniform", amplitude=0.5, seed=20110605)
    assert noisy.times == (0.0, 621.95)


def test_resolved_scene_merges_overrides(cfg):
    tw(cfg).update(alpha=2.0, exact={"method": "dop853"}, max_energy_drift=1e-4)
    tw(cfg)["initial"]["q"] = 0.6283185307179586
    r = cc.scene(cfg, "tw-weak")
    assert r.alpha == 2.0 and r.max_energy_drift == 1e-4
    assert r.exact == ExactIntegrator(method="dop853", dt_factor=None, rtol=1e-10)
    assert r.initial.q_expr == "0.6283185307179586"


def test_resolved_homoclinic_and_map(raw):
    h = cc.homoclinic(raw, "double")
    assert (h.guess, h.N, h.bc, h.amplitude, h.separation, h.mu, h.alpha) == ("double", 50, "periodic", 0.1, 9, 1.0,
                                                                               1.5)
    m = cc.map_entry(raw, "traj3")
    assert m.alpha == 1.5 and m.marks is False and m.starts == [[0.0, 1e-13]]


@pytest.mark.parametrize("fn", [cc.scene, cc.homoclinic, cc.map_entry])
def test_resolved_unknown_name(raw, fn):
    with pytest.raises(cc.ConfigError, match="nosuch"):
        fn(raw, "nosuch")


def test_schema_is_complete():
    """Every key of the generated schema has a description, every object forbids unknown keys, labels match
    KNOWN_FIGURES."""
    s = generated_schema()

    def walk(node, where):
        if isinstance(node, dict):
            for key, sub in node.get("properties", {}).items():
                assert "description" in sub, f"{where}.{key} has no description"
            if node.get("type") == "object" and "properties" in node and "allOf" not in node:
                assert node.get("additionalProperties") is False, f"{where} allows unknown keys"
            for k, v in node.items():
                if k != "if":  # conditions, not keys
                    walk(v, f"{where}.{k}")
        elif isinstance(node, list):
            for i, v in enumerate(node):
                walk(v, f"{where}[{i}]")

    walk(s, "schema")
    assert sorted(s["properties"]["figures"]["propertyNames"]["enum"]) == sorted(cc.KNOWN_FIGURES)
    assert s["$defs"]["angleString"]["pattern"] == cc.ANGLE_PATTERN


# ------------------------------------------------------------------ one test per class of bad input

def test_alpha_not_above_one(cfg):
    cfg.setdefault("defaults", {})["alpha"] = 1.0
    one_error(cfg, "defaults.alpha = 1.0", "must be > 1")


@pytest.mark.parametrize("section,name", [("scenes", "tw-weak"), ("homoclinic", "site"), ("map", "traj3")])
def test_alpha_override_not_above_one(cfg, section, name):
    cfg[section][name]["alpha"] = 0.5
    one_error(cfg, f"{section}.{name}.alpha = 0.5", "must be > 1")


def test_N_below_two(cfg):
    tw(cfg)["N"] = 1
    assert one_error(cfg) == "config error: scenes.tw-weak.N = 1: must be >= 2"


def test_snapshots_not_increasing(cfg):
    tw(cfg)["store"]["snapshots"] = [400.0, 333.7]
    one_error(cfg, "scenes.tw-weak.store.snapshots[1] = 333.7", "increasing")


def test_negative_times(cfg):
    tw(cfg)["store"]["snapshots"] = [-1.0, 333.7]
    one_error(cfg, "scenes.tw-weak.store.snapshots[0] = -1.0", "must be >= 0")
    cfg = copy.deepcopy(cfg)
    tw(cfg)["store"]["snapshots"] = [333.7]
    tw(cfg)["t_end"] = -5.0
    one_error(cfg, "scenes.tw-weak.t_end = -5.0", "must be > 0")


def test_snapshot_beyond_t_end(cfg):
    tw(cfg)["store"]["snapshots"] = [333.7, 700.0]
    one_error(cfg, "scenes.tw-weak.store.snapshots[1] = 700.0", "t_end = 621.95")


@pytest.mark.parametrize("q", ["6pi/5", "-pi", -3.2, 4])
def test_q_outside_minus_pi_pi(cfg, q):
    tw(cfg)["initial"]["q"] = q
    one_error(cfg, f"scenes.tw-weak.initial.q = {q!r}", "(-pi, pi]")


def test_q_pi_is_allowed(cfg):
    tw(cfg)["initial"]["q"] = "pi"
    cc.validate(cfg)


def test_q_N_over_2pi_not_integer_on_a_ring(cfg):
    tw(cfg)["initial"]["q"] = "pi/7"
    line = one_error(cfg, "scenes.tw-weak.initial.q = 'pi/7'", "q N/(2 pi) must be an integer", "3.571428571")
    assert "N = 50" in line


def test_q_N_over_2pi_free_ends_accepted(cfg):
    tw(cfg)["initial"]["q"] = "pi/7"
    tw(cfg)["bc"] = "free"
    assert cc.validate(cfg)["scenes"]["tw-weak"]["bc"] == "free"


def test_omega_tw_not_above_one(cfg):
    tw(cfg)["initial"]["omega_tw"] = 1.0
    one_error(cfg, "scenes.tw-weak.initial.omega_tw = 1.0", "must be > 1", "(freq)")


def test_q_zero_with_omega_tw(cfg):
    tw(cfg)["initial"]["q"] = 0
    one_error(cfg, "scenes.tw-weak.initial.q = 0", "give a instead of omega_tw")


def test_both_a_and_omega_tw(cfg):
    tw(cfg)["initial"]["a"] = 0.02
    one_error(cfg, "scenes.tw-weak.initial", "exactly one of a and omega_tw", "a = 0.02", "omega_tw = 1.01")


def test_neither_a_nor_omega_tw(cfg):
    del tw(cfg)["initial"]["omega_tw"]
    one_error(cfg, "scenes.tw-weak.initial", "exactly one of a and omega_tw", "neither")


def test_unknown_scene_in_figure(cfg):
    cfg["figures"]["plot4-5"]["scenes"] = ["tw-weakk"]
    one_error(cfg, "figures.plot4-5.scenes[0] = 'tw-weakk'", "unknown scene")


def test_figure_time_not_stored(cfg):
    cfg["figures"]["plot4-5"]["times"] = [620.05]
    one_error(cfg, "figures.plot4-5.times[0] = 620.05", "not a stored time")


def test_unknown_figure_label(cfg):
    cfg["figures"]["plot99"] = {"scenes": ["tw-weak"]}
    one_error(cfg, "figures.plot99", "unknown figure label 'plot99'")


def test_wrong_type(cfg):
    tw(cfg)["N"] = "fifty"
    assert one_error(cfg) == "config error: scenes.tw-weak.N = 'fifty': must be an integer"


def test_numeric_strings_are_read_as_numbers(cfg):
    """PyYAML reads 1e-10 as a string; snakemake --config nested values are all strings."""
    cfg.setdefault("defaults", {}).setdefault("exact", {})["rtol"] = "1e-10"
    assert cc.validate(cfg)["defaults"]["exact"]["rtol"] == 1e-10


def test_config_override_strings_validate(raw):
    """snakemake --config parses nested values with YAML's BaseLoader: every scalar is a string."""
    as_strings = yaml.load(yaml.safe_dump(raw), Loader=yaml.BaseLoader)
    assert as_strings["scenes"]["tw-weak"]["N"] == "50"
    assert cc.validate(as_strings) == cc.validate(raw)
    as_strings["scenes"]["tw-weak"]["N"] = "1"
    one_error(as_strings, "scenes.tw-weak.N = 1: must be >= 2")


def test_unknown_key(cfg):
    tw(cfg)["Nn"] = 50
    one_error(cfg, "scenes.tw-weak.Nn = 50", "unknown key", "did you mean 'N'")


def test_missing_key(cfg):
    del tw(cfg)["t_end"]
    one_error(cfg, "scenes.tw-weak.t_end", "missing")


def test_enum(cfg):
    cfg.setdefault("defaults", {}).setdefault("dps", {})["method"] = "srkn6"
    one_error(cfg, "defaults.dps.method = 'srkn6'", "must be one of dop853, dop853_numba, rk45")


def test_not_finite(cfg):
    tw(cfg)["t_end"] = float("inf")
    one_error(cfg, "scenes.tw-weak.t_end = inf", "finite")


def test_breather_missing_homoclinic(cfg):
    cfg["scenes"]["br"] = copy.deepcopy(BREATHER)
    cfg["scenes"]["br"]["initial"]["homoclinic"] = "sitee"
    one_error(cfg, "scenes.br.initial.homoclinic = 'sitee'", "no homoclinic entry", "site, bond, double")


def test_breather_checks(cfg):
    cfg["scenes"]["br"] = copy.deepcopy(BREATHER)
    cc.validate(cfg)
    cfg["scenes"]["br"].update(N=40, bc="free")
    cfg["scenes"]["br"]["initial"]["amplitude"] = 0.1
    lines = "\n".join(errors(cfg))
    assert "scenes.br.N = 40: must equal homoclinic.site.N = 50" in lines
    assert "scenes.br.bc = 'free': must equal homoclinic.site.bc = 'periodic'" in lines
    assert "scenes.br.initial: give exactly one of omega_sw and amplitude, got both" in lines


def test_names_unique_across_sections(cfg):
    cfg["scenes"]["site"] = copy.deepcopy(tw(cfg))
    one_error(cfg, "scenes.site", "also used by homoclinic.site")


@pytest.mark.parametrize("section, name, said", [
    ("scenes", "TW-Weak", "scenes.TW-Weak: name 'TW-Weak' differs from scenes.tw-weak only in case"),
    # homoclinic names are claimed before scene names (as for equal names): the scene is the one said
    ("homoclinic", "Tw-weak", "scenes.tw-weak: name 'tw-weak' differs from homoclinic.Tw-weak only in case")])
def test_names_that_differ_only_in_case_are_refused(cfg, section, name, said):
    """results/sim/tw-weak and results/sim/TW-Weak are one folder on macOS's and Windows's file systems."""
    cfg[section][name] = copy.deepcopy(tw(cfg) if section == "scenes" else cfg["homoclinic"]["site"])
    one_error(cfg, said, "case-insensitive file system")


def test_all_problems_are_reported(cfg):
    tw(cfg)["N"] = 1
    tw(cfg)["Nn"] = 2
    cfg.setdefault("defaults", {})["alpha"] = 0.9
    cfg["figures"]["plot4-5"]["scenes"] = ["nosuch"]
    lines = errors(cfg)
    assert len(lines) == 4, lines


def test_not_a_mapping():
    with pytest.raises(cc.ConfigError, match="must be a mapping"):
        cc.validate([1, 2])


def test_load_bad_yaml(tmp_path):
    p = tmp_path / "c.yaml"
    p.write_text("scenes: [\n")
    with pytest.raises(cc.ConfigError, match="not valid YAML"):
        cc.load(p)


def test_command_line(capsys, tmp_path, raw):
    assert cc.main([str(CONFIG)]) == 0
    assert "OK" in capsys.readouterr().out
    bad = copy.deepcopy(raw)
    bad["scenes"]["tw-weak"]["N"] = 1
    p = tmp_path / "bad.yaml"
    p.write_text(yaml.safe_dump(bad))
    assert cc.main([str(p)]) == 1
    assert "scenes.tw-weak.N = 1: must be >= 2" in capsys.readouterr().err


# ------------------------------------------------------------------ angles and stored times

@pytest.mark.parametrize("text,value", [
    ("pi", math.pi), ("pi/5", math.pi / 5), ("4pi/5", 4 * math.pi / 5), ("-52pi/100", -0.52 * math.pi),
    ("4*pi/5", 4 * math.pi / 5), (" 2 * pi / 50 ", math.pi / 25), ("-pi/2", -math.pi / 2), ("0.5pi", math.pi / 2),
    ("+pi/3", math.pi / 3), ("0.25", 0.25), (1, 1.0), (-0.3, -0.3),
])
def test_parse_angle(text, value):
    assert cc.parse_angle(text) == pytest.approx(value, rel=1e-15)


@pytest.mark.parametrize("junk", ["pix", "", "pi/", "*pi", "pi/0", "2pi5", "tau", True, None, [1], float("nan")])
def test_parse_angle_junk(junk):
    with pytest.raises(cc.ConfigError):
        cc.parse_angle(junk)


def test_store_times_grid_and_snapshots_merged():
    assert cc.store_times([0.1, 0.5], 0.25, 1.0) == [0.0, 0.1, 0.25, 0.5, 0.75, 1.0]


def test_store_times_includes_t_end_off_the_grid():
    assert cc.store_times(None, 0.4, 1.0) == [0.0, 0.4, 0.8, 1.0]


def test_store_times_dedup_within_tolerance():
    t = cc.store_times([0.3 + 4e-10, 0.35, 1.0 - 5e-10], 0.1, 1.0)
    assert t == [0.0, 0.1, 0.2, 0.3, 0.35, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0]


def test_store_times_snapshots_only():
    assert cc.store_times([621.95], None, 621.95) == [0.0, 621.95]
    assert cc.store_times([0.0, 5.0], None, 10.0) == [0.0, 5.0, 10.0]


def test_validate_is_idempotent_and_remembered():
    """A validated config validates to itself, and its typed config is remembered: the entries a job resolves
    from it cost no validation."""
    cfg = cc.load(CONFIG)
    assert cc.validate(cfg) == cfg
    _TYPED.clear()
    cfg = cc.load(CONFIG)
    typed = cc.typed(cfg)
    assert cc.typed(cfg) is typed and cc.scene(cfg, "tw-weak") is typed.scenes["tw-weak"]


def test_validating_config_yaml_takes_under_0_2_s_of_cpu(raw):
    """The whole pass on config.yaml, nothing remembered (the modules imported by a first validation), in the CPU
    time of this process: the best of three, the machine being shared."""
    cc.validate(copy.deepcopy(raw))
    best = math.inf
    for _ in range(3):
        _TYPED.clear()
        _MADE.clear()
        cfg = copy.deepcopy(raw)
        t0 = time.process_time()
        cc.validate(cfg)
        best = min(best, time.process_time() - t0)
    assert best < 0.2, f"validating config.yaml took {best:.3f} s of CPU"
