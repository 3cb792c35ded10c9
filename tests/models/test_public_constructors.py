"""The Python API's public constructors (materials, cradles, releases, damping, the terms of an imperfect cradle):
any value of any type is either taken (as the config would read it) or refused in one line naming the key and
the value, never a ZeroDivisionError, an OverflowError or a traceback from deeper down; a Cradle built directly
is checked as real_cradle and the config check it."""
from __future__ import annotations

import dataclasses
import math

import pytest

from cradle.models import physical as ph
from cradle.models.damping import Damping
from cradle.models.inhomogeneity import Inhomogeneity
from cradle.models.lattice_terms import Terms
from cradle.models.onsite import OnSite
from cradle.models.precompression import Precompression
from cradle.specs.values import ConfigError

VALUES = [0, 0.0, 1e-300, -1e-300, 1e300, -1e300, math.nan, math.inf, -math.inf, "x", "1", None, [1.0], [], {}, True,
          object()]
#: each constructor with valid keyword arguments
BUILDS = {"material": (ph.Material, {"name": "m", "E": 2e11, "nu": 0.3, "rho": 7800.0, "source": "s"}),
          "cradle": (ph.Cradle, {"material": "steel", "radius": 0.01, "length": 0.1}),
          "real_cradle": (ph.real_cradle, {"material": "steel", "radius": 0.01, "length": 0.1}),
          "release": (ph.Release, {"angle": 10.0}),
          "damping": (Damping, {"onsite": 0.1, "contact": 0.1}),
          "precompression": (Precompression, {"delta0": 0.1}),
          "onsite": (OnSite, {"potential": "quartic", "beta": 0.1}),
          "inhomogeneity": (Inhomogeneity, {"sigma": 0.1, "seed": 1}),
          "terms": (Terms, {})}
KEYS = {"material": ["name", "E", "nu", "rho", "source"],
        "real_cradle": ["material", "radius", "length", "omega0", "g"]}


def _shown(value) -> str:
    """A value as a test id: the same in every process (xdist's workers must collect the same ids)."""
    return "object()" if type(value) is object else repr(value)


def _cases():
    for name, (make, kwargs) in BUILDS.items():
        keys = KEYS.get(name) or [f.name for f in dataclasses.fields(make)]
        for key in keys:
            for value in VALUES:
                yield pytest.param(make, {**kwargs, key: value}, key, id=f"{name}.{key}={_shown(value)}")


@pytest.mark.parametrize("make, kwargs, key", list(_cases()))
def test_any_value_is_taken_or_refused_in_one_line(make, kwargs, key):
    try:
        made = make(**kwargs)
    except (ValueError, TypeError) as err:
        assert "\n" not in str(err) and key in str(err), str(err)
        return
    for f in dataclasses.fields(made):   # what was taken is what the config would have read
        value = getattr(made, f.name)
        assert not isinstance(value, float) or math.isfinite(value), (f.name, value)
        assert not (isinstance(value, str) and f.name not in ("name", "source", "material", "potential",
                                                              "distribution", "bc")), (f.name, value)


@pytest.mark.parametrize("key, value, why", [("radius", 1e-300, "must be >= 1e-06"),
                                             ("radius", 0, "must be >= 1e-06"),
                                             ("length", 1e-300, "must be >= 0.001"),
                                             ("g", math.inf, "must be a finite number"),
                                             ("radius", "big", "must be a number")])
def test_a_cradle_built_directly_is_checked(key, value, why):
    with pytest.raises(ConfigError) as err:
        ph.Cradle(**{"material": "steel", "radius": 0.01, "length": 0.1, key: value})
    assert str(err.value) == f"config error: cradle.{key} = {value!r}: {why}"


def test_a_cradle_without_length_or_omega0_is_refused_where_its_scales_are_made():
    spec = ph.Cradle(material="steel", radius=0.01)
    with pytest.raises(ConfigError) as err:
        ph.scales(spec)
    assert str(err.value) == "cradle: give the pendulum length or omega0, one of them (given: neither)"


def test_a_number_written_as_a_string_is_stored_as_the_number():
    assert ph.Cradle(material="steel", radius="0.01", length=0.1).radius == 0.01
    assert ph.Material(name="m", E="2e11", nu=0.3, rho=7800, source="s").E == 2e11
    assert Damping(onsite="1e-3").onsite == 1e-3
