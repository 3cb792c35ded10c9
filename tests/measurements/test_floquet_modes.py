"""cradle.measurements.floquet_modes: where a Floquet mode lives, checked against what mathematics fixes.

* A mode on one site has participation ratio 1, a plane wave e^{i q n} on N sites N; weights sum to 1.
* The measures are unchanged by the ring's shift (A and the mode rolled together), by any complex multiple of the
  eigenvector and by the TB's phase rotation A -> e^{i phi} A (each site's (x_n, y_n) turned by phi).
* The top mode of a block-diagonal symplectic matrix is the eigenvector of its largest eigenvalue, on the sites
  that block acts on; the growth rate is ln|mu| / T.
* A power law y = a N^s gives back s with zero error; N^-1 weights on the core of an extended mode give slope -1.
"""
from __future__ import annotations

import numpy as np
import pytest

from cradle.measurements import floquet_modes as FM


def _profile(N: int, centre: int = 7) -> np.ndarray:
    """A localised state with a small oscillatory tail (doubly exponential core, plane-wave tail of 1e-5)."""
    n = np.arange(N)
    d = np.abs((n - centre + N / 2) % N - N / 2)
    return np.exp(-(1.6 ** d)) * np.exp(0.3j * n) + 1e-5 * np.exp(0.6j * n)


def test_delta_and_plane_wave_participation():
    N = 40
    delta = np.zeros(2 * N, complex)
    delta[5] = 0.3 - 2j
    w = FM.site_weights(delta)
    assert FM.participation(w) == pytest.approx(1.0, abs=1e-15)
    assert w.sum() == pytest.approx(1.0, abs=1e-15)
    q = 2 * np.pi * 3 / N
    wave = np.exp(1j * q * np.arange(N))
    # the perturbation dA = wave in (Re, Im), and the complex eigenvector (z, -i z) of a complex-linear mode z
    for v in (np.concatenate([wave.real, wave.imag]), np.concatenate([wave, -1j * wave])):
        w = FM.site_weights(v)
        assert w.sum() == pytest.approx(1.0, abs=1e-14)
        assert FM.participation(w) == pytest.approx(N, rel=1e-13)
    # a state spread evenly over k sites occupies k of them
    v = np.zeros(2 * N, complex)
    v[:9] = np.exp(1j * np.arange(9))
    v[N:N + 9] = 0.5 * np.exp(-2j * np.arange(9))
    assert FM.participation(FM.site_weights(v)) == pytest.approx(9.0, rel=1e-14)
    with pytest.raises(ValueError, match="2N"):
        FM.site_weights(np.ones(7))


def test_zero_vector_refused():
    with pytest.raises(ValueError, match="zero vector"):
        FM.site_weights(np.zeros(6, complex))


def test_invariant_under_shift_eigenvector_phase_and_tb_phase():
    rng = np.random.default_rng(3)
    N = 32
    A = _profile(N)
    v = (rng.normal(size=2 * N) + 1j * rng.normal(size=2 * N)) * np.concatenate([np.abs(A), np.abs(A)]) ** 0.2
    x, y = v[:N], v[N:]
    base = FM.site_weights(v)
    cores = [FM.core_mask(A, k, lv) for k, lv in FM.CORE_DEFINITIONS]
    ref = (FM.participation(base), *[FM.core_fraction(base, m) for m in cores])
    assert all(0.0 < r for r in ref[1:]) and ref[0] > 1.0
    s, z, phi = 11, 0.4 - 1.7j, 0.9
    c, sn = np.cos(phi), np.sin(phi)
    cases = {"shift": (np.roll(A, s), np.concatenate([np.roll(x, s), np.roll(y, s)])),
             "eigenvector phase": (A, z * v),
             "TB phase": (np.exp(1j * phi) * A, np.concatenate([c * x - sn * y, sn * x + c * y]))}
    for name, (A2, v2) in cases.items():
        w = FM.site_weights(v2)
        got = (FM.participation(w), *[FM.core_fraction(w, FM.core_mask(A2, k, lv)) for k, lv in FM.CORE_DEFINITIONS])
        assert got == pytest.approx(ref, rel=1e-12), name


def test_core_masks():
    N = 48
    A = _profile(N, centre=40)
    amp = FM.core_mask(A, "amplitude", 1e-2)
    # |A| > 1e-2 max: exp(-1.6^d) > 1e-2 e^-1, i.e. 1.6^d < 1 + ln 100: d <= 3
    assert np.flatnonzero(amp).tolist() == [37, 38, 39, 40, 41, 42, 43]
    norm = FM.core_mask(A, "norm", 0.999)
    a2 = np.abs(A) ** 2 / np.sum(np.abs(A) ** 2)
    assert a2[norm].sum() >= 0.999
    d = FM.ring_distance(N, 40.0)
    r = d[norm].max()
    assert a2[d <= r - 1].sum() < 0.999           # the smallest such window
    assert norm.sum() == 2 * r + 1
    with pytest.raises(ValueError, match="kind"):
        FM.core_mask(A, "width", 3)


def test_top_mode_of_a_block_matrix():
    """exp of a Hamiltonian matrix acting on sites 0-1 as a hyperbolic block, elsewhere as rotations: the top mode is
    the block's unstable eigenvector, on those two sites only."""
    from scipy.linalg import expm

    from cradle.measurements import floquet_bubbles as FB

    N = 10
    J = FB.symplectic_form(N)
    S = np.diag(np.concatenate([np.linspace(0.1, 0.5, N), np.linspace(0.1, 0.5, N)]))
    # sites 0 and 1: H = g (x0 x1 - y0 y1) couples them into a hyperbolic pair of rate g
    g = 0.3
    S[0, 0] = S[1, 1] = S[N, N] = S[N + 1, N + 1] = 0.0
    S[0, 1] = S[1, 0] = g
    S[N, N + 1] = S[N + 1, N] = -g
    T = 2.0
    M = expm(T * J @ S)
    assert FB.symplectic_defect(M) < 1e-12
    A = np.zeros(N, complex)
    A[0], A[1] = 1.0, 0.5
    m = FM.mode_measures(M, A, T, trivial=0)
    assert m["growth"] == pytest.approx(g, rel=1e-10)
    assert m["participation"] == pytest.approx(2.0, rel=1e-10)
    assert m["core_fraction_0"] == pytest.approx(1.0, abs=1e-12)
    assert m["participation_share"] == pytest.approx(2.0 / N, rel=1e-10)


def test_power_slope():
    N = np.array([24, 32, 48, 64, 128.0])
    s, e = FM.power_slope(N, 3.0 * N**-0.7)
    assert s == pytest.approx(-0.7, abs=1e-12) and e < 1e-12
    # an extended mode: PR a fixed share of N, weight on a fixed core of 5 sites about 5/N
    w = [np.full(int(n), 1.0 / n) for n in N]
    s, _ = FM.power_slope(N, [x[:5].sum() for x in w])
    assert s == pytest.approx(-1.0, abs=1e-12)
    assert np.isnan(FM.power_slope(N[:2], N[:2])[0])


RINGS = np.array([24, 32, 48, 64, 80, 96, 112, 128, 160.0])


def test_rule_reads_an_extended_mode_with_growth_1_over_n_stable():
    """Two extended modes meeting through the core: growth ~ 1/N, core fraction ~ (core sites)/N."""
    v, info = FM.mode_verdict(RINGS, 0.02 / RINGS, 2.0 / RINGS, 1e-5)
    assert v == FM.STABLE
    assert FM.mode_verdict(RINGS, 0.02 / RINGS, 2.0 / RINGS, 1e-5, resolved=True)[0] == FM.STABLE
    assert info["growth_slope"] == pytest.approx(-1.0, abs=1e-12)
    assert info["core_slope"] == pytest.approx(-1.0, abs=1e-12)
    assert info["unstable_rings"] == RINGS.size
    # the same with growth below the threshold on the largest rings: read over the unstable ones
    v, info = FM.mode_verdict(RINGS, 1.5e-3 / RINGS, 2.0 / RINGS, 1e-5)
    assert v == FM.STABLE and info["unstable_rings"] == 8


def test_rule_reads_a_localised_mode_with_a_constant_rate_unstable():
    """A mode of the core meeting the tail's modes: an O(1) share on the core, a rate that does not fade."""
    v, _ = FM.mode_verdict(RINGS, np.full(RINGS.size, 3e-4), np.full(RINGS.size, 0.6), 1e-5)
    assert v == FM.UNSTABLE
    # on the core less than half, but not fading with N (slope 0 against -1): not a finite-size effect
    v, info = FM.mode_verdict(RINGS, 3e-4 * RINGS**-0.5, np.full(RINGS.size, 0.2), 1e-5)
    assert v == FM.UNSTABLE and info["core_slope"] == pytest.approx(0.0, abs=1e-12)


def test_rule_stable_everywhere_and_undecided_cases():
    stable = np.full(RINGS.size, 1e-14)
    assert FM.mode_verdict(RINGS, stable, np.full(RINGS.size, 0.99), 1e-5)[0] == FM.STABLE
    assert FM.mode_verdict(RINGS[:3], stable[:3], np.full(3, 0.99), 1e-5)[0] == FM.UNDECIDED
    # unstable on two rings only: no slope to read
    g = stable.copy()
    g[[3, 7]] = 1e-4
    assert FM.mode_verdict(RINGS, g, 2.0 / RINGS, 1e-5)[0] == FM.UNDECIDED
    # extended (core ~ 1/N) but the growth does not fall: not a finite-size effect either way
    assert FM.mode_verdict(RINGS, 3e-4 * RINGS**0.1, 2.0 / RINGS, 1e-5)[0] == FM.UNDECIDED
    # growth scattered about 1/N: consistent with it, its fall not resolved at two standard errors
    g = 0.02 / RINGS * np.array([3.0, 0.3, 1.0, 2.0, 0.4, 1.5, 0.5, 2.5, 1.0]) * RINGS**0.6
    _, info = FM.mode_verdict(RINGS, g, 2.0 / RINGS, 1e-5)
    assert info["growth_slope"] - 2 * info["growth_slope_error"] <= -1.0 < info["growth_slope"]
    assert info["growth_slope"] + 2 * info["growth_slope_error"] >= 0.0
    assert FM.mode_verdict(RINGS, g, 2.0 / RINGS, 1e-5)[0] == FM.STABLE
    assert FM.mode_verdict(RINGS, g, 2.0 / RINGS, 1e-5, resolved=True)[0] == FM.UNDECIDED
    # a core fraction falling as N^-0.6: within 0.5 of -1 but not within 0.3
    f = 0.3 * RINGS**-0.6
    assert FM.mode_verdict(RINGS, 0.02 / RINGS, f, 1e-5, 0.3)[0] == FM.UNDECIDED
    assert FM.mode_verdict(RINGS, 0.02 / RINGS, f, 1e-5, 0.5)[0] == FM.STABLE
    # a core fraction ~ 1/N on average but so scattered that a share not falling (slope 0) is not excluded
    f = 2.0 / RINGS * np.array([1.0, 6.0, 0.5, 5.0, 0.6, 4.0, 1.0, 8.0, 2.0])
    _, info = FM.mode_verdict(RINGS, 0.02 / RINGS, f, 1e-5)
    assert abs(info["core_slope"] + 1.0) <= 0.3 and info["core_slope"] + 2 * info["core_slope_error"] >= 0.0
    assert np.all(f < FM.CORE_SHARE)
    assert FM.mode_verdict(RINGS, 0.02 / RINGS, f, 1e-5)[0] == FM.UNDECIDED
    # a core fraction whose slope is near 0 but so scattered that 1/N is not excluded: not reading 2 either
    f = 0.05 * np.array([1.0, 0.1, 3.0, 0.2, 1.0, 0.1, 5.0, 0.1, 1.0])
    _, info = FM.mode_verdict(RINGS, 0.02 / RINGS, f, 1e-5)
    assert info["core_slope"] > -0.3 and info["core_slope"] - 2 * info["core_slope_error"] <= -1.0
    assert FM.mode_verdict(RINGS, 0.02 / RINGS, f, 1e-5)[0] == FM.UNDECIDED
