"""Physical units (cradle.models.physical): the scales between SI and (nc), the Hertz constants, the pendulum,
the collision time's integral, and ``cradle scale`` with its one-line refusals."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from cradle.models import physical as ph
from cradle.pipeline.cli import main
from cradle.specs.values import ConfigError

DESK = ph.real_cradle("steel", 0.01, length=0.1)


@pytest.mark.parametrize("spec", [DESK, ph.real_cradle("ptfe", 0.02, length=0.3),
                                  ph.real_cradle("brass", 0.005, omega0=2e4)])
def test_round_trips_are_exact_to_rounding(spec):
    s = ph.scales(spec)
    values = np.array([1e-3, 0.01, 0.02118, 1.0, 3e17])
    for quantity in ph.QUANTITIES:
        np.testing.assert_allclose(ph.from_si(ph.to_si(values, quantity, s), quantity, s), values, rtol=4e-16)
        np.testing.assert_allclose(ph.to_si(ph.from_si(values, quantity, s), quantity, s), values, rtol=4e-16)


@pytest.mark.parametrize("spec", [DESK, ph.real_cradle("glass", 0.03, length=1.0), ph.real_cradle("steel", 0.01,
                                                                                                  omega0=1e5)])
def test_the_scales_satisfy_their_defining_balance(spec):
    s = ph.scales(spec)
    # on-site force = contact force at the displacement X; the other scales from T and X
    assert s.m * s.omega0**2 * s.X == pytest.approx(s.k * s.X**1.5, rel=1e-14)
    assert s.X == pytest.approx((s.m * s.omega0**2 / s.k) ** 2, rel=1e-14)
    assert (s.T, s.V, s.F, s.E) == pytest.approx((1 / s.omega0, s.X * s.omega0, s.m * s.omega0**2 * s.X,
                                                   s.m * s.omega0**2 * s.X**2), rel=1e-14)


@pytest.mark.parametrize("name", list(ph.MATERIALS))
def test_identical_spheres_reduce_to_half_modulus_and_half_radius(name):
    mat = ph.lookup_material(name)
    assert ph.reduced_modulus(mat.E, mat.nu, mat.E, mat.nu) == pytest.approx(mat.E / (2 * (1 - mat.nu**2)), rel=1e-15)
    assert ph.reduced_radius(0.01, 0.01) == pytest.approx(0.005, rel=1e-15)
    s = ph.scales(ph.real_cradle(name, 0.01, length=0.1))
    assert s.k == pytest.approx(4 / 3 * mat.E / (2 * (1 - mat.nu**2)) * math.sqrt(0.005), rel=1e-14)
    assert s.m == pytest.approx(4 / 3 * math.pi * 1e-6 * mat.rho, rel=1e-14)


def test_two_different_spheres():
    steel, ptfe = ph.lookup_material("steel"), ph.lookup_material("ptfe")
    e = ph.reduced_modulus(steel.E, steel.nu, ptfe.E, ptfe.nu)
    assert 1 / e == pytest.approx((1 - steel.nu**2) / steel.E + (1 - ptfe.nu**2) / ptfe.E, rel=1e-15)
    assert ph.reduced_radius(0.01, 0.03) == pytest.approx(0.0075, rel=1e-15)


def test_pendulum_omega0_and_standard_gravity():
    assert ph.STANDARD_GRAVITY == 9.80665
    assert ph.scales(DESK).omega0 == pytest.approx(math.sqrt(9.80665 / 0.1), rel=1e-15)
    assert ph.scales(ph.real_cradle("steel", 0.01, length=0.1, g=9.81)).omega0 == pytest.approx(math.sqrt(98.1))
    assert ph.scales(ph.real_cradle("steel", 0.01, omega0=123.0)).omega0 == 123.0
    # a release: the horizontal displacement L sin(theta), and the speed at the bottom from energy
    assert ph.release_amplitude(DESK, 20) * ph.scales(DESK).X == pytest.approx(0.1 * math.sin(math.radians(20)))
    assert ph.release_speed(DESK, 20) ** 2 == pytest.approx(2 * 9.80665 * 0.1 * (1 - math.cos(math.radians(20))))


def test_the_collision_integral_is_landau_lifshitz_1_4716():
    integral, _ = quad(lambda u: 1 / math.sqrt(1 - u**2.5), 0, 1, limit=200)
    assert abs(integral - 1.4716) < 1e-4
    assert ph.COLLISION_INTEGRAL == pytest.approx(integral, rel=1e-9)


def test_collision_time_closed_form_and_its_scaling():
    s = ph.scales(DESK)
    v = 0.3
    delta_max = (5 * (s.m / 2) * v**2 / (4 * s.k)) ** 0.4
    assert ph.collision_time(DESK, v) == pytest.approx(2 * ph.COLLISION_INTEGRAL * delta_max / v, rel=1e-15)
    # t_c ~ v^(-1/5): ten times faster, 10^(1/5) times shorter
    assert ph.collision_time(DESK, 3.0) / ph.collision_time(DESK, 0.3) == pytest.approx(10 ** -0.2, rel=1e-12)


@pytest.mark.parametrize("v", [299792458.0, 1e300])
def test_collision_time_refuses_a_speed_at_or_beyond_light(v):
    # v^2 of 1e300 overflowed inside (OverflowError); the speed of light is the bound no sphere reaches
    with pytest.raises(ConfigError, match=rf"^v = {v!r}: must be < 299792458$".replace("+", r"\+")):
        ph.collision_time(DESK, v)


@pytest.mark.parametrize("kwargs, line", [
    (dict(material="stel", radius=0.01, length=0.1), "material = 'stel': unknown; did you mean 'steel'?"),
    (dict(material="steel", radius=-0.01, length=0.1), "cradle.radius = -0.01"),
    (dict(material="steel", radius=0.01, length=0.0), "cradle.length = 0.0"),
    (dict(material="steel", radius=0.01), "give the pendulum length or omega0"),
    (dict(material="steel", radius=0.01, length=0.1, omega0=3.0), "give the pendulum length or omega0"),
])
def test_bad_cradles_are_one_line(kwargs, line):
    with pytest.raises(ConfigError) as err:
        ph.real_cradle(**kwargs)
    assert line in str(err.value) and "\n" not in str(err.value)


@pytest.mark.parametrize("angle", [0, -5, 90, 120])
def test_a_release_angle_outside_0_90_is_refused(angle):
    with pytest.raises(ConfigError, match=f"release.angle = {angle}"):
        ph.release_amplitude(DESK, angle)


def test_cradle_scale_prints_the_scales(capsys):
    assert main(["scale", "--material", "steel", "--radius", "0.01", "--length", "0.1", "--amplitude", "0.01",
                 "--angle", "20"]) == 0
    out = capsys.readouterr().out
    s = ph.scales(DESK)
    for text in (f"{s.T:.4e} s", f"{s.X:.4e} m", f"{s.V:.4e} m/s", f"{s.F:.4e} N", f"{s.E:.4e} J",
                 f"amplitude 0.01 (nc) = {0.01 * s.X:.4e} m", f"{ph.release_amplitude(DESK, 20):.4e} in (nc) units"):
        assert text in out
    assert main(["scale", "--material", "brass", "--radius", "0.01", "--omega0", "1e4"]) == 0
    assert "stiff oscillator omega_0 = 10000 rad/s" in capsys.readouterr().out


@pytest.mark.parametrize("argv, line", [
    (["--material", "stel", "--radius", "0.01", "--length", "0.1"], "did you mean 'steel'?"),
    (["--material", "steel", "--radius", "-0.01", "--length", "0.1"], "cradle.radius = -0.01"),
    (["--material", "steel", "--radius", "0.01", "--length", "0.1", "--angle", "90"], "release.angle = 90.0"),
    (["--material", "steel", "--radius", "0.01", "--omega0", "1e4", "--angle", "20"], "no pendulum length"),
    (["--material", "steel", "--radius", "0.01"], "--length --omega0 is required"),
    (["--material", "steel", "--radius", "nan", "--length", "0.1"], "--radius: invalid finite number value: 'nan'"),
    (["--material", "steel", "--radius", "0.01", "--length", "0.1", "--amplitude", "inf"], "--amplitude: invalid"),
    # two bad values: both said, each once, on the one line
    (["--material", "steel", "--radius", "1e308", "--length", "1e-308"],
     "cradle.length = 1e-308: must be >= 0.001; cradle.radius = 1e+308: must be <= 10"),
])
def test_cradle_scale_refuses_in_one_line_exit_2(argv, line, capsys):
    assert main(["scale", *argv]) == 2
    captured = capsys.readouterr()
    err = captured.err.strip()
    assert captured.out == "" and "\n" not in err and err.startswith("cradle: error: ") and line in err


# ----------------------------------------------------------------------------- any value of any type: one line

# a string that reads as a number is that number, as `--config` gives it; "abc" is no number
BAD = [0, 0.0, 1e-300, -1e-300, 1e300, -1e300, float("nan"), float("inf"), -float("inf"), "abc", None, True]


def _one_line_naming(err: ConfigError, key: str, value) -> str:
    text = str(err)
    assert "\n" not in text and f"{key} = " in text and ("nan" if value != value else repr(value)[:6]) in text, text
    return text


@pytest.mark.parametrize("key", ["radius", "length", "omega0", "g"])
@pytest.mark.parametrize("value", BAD)
def test_a_cradle_refuses_any_bad_value_in_one_line(key, value):
    kwargs = {"radius": 0.01, "length": 0.1, "g": ph.STANDARD_GRAVITY}
    if key == "omega0":
        kwargs.pop("length")
    kwargs[key] = value
    with pytest.raises(ConfigError) as err:
        ph.real_cradle("steel", **kwargs)
    if value is None and key in ("length", "omega0"):   # None: not given, and one of them must be
        assert str(err.value) == "cradle: give the pendulum length or omega0, one of them (given: neither)"
        return
    _one_line_naming(err.value, f"cradle.{key}", value)


@pytest.mark.parametrize("material", [None, 3, "", "stel", ["steel"]])
def test_a_cradle_refuses_any_bad_material_in_one_line(material):
    with pytest.raises(ConfigError) as err:
        ph.real_cradle(material, 0.01, length=0.1)
    assert "\n" not in str(err.value) and str(err.value).startswith(f"material = {material!r}: ")


@pytest.mark.parametrize("key, value", [(k, v) for k in ("E", "nu", "rho") for v in [*BAD, -1.0]
                                        if not (k == "nu" and v in (0, 1e-300, -1e-300))])  # nu = 0: cork
def test_a_material_refuses_any_bad_constant_in_one_line(key, value):
    good = {"E": 2e11, "nu": 0.3, "rho": 7800.0}
    with pytest.raises(ConfigError) as err:
        ph.Material(name="m", **{**good, key: value}, source="test")
    _one_line_naming(err.value, f"material 'm'.{key}", value)


def test_the_materials_the_paper_meets_divide_by_nothing():
    """E = 0 and nu = 1 divided by zero in reduced_modulus: refused when the material is made."""
    for key, value in (("E", 0.0), ("nu", 1.0), ("E", -1.0)):
        with pytest.raises(ConfigError, match=f"material 'm'.{key} = "):
            ph.Material(name="m", **{"E": 2e11, "nu": 0.3, "rho": 7800.0, key: value}, source="test")


def test_every_scale_is_finite_and_nonzero_at_the_corners_of_the_bounds():
    """The bounds are those that keep (nc)'s scales finite: every corner of the box of materials and cradles."""
    import itertools
    import math

    for E, nu, rho, R, w0, (g, L) in itertools.product((1e3, 1e13), (-0.999, 0.5), (1.0, 1e5), (1e-6, 10.0),
                                                     (None, 1e-3, 1e9), ((1e-3, 1e3), (1e3, 1e-3))):
        mat = ph.Material(name="corner", E=E, nu=nu, rho=rho, source="test")
        ph.MATERIALS["corner"] = mat
        try:
            # made directly: the material's name is not one of the config's (the bounds are those of real_cradle)
            spec = ph.Cradle(material="corner", radius=R, omega0=w0) if w0 else \
                ph.Cradle(material="corner", radius=R, length=L, g=g)
            s = ph.scales(spec)
            values = [getattr(s, f) for f in ("m", "k", "T", "X", "V", "F", "E")]
            if w0 is None:
                for angle in (1e-3, 89.999):
                    v = ph.release_speed(spec, angle)
                    values += [ph.release_amplitude(spec, angle), v, ph.collision_time(spec, v)]
            assert all(math.isfinite(x) and x > 0 for x in values), (E, nu, rho, R, w0, g, L, values)
        finally:
            del ph.MATERIALS["corner"]


@pytest.mark.parametrize("flag", ["--radius", "--length", "--angle"])
@pytest.mark.parametrize("value", ["0", "1e-300", "-1e-300", "1e300", "-1e300", "nan", "inf", "abc"])
def test_cradle_scale_refuses_any_bad_value_in_one_line(flag, value, capsys):
    argv = {"--radius": "0.01", "--length": "0.1", "--angle": "20"}
    argv[flag] = value          # "--angle -1e300" as typed: argparse alone took -1e300 for an option
    assert main(["scale", "--material", "steel", *[x for kv in argv.items() for x in kv]]) == 2
    captured = capsys.readouterr()
    err = captured.err.strip()
    assert captured.out == "" and "\n" not in err and err.startswith("cradle: error: "), err
    key = {"--radius": "cradle.radius", "--length": "cradle.length", "--angle": "release.angle"}[flag]
    assert (f"{flag}: invalid" in err and repr(value) in err) if value in ("nan", "inf", "abc") else \
        (f"{key} = " in err and ("must be >" in err or "must be <" in err)), err
