"""dissipation (cradle.analyses.dissipation): lifetimes of breathers and waves in the damped cradle.

The numbers checked are fixed by closed forms: on (dpsdamped) with the on-site term alone,
d/dtau sum |A_n|^2 = -gamma~ sum |A_n|^2 exactly, so the squared l2 norm halves at tau = ln 2 / gamma~; with the
contact term alone a plane wave keeps its shape and R^(1-alpha) = 1 + (alpha-1) Im(kappa) Omega tau; the linear
lattice's damped plane wave x_n = a e^{-gamma t/2} cos(omega_d t + q n) has H(t) = H(0) e^{-gamma t} exactly
(the sum over n of the phases removes the oscillating terms), the contacts changing it by at most their share of
the energy; the two-bead Kuwabara-Kono collision has 1 - e = C1 b - C2 b^2 + ... (Schwager & Poeschel 2008).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from cradle.analyses import dissipation as dis
from cradle.analyses.protocol import FULL, form_spec
from cradle.models import restitution as rs
from cradle.specs.declare import from_plain

ALPHA = dis.ALPHA


def _interpolation_bound(h: float, curvature: float, slope: float) -> float:
    """Time error of the log-linear interpolation of :func:`dis.lifetime`: h^2/8 max |(ln r)''| / min |(ln r)'|."""
    return h * h / 8.0 * curvature / slope


def test_dps_onsite_lifetime_is_ln2_over_gamma():
    """On-site damping alone: sum |A_n|^2 halves at tau = ln 2 / gamma~ (and reaches 1/e at 1 / gamma~), for any
    data (here plot18's breather profile and a random ring); ln r is linear, so the interpolation is exact."""
    from cradle.integrators import integrate_dps
    from cradle.models.dps_damped import DpsDamping

    rng = np.random.default_rng(7)
    spec = from_plain(dis.Dissipation, {"N": 16, "wave_mode": 2, "waves": [1.01]})
    breather = dis.families(spec)[0][1]
    for A0 in (breather.A0, rng.normal(size=12) + 1j * rng.normal(size=12)):
        for g in (0.3, 2.0):
            tau = np.linspace(0.0, 1.5 / g, 301)
            sol = integrate_dps(A0, tau, alpha=ALPHA, rtol=1e-12, damping=DpsDamping(gamma=g))
            l2 = np.sum(np.abs(sol.A) ** 2, axis=1)
            assert dis.lifetime(tau, l2 / l2[0], 0.5) == pytest.approx(math.log(2.0) / g, rel=1e-9)
            assert dis.lifetime(tau, l2 / l2[0], math.exp(-1.0)) == pytest.approx(1.0 / g, rel=1e-9)


@pytest.mark.parametrize("eta", [0.3, 3.0])
def test_dps_contact_lifetime_of_a_plane_wave(eta):
    """Contact damping alone on a plane wave: the lifetime of the run equals the closed form (clipping included
    through kappa), to the interpolation bound of the sampling."""
    from cradle.integrators import integrate_dps
    from cradle.models import dps, initial
    from cradle.models.dps_damped import DpsDamping, contact_factor

    N, q = 20, 2.0 * np.pi * 2 / 20
    init = initial.travelling_wave(N, q, ALPHA, omega_tw=1.01)
    c = (ALPHA - 1.0) * contact_factor(eta, ALPHA).imag * dps.plane_wave_frequency(1.0, q, ALPHA)
    for level in dis.LEVELS:
        expected = dis.closed_lifetime("contact", eta, level, "wave-1.01", init.info, q)
        tau_end = 2.0 * expected * init.eps ** (ALPHA - 1.0)
        tau = np.linspace(0.0, tau_end, 2001)
        sol = integrate_dps(init.A0, tau, alpha=ALPHA, rtol=1e-12, damping=DpsDamping(eta=eta))
        l2 = np.sum(np.abs(sol.A) ** 2, axis=1)
        t = tau * init.eps ** (1.0 - ALPHA)
        # ln r = -(2/(alpha-1)) ln(1 + c tau): |(ln r)''| <= 2 c^2/(alpha-1),
        # |(ln r)'| >= 2 c/((alpha-1)(1 + c tau_end)) (per unit tau; times d tau/dt per unit t)
        scale = init.eps ** (ALPHA - 1.0)  # d tau / dt
        bound = _interpolation_bound(t[1] - t[0], 2.0 * (c * scale) ** 2 / (ALPHA - 1.0),
                                     2.0 * c * scale / ((ALPHA - 1.0) * (1.0 + c * tau_end)))
        assert abs(dis.lifetime(t, l2 / l2[0], level) - expected) <= bound + 1e-9 * expected


@pytest.mark.parametrize("a", [1e-8, 1e-4])
def test_lattice_linear_limit_onsite(a):
    """The damped lattice's small-amplitude limit: a damped plane wave loses energy as e^{-gamma t} up to the
    contacts' share of H, below (2 sin(q/2))^(alpha+1) a^(alpha-1) (the largest compression is 2 a sin(q/2))."""
    from cradle.integrators import integrate_lattice
    from cradle.models.damping import Damping

    N, q, g = 50, np.pi / 5, 0.05
    n = np.arange(N)
    wd = math.sqrt(1.0 - g * g / 4.0)
    x0, v0 = a * np.cos(q * n), a * (-(g / 2.0) * np.cos(q * n) - wd * np.sin(q * n))
    t = np.linspace(0.0, 2.0 * math.log(2.0) / g, 2001)
    lat = integrate_lattice(x0, v0, t, alpha=ALPHA, method="dop853_numba", rtol=1e-12, damping=Damping(onsite=g))
    r = lat.energy / lat.energy[0]
    share = (2.0 * math.sin(q / 2.0)) ** (ALPHA + 1.0) * a ** (ALPHA - 1.0)
    assert np.max(np.abs(np.log(r) + g * t)) <= share
    assert abs(g * dis.lifetime(t, r, 0.5) / math.log(2.0) - 1.0) <= share


def test_restitution_of_the_collision_against_schwager_poeschel():
    """1 - e of the (ncdamped) collision is C1 b - C2 b^2 + ... with C1 in closed form
    (restitution.first_order_coefficient) and C2 < 1 (0.80, measured in tests/models/test_restitution.py): at
    b = 1e-4 the quotient is C1 within b; scaled_for inverts it."""
    b = 1e-4
    assert restitution_quotient(b) == pytest.approx(dis.SCHWAGER_C1, abs=b)
    e = 0.95
    assert 1.0 - rs.restitution(rs.scaled_for(e)) == pytest.approx(1.0 - e, abs=1e-9)


def restitution_quotient(b: float) -> float:
    return (1.0 - rs.restitution(b)) / b


TINY = {"N": 16, "wave_mode": 2, "waves": [1.01], "onsite": [0.05, 0.1], "contact": [1.0, 3.0], "t_end": 40.0,
        "window": 10.0, "validity_eps": [0.01, 0.005], "validity_T": [0.5]}


def test_compute_on_a_tiny_form():
    """The stored tree of a tiny form: the DpS on-site lifetimes are ln 2 / gamma and 1 / gamma (exact), the
    wave's DpS contact lifetimes the closed form (to the interpolation bound at spacing 0.1, far below 1e-3), the
    breather's DpS frequency follows the exact on-site law (the window mean of the phase rate, least squares),
    the lattice runs keep H + D = H(0)."""
    spec = form_spec(from_plain(dis.Dissipation, TINY), FULL)
    tree = dis.compute(spec)
    lt = tree["lifetimes"]
    terms = lt["term_of_case"].values
    dps, closed = lt["lifetime_dps"].values, lt["lifetime_closed"].values
    on = terms == 0
    assert np.allclose(dps[:, on], closed[:, on], rtol=1e-8)
    assert np.allclose(closed[:, on, 0] * lt["damping"].values[on], math.log(2.0))
    fams = [s.strip() for s in tree.attrs["family_names"].split(",")]
    jw = fams.index("wave-1.01")
    ok = np.isfinite(dps[jw, ~on])
    assert ok.any()
    assert np.allclose(dps[jw, ~on][ok], closed[jw, ~on][ok], rtol=1e-3)
    assert np.isnan(closed[fams.index("breather"), ~on]).all()
    dr = tree["drift"]
    # a least-squares slope weights the window by 6u(1-u), the closed form is the uniform mean: for
    # omega - 1 = A e^{-r t} they differ by A r^2 w^2 (1/12 - 1/20) / 2 = A r^2 w^2 / 60 at leading order
    w, w0 = spec.window, float(lt["omega0_family"].values[fams.index("breather")])
    r = 0.5 * (ALPHA - 1.0) * lt["damping"].values[on]
    bound = 2.0 * (w0 - 1.0) * (r * w) ** 2 / 60.0
    assert np.all(np.abs(dr["omega_dps"].values[on] - dr["omega_closed"].values[on]) <= bound[:, None])
    assert float(np.nanmax(lt["balance_drift"].values)) < 1e-6
    assert tree["validity"]["abs_error"].shape == (2, 2, 1)
    assert float(tree["steel"]["eta_steel"].values[0]) > 0


def test_check_refuses_a_wave_beyond_the_zone():
    from cradle.specs.values import Errors

    spec = from_plain(dis.Dissipation, {"N": 16, "wave_mode": 8})
    out = Errors()
    spec.check(["beyond", "dissipation"], None, out)
    assert out.lines == ["config error: beyond.dissipation.wave_mode = 8: must be below N / 2 (N = 16; q < pi)"]
