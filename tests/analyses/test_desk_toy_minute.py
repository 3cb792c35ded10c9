"""desk-toy-minute (cradle.analyses.desk_toy_minute): a desk toy watched for a minute, in SI.

The numbers checked are fixed by physics or by the code's contract: stored plus dissipated energy is the initial
energy (to the integrator's accuracy for (ncdamped), to rounding for the hard spheres); the contacts conserve
momentum, so the centre of mass of (ncdamped) is the damped oscillator X'' + gamma X' + X = 0 in closed form; the
hard-sphere cradle of two balls exchanges them exactly with e = 1 and, with e < 1, keeps its centre-of-mass mode
while each collision multiplies the relative amplitude by e: S = 1 / (1 + e^(2k)) after k collisions; the
in-phase times and the energy at the end move by less than 1 % when the tolerance is tightened tenfold.
"""
from __future__ import annotations

import copy
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from cradle.analyses import desk_toy_minute as dm
from cradle.analyses.protocol import FULL, REDUCED, form_spec
from cradle.measurements import desk_toy_minute as mm
from cradle.models import restitution as rs
from cradle.models.hard_spheres import hard_sphere_run
from cradle.models.physical import scales, to_si
from cradle.pipeline import config as cc
from cradle.specs.declare import from_plain

ROOT = Path(__file__).resolve().parents[2]


def _spec(form=REDUCED, **over):
    return form_spec(from_plain(dm.DeskToyMinute, over), form)


@pytest.fixture(scope="module")
def reduced():
    spec = _spec()
    return spec, dm.compute(spec, {})


@pytest.fixture(scope="module")
def settles():
    """Three balls, one lifted, 20 s: long enough for both order parameters to settle under every threshold
    (measured in the full form: S >= 0.99 after 14.1 s at e = 0.9)."""
    spec = _spec(FULL, chains=[3], lifted=[1], duration=20.0, restitution=[0.9], drag_rates=[1e-3])
    return spec, dm.compute(spec, {})


def test_reduced_form_is_5_balls_over_4_seconds(reduced):
    spec, tree = reduced
    assert spec.chains == [5] and spec.lifted == [1, 2] and spec.duration == 4.0
    assert str(tree.attrs["desk_toys"]) == "n5-lifted1, n5-lifted2"
    g = tree["n5-lifted1"]
    s = scales(dm.DEFAULT_CRADLE)
    # every k pi / omega_0 is a stored time; the out-swings are the times k pi in seconds
    assert np.allclose(g["swing_time"].values, to_si(np.pi * np.arange(1, g.sizes["swing"] + 1), "time", s),
                       rtol=1e-15)
    assert g.sizes["swing"] == int(4.0 / (math.pi * s.T))
    names = [str(c) for c in g["case"].values]
    assert len(names) == 2 * 2 + 2 * 2 and all(isinstance(n, str) for n in names)   # (ncdamped), hard e, e(v)
    for var in g.to_dataset(inherit=False).data_vars.values():
        assert "long_name" in var.attrs and "units" in var.attrs
    # the released ball starts L sin(theta) from the line: its swing amplitude before any impact, in metres
    assert g.attrs["amplitude_m"] == pytest.approx(0.1 * math.sin(math.radians(20.0)), rel=1e-12)


def test_energy_plus_dissipation_is_the_initial_energy(reduced):
    """H + D = H(0): for (ncdamped) within the integrator's own measure of it (the max over every step of
    |H + D - H(0)| / H(0)) and within the sum of the local tolerances of its steps (steps * rtol); for the hard
    spheres to rounding (a few units of eps per collision)."""
    spec, tree = reduced
    for name in ("n5-lifted1", "n5-lifted2"):
        g = tree[name]
        for c, case in enumerate(str(x) for x in g["case"].values):
            bal = float(g["energy_balance"].values[c])
            steps = int(g["steps"].values[c])
            if case.startswith("nc"):
                assert bal <= steps * spec.rtol
                assert float(g["dissipated"].values[c, -1]) > 0.0
            else:
                assert bal <= 10 * (steps + 1) * np.finfo(float).eps


def test_centre_of_mass_is_the_damped_oscillator():
    """Contacts push both balls equally and oppositely, Kuwabara-Kono damping included: the centre of mass X of
    (ncdamped) obeys X'' + gamma X' + X = 0 from X(0) = -A lifted / N, X'(0) = 0, whatever the collisions."""
    from cradle.models import desk_toy as dt

    spec = _spec()
    e, A = dm.contacts(spec)[0]
    rate = dm.drag_rates(spec)[1]
    toy = dt.desk_toy(5, 2, spec.angle_deg, dm.DEFAULT_CRADLE)
    x0, _, s = dt.desk_toy_initial(toy)
    damping = dm.damping_of(A, rate, s)
    t = dm.time_grid(spec.duration / s.T, spec.samples)
    run = dm.minute_run(x0, t, damping, spec.rtol)
    g = damping.onsite
    w = math.sqrt(1.0 - g**2 / 4.0)
    X0 = float(np.mean(x0))
    exact = X0 * np.exp(-g * t / 2.0) * (np.cos(w * t) + g / (2.0 * w) * np.sin(w * t))
    err = np.max(np.abs(run.x.mean(axis=1) - exact)) / abs(x0[0])
    assert err <= run.n_steps * spec.rtol


def test_two_hard_spheres_e1_exchange_exactly():
    """e = 1, N = 2, one lifted: the balls swap velocities at each impact t = pi/2 + j pi; at every out-swing one
    ball is out with the full amplitude and the other at rest: R = S = 1/2, never in phase."""
    A = 3.0
    t = dm.time_grid(20 * math.pi, 16)
    hs = hard_sphere_run(np.array([-A, 0.0]), np.zeros(2), t, restitution=1.0)
    idx, _ = mm.swing_indices(t)
    assert np.all(mm.balls_out(hs.x[idx], hs.v[idx]) == 1)
    amp = np.abs(mm.analytic(hs.x[idx], hs.v[idx]))
    far = np.where(np.arange(1, idx.size + 1) % 2 == 1, 1, 0)         # k odd: the far ball, k even: the released
    assert np.allclose(amp[np.arange(idx.size), far], A, rtol=1e-13)
    assert np.allclose(amp[np.arange(idx.size), 1 - far], 0.0, atol=1e-13 * A)
    assert np.allclose(mm.com_share(hs.x[1:], hs.v[1:]), 0.5, rtol=1e-13)
    assert math.isnan(mm.settle_time(t, mm.com_share(hs.x, hs.v), 0.9))


@pytest.mark.parametrize("e", [0.9, 0.5])
def test_two_hard_spheres_lose_the_relative_mode_by_e_per_collision(e):
    """N = 2, one lifted, restitution e: the centre-of-mass amplitude A/2 is kept, the relative amplitude is e^k A
    after k collisions (at t = pi/2 + (k-1) pi), so S = 1 / (1 + e^(2k)) between collisions k and k+1, and S stays
    >= s from the collision k* = ceil(ln(1/s - 1) / (2 ln e))."""
    A = 2.0
    t = dm.time_grid(30 * math.pi, 16)
    hs = hard_sphere_run(np.array([-A, 0.0]), np.zeros(2), t, restitution=e)
    S = mm.com_share(hs.x, hs.v)
    phase = (t - math.pi / 2) / math.pi
    k = np.floor(phase + 1.0).astype(int)                           # collisions by t
    away = np.abs(phase - np.round(phase)) > 1e-6                   # samples at a collision instant left out
    assert np.allclose(S[away], 1.0 / (1.0 + e ** (2.0 * np.maximum(k[away], 0))), rtol=1e-12, atol=1e-14)
    for s in (0.9, 0.99):
        kstar = math.ceil(math.log(1.0 / s - 1.0) / (2.0 * math.log(e)))
        t_k = math.pi / 2 + (kstar - 1) * math.pi
        got = mm.settle_time(t, S, s)
        # the crossing is interpolated between the two samples around the collision
        assert t_k - 2 * math.pi / 16 <= got <= t_k + 2 * math.pi / 16


def test_in_phase_times_and_final_energy_converged_in_the_tolerance(settles):
    """Tightening rtol tenfold moves the in-phase times (both order parameters, every threshold) and the energy at
    the end by less than 1 % (issue 38's criterion)."""
    _, tree = settles
    g = tree["n3-lifted1"]
    nc = [i for i, c in enumerate(g["case"].values) if str(c).startswith("nc")]
    for key in ("inphase_time_phase", "inphase_time_share"):
        a, b = g[key].values[nc], g["tight_" + key].values[nc]
        assert np.all(np.isfinite(a)) and np.all(np.isfinite(b))
        assert np.all(np.abs(b - a) <= 0.01 * a)
    E, Et = g["energy"].values[nc, -1], g["tight_energy_end"].values[nc]
    assert np.all(np.abs(Et - E) <= 0.01 * E)


def test_in_phase_energy_is_the_centre_of_mass_share(settles):
    """Once S -> 1 every mode but the centre of mass has been dissipated: the energy left is the centre-of-mass
    mode's, lifted / N of H(0) times the drag's decay, within the share 1 - S still elsewhere."""
    spec, tree = settles
    g = tree["n3-lifted1"]
    c = 0
    S_end = float(g["com_share"].values[c, -1])
    assert S_end > 0.99
    T_s = float(g.attrs["T_s"])
    t_end = float(g["t"].values[-1]) / T_s
    gamma = spec.drag_rates[0] * T_s
    com = (1.0 / 3.0) * float(g["energy"].values[c, 0]) * math.exp(-gamma * t_end)
    # the damped oscillator's energy oscillates about exp(-gamma t) by O(gamma): within gamma of it
    assert float(g["energy"].values[c, -1]) == pytest.approx(com, rel=(1.0 - S_end) + gamma)


def test_restitution_and_kk_constant_are_inverse(reduced):
    spec, _ = reduced
    s = scales(dm.DEFAULT_CRADLE)
    for e, A in dm.contacts(spec):
        assert dm.restitution_of(A, spec.restitution_speed, s) == pytest.approx(e, abs=1e-9)
    given = _spec(kk_constant=[1e-6])
    (e, A), = dm.contacts(given)
    assert A == 1e-6 and 0.0 < e < 1.0


def test_drag_rates_bracket_and_are_ordered():
    from cradle.models import air_drag

    lo, hi = air_drag.bracketing_rates(dm.DEFAULT_CRADLE, 20.0)
    assert 0.0 < lo < hi
    # Stokes: 6 pi mu R / m = 4.5 mu / (rho R^2) for a sphere
    from cradle.models.physical import MATERIALS

    assert lo == pytest.approx(4.5 * air_drag.AIR_VISCOSITY / (MATERIALS["steel"].rho * 0.01**2), rel=1e-12)
    # Schiller-Naumann reduces to Stokes' 24 / Re as Re -> 0
    assert air_drag.drag_coefficient(1e-8) * 1e-8 == pytest.approx(24.0, rel=1e-5)


def test_figure_draws_from_the_reduced_run(reduced, tmp_path):
    from cradle.figures import draw_analysis

    paths = draw_analysis("desk_toy_minute", reduced[1], tmp_path / "desk-toy-minute", note="test")
    assert len(paths) == 2 and all(p.stat().st_size > 0 for p in paths)


def test_config_refuses_a_lifted_count_past_the_longest_chain():
    raw = yaml.safe_load((ROOT / "config.yaml").read_text())
    bad = copy.deepcopy(raw)
    bad["beyond"]["desk-toy-minute"] = {"lifted": [1, 5], "chains": [3, 5]}
    with pytest.raises(cc.ConfigError, match=r"beyond\.desk-toy-minute\.lifted\[1\] = 5: must be < the longest"):
        cc.analysis_spec(bad, "desk-toy-minute", "full")
    assert cc.analysis_spec(raw, "desk-toy-minute", "reduced").chains == [5]
    assert cc.analysis_spec(raw, "desk-toy-minute", "full").chains == [3, 5, 7, 10]


def test_restitution_law_is_the_two_ball_collision_of_the_contact():
    """e(u) of the hard spheres is (ncdamped)'s two-ball restitution: exact at the tabulated b (to rounding of the
    log-log interpolation), rising as the approach speed falls (1 - e ~ u^(1/5)), and equal to the contact's e at the
    reference speed within the interpolation between those nodes: linear in log-log with a step h = ln(10)/8, an
    error of h^2/8 times the curvature of log(1 - e) against log b, under 1e-3 of 1 - e where 1 - e ~ 0.1."""
    spec = _spec()
    s = scales(dm.DEFAULT_CRADLE)
    e, A = dm.contacts(spec)[0]
    law = dm.restitution_law(A, s)
    scale = A * (s.k / (s.m / 2.0)) ** 0.4 * s.V**0.2
    for b in dm._B_TABLE[40:60:5]:
        u = (b / scale) ** 5.0
        assert law(u) == pytest.approx(rs.restitution(float(b)), rel=1e-12)
    speeds = np.logspace(-6, 0, 13) * spec.restitution_speed / s.V
    values = [law(u) for u in speeds]
    assert all(a > b for a, b in zip(values, values[1:], strict=False))
    assert law(spec.restitution_speed / s.V) == pytest.approx(e, abs=1e-4)


def test_two_hard_spheres_with_a_restitution_law():
    """N = 2, one lifted, e(u): the relative amplitude after collision k is a_k = e(a_(k-1)) a_(k-1) (the pair meets
    at the relative speed a_(k-1)), so S = 1 / (1 + (a_k / A)^2) between collisions k and k+1."""
    A = 1.5

    def law(u: float) -> float:
        return 1.0 - 0.1 * u ** 0.2

    t = dm.time_grid(12 * math.pi, 16)
    hs = hard_sphere_run(np.array([-A, 0.0]), np.zeros(2), t, restitution=law)
    S = mm.com_share(hs.x, hs.v)
    a = [A]
    for _ in range(12):
        a.append(law(a[-1]) * a[-1])
    phase = (t - math.pi / 2) / math.pi
    k = np.maximum(np.floor(phase + 1.0).astype(int), 0)
    away = np.abs(phase - np.round(phase)) > 1e-6
    expect = 1.0 / (1.0 + (np.array(a)[k] / A) ** 2)
    assert np.allclose(S[away], expect[away], rtol=1e-12, atol=1e-14)
    assert np.allclose(hs.separation / hs.approach, [law(u) for u in hs.approach], rtol=1e-12)


def test_trend_row_of_the_cradle_itself_is_its_own_run():
    """The trends' first row is the spec's own cradle, 5 balls, 1 lifted, the first contact and Stokes' drag: the
    run of case 0 of n5-lifted1, to the bit; a longer string swings slower (omega_0 = sqrt(g/L)) and its e at the
    reference speed is the same A's on the same balls."""
    spec = _spec(FULL, chains=[5], lifted=[1], duration=4.0, trend_lengths=[0.2], trend_radii=[])
    tree = dm.compute(spec, {})
    tr, g = tree["trends"], tree["n5-lifted1"]
    assert [str(n) for n in tr["trend"].values] == ["L=0.1 m, R=0.01 m", "L=0.2 m, R=0.01 m"]
    for key in ("inphase_time_phase", "inphase_time_share"):
        assert np.array_equal(tr[key].values[0], g[key].values[0], equal_nan=True)
    assert tr["drag_rate"].values[0] == g["drag_rate"].values[0]
    assert tr["restitution"].values[1] == pytest.approx(tr["restitution"].values[0], rel=1e-12)


def test_separation_of_the_tolerances_is_the_integrators_error_before_the_rocking(reduced):
    """Before the balls rock, a run and its rerun at rtol / 10 differ by the integrator's error: a few rtol of the
    amplitude added at each impact of the first swings of the reduced form, flat between impacts (once 1e-9 of it
    whatever rtol, at the first impact of the touching balls: a spurious contact event, fixed in
    cradle.integrators._dop853_events). It stays below the lower edge of separation_band, the level the analysis
    declares the integrator's error to lie under (the growth rate is fitted above it)."""
    spec, tree = reduced
    for name in ("n5-lifted1", "n5-lifted2"):
        g = tree[name]
        nc = [i for i, c in enumerate(g["case"].values) if str(c).startswith("nc")]
        early = g["t"].values <= 1.5
        sep = g["separation"].values[nc][:, early] / g.attrs["amplitude_m"]
        assert np.all(sep < spec.separation_band[0] * spec.rtol)
        assert np.all(np.isnan(g["separation"].values[[i for i in range(g.sizes["case"]) if i not in nc]]))


def test_growth_rate_of_an_exponential_separation():
    """A separation 1e-12 e^(3 t) saturating at 1e-2: the rate fitted between the bounds is 3."""
    t = np.linspace(0.0, 12.0, 241)
    d = np.minimum(1e-12 * np.exp(3.0 * t), 1e-2)
    assert mm.growth_rate(t, d, 1e-10, 1e-3) == pytest.approx(3.0, rel=1e-9)
    assert math.isnan(mm.growth_rate(t, d, 1e-10, 1.0))      # never reaches the upper bound
    with pytest.raises(ValueError, match="low"):
        mm.growth_rate(t, d, 1e-3, 1e-10)


def test_ensemble_of_a_regular_cradle_settles_together_and_converges(settles):
    """The 3-ball cradle at e = 0.9 does not rock chaotically: release displacements spread by 1e-6 give in-phase
    times spread by no more (no amplification), and the ensemble's mean S settles at the same time at rtol and
    rtol / 10 (within 1 %, issue 38's criterion)."""
    spec, tree = settles
    g = tree["n3-lifted1"]
    i = [k for k, c in enumerate(g["case"].values) if str(c).startswith("nc")][0]
    members = g["member_inphase_time_share"].values[i]        # (member, tolerance, threshold)
    assert members.shape == (spec.ensemble, 2, len(spec.share_thresholds))
    assert np.all(np.isfinite(members))
    spread = (members.max(axis=0) - members.min(axis=0)) / np.median(members, axis=0)
    assert np.all(spread <= spec.ensemble_spread)
    mean_time = g["ensemble_inphase_time_share"].values[i]     # (tolerance, threshold)
    assert np.all(np.abs(mean_time[1] - mean_time[0]) <= 0.01 * mean_time[0])
