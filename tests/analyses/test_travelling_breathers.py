"""travelling-breathers (cradle.analyses.travelling_breathers): DpS travelling breathers, checked from mathematics.

On a tiny spec (a ring of 16, three velocities; on a ring of 12 the core fills the ring and the slow end is
lost in the tail): every stored TB satisfies (tb) to 1e-10 relative, re-integrated
by the project's other DOP853 (dop853_numba, not the shooting's scipy one); the norm is the family's; the direct
run conserves the norm and H and stays a TB over its periods; DpS's scaling maps the family onto itself (the TB
re-solved at lambda^(1-alpha) T, lambda^2 P from another member's profile is lambda A, theta unchanged); the four
trivial multipliers modulo shift sit at 1 within the stored defect, which is small; multipliers come in the
symplectic pairs mu, 1/conj(mu); at the slow end the TB passes the static breathers of (dpsstn) ever closer as
c decreases. On larger rings: a TB embedded in a larger ring solves it after Newton, the core-first corrector
converges on 128 sites where the plain one stalls, the family followed through its fold by pseudo-arclength solves
(tb) at every stored member, and the arclength tangent is the natural one away from a fold.
"""
from __future__ import annotations

import numpy as np
import pytest

from cradle.analyses import travelling_breathers as tb
from cradle.analyses.travelling_breathers import dps_family, fine_scan, lattice, limit_fold, limit_tail, verdict_checks
from cradle.integrators import integrate_dps
from cradle.models import dps_travelling as M
from cradle.specs.declare import from_plain
from cradle.specs.values import ConfigError


def _tiny(**over):
    plain = {"N": 16, "check_N": [18], "check_rtol": [1e-12], "speeds": [0.06, 0.08, 0.1], "direct_speed": 0.08,
             "direct_periods": 3, "static_samples": 16, "motion_eps": [0.01, 0.003, 0.001, 3e-4], "motion_sites": 8,
             "motion_ring": 30, "motion_samples": 8, "lattice": False, "limit_N": [16, 18], "limit_step": 0.004,
             "limit_halfwidth": 0.004, "limit_large_N": [20], "limit_large_step": 0.004, "limit_fold_N": [16],
             "limit_fold_points": 8, **over}
    return from_plain(tb.TravellingBreathers, plain)


@pytest.fixture(scope="module")
def tiny():
    spec = _tiny()
    return spec, tb.compute(spec, {})


def _members(tree):
    prof = tree["profiles"]
    A = np.asarray(prof["A_re"].values) + 1j * np.asarray(prof["A_im"].values)
    fam = tree["family"]
    return A, np.asarray(fam["period"].values), np.asarray(fam["theta"].values)


def test_every_stored_tb_solves_the_shift_map(tiny):
    spec, tree = tiny
    A, T, theta = _members(tree)
    assert A.shape[0] == 3
    for a, t, th in zip(A, T, theta, strict=True):
        B = integrate_dps(a, np.array([0.0, t]), alpha=spec.alpha, rtol=1e-13).A[-1]
        assert M.relative_residual(a, B, th) <= 1e-10
        assert abs(np.sum(np.abs(a) ** 2) - spec.norm) <= 1e-12 * spec.norm
    assert float(tree.attrs["max_residual"]) <= spec.newton_tol


def test_direct_run_conserves_norm_and_energy_and_stays_a_tb(tiny):
    _, tree = tiny
    assert float(tree.attrs["direct_norm_drift"]) < 1e-10
    assert float(tree.attrs["direct_energy_drift"]) < 1e-10
    assert float(np.max(tree["direct"]["residual"].values)) < 1e-8


def test_scaling_maps_the_family_onto_itself(tiny):
    _, tree = tiny
    assert int(tree.attrs["scaling_converged"]) == 1
    assert float(tree.attrs["scaling_profile_error"]) <= 1e-10
    assert float(tree.attrs["scaling_theta_error"]) <= 1e-10


def test_trivial_multipliers_and_symplectic_pairs(tiny):
    spec, tree = tiny
    mu = np.asarray(tree["multipliers"]["mu_re"].values) + 1j * np.asarray(tree["multipliers"]["mu_im"].values)
    defect = np.asarray(tree["family"]["trivial_defect"].values)
    for m, d in zip(mu, defect, strict=True):
        near = np.sort(np.abs(m - 1.0))
        assert near[dps_family.TRIVIAL - 1] == pytest.approx(d, rel=1e-12)
        # two Jordan blocks of size 2 split by ~sqrt(rounding of the monodromy): stated, not tuned
        assert d < 1e-5
        # (dfnls) is Hamiltonian: mu and 1/conj(mu) are both multipliers
        partner = 1.0 / np.conj(m)
        assert np.max(np.min(np.abs(m[:, None] - partner[None, :]), axis=1)) < 1e-6


def test_slow_end_approaches_the_static_breathers(tiny):
    """The distance to the nearer static breather shrinks as c decreases, as c^2: |A_n| is even in c (the
    reflection n -> -n with complex conjugation maps a TB of c to one of -c), so the c = 0 end is the static
    breather and the first correction is O(c^2)."""
    _, tree = tiny
    fam = tree["family"]
    d = np.minimum(fam["static_distance_site"].values, fam["static_distance_bond"].values)
    assert np.all(np.diff(d) > 0)
    assert abs(float(tree.attrs["static_distance_power"]) - 2.0) < 0.25


def test_static_profiles_are_those_of_the_breathers_analysis():
    """phi = s a with a the mu = 1 solution of (dpsstn) the breathers analysis solves; Omega from the scaling."""
    from cradle.models import dps, homoclinic, stationary

    prof = dps_family.static_profiles(12, 1.5, 1.0)
    for kind, (phi, om) in prof.items():
        a = homoclinic.solve(homoclinic.initial_guess(12, kind, 1.5, 0.1), 1.5).a
        s = np.sqrt(1.0 / np.sum(a**2))
        assert np.array_equal(phi, s * a)
        # phi e^{i Omega tau} solves (dfnls): p-Laplacian(phi) = -2 tau0 Omega phi
        lap = dps.p_laplacian(phi, 1.5)
        assert np.max(np.abs(lap + 2 * dps.tau0(1.5) * om * phi)) < 1e-12 * np.max(np.abs(phi))
        assert np.max(np.abs(stationary.stationary_residual(a, 1.5))) < 1e-12


def test_claims_rows_have_the_table_columns(tiny):
    _, tree = tiny
    rows = tree["claims"]
    assert rows.sizes["row"] == 3
    assert set(rows["verdict"].values) <= {"agrees", "disagrees", "not comparable"}
    assert all(str(x).startswith("analyses/travelling-breathers.md#") for x in rows["explained_in"].values)


def test_check_names_each_key_in_one_line():
    from cradle.specs.values import Errors

    spec = from_plain(tb.TravellingBreathers, {"N": 12, "check_N": [14, 12], "speeds": [0.1, 0.08, 0.12],
                                               "direct_speed": 0.2})
    out = Errors()
    spec.check(["beyond", "travelling-breathers"], None, out)
    assert len(out.lines) == 3
    for key in ("speeds", "direct_speed", "check_N"):
        assert any(line.startswith(f"config error: beyond.travelling-breathers.{key} = ") for line in out.lines)
    with pytest.raises(ConfigError, match="N = 4: must be >= 8"):
        _tiny(N=4)


def test_lattice_keys_checked_in_one_line():
    from cradle.specs.values import Errors

    spec = from_plain(tb.TravellingBreathers, {"lattice_source": 0.07, "lattice_steps": [0.01, 0.02],
                                               "lattice_eps": [0.001, 0.003, 0.002]})
    out = Errors()
    spec.check(["beyond", "travelling-breathers"], None, out)
    for key in ("lattice_source", "lattice_steps", "lattice_eps"):
        assert any(line.startswith(f"config error: beyond.travelling-breathers.{key} = ") for line in out.lines)


def test_robustness_rows_are_the_family_and_the_checks(tiny):
    """/robustness holds the ring of N and the tolerance rtol as its first rows (the family itself), the first
    check ring and check tolerance as /family's *_N and *_rtol; settled is 1 (0) exactly where every row says
    unstable (stable)."""
    spec, tree = tiny
    rob, fam = tree["robustness"], tree["family"]
    assert list(rob["ring"].values) == [spec.N, *spec.check_N]
    assert list(rob["rtol"].values) == [spec.rtol, *spec.check_rtol]
    assert np.array_equal(rob["growth_rate"].values[0], fam["growth_rate"].values)
    assert np.array_equal(rob["growth_rate_tol"].values[0], fam["growth_rate"].values)
    assert np.array_equal(rob["tail"].values[0], fam["tail"].values)
    assert np.array_equal(rob["unstable"].values[1], fam["unstable_N"].values)
    assert np.array_equal(rob["growth_rate_tol"].values[1], fam["growth_rate_rtol"].values)
    rows = np.concatenate([rob["unstable"].values, rob["unstable_tol"].values])
    settled = rob["settled"].values
    assert np.array_equal(settled == verdict_checks.SETTLED_UNSTABLE, np.all(rows == 1, axis=0))
    assert np.array_equal(settled == verdict_checks.SETTLED_STABLE, np.all(rows == 0, axis=0))
    # an unstable mode's participation ratio is between one site and the whole ring; stable members have none
    ext = rob["mode_extent"].values
    un = rob["unstable"].values == 1
    assert np.all(np.isnan(ext[~un]))
    assert np.all((ext[un] >= 1.0 / spec.N) & (ext[un] <= 1.0))


def test_tail_wave_and_its_mi_rate():
    """A plane wave R e^{i q n} that fits the ring (q = 2 pi k / N; a bump elsewhere for the centre) has tail_wave
    (q, R); its MI rate is 0 for |q| <= pi/2 (every such plane wave of (dfnls) is stable) and positive beyond."""
    N, R = 32, 1e-4
    q = 2 * np.pi * 11 / N
    n = np.arange(N)
    A = R * np.exp(1j * q * n)
    A[14:19] = [0.1, 0.5, 1.0, 0.5, 0.1]
    q_m, R_m = verdict_checks.tail_wave(A)
    assert q_m == pytest.approx(q, abs=1e-12)
    assert R_m == pytest.approx(R, rel=1e-12)
    assert verdict_checks.tail_mi_rate(1.0, R, 1.5) == 0.0
    assert verdict_checks.tail_mi_rate(q, R, 1.5) > 0.0


def test_limit_scan_rows_and_rule(tiny):
    """/robustness_limit: every scanned TB's multipliers come in the quadruples of a symplectic map (a real
    pair mu, 1/mu on the axis, a pair on the circle, a quartet off it) to 1e-8 (the trivial Jordan blocks split
    by rounding ~ the square root of the monodromy's error, as the stored trivial defect); the per-member
    statistics are those of the fine data; the verdict is limit_rule's; a point is unstable exactly where its
    growth rate exceeds the threshold."""
    spec, tree = tiny
    lim = tree["robustness_limit"]
    assert list(lim["limit_ring"].values) == spec.limit_N
    assert np.nanmax(lim["quartet_defect"].values) < 1e-8
    cf = lim["c_fine"].values
    c = tree["c"].values
    G = lim["growth_rate"].values
    for j, x in enumerate(c):
        near = np.abs(cf - x) <= spec.limit_halfwidth + 1e-9
        for i in range(len(spec.limit_N)):
            g = G[i, near][np.isfinite(G[i, near])]
            assert lim["typical_growth"].values[j, i] == pytest.approx(np.median(g), rel=0, abs=0)
            assert lim["unstable_fraction"].values[j, i] == np.mean(g > spec.stability_threshold)
        v, k = fine_scan.limit_rule(np.array(spec.limit_N, float), lim["typical_growth"].values[j],
                             spec.stability_threshold)
        assert lim["verdict"].values[j] == v
    unstable = lim["unstable"].values
    assert np.array_equal(unstable == 1, np.isfinite(G) & (G > spec.stability_threshold))


def test_limit_rule_cases():
    """The rule on made-up medians: the two largest rings agree -> their verdict (whatever the smaller rings say);
    they differ -> undecided; a ring not reached (NaN) is left out; k is the slope of -ln g against ln N."""
    N = np.array([24.0, 48.0, 96.0])
    thr = 1e-5
    v, k = fine_scan.limit_rule(N, np.array([1e-3, 1e-3, 1e-3]), thr)
    assert v == fine_scan.LIMIT_UNSTABLE and k == pytest.approx(0.0, abs=1e-12)
    v, k = fine_scan.limit_rule(N, 1e-3 * 24 / N, thr)
    assert v == fine_scan.LIMIT_UNSTABLE and k == pytest.approx(1.0, abs=1e-12)
    assert fine_scan.limit_rule(N, np.array([1e-3, 1e-15, 1e-7]), thr)[0] == fine_scan.LIMIT_STABLE
    assert fine_scan.limit_rule(N, np.array([1e-15, 1e-15, 1e-3]), thr)[0] == fine_scan.LIMIT_UNDECIDED
    assert fine_scan.limit_rule(N, np.array([1e-15, 1e-3, np.nan]), thr)[0] == fine_scan.LIMIT_UNDECIDED
    assert fine_scan.limit_rule(N, np.array([1e-3, 1e-3, np.nan]), thr)[0] == fine_scan.LIMIT_UNSTABLE


def test_tail_rule_verdict_cases():
    """The tail rule on made-up inputs: a tail that is MI-unstable decides (unstable) whatever the fit; otherwise a
    verdict needs g_inf two standard errors on one side of the threshold (a g_inf merely consistent with 0 is
    undecided when it is also consistent with instability); a fit missing or degenerate is undecided."""
    thr = 1e-5

    def fit(g, e):
        return {"g_inf": g, "g_inf_error": e}

    assert limit_tail.tail_rule_verdict(True, fit(np.nan, np.nan), thr) == fine_scan.LIMIT_UNSTABLE
    assert limit_tail.tail_rule_verdict(False, fit(-3e-5, 1e-5), thr) == fine_scan.LIMIT_STABLE
    assert limit_tail.tail_rule_verdict(False, fit(1e-7, 1e-6), thr) == fine_scan.LIMIT_STABLE
    assert limit_tail.tail_rule_verdict(False, fit(2e-4, 1e-5), thr) == fine_scan.LIMIT_UNSTABLE
    assert limit_tail.tail_rule_verdict(False, fit(2e-4, 2e-4), thr) == fine_scan.LIMIT_UNDECIDED
    assert limit_tail.tail_rule_verdict(False, fit(1e-6, 1e-5), thr) == fine_scan.LIMIT_UNDECIDED
    assert limit_tail.tail_rule_verdict(False, fit(np.nan, np.nan), thr) == fine_scan.LIMIT_UNDECIDED
    assert limit_tail.tail_rule_verdict(False, {**fit(2e-4, 1e-5), "degenerate": 1.0}, thr) == fine_scan.LIMIT_UNDECIDED
    assert limit_tail.tail_mi_unstable(np.pi / 2 + 1e-9) and not limit_tail.tail_mi_unstable(np.pi / 2 - 1e-9)
    assert limit_tail.tail_mi_unstable(-2.0) and limit_tail.tail_mi_unstable(2 * np.pi + 2.0)
    assert not limit_tail.tail_mi_unstable(-1.0)


def test_limit_tail_rows_and_rule(tiny):
    """/limit_tail: q is theta modulo 2 pi; the tail's kind is the sign of cos q and its unit MI rate the closed
    form; theta is the same on every ring and tolerance (it is the rule's input: DpS's (tb) fixes it for the
    member, not the ring; to the Newton tolerance); the envelope is the largest growth over the stored fine data of
    the member's kind; the verdict is tail_rule_verdict's; every larger ring's TB has a symplectic spectrum."""
    from cradle.analyses import mi_diagram

    spec, tree = tiny
    lt, lim, large = tree["limit_tail"], tree["robustness_limit"], tree["limit_large"]
    theta = tree["family"]["theta"].values
    q = lt["tail_q"].values
    assert np.allclose(np.exp(1j * q), np.exp(1j * theta), rtol=0, atol=1e-15)
    kind = lt["tail_mi_unstable"].values
    assert np.array_equal(kind == 1, np.cos(q) < 0)
    unit = lt["unit_amplitude_mi_rate"].values
    assert np.array_equal(unit, [mi_diagram.max_growth_rate(x, spec.alpha)[0] for x in q])
    assert np.all(unit[kind == 0] == 0) and np.all(unit[kind == 1] > 0)
    assert np.max(lt["theta_spread"].values) < 1e-8
    assert list(lt["fit_ring"].values) == [*spec.limit_N, *spec.limit_large_N]
    assert np.nanmax(large["quartet_defect"].values) < 1e-8
    rings = [(lim["c_fine"].values, lim["growth_rate"].values[i], lim["theta"].values[i])
             for i in range(len(spec.limit_N))]
    rings += [(large["c_large"].values, large["growth_rate"].values[i], large["theta"].values[i])
              for i in range(len(spec.limit_large_N))]
    for j, x in enumerate(tree["c"].values):
        for i, (grid, g, th) in enumerate(rings):
            keep = (np.abs(grid - x) <= spec.limit_halfwidth + 1e-9) & np.isfinite(g)
            keep &= (np.cos(th) < 0) == bool(kind[j])
            env = lt["envelope"].values[j, i]
            # the larger ring's grid (step limit_large_step) holds every point of the fine grid here
            assert (np.isnan(env) and not keep.any()) or env == np.max(g[keep])
        fit = {"g_inf": lt["fit_g_inf"].values[j], "g_inf_error": lt["fit_g_inf_error"].values[j],
               "degenerate": lt["fit_degenerate"].values[j]}
        assert lt["verdict"].values[j] == limit_tail.tail_rule_verdict(bool(kind[j]), fit, spec.stability_threshold)


@pytest.mark.slow
def test_a_window_is_a_krein_collision():
    """A window of the ring of 24 resolved in steps h = 2e-6 of c (c = 0.11925-0.11931, growth 2.4e-4 per unit
    tau): a multiplier of signature + and one of signature - approach each other on the circle, leave it as a
    quartet at the same argument and come back with their order swapped. The two-mode model fitted to their
    splitting outside the window alone (measurements.floquet_bubbles.collision_fit) gives its width 4 g / s and
    its height g; both agree with the measured ones to the grid's resolution (edges within h each: width within
    2 h, and the height s w / 4 the width implies within s 2 h / 4)."""
    from cradle.analyses.protocol import FULL, form_spec
    from cradle.integrators import dps_travelling as DT
    from cradle.measurements import floquet_bubbles as FB

    spec = form_spec(from_plain(tb.TravellingBreathers, {}), FULL)
    first = dps_family.first_member(spec, 24, spec.rtol)
    lead, _ = DT.continue_family(first, [0.09, 0.1, 0.11, 0.119, 0.11924], spec.newton_tol, spec.rtol,
                                 min_step=fine_scan.LIMIT_MIN_STEP)
    h = 2e-6
    scan = fine_scan.bubble_scan(spec, lead[-1], np.round(0.11924 + h * np.arange(1, 46), 12), 1.31, 0.05)
    r = FB.bubble(scan, spec.stability_threshold, 1.31, 2e-5)
    assert r["width_measured"] > 10 * h                     # resolved
    assert abs(r["width_model"] - r["width_measured"]) <= 2 * h
    tol = r["detuning_rate"] * 2 * h / 4
    assert abs(r["height_model"] - r["height_measured"]) <= tol
    assert abs(FB.collision_peak(r["width_measured"], r["detuning_rate"]) - r["height_measured"]) <= tol


@pytest.fixture(scope="module")
def lattice_tree():
    """The lattice part on a small spec: three TBs of (nc) from the c = 0.1 member's ansatz on the ring of 16, one
    continuation step of 1 %, a short launch; the three carried to a ring of 20 and the step taken there too (the
    corrector on the core first), one TB at eps = 0.01 solved the core first; on the ring of 20 the signed tail on a
    grid of +-0.02 % in c about the eps = 0.003 TB and the +1 % member, and its zeros."""
    spec = _tiny(lattice=True, lattice_eps=[0.005, 0.004, 0.003], lattice_steps=[0.0, 0.01], lattice_periods=1,
                 lattice_rings=[20], lattice_family_rings=[20], lattice_large_eps=[0.01], lattice_zero_rings=[20],
                 lattice_zero_grid=[-0.0002, 0.0, 0.0002])
    fam, _ = dps_family.family(spec, spec.N, spec.rtol)
    return spec, lattice.lattice_groups(spec, fam)


#: DOP853 tolerance of the re-integration that checks (tbnc): the check's own error must sit well below the 1e-10 it
#: checks. On the lattice fixture's TBs (periods ~100-200) the residual the check reports falls with its tolerance
#: until, at this one, it meets Newton's own (<= newton_tol); at 1e-13 the check's error alone came to the bound
CHECK_RTOL = 1e-14


@pytest.mark.slow
def test_stored_lattice_tbs_solve_tbnc(lattice_tree):
    """Every stored TB of (nc) satisfies (tbnc) to 1e-10 (relative), re-integrated by the contact-event DOP853 at
    another tolerance; its multipliers come in pairs mu, 1/mu; launched the same way it keeps its energy."""
    from cradle.integrators import lattice_travelling as LT

    spec, (groups, attrs) = lattice_tree
    data, _ = groups["/lattice_eps"]
    states, _ = groups["/lattice_states"]
    for x, v, T in zip(states["x"], states["v"], data["period"], strict=True):
        z = np.concatenate([x, v])
        assert LT.relative_residual(z, LT.flow(z, T, spec.alpha, CHECK_RTOL)) <= 1e-10
    assert max(data["residual"]) <= 1e-10
    assert attrs["lattice_max_reciprocal_defect"] < 1e-6
    # the exact TB launched travels at its own speed (in units of the DpS TB's c eps^(alpha-1)): T_d eps^(1-alpha)/T
    own = np.asarray(data["ansatz_period"]) / np.asarray(data["period"])
    assert np.max(np.abs(np.asarray(data["exact_speed"]) - own)) < 1e-3
    assert max(data["exact_energy_drift"]) < 1e-8


def _stored_members(groups: dict) -> list[tuple[np.ndarray, float]]:
    """(z, T) of every TB stored in /lattice_rings and /lattice_large (the NaN-padded rows cut to their ring)."""
    out = []
    rings, _ = groups["/lattice_rings"]
    for key in ("", "_family"):
        for x_r, v_r, T_r in zip(rings["x" + key], rings["v" + key], rings["period" + key], strict=True):
            for x, v, T in zip(x_r, v_r, T_r, strict=True):
                if np.isfinite(T):
                    keep = np.isfinite(x)
                    out.append((np.concatenate([x[keep], v[keep]]), float(T)))
    large, _ = groups["/lattice_large"]
    out += [(np.concatenate([x, v]), float(T)) for x, v, T in zip(large["x"], large["v"], large["period"],
                                                                  strict=True)]
    return out


@pytest.mark.slow
def test_every_ring_and_large_eps_member_solves_tbnc(lattice_tree):
    """Every TB stored on the other rings and at larger eps satisfies (tbnc) to 1e-10 (relative), re-integrated by the
    contact-event DOP853 at another tolerance: the ring of 16 (its three, the continuation's two members, eps = 0.01
    solved the core first) and the ring of 20 (the three carried, the continuation's two)."""
    from cradle.integrators import lattice_travelling as LT

    spec, (groups, attrs) = lattice_tree
    members = _stored_members(groups)
    assert sorted(z.size // 2 for z, _ in members) == [16] * 6 + [20] * 5
    for z, T in members:
        assert LT.relative_residual(z, LT.flow(z, T, spec.alpha, CHECK_RTOL)) <= 1e-10
    assert attrs["lattice_rings_max_residual"] <= spec.newton_tol
    assert attrs["lattice_large_max_residual"] <= spec.newton_tol


@pytest.mark.slow
def test_ring_and_large_eps_multipliers_symplectic(lattice_tree):
    """The multipliers modulo shift of every new member come in pairs mu, 1/mu (the monodromy of a Hamiltonian
    flow composed with a permutation of the (x_n, v_n) pairs is symplectic); four of them at 1 (time shift and energy,
    the carrier's phase and the wave action) within 1e-3."""
    _, (groups, _) = lattice_tree
    for name in ("/lattice_rings", "/lattice_large"):
        data, _ = groups[name]
        assert np.nanmax(data["reciprocal_defect"]) < 1e-6
        assert np.nanmax(data["trivial_defect"]) < 1e-3


@pytest.mark.slow
def test_ring_and_large_eps_direct_runs_conserve_energy(lattice_tree):
    """The TB carried to the ring of 20 and the one at eps = 0.01, run by (nc) for two periods: the energy kept to
    1e-11 per period, and after k periods the start shifted by k sites."""
    from cradle.integrators import lattice_travelling as LT

    spec, (groups, _) = lattice_tree
    members = _stored_members(groups)
    for z, T in (members[3], members[-1]):       # the first on the ring of 20, the one at eps = 0.01
        run = LT.direct_run(LT.LatticeTB(z, T, spec.alpha, 0.0, True, 0), 2)
        assert np.all(run["energy_drift"][1:] < 1e-11 * run["k"][1:])
        assert np.max(run["residual"]) < 1e-9


@pytest.mark.slow
def test_tail_zero_is_bracketed_and_solves_tbnc(lattice_tree):
    """Each located zero of the signed tail (on the ring of 20; the branch of the eps = 0.003 TB at least): the grid's
    signed tails at the bracket's ends have opposite signs, the zero's c lies between them and its |sigma| is below
    every grid point's; the stored TB satisfies (tbnc) to 1e-10 re-integrated at another tolerance, its multipliers
    come in pairs mu, 1/mu and four of them lie at 1 within 1e-3."""
    from cradle.integrators import lattice_travelling as LT

    spec, (groups, _) = lattice_tree
    data, coords = groups["/lattice_zeros"]
    c = np.asarray(data["c_tb"])
    assert np.isfinite(c[0, 0])
    for i, j in zip(*np.nonzero(np.isfinite(c)), strict=True):
        cg, sg = np.asarray(data["c_tb_grid"][i, j]), np.asarray(data["sigma_grid"][i, j])
        k = int(np.flatnonzero(cg == data["bracket_low"][i, j])[0])
        assert cg[k + 1] == data["bracket_high"][i, j]
        assert sg[k] * sg[k + 1] < 0
        assert cg[k] < c[i, j] < cg[k + 1]
        assert abs(data["sigma"][i, j]) < np.nanmin(np.abs(sg))
        N = int(coords["zero_ring"][i])
        z = np.concatenate([data["x"][i, j, :N], data["v"][i, j, :N]])
        assert LT.relative_residual(z, LT.flow(z, 1.0 / c[i, j], spec.alpha, CHECK_RTOL)) <= 1e-10
        assert data["reciprocal_defect"][i, j] < 1e-6
        assert data["trivial_defect"][i, j] < 1e-3


def test_embed_centres_the_breather_and_adds_rest_sites():
    """embed: on the ring of N the state's largest |xi_n| sits at N0 // 2 + (N - N0) // 2, its N0 sites in order (a
    rotation of the ring), the other N - N0 at rest."""
    from cradle.integrators import lattice_travelling as LT

    N0, N = 6, 11
    x, v = np.array([0.1, 0.0, -0.2, 0.3, 0.9, 0.05]), np.array([0.0, 0.2, 0.1, 0.0, -0.4, 0.1])
    z = LT.embed(np.concatenate([x, v]), N)
    X, V = z[:N], z[N:]
    assert int(np.argmax(np.hypot(X, V))) == N0 // 2 + (N - N0) // 2
    r = N0 // 2 - 4    # the peak at site 4 moved to N0 // 2
    assert np.array_equal(X[2:8], np.roll(x, r)) and np.array_equal(V[2:8], np.roll(v, r))
    assert not np.any(X[:2]) and not np.any(X[8:]) and not np.any(V[:2]) and not np.any(V[8:])
    with pytest.raises(ValueError, match="smaller"):
        LT.embed(z, N0)


def test_ring_keys_checked_in_one_line():
    from cradle.specs.values import Errors

    spec = from_plain(tb.TravellingBreathers, {"lattice_rings": [32, 24], "lattice_family_rings": [20],
                                               "lattice_large_eps": [0.004, 0.01], "lattice_zero_rings": [32],
                                               "lattice_zero_eps": 0.004, "lattice_zero_step": 0.03,
                                               "lattice_zero_grid": [0.001, -0.001]})
    out = Errors()
    spec.check(["beyond", "travelling-breathers"], None, out)
    for key in ("lattice_rings", "lattice_family_rings", "lattice_large_eps", "lattice_zero_rings",
                "lattice_zero_eps", "lattice_zero_step", "lattice_zero_grid"):
        assert any(line.startswith(f"config error: beyond.travelling-breathers.{key} = ") for line in out.lines)


@pytest.mark.slow
def test_lattice_tbs_approach_dps(lattice_tree):
    """The distance to the DpS TB through the ansatz falls with eps (the ansatz's error, of order eps^(alpha-1))."""
    _, (groups, _) = lattice_tree
    d = np.asarray(groups["/lattice_eps"][0]["ansatz_distance"])
    assert np.all(np.diff(d) < 0)


# ----------------------------------------------------------------- DpS Newton on large rings; the member and the folds


def _solves_tb(A: np.ndarray, T: float, theta: float, alpha: float) -> float:
    """The shift-map residual of (A, T, theta) re-integrated by the project's other DOP853 (dop853_numba)."""
    B = integrate_dps(A, np.array([0.0, T]), alpha=alpha, rtol=1e-13).A[-1]
    return M.relative_residual(A, B, theta)


def test_a_tb_embedded_in_a_larger_ring_solves_it():
    """A TB of the ring of 16 set on a ring of 24 (tb_launch.embedded: zeros on the far side) is a TB there up to its
    own far field: the shift-map residual of the embedded state is at most a few times the small ring's tail (the
    field cut at the seam; DpS's coupling vanishes with the amplitude, so the zeros added are at rest), and Newton
    from it converges to the stated 1e-10 (re-integrated by the other DOP853) with theta unchanged to that order
    (DpS's (tb) fixes theta for the member, not the ring)."""
    from cradle.analyses.protocol import FULL, form_spec
    from cradle.integrators import dps_travelling as DT
    from cradle.models import tb_launch

    spec = form_spec(from_plain(tb.TravellingBreathers, {}), FULL)
    small = dps_family.first_member(spec, 16, spec.rtol)
    A = tb_launch.embedded(small.A, 24)
    assert _solves_tb(A, small.T, small.theta, spec.alpha) <= 4 * M.tail_amplitude(small.A)
    big = DT.newton(A, small.T, small.theta, spec.alpha, spec.norm, tol=spec.newton_tol)
    assert big.converged and _solves_tb(big.A, big.T, big.theta, spec.alpha) <= 1e-10
    assert abs(np.angle(np.exp(1j * (big.theta - small.theta)))) <= 1e-6


@pytest.mark.slow
def test_core_first_converges_where_plain_newton_stalls():
    """On a ring of 128 Newton from the pushed breather stops above 1e-10 (its first step puts some 1e-3 of the peak
    on the far sites, and it heads for a TB on a plane-wave tail of that size); newton_core_first, the core's sites
    first, converges: the residual re-integrated by the other DOP853 <= 1e-10, the norm the family's, four
    multipliers at 1 within a small defect and the others in symplectic pairs mu, 1/conj(mu)."""
    from cradle.analyses.protocol import FULL, form_spec
    from cradle.integrators import dps_travelling as DT
    from cradle.measurements import floquet_bubbles as FB

    spec = form_spec(from_plain(tb.TravellingBreathers, {}), FULL)
    phi, _ = dps_family.static_profiles(128, spec.alpha, spec.norm)["site"]
    A, T, theta = DT.start(phi, spec.kick, spec.alpha)
    plain = DT.newton(A, T, theta, spec.alpha, spec.norm, tol=spec.newton_tol)
    assert not plain.converged and plain.residual > 1e-10
    b, first_stage = DT.newton_core_first(A, T, theta, spec.alpha, spec.norm, tol=spec.newton_tol)
    assert b.converged and first_stage <= DT.CORE_TOL
    assert _solves_tb(b.A, b.T, b.theta, spec.alpha) <= 1e-10
    assert abs(b.norm - spec.norm) <= 1e-12
    defect, _, _, _ = dps_family.verdict(b, spec.stability_threshold)
    assert defect < 1e-5
    assert FB.quartet_defect(b.multipliers) < 1e-8


def test_member_and_fold_rows(tiny):
    """/limit_tail's member_growth is the growth at c itself on each ring's grid and member_verdict the rule's;
    /limit_fold's members solve (tb) at their own T (re-integrated by the other DOP853) at the family's norm (to
    the Newton tolerance: the norm is one of its equations), in
    order along the arclength (first member, natural continuation upwards, then pseudo-arclength), and the folds
    and extrema the attributes name are turns of c and of H along the stored arc."""
    spec, tree = tiny
    lt, lim, large = tree["limit_tail"], tree["robustness_limit"], tree["limit_large"]
    rings = [(lim["c_fine"].values, lim["growth_rate"].values[i]) for i in range(len(spec.limit_N))]
    rings += [(large["c_large"].values, large["growth_rate"].values[i]) for i in range(len(spec.limit_large_N))]
    for j, x in enumerate(tree["c"].values):
        for i, (grid, g) in enumerate(rings):
            hit = np.flatnonzero(np.abs(grid - x) <= 1e-9)
            want = g[hit[0]] if hit.size else np.nan
            assert np.array_equal(lt["member_growth"].values[j, i], want, equal_nan=True)
        fit = {"g_inf": lt["member_fit_g_inf"].values[j], "g_inf_error": lt["member_fit_g_inf_error"].values[j],
               "degenerate": lt["member_fit_degenerate"].values[j]}
        want_v = limit_tail.member_verdict(bool(lt["tail_mi_unstable"].values[j]), lt["member_growth"].values[j], fit,
                                   spec.stability_threshold)
        assert lt["member_verdict"].values[j] == want_v
    fold = tree["limit_fold"]
    c, H = fold["velocity"].values[0], fold["energy"].values[0]
    ok = np.isfinite(c)
    assert ok.sum() >= spec.limit_fold_points
    A = fold["A_re"].values[0] + 1j * fold["A_im"].values[0]
    for i in np.flatnonzero(ok):
        assert fold["residual"].values[0, i] <= spec.limit_large_newton_tol
        # the norm is one of the equations the same Newton solves: to its tolerance
        assert abs(np.sum(np.abs(A[i]) ** 2) - spec.norm) <= spec.limit_large_newton_tol * spec.norm
    for i in np.flatnonzero(ok)[:: max(1, ok.sum() // 4)]:
        assert _solves_tb(A[i], 1.0 / c[i], fold["theta"].values[0, i], spec.alpha) <= 1e-10
    folds, extrema = limit_fold.fold_turns(c, H)
    assert tree.attrs["fold_16_c_turns"] == (", ".join(f"{x:.7f}" for x in folds) or "none")
    assert tree.attrs["fold_16_dH_dc_zero"] == (", ".join(f"{x:.7f}" for x in extrema) or "none")


def test_mode_rows_and_rule(tiny):
    """/limit_tail's member_participation and member_core_fraction are the fine scans' mode measures at c itself on
    each ring (participation over N in (0, 1], core fractions in [0, 1]), and mode_verdict is MODE_RULE's on them
    (unstable where the tail is MI-unstable)."""
    from cradle.measurements import floquet_modes as FM

    spec, tree = tiny
    lt, lim, large = tree["limit_tail"], tree["robustness_limit"], tree["limit_large"]
    for name in ("mode_participation", "mode_core_fraction", "mode_core_fraction_norm"):
        for grp in (lim, large):
            v = grp[name].values[np.isfinite(grp["growth_rate"].values)]
            assert v.size and np.all(np.isfinite(v)) and np.all((v >= 0) & (v <= 1 + 1e-12))
    assert np.all(lim["mode_participation"].values[np.isfinite(lim["growth_rate"].values)] > 0)
    rings = [(lim["c_fine"].values, lim, i) for i in range(len(spec.limit_N))]
    rings += [(large["c_large"].values, large, i) for i in range(len(spec.limit_large_N))]
    for j, x in enumerate(tree["c"].values):
        for i, (grid, grp, k) in enumerate(rings):
            hit = np.flatnonzero(np.abs(grid - x) <= 1e-9)
            for mine, theirs in (("member_participation", "mode_participation"),
                                 ("member_core_fraction", "mode_core_fraction"),
                                 ("member_core_fraction_norm", "mode_core_fraction_norm")):
                want = grp[theirs].values[k, hit[0]] if hit.size else np.nan
                assert np.array_equal(lt[mine].values[j, i], want, equal_nan=True)
        if lt["tail_mi_unstable"].values[j]:
            assert lt["mode_verdict"].values[j] == fine_scan.LIMIT_UNSTABLE
            continue
        want_v, info = FM.mode_verdict(lt["fit_ring"].values, lt["member_growth"].values[j],
                                       lt["member_core_fraction"].values[j], spec.stability_threshold)
        assert lt["mode_verdict"].values[j] == want_v
        assert np.array_equal(lt["mode_core_slope"].values[j], info["core_slope"], equal_nan=True)
    assert tree.attrs["mode_rule"] == FM.MODE_RULE
    assert (FM.STABLE, FM.UNSTABLE, FM.UNDECIDED) == (fine_scan.LIMIT_STABLE, fine_scan.LIMIT_UNSTABLE,
                                                    fine_scan.LIMIT_UNDECIDED)


def test_fold_turns_and_real_edges_on_made_up_arcs():
    """fold_turns: c rising then falling is one fold at the top; H falling then rising while c keeps falling is one
    extremum of H(c); real_edges: the midpoints where the growth through +1 crosses the threshold."""
    c = np.array([0.1, 0.2, 0.3, 0.25, 0.2, 0.15, np.nan])
    H = np.array([1.0, 2.0, 3.0, 2.5, 2.4, 2.6, np.nan])
    assert limit_fold.fold_turns(c, H) == ([0.3], [0.2])
    g = np.array([0.0, 0.0, 1.0, 1.0, 0.0, 0.0, np.nan])
    assert limit_fold.real_edges(c, g, 0.5) == [0.25, 0.225]


def test_member_verdict_cases():
    """The member is stable when stable on every ring reached (at least 4): no growth to extrapolate; otherwise its
    fit reads as the tail rule's, and a tail that is MI-unstable decides."""
    thr = 1e-5
    nofit = {"g_inf": np.nan, "g_inf_error": np.nan}
    assert limit_tail.member_verdict(False, np.array([1e-14, 2e-14, np.nan, 3e-14, 5e-14]), nofit,
                                     thr) == fine_scan.LIMIT_STABLE
    assert limit_tail.member_verdict(False, np.array([1e-14, 2e-14, 3e-14]), nofit, thr) == fine_scan.LIMIT_UNDECIDED
    assert limit_tail.member_verdict(False, np.array([1e-14, 2e-4, 3e-14, 1e-4]), nofit,
                                     thr) == fine_scan.LIMIT_UNDECIDED
    assert limit_tail.member_verdict(True, np.array([1e-14, 2e-14, 3e-14, 1e-14]), nofit,
                                     thr) == fine_scan.LIMIT_UNSTABLE
    fit = {"g_inf": 2e-4, "g_inf_error": 1e-5}
    assert limit_tail.member_verdict(False, np.array([1e-4, 2e-4, 3e-4, 2e-4]), fit, thr) == fine_scan.LIMIT_UNSTABLE


def test_fold_keys_checked_in_one_line():
    from cradle.specs.values import Errors

    spec = from_plain(tb.TravellingBreathers, {"limit_fold_N": [80, 48]})
    out = Errors()
    spec.check(["beyond", "travelling-breathers"], None, out)
    assert out.lines == ["config error: beyond.travelling-breathers.limit_fold_N = [80, 48]: must be strictly "
                         "increasing"]


def test_arclength_tangent_is_the_natural_one_away_from_a_fold():
    """Away from a fold the family is a graph over T: the unit null vector of the bordered Jacobian in
    (Re A, Im A, theta, T) that arc_newton returns at a converged member is (dA/dT, dtheta/dT, 1) of the natural
    continuation's tangent, normalised (both solve the same linear equations; to the rounding of an SVD and a
    least-squares solve on a Jacobian integrated to rtol 1e-13)."""
    from cradle.analyses.protocol import FULL, form_spec
    from cradle.integrators import dps_travelling as DT

    spec = form_spec(from_plain(tb.TravellingBreathers, {}), FULL)
    first = dps_family.first_member(spec, 16, spec.rtol)
    # the tangent depends on the phase conditions' slice: both about the member itself
    b = DT.newton(first.A, first.T, first.theta, spec.alpha, spec.norm, first.A, spec.newton_tol, rtol=spec.rtol)
    assert b.converged and b.dA_dT is not None
    x = np.concatenate([M.real(b.A), [b.theta, b.T]])
    natural = np.concatenate([M.real(b.dA_dT), [b.dtheta_dT, 1.0]])
    natural /= np.linalg.norm(natural)
    same, t = DT.arc_newton(x, natural, spec.alpha, spec.norm, b.A, spec.newton_tol, rtol=spec.rtol)
    assert same.converged and same.iterations == 0
    assert np.max(np.abs(t - natural)) < 1e-8
