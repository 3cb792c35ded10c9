"""The pulse measurements (cradle.measurements.pulse) on runs whose answer is known: a travelling profile
v_n(t) = g(n - c t) gives arrival times n / c, speed c and the FWHM of g."""
from __future__ import annotations

import numpy as np
import pytest

from cradle.measurements import pulse


def _travelling(c=1.7, sigma=0.6, N=12, T=9.0, samples=20001):
    t = np.linspace(0.0, T, samples)
    n = np.arange(N)
    v = np.exp(-0.5 * ((n[None, :] - c * t[:, None] - 1.0) / sigma) ** 2)   # peak of bead n at t = (n - 1) / c
    return t, v, c, sigma


def test_peaks_speeds_and_widths_of_a_travelling_profile():
    t, v, c, sigma = _travelling()
    tn, vn = pulse.peaks(t, v)
    inner = slice(2, 12)
    assert np.allclose(tn[inner], (np.arange(12)[inner] - 1.0) / c, atol=1e-7)
    assert np.allclose(vn[inner], 1.0, atol=1e-7)
    sp = pulse.local_speeds(tn)
    assert np.isnan(sp[0]) and np.isnan(sp[-1])
    assert np.allclose(sp[2:-1], c, rtol=1e-6)
    assert pulse.fitted_speed(tn, np.arange(2, 12)) == pytest.approx(c, rel=1e-6)
    w = pulse.widths(t, v, sp)
    fwhm = 2.0 * np.sqrt(2.0 * np.log(2.0)) * sigma
    assert np.allclose(w[2:-1], fwhm, rtol=1e-5)
