"""Exact breathers of (nc) (cradle.integrators.lattice_breathers, cradle.models.dps_breathers,
cradle.analyses.breathers): the period map fixes them, their multipliers are symplectic with the trivial
pair at +1, their symmetry classes, dE/dJ = omega_b / (2 pi) along a family, the DpS limit with its
exponent, the DpS stability scaling and barrier formula, a tiny family in seconds."""
import copy
import time

import numpy as np
import pytest

from cradle.integrators import lattice_breathers as lb
from cradle.models import dps, dps_breathers as db, homoclinic
from tolerance import EPS, bound_of, eigenvalue_bounds, sqrt_bounds

ALPHA = 1.5
N = 10


@pytest.fixture(scope="module")
def profiles():
    return {k: homoclinic.solve(homoclinic.initial_guess(N, k, ALPHA, 0.1), ALPHA).a for k in ("site", "bond")}


@pytest.fixture(scope="module")
def breathers(profiles):
    """Site and bond breathers at omega_b = 1.1 on a ring of 10 beads, from the DpS start."""
    return {k: lb.newton(lb.dps_start(a, 1.1, ALPHA), 1.1, ALPHA, kind=k) for k, a in profiles.items()}


@pytest.mark.parametrize("kind", ["site", "bond"])
def test_period_map_fixes_the_breather(breathers, kind):
    """z(T) = z(0) over a full period integrated afresh (the Newton solve used T/2 or T/4), at the shooting
    tolerance and at the finer one of the resolution check."""
    b = breathers[kind]
    assert b.converged and b.half_residual <= 1e-11
    r, J = lb.period_residual(b)
    r_fine, J_fine = lb.period_residual(b, rtol=2.5e-14)
    assert r <= 1e-9 and r_fine <= 1e-9
    assert abs(J / J_fine - 1) <= 1e-10
    # localised (the antipode of the centre ~1e-4 on this small ring), not the DpS start: differs at O(omega_b - 1)
    assert abs(b.x0[0]) <= 1e-3 * b.amplitude
    assert 0.05 < np.max(np.abs(b.x0 - lb.dps_start(homoclinic.solve(homoclinic.initial_guess(
        N, kind, ALPHA, 0.1), ALPHA).a, 1.1, ALPHA))) / b.amplitude < 0.3


def test_symmetry_classes(breathers):
    """(nc) is invariant under x_n -> -x_{2c-n}: bond x(0) = -S x(0); site x(T/2) = -S x(0)."""
    b = breathers["bond"]
    S = lb.reflection(N, N // 2 + 0.5)
    assert np.max(np.abs(b.x0 + S @ b.x0)) <= 1e-14 * b.amplitude
    s = breathers["site"]
    S = lb.reflection(N, N // 2)
    x_half, v_half, _, _ = lb.flow(s.x0, np.zeros(N), s.T / 2, ALPHA)
    assert np.max(np.abs(x_half + S @ s.x0)) <= 1e-9 * s.amplitude
    assert np.max(np.abs(v_half)) <= 1e-9 * s.amplitude
    # the site breather's x(0) itself is not reflection-symmetric (even harmonics of the one-sided force)
    assert np.max(np.abs(s.x0 - S @ s.x0)) > 1e-3 * s.amplitude


@pytest.mark.parametrize("kind", ["site", "bond"])
def test_multipliers_are_symplectic_with_the_trivial_pair(breathers, kind):
    """mu, 1/mu, conj mu all present (2N of them); two at +1 (phase and frequency: a Jordan block, so an
    error ~ sqrt(integration error)); the core monodromy agrees with the full 2N x 2N one."""
    b = breathers[kind]
    fl = lb.floquet(b, kind)
    assert fl.mu.size == 2 * N
    c = lb.multiplier_checks(fl.mu)
    # M = R M(T/2)^-1 R M(T/2) is conjugate to its inverse by construction, and real: the pairings hold to the
    # rounding of the solve and of eig (mu <-> 1/mu moves by (1 + 1/|mu|^2) times a multiplier's bound)
    mu, bounds = _multiplier_bounds(b)
    at = bound_of(fl.mu, mu, bounds)
    assert c["reciprocal"] <= np.max(at * (1 + 1 / np.abs(fl.mu) ** 2)) and c["conjugate"] <= np.max(at)
    # the trivial pair is a Jordan block, split by ~ sqrt of the orbit's integration error (1e-6 .. 1e-5 over
    # the OpenBLAS kernel types, whose rounding the adaptive steps amplify; the symplectic defect of M is ~1e-14,
    # so it is not rounding): 1e-4, the precision the analysis reports beside a pinning multiplier near +1
    assert fl.trivial <= 1e-4
    _, mu_full, _ = lb.monodromy(b, rel=None)
    assert np.max(np.min(np.abs(fl.mu[:, None] - mu_full[None, :]), axis=1)) <= 1e-4


def _multiplier_bounds(b):
    """Rounding bounds on the multipliers of b (tolerance.eigenvalue_bounds on the core monodromy M, with the
    backward error of forming M by a solve with M(T/2): n eps cond(M(T/2)) ||M||)."""
    M, _, idx = lb.monodromy(b)
    Mh = lb.half_period_map(b, idx)
    mu, bounds = eigenvalue_bounds(M, backward=M.shape[0] * EPS * np.linalg.cond(Mh) * np.linalg.norm(M, 2))
    tail = np.full(2 * (b.x0.size - idx.size), EPS)    # exp(+-iT) of the harmonic tail, one rounding
    return np.concatenate([mu, np.repeat(np.exp([1j * b.T, -1j * b.T]), b.x0.size - idx.size)]), \
        np.concatenate([bounds, tail])


def test_stability_verdicts_site_unstable_bond_stable(breathers):
    """The pinning pair: real (unstable) for the site breather, on the unit circle for the bond one; the
    DpS eigenvalues have the same verdicts."""
    s, b = lb.floquet(breathers["site"], "site"), lb.floquet(breathers["bond"], "bond")
    assert s.odd_growing and s.rate > 1e-5
    # stable: every non-trivial multiplier on the unit circle (simple ones stay there under reversible
    # errors), so |mu| - 1, and ln|mu| = rate T, to the rounding bound of each multiplier
    mu, bounds = _multiplier_bounds(breathers["bond"])
    nontrivial = np.ones(mu.size, bool)
    nontrivial[np.argsort(np.abs(mu - 1.0))[:2]] = False
    assert b.rate * breathers["bond"].T <= np.max(bounds[nontrivial]) < 1e-3 * s.rate * breathers["site"].T
    assert np.min(np.abs(np.abs(b.mu_odd) - 1.0)) <= np.max(bound_of(b.mu_odd, mu, bounds))


def test_dps_stability_scales_with_omega_and_pairs_site_with_bond(profiles):
    """(dfnls) is homogeneous: at amplitude scaled by c its eigenvalues scale by c^(alpha-1), i.e. by
    omega_b - 1; the site breather has a real pinning pair, the bond breather an imaginary one."""
    a = profiles["site"]
    lam1, _ = db.stability(a, 1.01, ALPHA)
    lam2, _ = db.stability(a, 1.04, ALPHA)
    g1, g2 = np.max(lam1.real), np.max(lam2.real)
    # lambda = +-sqrt(ev), ev the eigenvalues of -A B: each ev known to its rounding bound (A and B formed with a
    # few roundings per entry: backward error ~ 4 eps ||A|| ||B||), and lambda to the square root's bound
    r1, r2 = (float(_lambda_bound(a, om, g)[0]) / g for om, g in ((1.01, g1), (1.04, g2)))
    assert g1 > 0 and g2 / g1 == pytest.approx(4.0, rel=r1 + r2)
    lamb, _ = db.stability(profiles["bond"], 1.04, ALPHA)
    # the bond breather's spectrum is on the imaginary axis, up to the zero pair (phase and its partner): a
    # simple zero of -A B, so lambda = sqrt(ev) is known only to ~ sqrt(eps ||A B||) (~ 1e-9 here, the pinning
    # growth g2 ~ 6e-5)
    bound = _lambda_bound(profiles["bond"], 1.04, lamb)
    assert np.max(lamb.real) <= np.max(bound) < 1e-3 * g2


def _lambda_bound(a, omega, lam):
    """Rounding bounds on the DpS eigenvalues lambda nearest ``lam`` (tolerance.eigenvalue_bounds on -A B)."""
    A, B = db.operators(a, omega, ALPHA)
    M = -A @ B
    ev, b = eigenvalue_bounds(M, backward=4 * EPS * np.linalg.norm(A, 2) * np.linalg.norm(B, 2))
    lb_ = sqrt_bounds(ev, b)
    roots = np.concatenate([np.sqrt(ev.astype(complex)), -np.sqrt(ev.astype(complex))])
    return bound_of(lam, roots, np.concatenate([lb_, lb_]))


def test_dps_barrier_formula_matches_direct_hamiltonian(profiles):
    """-2 (H_bond - H_site) at equal norm, with H of (dfnls) evaluated directly on the scaled profiles."""
    J = 1e-3
    P = J / (4 * np.pi)
    H = {k: dps.hamiltonian(np.sqrt(P / np.sum(a**2)) * a, ALPHA) for k, a in profiles.items()}
    assert db.pn_barrier(profiles["site"], profiles["bond"], J, ALPHA) == pytest.approx(
        -2 * (H["bond"] - H["site"]), rel=1e-10)


@pytest.fixture(scope="module")
def families(profiles):
    t0 = time.perf_counter()
    out = {k: lb.continue_family(a, [1.0025, 1.005, 1.01], ALPHA, kind=k)[0] for k, a in profiles.items()}
    return out, time.perf_counter() - t0


def test_tiny_family_in_seconds(families):
    fams, wall = families
    assert all(len(f) == 3 and all(b.converged for b in f) for f in fams.values())
    assert wall < 60.0   # ~5 s on an idle core; generous for a shared machine


def test_exact_breather_tends_to_dps_with_exponent_one(families, profiles):
    """max|x - x_DpS| / max|x| ~ C (omega_b - 1)^p with p -> 1 (= (alpha - 1) x 1/(alpha - 1): the relative
    correction is O(eps^(alpha-1)) as for the travelling waves of Theorem 1)."""
    fams, _ = families
    for kind, fam in fams.items():
        om = np.array([b.omega for b in fam])
        d = [np.max(np.abs(b.x0 - lb.dps_start(profiles[kind], b.omega, ALPHA))) / b.amplitude for b in fam]
        p = np.polyfit(np.log(om - 1), np.log(d), 1)[0]
        assert p == pytest.approx(1.0, abs=0.01)
        assert d[0] < 0.005


def test_energy_action_relation_along_a_family(families):
    """dE/dJ = 1/T = omega_b / (2 pi) for a family of periodic orbits: between two breathers,
    Delta E = Delta J / (2 pi) + int (omega_b - 1) dJ / (2 pi), the integral with omega_b - 1 = c J^p through
    both ends (J ~ (omega_b - 1)^4 here, so a trapezoid in J would be first order)."""
    fams, _ = families
    for fam in fams.values():
        E = np.array([b.energy() for b in fam])
        J = np.array([lb.period_residual(b)[1] for b in fam])
        w = np.array([b.omega for b in fam]) - 1
        for i in range(len(fam) - 1):
            p = np.log(w[i + 1] / w[i]) / np.log(J[i + 1] / J[i])
            c = w[i] / J[i] ** p
            integral = c * (J[i + 1] ** (p + 1) - J[i] ** (p + 1)) / (p + 1)
            dE = (J[i + 1] - J[i] + integral) / (2 * np.pi)
            assert dE / (E[i + 1] - E[i]) == pytest.approx(1.0, abs=1e-5)


def test_config_errors_name_the_key():
    import yaml

    from cradle.pipeline import config as cc
    from cradle.pipeline.config.reference import schema_path

    cfg = yaml.safe_load((schema_path().parents[3] / "config.yaml").read_text())
    assert cc.analysis_spec(cfg, "breathers", "reduced").N == 10
    bad = copy.deepcopy(cfg)
    bad["beyond"].setdefault("breathers", {})["pn_omega"] = 1.11
    with pytest.raises(ValueError, match="beyond.breathers.pn_omega"):
        cc.analysis_spec(bad, "breathers", "full")
    bad = copy.deepcopy(cfg)
    bad["beyond"].setdefault("breathers", {})["omegas"] = [1.1, 1.05]
    with pytest.raises(ValueError, match="beyond.breathers.omegas"):
        cc.analysis_spec(bad, "breathers", "full")


def test_tail_recursion_continues_the_resolved_tail_double_exponentially():
    """The tail recursion in log variables (cradle.integrators.lattice_breather_tails), started where |x_n| drops
    below 1e-4 max|x|, reproduces the beads the trajectory still resolves (down to 1e-11) to within the
    neglected relative terms O(|x_n / x_{n-1}|), and decays double-exponentially: ln(-ln|x_n|) has slope
    -> ln(alpha) (the DpS value) along the tail."""
    from cradle.integrators import lattice_breather_tails as lbt

    n = 30
    a = homoclinic.solve(homoclinic.initial_guess(n, "site", ALPHA, 0.1), ALPHA).a
    b = lb.newton(lb.dps_start(a, 1.1, ALPHA), 1.1, ALPHA, kind="site")
    _, early, first_e = lbt.log10_tail(b, n // 2, 14, start_rel=1e-4)
    _, late, first_l = lbt.log10_tail(b, n // 2, 14, start_rel=1e-11)
    assert first_l > first_e
    ratio = 10.0 ** (late[first_e] - late[first_e - 1])         # |x_n / x_{n-1}| at the first recursed bead
    assert abs(early[first_e] - late[first_e]) <= 2 * ratio / np.log(10)
    assert np.all(np.diff(late) < 0) and late[-1] < -200          # far below double precision
    slope = lbt.double_exponential_slope(late, np.log10(b.amplitude), first_l)
    assert slope == pytest.approx(np.log(ALPHA), abs=0.02)


def test_pinning_exponent_tends_to_dps_linearly(profiles):
    """As omega_b -> 1 the lattice pinning growth of the site breather tends to the DpS eigenvalue, with a
    relative correction linear in omega_b - 1 (large, ~ -47 (omega_b - 1): the DpS pinning eigenvalue is
    itself tiny, which is why the lattice verdicts alternate at larger amplitude)."""
    a = profiles["site"]
    dev = []
    for om in (1.001, 1.002):
        b = lb.newton(lb.dps_start(a, om, ALPHA), om, ALPHA, kind="site")
        fl = lb.floquet(b, "site")
        lam, _ = db.stability(a, om, ALPHA)
        dev.append(fl.rate / np.max(lam.real) - 1.0)
    assert abs(dev[0]) < 0.1
    assert dev[1] / dev[0] == pytest.approx(2.0, rel=0.2)


def test_exchange_refinement_stores_verdict_multiplier_precision_and_the_refined_verdict(families):
    """breather_exchanges.refine on a bracket of the tiny family: per side the verdict (the sign of sigma), the
    pinning offset |mu - 1| with the trivial defect beside it, the same re-solved at check_rtol on a ring
    REFINE_RING times larger; where the offset stands well above its precision the refined verdict is the same."""
    from cradle.analyses import breather_exchanges as be
    from cradle.analyses.breathers_spec import Breathers

    fams, _ = families
    spec = Breathers()
    fam = fams["site"]
    floquets = {("ring site", b.omega): lb.floquet(b, "site", N // 2, spec.rtol) for b in fam}
    (row,) = be.refine(fam, floquets, "ring site", "site", N // 2, [(1.0075, 0.0025)], spec, print)
    assert row["refined_N"] == 16 and row["omega_side"] == [1.005, 1.01]
    for k, b in enumerate(fam[1:]):
        fl = floquets[("ring site", b.omega)]
        assert row["unstable_side"][k] == float(be.sigma(fl, b.T) > 0)
        assert row["pinning_offset"][k] == np.min(np.abs(fl.mu_odd - 1.0)) and row["pinning_precision"][k] == fl.trivial
        if row["pinning_offset"][k] > 10 * max(row["pinning_precision"][k], row["pinning_precision_refined"][k]):
            assert row["unstable_refined"][k] == row["unstable_side"][k]
    assert row["refined_agrees"] == float(row["unstable_side"] == row["unstable_refined"])
