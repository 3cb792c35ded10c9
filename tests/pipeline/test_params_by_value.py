"""A job's parameters by value (cradle.specs.declare.plain): key order, the way a number or an angle is
written change nothing Snakemake compares; a different value does."""
from __future__ import annotations

import copy
import json

import pytest
import yaml

from conftest import ROOT
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
