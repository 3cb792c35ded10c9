"""Reading config.yaml safely and fast (cradle.pipeline.config.loading): a key given twice refused wherever it
stands, merge keys honoured, alias bombs, huge lists and deep nesting refused in well under a second of CPU,
a file that is not UTF-8 one line; strings and lists without a declared maximum have a default one."""
from __future__ import annotations

import time

import pytest

from conftest import ROOT, run_snakemake
from cradle.pipeline import config as cc
from cradle.pipeline.workdir import copy_workflow
from cradle.specs.values import (
    CONFIG_MAX_BYTES as MAX_BYTES,
    CONFIG_MAX_DEPTH as MAX_DEPTH,
    CONFIG_MAX_VALUES as MAX_VALUES,
    DEFAULT_MAX_ITEMS,
    DEFAULT_MAX_LENGTH,
    NAME_MAX_LENGTH,
)

CONFIG = (ROOT / "config.yaml").read_text()
SCENE = "scenes:\n  tw-weak:"


def _refused(tmp_path, text: str | bytes, name: str = "c.yaml") -> str:
    """The one line read_yaml refuses ``text`` with, checked to take under a second of CPU."""
    p = tmp_path / name
    p.write_bytes(text if isinstance(text, bytes) else text.encode())
    t0 = time.process_time()
    with pytest.raises(cc.ConfigError) as err:
        cc.read_yaml(p)
    assert time.process_time() - t0 < 1.0
    line = str(err.value)
    assert "\n" not in line and line.startswith(f"config error: {p}")
    return line


def test_two_equal_keys_on_one_line_are_refused(tmp_path):
    line = _refused(tmp_path, "map:\n  a: {box: 0.1, box: 0.2, iterations: 3}\n")
    assert "line 2: key 'box' given twice in one mapping (first on the same line, column 7)" in line


def test_equal_keys_are_compared_by_value_not_by_text(tmp_path):
    """``0x10`` and ``16`` are the same integer key; YAML would keep the last."""
    line = _refused(tmp_path, "a:\n  16: 1\n  0x10: 2\n")
    assert "line 3: key 16 given twice in one mapping (first on line 2)" in line


def test_a_merge_key_with_an_override_is_valid(tmp_path):
    p = tmp_path / "c.yaml"
    p.write_text("base: &b {t_end: 10, N: 5}\nx:\n  <<: *b\n  t_end: 20\n")
    assert cc.read_yaml(p)["x"] == {"t_end": 20, "N": 5}


def test_a_key_twice_beside_a_merge_key_is_refused(tmp_path):
    line = _refused(tmp_path, "base: &b {t_end: 10}\nx:\n  <<: *b\n  t_end: 20\n  t_end: 30\n")
    assert "line 5: key 't_end' given twice" in line


def test_a_merge_of_scenes_in_config_yaml_gives_the_same_scene(tmp_path):
    """config.yaml with tw-weak's keys merged from an anchor and t_end overridden: tw-weak as before."""
    text = CONFIG.replace(SCENE, "x-base: &twbase {t_end: 1.0}\n" + SCENE + "\n    <<: *twbase", 1)
    p = tmp_path / "c.yaml"
    p.write_text(text)
    raw = cc.read_yaml(p)
    raw.pop("x-base")
    assert raw == cc.read_yaml(ROOT / "config.yaml")


def test_a_billion_laughs_is_refused_at_once(tmp_path):
    rows = ["a: &a [lol, lol, lol, lol, lol, lol, lol, lol, lol]"]
    for prev, name in zip("abcdefgh", "bcdefghi", strict=True):
        rows.append(f"{name}: &{name} [{', '.join([f'*{prev}'] * 9)}]")
    line = _refused(tmp_path, "\n".join(rows) + "\n")
    assert f"line 5: more than {MAX_VALUES} values (aliases counted as the values they stand for)" in line


LAST = CONFIG.count("\n") + 2   # the line after config.yaml's last line and an empty one
MANY = f"line {LAST}: more than {MAX_VALUES} values"


@pytest.mark.parametrize("n, sep, why", [(MAX_VALUES + 1, ", ", MANY), (1_000_000, ",", MANY),
                                        (1_000_000, ", ", f"larger than {MAX_BYTES} bytes")])
def test_a_huge_list_is_refused_at_once(tmp_path, n, sep, why):
    line = _refused(tmp_path, CONFIG + f"\nhuge: [{sep.join(['1.5'] * n)}]\n")
    assert why in line


def test_deep_nesting_is_refused(tmp_path):
    text = "".join(f"{'  ' * i}k{i}:\n" for i in range(MAX_DEPTH + 5)) + "  " * (MAX_DEPTH + 5) + "v: 1\n"
    assert f"nested more than {MAX_DEPTH} deep" in _refused(tmp_path, text)


def test_an_integer_past_python_s_digit_limit_is_one_line_with_its_line(tmp_path):
    """PyYAML's int() of 5001 digits raises a ValueError from deep inside the loader (Python's limit of 4300)."""
    line = _refused(tmp_path, CONFIG + f"\nhuge: [1{'0' * 5000}]\n")
    assert "not valid YAML: an integer of 5001 digits" in line and f"line {LAST}" in line


@pytest.mark.parametrize("written, shown", [(f"0x{'f' * 5000}", "an integer of about 6021 digits"),
                                            (f"1{'0' * 400}", "1" + "0" * 76 + "...")])
def test_an_integer_beyond_every_double_is_refused_naming_its_key(tmp_path, written, shown):
    """A hexadecimal integer has no digit limit and 400 digits none to reach: each is a value no double holds,
    refused at its key (the message's rendering of it does not hit the limit either)."""
    p = tmp_path / "c.yaml"
    p.write_text(CONFIG.replace("    t_end: 621.95\n", f"    t_end: {written}\n", 1))   # tw-weak's
    with pytest.raises(cc.ConfigError) as err:
        cc.load(p)
    line = str(err.value)
    assert line == f"config error: scenes.tw-weak.t_end = {shown}: must be a number a double holds (|x| < 1.8e308)"


def test_a_command_line_integer_past_the_digit_limit_is_one_line():
    """`--config` values arrive as text: 5001 digits read as the double they spell (inf), not int()'s ValueError."""
    config = cc.read_yaml(ROOT / "config.yaml")
    config["scenes"]["tw-weak"]["t_end"] = "1" + "0" * 5000
    with pytest.raises(cc.ConfigError) as err:
        cc.validate(config)
    assert str(err.value) == "config error: scenes.tw-weak.t_end = inf: must be a finite number"


def test_a_file_that_is_not_utf8_is_one_line(tmp_path):
    line = _refused(tmp_path, CONFIG.encode() + b"\nx: \"caf\xe9\"\n")
    assert line.endswith(f": line {LAST}: byte 0xe9 is not UTF-8 text (invalid continuation byte); save the file as "
                         f"UTF-8")


def test_config_yaml_is_far_below_the_bounds():
    """The bounds leave room: config.yaml is a tenth of each of them or less (its read's CPU time is measured by
    benchmarks/validation_cost.py, not here)."""
    import yaml

    from cradle.pipeline.config.loading import _Parser

    text = (ROOT / "config.yaml").read_text()
    depth = deepest = values = 0
    for event in yaml.parse(text, Loader=_Parser):
        if isinstance(event, (yaml.ScalarEvent, yaml.CollectionStartEvent, yaml.AliasEvent)):
            values += 1
        if isinstance(event, yaml.CollectionStartEvent):
            depth += 1
            deepest = max(deepest, depth)
        elif isinstance(event, yaml.CollectionEndEvent):
            depth -= 1
    assert len(text.encode()) * 10 < MAX_BYTES and values * 10 < MAX_VALUES and deepest * 5 < MAX_DEPTH, \
        (len(text.encode()), values, deepest)


def test_a_list_without_a_declared_maximum_has_the_default_one():
    raw = cc.read_yaml(ROOT / "config.yaml")
    raw["map"]["traj3"]["starts"] = [[0.0, 0.1]] * (DEFAULT_MAX_ITEMS + 1)
    with pytest.raises(cc.ConfigError) as err:
        cc.validate(raw)
    assert str(err.value).startswith("config error: map.traj3.starts = [[0.0, 0.1], ")
    assert str(err.value).endswith(f": must have at most {DEFAULT_MAX_ITEMS} items")


def test_a_string_without_a_declared_maximum_has_the_default_one():
    raw = cc.read_yaml(ROOT / "config.yaml")
    raw["scenes"]["tw-weak"]["initial"]["q"] = "pi/5" + " " * DEFAULT_MAX_LENGTH
    with pytest.raises(cc.ConfigError) as err:
        cc.validate(raw)
    assert str(err.value).endswith(f": must be at most {DEFAULT_MAX_LENGTH} characters long")
    assert str(err.value).startswith("config error: scenes.tw-weak.initial.q = 'pi/5 ")


def test_a_long_scene_name_is_refused_before_any_file_is_named(tmp_path):
    raw = cc.read_yaml(ROOT / "config.yaml")
    name = "s" * 300
    raw["scenes"][name] = raw["scenes"]["tw-weak"]
    with pytest.raises(cc.ConfigError) as err:
        cc.validate(raw)
    assert str(err.value) == (f"config error: scenes.{'s' * 20}...: bad name of 300 characters: at most "
                              f"{NAME_MAX_LENGTH} (names are part of file names)")
    raw["scenes"].pop(name)
    raw["scenes"]["s" * NAME_MAX_LENGTH] = raw["scenes"]["tw-weak"]
    assert "s" * NAME_MAX_LENGTH in cc.validate(raw)["scenes"]


BOMB = "\n".join(["a: &a [lol, lol, lol, lol, lol, lol, lol, lol, lol]"] + [
    f"{name}: &{name} [{', '.join([f'*{prev}'] * 9)}]" for prev, name in zip("abcdefgh", "bcdefghi", strict=True)])


@pytest.mark.slow
@pytest.mark.parametrize("text, words", [
    ("budget: {memory_gb: 8, memory_gb: 9}\n", "line 1: key 'memory_gb' given twice in one mapping"),
    (BOMB + "\n", f"line 5: more than {MAX_VALUES} values"),
])
def test_a_configfile_given_to_snakemake_goes_through_the_bounded_reader_before_any_job(tmp_path, text, words):
    """Snakemake reads a --configfile itself before the Snakefile runs (its loader keeps the last of two equal
    keys and builds an alias bomb as shared references); workflow/rules/common.smk then reads every one of
    workflow.configfiles with cradle's reader, before validation and before any job: one line naming the file."""
    work = copy_workflow(ROOT, tmp_path / "wf")
    (work / "extra.yaml").write_text(text)
    proc = run_snakemake(work, "-n", "--configfile", "extra.yaml", timeout=120)
    out = proc.stdout + proc.stderr
    said = [line for line in out.splitlines() if line.startswith("config error:")]
    assert proc.returncode != 0 and len(said) == 1, out[-2000:]
    assert said[0].startswith(f"config error: {work / 'extra.yaml'}: {words}"), said
    assert not (work / "results").exists()


@pytest.mark.slow
def test_a_configfile_that_is_not_utf8_is_refused_by_snakemakes_own_loader_first(tmp_path):
    """The one case cradle's reader never sees (docs/recovery.md): Snakemake's loader stops on a --configfile that is
    not UTF-8 with its own UnicodeDecodeError, before the Snakefile runs; nothing is built. A change of Snakemake
    that reads it otherwise shows here."""
    work = copy_workflow(ROOT, tmp_path / "wf")
    (work / "extra.yaml").write_bytes(b"budget:\n  memory_gb: 8\nx: \"caf\xe9\"\n")
    proc = run_snakemake(work, "-n", "--configfile", "extra.yaml", timeout=120)
    assert proc.returncode != 0 and "UnicodeDecodeError" in proc.stdout + proc.stderr
    assert not (work / "results").exists()


def test_validating_config_yaml_imports_no_compiled_kernel_and_no_xarray():
    """The Snakefile validates before every run: the declarations, the budget and the checks need neither numba's
    kernels nor xarray (scipy.optimize only for the homoclinic entries solved at validation)."""
    import subprocess
    import sys

    code = ("import sys; from cradle.pipeline import config as cc; loaded = set(sys.modules); "
            f"cc.validate(cc.read_yaml({str(ROOT / 'config.yaml')!r})); "
            "heavy = ('numba', 'xarray', 'pandas', 'matplotlib', 'netCDF4', 'cradle.integrators'); "
            "print(sorted(m for m in heavy if m in loaded), sorted(m for m in heavy if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    assert out == "[] []"
