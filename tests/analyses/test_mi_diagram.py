"""Modulational instability of the DpS plane waves (cradle.analyses.mi_diagram): the rotating-frame fixed point,
the sideband stability matrix against a finite-difference Jacobian and direct DpS runs, scale invariance,
and the threshold q_c = pi/2."""
import numpy as np
import pytest

from cradle.analyses import mi_diagram as MI
from cradle.models import dps


@pytest.mark.parametrize("alpha", [1.5, 2.0, 3.0])
@pytest.mark.parametrize("R", [0.3, 1.0, 2.5])
def test_plane_wave_is_a_fixed_point_of_the_rotating_frame(alpha, R):
    N = 200
    worst = max(np.max(np.abs(MI.rotating_rhs(np.zeros(N), 2 * np.pi * k / N, R, alpha))) for k in range(N))
    assert worst < 1e-13 * max(1.0, R ** alpha)
    # and the explicit (ansatz3) solves (dfnls) in the lab frame
    n = np.arange(N)
    q = 2 * np.pi * 37 / N
    A = dps.plane_wave(n, 0.4, R, q, 0.3, alpha)
    dA = 1j * dps.plane_wave_frequency(R, q, alpha) * A
    np.testing.assert_allclose(dps.rhs(A, alpha), dA, atol=1e-13 * max(1.0, R ** alpha))


@pytest.mark.parametrize("alpha", [1.5, 3.0])
def test_growth_rate_matches_the_linearised_lattice(alpha):
    """Closed form = 2x2 sideband matrix = spectrum of the finite-difference Jacobian of the rotating frame."""
    N, R = 40, 1.3
    for k in (6, 14, 17):   # q = 0.94 (stable), 2.20, 2.67
        q = 2 * np.pi * k / N

        def f(x, q=q):
            r = MI.rotating_rhs(x[:N] + 1j * x[N:], q, R, alpha)
            return np.r_[r.real, r.imag]

        h = 1e-6
        J = np.array([(f(h * e) - f(-h * e)) / (2 * h) for e in np.eye(2 * N)]).T
        lam_fd = np.max(np.linalg.eigvals(J).real)
        p = 2 * np.pi * np.arange(N) / N
        lam = MI.growth_rate(q, p, alpha, R)
        # the neutral Goldstone pair (a Jordan block) puts ~ sqrt(FD error) ~ 1e-5 into the FD spectrum
        assert abs(lam_fd - lam.max()) < 1e-4 * max(1.0, lam.max())
        np.testing.assert_allclose(lam, MI.growth_rate_matrix(q, p, alpha, R), atol=1e-6)


@pytest.mark.parametrize("alpha,k_q,m_p", [(1.5, 100, 27), (1.5, 55, 100), (2.0, 80, 20), (3.0, 70, 10)])
def test_growth_rate_matches_direct_dps_runs(alpha, k_q, m_p):
    sim, theory = MI.simulated_growth(alpha, N=200, k_q=k_q, m_p=m_p)
    assert theory > 0
    assert abs(sim / theory - 1.0) < 0.05, (sim, theory)


def test_scale_invariance():
    """lambda tau0 R^(1-alpha) depends on (q, p) only; a direct run at R = 3 agrees with R = 1 rescaled."""
    q = np.linspace(0, np.pi, 61)[:, None]
    p = np.linspace(-np.pi, np.pi, 81)[None, :]
    for alpha in (1.5, 2.0, 3.0):
        ref = MI.scaled_growth_rate(q, p, alpha)
        for R in (0.01, 0.7, 40.0):
            np.testing.assert_allclose(MI.growth_rate(q, p, alpha, R) * dps.tau0(alpha) * R ** (1 - alpha), ref,
                                       rtol=1e-12, atol=1e-14)
    sim, theory = MI.simulated_growth(1.5, N=200, k_q=100, m_p=27, R=3.0)
    np.testing.assert_allclose(theory, MI.growth_rate(np.pi, 2 * np.pi * 27 / 200, 1.5, 1.0) * 3.0**0.5, rtol=1e-12)
    assert abs(sim / theory - 1.0) < 0.05


@pytest.mark.parametrize("alpha", [1.2, 1.5, 2.0, 3.0])
def test_threshold_is_pi_over_2_and_p_pi_goes_first(alpha):
    qc, pc = MI.threshold(alpha)
    assert abs(qc - np.pi / 2) < 1e-9 and abs(pc - np.pi) < 1e-3
    p = np.linspace(-np.pi, np.pi, 401)[None, :]
    q_stable = np.linspace(0, np.pi / 2, 101)[:-1, None]
    assert np.all(MI.scaled_growth_rate(q_stable, p, alpha) == 0.0)
    assert np.max(MI.scaled_growth_rate(np.pi / 2, p, alpha)) < 1e-7   # cos(pi/2) = 6e-17 in floating point
    # q = pi: max_p lambda tau0 = 2^(alpha-1) (alpha-1)/sqrt(alpha) at cos p = 1/alpha
    g, p = MI.max_over_p(np.pi, alpha)
    np.testing.assert_allclose(g, 2 ** (alpha - 1) * (alpha - 1) / np.sqrt(alpha), rtol=1e-12)
    np.testing.assert_allclose(p, np.arccos(1 / alpha), atol=1e-5)


def test_mi_diagram_file_is_a_tree_named_as_in_the_paper(tmp_path):
    """A tiny `mi-diagram` run, written and read back: the thresholds at the root, the map over (q, p)
    in /map, the direct runs in /checks, values as the closed form gives them; it reads no file; the
    figure draws from the file."""
    from cradle.data.io import open_tree, write_netcdf
    from cradle.figures import save_figure
    from cradle.figures.mi_diagram import draw
    from cradle.specs.declare import from_plain

    spec = from_plain(MI.MIDiagram, {"alpha": [1.5], "n_q": 5, "n_p": 7, "check_N": 40, "check_pairs": [[14, 3]]})
    assert MI.ANALYSIS.reads_of(spec) == {}
    tree = open_tree(write_netcdf(MI.compute(spec, {}), tmp_path / "mi-diagram.nc"))
    assert {node.path for node in tree.subtree} == {"/", "/map", "/checks"}
    assert tree["map"]["growth"].dims == ("alpha", "q", "p")
    q, p = tree["map"]["q"].values, tree["map"]["p"].values
    np.testing.assert_array_equal(tree["map"]["growth"].values[0], MI.scaled_growth_rate(q[:, None], p[None, :], 1.5))
    assert abs(tree["q_threshold"].values[0] - np.pi / 2) < 1e-9
    chk = tree["checks"]
    assert chk["q"].values[0, 0] == 2 * np.pi * 14 / 40 and abs(chk["rel_error"].values[0, 0]) < 0.05
    assert all(path.stat().st_size > 0 for path in save_figure(draw(tree), tmp_path / "mi-diagram"))


@pytest.mark.parametrize("alpha", [1.2, 1.5, 3.0])
def test_max_growth_rate_closed_form(alpha):
    """max_growth_rate's closed form: the maximum of growth_rate over a fine grid of p (never below it, equal to
    within the grid's resolution), at the stated sideband; the band is where growth_rate > 0; zero with no band for
    cos q >= 0; the rate scales as R^(alpha-1); at q = pi it is 2^(alpha-1) (alpha-1) / (sqrt(alpha) tau0) at
    cos p = 1/alpha (the case a <= 0), and for -(alpha-1)/(alpha+1) < cos q < 0 the largest sideband is p = pi."""
    p = np.linspace(0.0, np.pi, 400001)
    h = p[1] - p[0]
    crossover = np.arccos(-(alpha - 1) / (alpha + 1))
    for q in (0.3, np.pi / 2 - 1e-3, np.pi / 2 + 1e-3, 0.5 * (np.pi / 2 + crossover), crossover + 0.05, 2.6, np.pi,
              -2.2):
        rate, p_max, lo, hi = MI.max_growth_rate(q, alpha, 1e-3)
        grid = MI.growth_rate(q, p, alpha, 1e-3)
        if np.cos(q) >= 0:
            assert rate == 0.0 and np.all(grid == 0.0) and np.isnan(lo) and np.isnan(hi)
            continue
        # never above it but for rounding (the two formulas round differently near cos q = 0), equal to within
        # the grid's resolution
        assert rate >= grid.max() * (1 - 1e-12) and rate == pytest.approx(grid.max(), rel=1e-8)
        assert float(MI.growth_rate(q, p_max, alpha, 1e-3)) == pytest.approx(rate, rel=1e-12)
        band = p[grid > 0]
        assert abs(band.min() - lo) <= h and abs(band.max() - hi) <= h
        if np.cos(q) > -(alpha - 1) / (alpha + 1):
            assert p_max == np.pi
        for R in (1e-8, 0.3):
            assert MI.max_growth_rate(q, alpha, R)[0] == pytest.approx(rate * (R / 1e-3) ** (alpha - 1), rel=1e-12)
    g, p_pi, _, _ = MI.max_growth_rate(np.pi, alpha, 1.0)
    assert g * dps.tau0(alpha) == pytest.approx(2 ** (alpha - 1) * (alpha - 1) / np.sqrt(alpha), rel=1e-12)
    assert np.cos(p_pi) == pytest.approx(1 / alpha, rel=1e-12)
