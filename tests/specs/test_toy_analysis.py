"""The worked example of docs/developing.md (tests/specs/fixtures/toy_analysis.py): one spec class, its reduced
form derived from the declarations, its check run on each form, one line per problem."""
import sys
from pathlib import Path

import pytest

from cradle.analyses.protocol import FULL, REDUCED, form_spec
from cradle.pipeline.config.checks import check_forms
from cradle.specs.declare import from_plain, plain
from cradle.specs.values import ConfigError, Errors

sys.path.insert(0, str(Path(__file__).parent / "fixtures"))
from toy_analysis import ANALYSIS, Toy  # noqa: E402 -- the fixture is a module of its own, not of cradle


def test_the_reduced_form_is_the_full_one_with_its_declared_and_given_overrides():
    spec = from_plain(Toy, {"samples": 32, "reduced": {"periods": 3}})
    assert ANALYSIS.forms == (REDUCED, FULL)
    assert plain(form_spec(spec, FULL)) == {"amplitudes": [0.01, 0.1, 1.0], "periods": 10, "samples": 32}
    assert plain(form_spec(spec, REDUCED)) == {"amplitudes": [0.1], "periods": 3, "samples": 32}
    assert ANALYSIS.compute(form_spec(spec, REDUCED), {}).energy.shape == (1, 3 * 32 + 1)


def test_a_reduced_key_is_read_as_its_field():
    with pytest.raises(ConfigError) as err:
        from_plain(Toy, {"reduced": {"periods": 0, "sample": 8}}, where="beyond.toy")
    assert err.value.errors == [
        "config error: beyond.toy.reduced.sample = 8: unknown key (allowed: amplitudes, periods, samples); did you "
        "mean 'samples'?",
        "config error: beyond.toy.reduced.periods = 0: must be >= 1"]


def test_the_check_runs_on_each_form_and_says_each_problem_once():
    out = Errors()
    check_forms(from_plain(Toy, {"amplitudes": [1.0, 0.5], "reduced": {"amplitudes": [0.2, 0.1]}}),
                ["beyond", "toy"], None, out)
    assert out.lines == ["config error: beyond.toy.amplitudes = [1.0, 0.5]: must be strictly increasing",
                         "config error: beyond.toy.reduced.amplitudes = [0.2, 0.1]: must be strictly increasing"]
