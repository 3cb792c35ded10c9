"""The map G (comp1)-(comp2) of the stationary DpS equation (dpsstn): area preservation,
reversibility, the explicit periodic orbits of the traj2 caption."""
import dataclasses

import numpy as np
import pytest

from cradle.figures import maps
from cradle.models import stationary as st
from cradle.scenes import stages
from cradle.scenes.spec import MapEntry

ALPHAS = [1.5, 2.0, 3.0]


def _random_points(seed=0, n=50, scale=0.5):
    U = np.random.default_rng(seed).uniform(-scale, scale, (n, 2))
    return U[np.abs(U[:, 1]) > 1e-3]  # G is not differentiable where b = 0


@pytest.mark.parametrize("alpha", ALPHAS)
def test_det_DG_is_one_and_jacobian_matches_finite_differences(alpha):
    for U in _random_points():
        J = st.jacobian(U, alpha)
        # det J = J00 J11 - J01 J10: the LU product and each entry (a few roundings each) err by a few eps times
        # the two products' sizes
        scale = abs(J[0, 0] * J[1, 1]) + abs(J[0, 1] * J[1, 0])
        assert np.linalg.det(J) == pytest.approx(1.0, abs=8 * np.finfo(float).eps * scale)
        h = 1e-7
        fd = np.column_stack([(st.G(U + h * e, alpha) - st.G(U - h * e, alpha)) / (2 * h) for e in np.eye(2)])
        assert np.allclose(fd, J, rtol=1e-5, atol=1e-6)


@pytest.mark.parametrize("alpha", ALPHAS)
def test_odd_invertible_and_reversible(alpha):
    U = _random_points(1)
    assert np.allclose(st.G(-U, alpha), -st.G(U, alpha), atol=1e-15)
    assert np.allclose(st.G_inverse(st.G(U, alpha), alpha), U, atol=1e-13)
    # R G^{-1} = G R with R(a, b) = (a, -a - b)
    assert np.allclose(st.reversor(st.G_inverse(U, alpha)), st.G(st.reversor(U), alpha), atol=1e-13)
    assert np.allclose(st.reversor(st.reversor(U)), U)


@pytest.mark.parametrize("alpha", ALPHAS)
@pytest.mark.parametrize("name, period", [("period2", 2), ("period3", 3), ("period4", 4)])
def test_explicit_periodic_orbits_of_traj2_caption(alpha, name, period):
    U = st.explicit_periodic_orbits(alpha)[name]
    assert U.shape == (period, 2)
    for j in range(period):
        assert np.allclose(st.G(U[j], alpha), U[(j + 1) % period], rtol=1e-13, atol=1e-15)
    # minimal period: no earlier return
    for p in range(1, period):
        if period % p == 0:
            assert not np.allclose(st.orbit(U[0], p, alpha)[-1], U[0])
    a = st.explicit_periodic_orbits(alpha)[name + "_a"]
    assert np.max(np.abs(st.stationary_residual(a, alpha))) < 1e-15
    lhs, rhs = np.sum(a**2), np.sum(np.abs(np.roll(a, -1) - a) ** (alpha + 1))
    assert lhs == pytest.approx(rhs, rel=1e-13)


def test_closed_forms_at_hertz():
    P = st.explicit_periodic_orbits(1.5)
    assert P["period2_a"][0] == pytest.approx(2.0**-5)            # 2^((alpha+1)/(1-alpha))
    assert P["period3_a"][1] == pytest.approx((1 + 2**1.5) ** -2)  # (1 + 2^alpha)^(1/(1-alpha))
    assert P["period4_a"][3] == pytest.approx(0.25)                # 2^(1/(1-alpha))


def test_box_cuts_escaping_orbits():
    orbit = st.orbit([5.0, 0.0], 50, 1.5, box=1.0)
    assert np.all(np.isnan(orbit))
    orbit = st.orbit([0.01, 0.0], 50, 1.5, box=1.0)
    assert np.all(np.isfinite(orbit))


def test_map_stage_stores_the_explicit_orbits_of_marked_entries():
    spec = MapEntry(alpha=1.5, box=0.1, iterations=20, starts=[[0.0, 1e-13]])
    plain = stages.map_orbits(spec, "plain")
    assert "mark_a" not in plain and plain.attrs["marks"] == 0
    ds = stages.map_orbits(dataclasses.replace(spec, marks=True), "marked")
    P = st.explicit_periodic_orbits(1.5)
    for period in (2, 3, 4):
        sel = ds["mark_period"].values == period
        U = P[f"period{period}"]
        assert np.array_equal(ds["mark_a"].values[sel], U[:, 0]) and np.array_equal(ds["mark_b"].values[sel], U[:, 1])
    assert np.array_equal(ds["map_a"].values, plain["map_a"].values, equal_nan=True)
    assert ds["mark_a"].attrs["units"] == "1" and ds["mark_a"].attrs["long_name"]


def test_map_figures_draw_from_datasets():
    ds = stages.map_orbits(MapEntry(alpha=1.5, box=0.1, iterations=200, starts=[[0.0, 1e-13], [0.02, 0.0]],
                                    marks=True), "o")
    fig = maps.draw_traj3({"o": ds}, {"scenes": ["o"]})
    assert len(fig.axes) == 1
    fig = maps.draw_traj2({f"p{i}": ds for i in range(6)}, {"scenes": [f"p{i}" for i in range(6)]})
    assert len(fig.axes) == 6
    # one dot cloud per orbit, marks of the period-2 and -3 orbits; the period-4 orbit (|a| = 0.25) lies outside
    # the box 0.1 of the panel and is not drawn
    assert len(fig.axes[0].lines) == 2 + 2
    assert fig.axes[0].lines[0].get_linestyle() == "None" and fig.axes[0].lines[0].get_rasterized()
