"""Public functions a library user calls, given a value of the wrong type or out of range: each refused in one line
naming the argument (a ConfigError from the shared declarations, cradle.specs.checked), where they raised TypeError,
ZeroDivisionError or OverflowError from inside (found by probing each argument with 0, +-1e-300, +-1e300, nan,
+-inf, a string, None, True and 2^70)."""
from __future__ import annotations

import math

import numpy as np
import pytest

import cradle
from cradle.specs.values import ConfigError

STEEL = cradle.real_cradle("steel", 0.01, length=0.1)


@pytest.mark.parametrize("call, line", [
    (lambda: cradle.collision_time(STEEL, 0), "v = 0: must be > 0"),
    (lambda: cradle.collision_time(STEEL, "s"), "v = 's': must be a number"),
    (lambda: cradle.packet(20, 1.5, amplitude=None, width=5), "amplitude = None: must be a number"),
    (lambda: cradle.packet(20, 1.5, amplitude=0.01, width="s"), "width = 's': must be a number"),
    (lambda: cradle.kick(20, 1.5, velocity=None), "velocity = None: must be a number"),
    (lambda: cradle.travelling_wave(20, "s", 1.5, a=0.01), "q = 's': must be a number"),
    (lambda: cradle.travelling_wave(20, 0.6, 1.5, a="s"), "a = 's': must be a number"),
    (lambda: cradle.pair(30, 1.5, amplitude=0.01, separation=None), "separation = None: must be an integer"),
    (lambda: cradle.orbits([[0.0, 1e-3]], math.inf, 1.5), "n_iter = inf: must be a finite number"),
    (lambda: cradle.slow_damping(cradle.Damping(onsite=0.1), None, 1.5), "eps = None: must be a number"),
    (lambda: cradle.gamma_star("s"), "N = 's': must be an integer"),
    (lambda: cradle.lattice_state(np.full(10, 0.01 + 0j), "s", 1.5), "eps = 's': must be a number"),
    (lambda: cradle.relative_error(np.ones(3), np.ones(3), None), "a = None: must be a number"),
    (lambda: cradle.approximate_displacement(np.full((2, 10), 0.01 + 0j), np.array([0.0, 1.0]), 0),
     "eps = 0: must be > 0"),
])
def test_a_bad_argument_is_one_line_naming_it(call, line):
    with pytest.raises(ConfigError) as err:
        call()
    text = str(err.value)
    assert "\n" not in text and text.startswith(line), text


def test_the_checked_functions_still_compute():
    assert cradle.collision_time(STEEL, 0.1) > 0
    assert cradle.gamma_star(10).shape == (10,)
    assert cradle.orbits([[0.0, 1e-3]], 3, 1.5).shape[-2:] == (4, 2)


@pytest.mark.parametrize("build", ["solve", "pair", "two_breathers"])
def test_a_homoclinic_too_large_for_memory_is_one_line(build):
    # N = 1e6 raised MemoryError from inside (a dense Jacobian of N^2 doubles, 7.3 TiB): refused before allocating it
    from cradle.models import homoclinic, initial, pairs

    call = {"solve": lambda: homoclinic.solve(np.zeros(10**6), alpha=1.5),
            "pair": lambda: initial.pair(10**6, 1.5, amplitude=0.1, separation=10),
            "two_breathers": lambda: pairs.two_breathers(10**6, 1.5)}[build]
    with pytest.raises(ValueError, match=r"^N = 1000000: the dense Jacobian alone needs 7\.45e\+03 GiB "
                                         r"\(N\^2 doubles\), more than this machine's .* GiB of memory$"):
        call()
