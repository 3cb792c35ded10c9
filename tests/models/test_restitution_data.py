"""The measured restitutions and the one assumption (cradle.models.restitution_data): every analysis that needs the
restitution of the steel desk toy takes it from there, and the two-ball collision turns the assumption into a
Kuwabara-Kono constant and back."""
from __future__ import annotations

import pytest

from cradle.analyses import desk_toy, desk_toy_minute, dissipation
from cradle.models import physical as ph, restitution as rs
from cradle.models.restitution_data import MEASUREMENTS, STEEL_ASSUMED
from cradle.specs.declare import from_plain


def test_no_assumption_is_kept_once_steel_is_measured():
    steel = [m for m in MEASUREMENTS if m.material == "steel"]
    assert not steel, ("a measured steel e(v) is tabulated: fit A (restitution.fit_constant), give it to the analyses "
                       "(kk_constant, restitution), and retire STEEL_ASSUMED")


def test_the_analyses_default_to_the_assumption():
    a = STEEL_ASSUMED
    assert a.bracket[0] < a.e < a.bracket[1]
    assert a.e in from_plain(desk_toy.DeskToyRuns, {}).restitution
    d = from_plain(dissipation.Dissipation, {})
    assert (d.steel_restitution, d.steel_speed) == (a.e, a.v)
    m = from_plain(desk_toy_minute.DeskToyMinute, {})
    assert tuple(m.restitution) == a.bracket and m.restitution_speed == a.v


def test_the_assumption_gives_one_constant_in_both_collisions():
    """A from restitution.scaled_for (b of the collision over kappa^(2/5) v^(1/5)) gives back e at v through
    restitution.restitution_at (the model's collision); the two integrate the same equation to rtol 1e-11."""
    a = STEEL_ASSUMED
    k, m_eff = rs._pair(rs.Measurement(a.material, 0.01, False, a.v, a.e, 1.0, "-"))
    s = ph.scales(ph.real_cradle(a.material, 0.01, length=0.1))
    assert (k, m_eff) == pytest.approx((s.k, s.m / 2.0), rel=1e-12)
    A = rs.scaled_for(a.e) / ((k / m_eff) ** 0.4 * a.v**0.2)
    assert float(rs.restitution_at(A, a.v, k, m_eff)[0]) == pytest.approx(a.e, abs=1e-9)
