"""A job's parameters by value (cradle.specs.declare.plain): key order, the way a number or an angle is
written change nothing Snakemake compares; a different value does."""
from __future__ import annotations

import copy
import json
import math

import pytest
import yaml

from conftest import ROOT, copy_workflow
from cradle.pipeline import config as cc
from cradle.specs.declare import plain
from cradle.specs.values import canonical_angle, parse_angle


@pytest.fixture(scope="module")
def raw():
    return yaml.safe_load((ROOT / "config.yaml").read_text())


def _params(cfg, name="tw-weak") -> str:
    """What Snakemake compares for a scene's job: the repr of its params."""
    return repr(plain(cc.scene(cfg, name)))


@pytest.mark.parametrize("text", ["pi/5", "1pi/5", "1*pi/5", "0.2pi", " pi / 5 ", "+pi/5", "1.0pi/5", "pi/5.0"])
def test_equal_angles_written_differently_have_one_form(text):
    assert canonical_angle(text) == "pi/5"
    assert parse_angle(canonical_angle(text)) == parse_angle(text)


@pytest.mark.parametrize("text", ["52pi/100", "-52pi/100", "51pi/100", "4pi/5", "pi", "pi/2", "57pi/100"])
def test_the_paper_s_angles_keep_their_text(text):
    """config.yaml's angles are already in the one form: the files' recorded texts (q_expr) do not change."""
    assert canonical_angle(text) == text


def test_an_angle_form_is_used_only_when_it_is_the_same_angle_bit_for_bit():
    for text in ("0.55pi", "0.4pi", "0.7pi", "-0.2pi", ".5pi", "0.3", "3", "-0.3", " - 2.5e-1"):
        assert parse_angle(canonical_angle(text)) == parse_angle(text), text
    assert canonical_angle("0.3") == 0.3 and canonical_angle(0.5) == 0.5
    assert canonical_angle("not an angle") == "not an angle"   # left to the schema to refuse


def test_reordered_keys_equal_numbers_and_equal_angles_give_the_same_params(raw):
    base = _params(raw)
    variants = []
    cfg = copy.deepcopy(raw)
    cfg["defaults"] = {"exact": {"rtol": 1e-10, "method": "srkn6c"}, "alpha": 1.5}
    variants.append(cfg)
    cfg = copy.deepcopy(cfg)
    cfg["defaults"]["exact"] = dict(reversed(list(cfg["defaults"]["exact"].items())))
    variants.append(cfg)
    for q in ("1pi/5", "1*pi/5", "0.2pi"):
        cfg = copy.deepcopy(raw)
        cfg["scenes"]["tw-weak"]["initial"]["q"] = q
        variants.append(cfg)
    for key, value in (("phi", 0), ("omega_tw", "1.01")):
        cfg = copy.deepcopy(raw)
        cfg["scenes"]["tw-weak"]["initial"][key] = value
        variants.append(cfg)
    cfg = copy.deepcopy(raw)
    cfg["scenes"]["tw-weak"]["t_end"] = "6.2195e2"   # YAML reads 6.2195e2 as a string
    variants.append(cfg)
    for cfg in variants:
        assert _params(cfg) == base, cfg["scenes"]["tw-weak"]
    cfg = copy.deepcopy(raw)
    cfg["scenes"]["tw-weak"]["initial"]["q"] = "2pi/5"   # another value: another job
    assert _params(cfg) != base


def test_numbers_are_typed_as_declared(raw):
    """An int where a number is declared is a float (loc1-packet's `width: 12`), an integral float where
    an integer is declared an int."""
    values = plain(cc.scene(raw, "loc1-packet"))
    assert isinstance(values["initial"]["width"], float) and isinstance(values["N"], int)
    cfg = copy.deepcopy(raw)
    cfg["scenes"]["tw-weak"]["N"] = 50.0
    assert json.dumps(plain(cc.scene(cfg, "tw-weak"))) == json.dumps(plain(cc.scene(raw, "tw-weak")))


def test_the_claims_table_reads_all_scenes_in_name_order(raw):
    """`scenes: all` is every scene sorted: moving a block of config.yaml does not rerun paper_checks."""
    moved = copy.deepcopy(raw)
    names = list(moved["scenes"])
    moved["scenes"] = {n: moved["scenes"][n] for n in names[1:] + names[:1]}
    one, other = (plain(cc.analysis_spec(c, "paper-checks", "full")) for c in (raw, moved))
    assert one == other and one["scenes"] == sorted(raw["scenes"])


def test_a_number_equal_to_a_multiple_of_pi_is_that_multiple():
    """``q: 0.6283185307179586`` is ``q: pi/5`` bit for bit: one parameter; a number that is no such multiple
    stays a number."""
    assert canonical_angle(0.6283185307179586) == canonical_angle("0.6283185307179586") == "pi/5"
    assert canonical_angle(-4 * math.pi / 5) == "-4pi/5" and canonical_angle(math.pi) == "pi"
    assert canonical_angle(0.6283185307179587) == 0.6283185307179587   # one ulp away: another angle
    for x in (0.5, 0.0, 1e-300, 1e300, math.inf):
        assert canonical_angle(x) == x


def test_q_as_the_number_of_pi_over_5_gives_the_same_params(raw):
    cfg = copy.deepcopy(raw)
    cfg["scenes"]["tw-weak"]["initial"]["q"] = 0.6283185307179586
    assert _params(cfg) == _params(raw)


@pytest.mark.slow
def test_q_written_as_its_number_reruns_nothing(tmp_path):
    """plot4-5's jobs up to date (``--touch``) in a copy of the workflow; ``q: 0.6283185307179586`` in place of
    ``q: pi/5`` plans nothing (the same double), ``q: 2pi/5`` plans tw-weak's job again."""
    from conftest import run_snakemake
    from cradle.pipeline import layout as L

    work = tmp_path / "cradle"
    copy_workflow(work, skip=("tests/", "docs/", "benchmarks/"))
    target = "results/figures/plot4-5.png"
    for out in map(str, [L.path("kernels"), *L.scene_paths("tw-weak").values(), *L.figure_paths("plot4-5").values()]):
        (work / out).parent.mkdir(parents=True, exist_ok=True)
        (work / out).touch()
    proc = run_snakemake(work, "--touch", "--forceall", "--cores", "1", target)
    assert proc.returncode == 0, proc.stderr[-3000:]
    config = work / "config.yaml"
    text = config.read_text()
    line = "initial: {kind: travelling, q: pi/5, omega_tw: 1.01, phi: 0.0}   # a ~ 2.118e-2 from (freq)"
    assert text.count(line) == 1
    config.write_text(text.replace(line, line.replace("q: pi/5", "q: 0.6283185307179586")))
    proc = run_snakemake(work, "-n", target)
    assert proc.returncode == 0 and "Nothing to be done" in proc.stdout + proc.stderr, proc.stderr[-3000:]
    config.write_text(text.replace(line, line.replace("q: pi/5", "q: 2pi/5")))
    proc = run_snakemake(work, "-n", target)
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert "simulate" in proc.stdout and "Nothing to be done" not in proc.stdout + proc.stderr
