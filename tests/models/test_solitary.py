"""The solitary wave of the Hertz chain (cradle.models.solitary): numbers fixed by mathematics.

* the speed exponent 1/5: waves solved independently at several speeds have v_m proportional to c^5 (homogeneity
  of the Hertz force), so the fitted exponent of c in v_m is 1/5 to 1e-6 (measured: 1e-15);
* the residual of (sw) in its differential form, at the rounding floor of a second derivative by Fourier
  differentiation, eps (pi points)^2 (the largest wavenumber squared times the rounding of R);
* the tail doubly exponential: the local slope of log(-log R) over one site tends to log(3/2), and follows the
  tail's asymptotic law (Laplace's method on the integral form) to within the march's O(1) error in -log R;
* the computed wave is a solution of the chain: laid on the lattice and integrated by the Hertz chain without
  on-site term, it is found translated by c t (to the integrator's tolerance);
* Nesterenko's closed forms: his speed at the amplitude of his own profile, and the width pi sqrt(5/2).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from cradle.analyses.solitary_wave import launch, tail_slopes
from cradle.models import solitary as S

EPS = np.finfo(float).eps


@pytest.fixture(scope="module")
def wave():
    return S.solve(1.0, length=40.0, points=32)


def test_speed_exponent_is_one_fifth(wave):
    speeds = np.array([0.3, 1.0, 3.0, 10.0])
    vm = np.array([S.solve(c, 40.0, 32).velocity_max for c in speeds])
    slope = np.polyfit(np.log(vm), np.log(speeds), 1)[0]
    assert abs(slope - 0.2) < 1e-6
    # and each amplitude against its own law: R_m ~ c^4, f_m ~ c^6
    for c in speeds:
        w = S.solve(c, 40.0, 32)
        assert w.strain_max / wave.strain_max == pytest.approx(c**4, rel=1e-12)
        assert w.force_max / wave.force_max == pytest.approx(c**6, rel=1e-12)


def test_iteration_converged_to_its_fixed_point(wave):
    assert wave.increment < 1e-15 * 10
    assert wave.stabiliser == pytest.approx(1.0, abs=1e-13)


def test_residual_of_the_advance_delay_equation_at_the_rounding_floor(wave):
    points = 32
    floor = EPS * (math.pi * points) ** 2
    r = S.residual(wave)
    assert r < 10.0 * floor
    # the same equation with the wave of another speed fails it at order one
    wrong = S.SolitaryWave(1.05, wave.xi, wave.strain, wave.velocity, 0, 0.0, 1.0)
    assert S.residual(wrong) > 1e-2


def test_velocity_is_c_times_strain_integral(wave):
    """Momentum: sum over a wavelength of v equals int v dxi = c^-1 int R^(3/2) (the box has unit length); and the
    displacement jump int R dxi relates to it by c^2 int R = int R^(3/2) (the integrated (sw))."""
    h = float(wave.xi[1] - wave.xi[0])
    f = wave.strain**1.5
    assert np.sum(wave.velocity) * h == pytest.approx(np.sum(f) * h / wave.c, rel=1e-13)
    assert wave.c**2 * np.sum(wave.strain) * h == pytest.approx(np.sum(f) * h, rel=1e-12)


def test_tail_is_doubly_exponential(wave):
    xi, logR = S.tail(wave, 30.0)
    meas, pred = tail_slopes(xi, logR, wave.c)
    y = -logR
    far = np.isfinite(meas) & (y > 1e5)
    assert far.any()
    # log(-log R) grows by log(3/2) per site far out (an exponential tail would give slopes -> 0)
    assert np.all(np.abs(meas[far] - math.log(1.5)) < 1e-3)
    # and follows the asymptotic law to the O(1) absolute error of the march in -log R (relative 1/y)
    ok = np.isfinite(meas) & (y > 1e3)
    assert np.all(np.abs(meas[ok] - pred[ok]) * y[ok] < 1.0)
    # where both exist, the march continues the Fourier solution, to its two approximations: the cells' log R
    # taken linear (error h^2 |(log R)''| / 8 per cell) and the neglected part of the integral (order R^(1/2))
    h = float(wave.xi[1] - wave.xi[0])
    i0 = np.searchsorted(wave.xi, xi[0])
    m = int(round(1.0 / h))
    curvature = np.max(np.abs(np.diff(np.log(wave.strain[i0 - m: i0 + m // 2]), 2))) / h**2
    bound = h**2 * curvature / 8.0 + math.sqrt(wave.strain[i0])
    for k in range(1, m // 2):
        assert abs(logR[k] - math.log(wave.strain[i0 + k])) < bound


def test_wave_travels_unchanged_in_the_lattice(wave):
    r = launch(wave, 8.0, 1e-13)
    assert r["strain_error"] < 1e-10
    assert r["velocity_error"] < 1e-10


def test_nesterenko_closed_forms():
    Rm = 2.0
    assert S.nesterenko_speed(Rm) == pytest.approx(2.0 / math.sqrt(5.0) * Rm**0.25, rel=1e-15)
    assert S.nesterenko_amplitude(float(S.nesterenko_speed(Rm))) == pytest.approx(Rm, rel=1e-14)
    # in the velocity amplitude: v_m = c R_m in the long-wave limit
    c = float(S.nesterenko_speed(Rm))
    assert S.nesterenko_speed_v(c * Rm) == pytest.approx(c, rel=1e-14)
    assert S.NESTERENKO_WIDTH == pytest.approx(math.pi * math.sqrt(2.5), rel=1e-15)
    xi = np.linspace(-3.0, 3.0, 6001)
    prof = S.nesterenko_profile(xi, 1.0)
    assert np.count_nonzero(prof > 0.0) * 1e-3 == pytest.approx(S.NESTERENKO_WIDTH, abs=2e-3)


def test_nesterenko_profile_solves_his_long_wave_equation():
    """The travelling form of Nesterenko's equation (module docstring of cradle.models.solitary), integrated twice:
    c^2 R = R^(3/2) + (1/10) R^(1/4) (R^(5/4))'', solved by R_m cos^4(sqrt(2/5) xi) at c = (2/sqrt(5)) R_m^(1/4);
    checked by central differences inside the support (error h^2)."""
    Rm = 1.7
    c = float(S.nesterenko_speed(Rm))
    h = 1e-3
    xi = np.arange(-2.3, 2.3, h)
    R = S.nesterenko_profile(xi, Rm)
    q = R**1.25
    d2 = (q[2:] - 2.0 * q[1:-1] + q[:-2]) / h**2
    lhs = c**2 * R[1:-1]
    rhs = R[1:-1] ** 1.5 + 0.1 * R[1:-1] ** 0.25 * d2
    assert np.max(np.abs(lhs - rhs)) / np.max(lhs) < 1e-5
