"""Arguments of the public integrators that were accepted and gave a wrong answer or a traceback (found by probing
integrate_lattice at the extremes): each refused before any work, in one line naming the argument and why."""
from __future__ import annotations

import numpy as np
import pytest

from cradle import integrate_lattice
from cradle.specs.values import ConfigError

X0 = np.zeros(10)
V0 = np.zeros(10)
V0[0] = 0.1


def _one_line(err: pytest.ExceptionInfo) -> str:
    text = str(err.value)
    assert "\n" not in text
    return text


def test_an_output_time_beyond_float64_s_resolution_is_refused():
    """t_out up to 1e300 ran one step of the whole span and returned nan without a word."""
    with pytest.raises(ValueError) as err:
        integrate_lattice(X0, V0, np.array([0.0, 1e300]), alpha=1.5)
    assert _one_line(err) == ("t_out must end by 4194304 (float64 tells stored times 1e-9 apart only below 2^22 = "
                              "4194304), got t_out[-1]=1e+300")


@pytest.mark.parametrize("kw", [{"dt": 1e-300}, {"dt": 1e-12, "t_end": 1e4}])
def test_a_step_whose_count_float64_cannot_hold_is_refused(kw):
    """dt = 1e-300 ran as one step per interval (the count wrapped past int64): an energy drift of 34 %."""
    t_end = kw.pop("t_end", 10.0)
    with pytest.raises(ValueError) as err:
        integrate_lattice(X0, V0, np.linspace(0.0, t_end, 3), alpha=1.5, **kw)
    assert _one_line(err).startswith(f"dt = {kw['dt']!r}: the run to t = {t_end:g} would take ")
    assert "steps, more than 2^53 = 9.01e+15 (float64 counts steps exactly only below; take a larger step)" in \
        str(err.value)


def test_a_step_float64_counts_still_runs():
    run = integrate_lattice(X0, V0, np.array([0.0, 1.0]), alpha=1.5, dt=0.01)
    assert run.n_steps == 100


def test_an_absolute_tolerance_whose_error_norm_overflows_is_refused():
    """atol = 1e-300 raised ZeroDivisionError in DOP853's first step (the norm squares state / atol)."""
    with pytest.raises(ConfigError) as err:
        integrate_lattice(X0, V0, np.array([0.0, 1.0]), alpha=1.5, method="dop853_numba", atol=1e-300)
    assert _one_line(err) == ("atol = 1e-300: must be >= 1e-150 (the error norm squares state / atol, which "
                              "overflows float64 below it)")
    run = integrate_lattice(X0, V0, np.array([0.0, 1.0]), alpha=1.5, method="dop853_numba", atol=1e-150)
    assert np.all(np.isfinite(run.x))


def test_a_complex_state_is_refused_not_cut_to_its_real_part():
    with pytest.raises(ValueError) as err:
        integrate_lattice(X0 + 1e-3j, V0, np.array([0.0, 1.0]), alpha=1.5)
    assert _one_line(err) == "x0 must be real (a position or velocity per bead), got complex values"
