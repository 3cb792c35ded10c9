"""Theorem 1 measured (cradle.analyses.theorem1): exact travelling waves of (ad) with V = V0 by a
sine-series Newton solver (cradle.models.waves), against the DpS dispersion relation (wleadingorder),
(va) and the q = pi binary oscillation (inteq)."""
import numpy as np
import pytest

from cradle.analyses import theorem1 as T
from cradle.models import dps, lattice, waves as W

M = 2**13   # small grids keep the tests fast; aliasing ~ M^-(alpha+1) ~ 1e-10


@pytest.mark.parametrize("alpha", [1.5, 2.0])
def test_dps_limit_and_correction_slope(alpha):
    """omega_a -> (wleadingorder) as a -> 0, the relative correction shrinking like a^(alpha-1)."""
    q = np.pi / 5
    a = np.geomspace(1e-4, 1e-2, 5) ** (1.0 / (alpha - 1.0))   # eps = a^(alpha-1) in [1e-4, 1e-2]
    waves = W.branch(a, q, alpha, modes=32, M=M)
    assert max(w.residual for w in waves) < 1e-12
    lam = np.array([w.lam for w in waves])
    assert np.all(np.abs(lam / T.lambda0(q, alpha) - 1.0) < 0.05)
    rel = T.relative_correction(lam, a, q, alpha)
    assert np.all(np.abs(rel) < 0.05) and abs(rel[0]) < 1e-4
    slope = T.log_slope(a, rel)
    assert abs(slope - (alpha - 1.0)) < 0.15, slope
    # the cancellation-free relative correction agrees with the naive one where the latter is accurate
    om = np.array([w.omega for w in waves])
    om_dps = T.omega_dps(a, q, alpha)
    np.testing.assert_allclose(rel[-1], (om[-1] - om_dps[-1]) / (om_dps[-1] - 1.0), rtol=1e-6)
    # omega_DpS of the theorem is omega_tw of (freq)
    np.testing.assert_allclose(om_dps, [dps.omega_tw(x, q, alpha) for x in a], rtol=1e-15)


@pytest.mark.parametrize("alpha", [1.5, 2.5])
def test_q_pi_matches_the_inteq_quadrature(alpha):
    """q = pi: the wave is x_n = (-1)^n a(t), a'' = -a - 2^alpha a|a|^(alpha-1) (inteq); same frequency to 1e-8."""
    for w in W.branch([1e-3, 1e-2, 0.1, 1.0, 5.0, 50.0], np.pi, alpha, modes=128, M=2**14)[::2]:
        amp, A = w.a, W.wave_max(w)
        assert abs(w.omega / T.binary_frequency(A, alpha) - 1.0) < 1e-8, (amp, w.omega)
        np.testing.assert_allclose(w.v[1::2], 0.0, atol=1e-14)   # only odd harmonics: u(xi + pi) = -u(xi)
    # the quadrature itself: small amplitude -> 1, and a direct integration of (inteq)
    from scipy.integrate import solve_ivp

    A = 0.7
    T_quad = T.binary_period(A, alpha)
    sol = solve_ivp(lambda t, y: [y[1], lattice.binary_oscillation_rhs(y[0], alpha)], (0, 2 * T_quad),
                    [A, 0.0], rtol=1e-12, atol=1e-14, dense_output=True)
    np.testing.assert_allclose(sol.sol(T_quad)[0], A, rtol=1e-8)
    np.testing.assert_allclose(sol.sol(T_quad / 2)[0], -A, rtol=1e-8)


def test_modes_convergence_and_algebraic_decay():
    """Errors in omega and v fall algebraically with the number of modes; |v_j| ~ j^-(alpha+3)."""
    alpha, q, a = 1.5, np.pi / 5, 0.1
    ref = W.solve(a, q, alpha, modes=256, M=M)
    xs = np.linspace(0, 2 * np.pi, 1025)
    errs_om, errs_v = [], []
    for J in (16, 32, 64):
        w = W.solve(a, q, alpha, modes=J, M=M, guess=ref)
        errs_om.append(abs(w.omega - ref.omega))
        errs_v.append(np.max(np.abs(T._sample_v(w, xs) - T._sample_v(ref, xs))))
    assert errs_v[0] > 5 * errs_v[1] > 25 * errs_v[2]   # ~ J^-3.3 here
    assert errs_om[0] > errs_om[1] > errs_om[2] and errs_om[2] < 1e-12
    s = T.decay_rate(ref.v)
    assert alpha + 2.5 < s < alpha + 3.5, s


def test_profile_correction_leading_term():
    """v_a -> K_h P_h N0(sin) of (va) (quadrature of (ph), (kh)) as a -> 0, and the remainder shrinks."""
    alpha, q = 1.5, np.pi / 2
    xi = np.linspace(0.0, 2 * np.pi, 33)
    lead = T.va_leading(xi, q, alpha)
    # the same operator in Fourier: (K_h P_h f)_j = f_j / (1 - j^2), j >= 2
    J = 256
    Nj = W.sine_coefficients(W.N_grid(np.r_[1.0, np.zeros(J - 1)], q, alpha, 2**14)[0], J)
    j = np.arange(2, J + 1)
    v0 = np.sin(np.outer(xi, j)) @ (Nj[1:] / (1.0 - j**2))
    np.testing.assert_allclose(lead, v0, atol=1e-7)
    errs = []
    for a in (1e-8, 1e-6, 1e-4):
        w = W.solve(a, q, alpha, modes=64, M=M)
        errs.append(np.max(np.abs(T._sample_v(w, xi) - lead)))
    assert errs[0] < 1e-3 and errs[0] < errs[1] < errs[2]


def test_exact_wave_solves_the_lattice():
    """The wave u(q n - omega t), q = 2 pi k / N, integrated as (nc) on a ring, comes back after t = 3 periods."""
    from scipy.integrate import solve_ivp

    alpha, N, k, a = 1.5, 10, 2, 0.5
    q = 2 * np.pi * k / N
    w = W.solve(a, q, alpha, modes=256, M=2**15)   # 64 modes: error 4e-7; 128: 5e-8; 256: 5e-9
    n = np.arange(N)
    c = w.coefficients()
    jj = np.arange(1, c.size + 1)

    def wave(t):
        xi = q * n - w.omega * t
        return np.sin(np.outer(xi, jj)) @ c, -w.omega * (np.cos(np.outer(xi, jj)) @ (jj * c))

    x0, v0 = wave(0.0)
    t_end = 3 * 2 * np.pi / w.omega
    sol = solve_ivp(lambda t, y: np.r_[y[N:], lattice.acceleration(y[:N], alpha)], (0, t_end), np.r_[x0, v0],
                    method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True)
    for t in (0.37 * t_end, t_end):
        x, v = wave(t)
        np.testing.assert_allclose(sol.sol(t)[:N], x, atol=3e-8 * a)
        np.testing.assert_allclose(sol.sol(t)[N:], v, atol=3e-8 * a)
    # the DpS frequency would drift visibly over the same span
    assert abs(w.omega - T.omega_dps(a, q, alpha)) * t_end > 1e-3


def test_theorem1_file_is_a_tree_named_as_in_the_paper(tmp_path):
    """A tiny `theorem1` run, written and read back: the groups /waves, /profiles, /convergence,
    /scenes hold the waves of cradle.models.waves under the paper's names, values as solved; a scene's
    a, q, alpha and t_end come from its initial-data file, read by name; the figure draws from the file."""
    import xarray as xr

    from cradle.analyses.protocol import Read
    from cradle.data.io import open_tree, write_netcdf
    from cradle.figures import save_figure
    from cradle.figures.theorem1 import draw
    from cradle.specs.declare import from_plain

    alpha, q = 1.5, np.pi / 2
    spec = from_plain(T.Theorem1, {"alpha": [alpha], "q": ["pi/2", "pi"], "a_min": 1e-3, "a_max": 0.1,
                                   "n_amplitudes": 3, "modes": 16, "grid_log2": 10, "slope_eps_max": 1.0,
                                   "convergence_a": 0.01, "convergence_modes": [8, 16], "n_xi": 9, "scenes": ["tw"]})
    assert spec.wavenumbers == [q, np.pi]
    assert T.ANALYSIS.reads_of(spec) == {"tw/initial": Read.of("initial", scene="tw")}
    initial = xr.Dataset(attrs={"scene": "tw", "alpha": alpha, "q": q, "a": 0.05, "omega_tw": 1.0, "t_end": 100.0})
    tree = open_tree(write_netcdf(T.compute(spec, {"tw/initial": initial}), tmp_path / "theorem1.nc"))
    assert {node.path for node in tree.subtree} == {"/", "/waves", "/profiles", "/convergence", "/scenes"}
    waves = tree["waves"]
    assert waves["omega"].dims == ("alpha", "q", "a") and waves["omega"].attrs["units"] == "1"
    np.testing.assert_array_equal(waves["a"].values, np.geomspace(1e-3, 0.1, 3))
    ws = W.branch(waves["a"].values, q, alpha, modes=16, M=2**10)
    np.testing.assert_array_equal(waves["omega"].sel(alpha=alpha, q=q).values, [w.omega for w in ws])
    np.testing.assert_allclose(waves["omega_dps"].sel(alpha=alpha, q=q).values,
                               T.omega_dps(waves["a"].values, q, alpha), rtol=1e-15)
    # q = pi: the binary oscillation (inteq) at the wave's amplitude has the wave's frequency
    np.testing.assert_allclose(waves["omega"].sel(q=np.pi).values, waves["omega_binary"].values, rtol=1e-6)
    assert tree["profiles"]["v_small"].dims == ("alpha", "q", "xi") and tree["profiles"]["xi"].size == 9
    assert list(tree["convergence"]["modes"].values) == [8, 16]
    assert tree["convergence"]["decay_rate"].dims == ("alpha", "q")
    sc = tree["scenes"]
    assert sc["q"].values[0] == q and sc["t_end"].values[0] == 100.0 and list(sc["scene"].values) == ["tw"]
    assert sc["a"].sel(scene="tw") == 0.05                                  # the scene by name
    assert sc["drift"].values[0] == pytest.approx(abs(sc["omega"].values[0] - sc["omega_dps"].values[0]) * 100.0)
    assert tree.attrs["q_expr"] == "pi/2, pi"
    assert all(p.stat().st_size > 0 for p in save_figure(draw(tree), tmp_path / "theorem1"))
