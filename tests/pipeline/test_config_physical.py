"""Scenes of a real cradle (issue "The cradle on the bench"): a scene's `cradle:`, its `units: si` and the damping
terms, validated before any work in one line naming the key and the value, and SI values converted to (nc)'s units
with the scales of :mod:`cradle.models.physical`."""
import copy
import math

import pytest
import yaml

from cradle.models import physical
from cradle.pipeline import config as cc
from cradle.specs.values import ConfigError
from test_config import CONFIG, one_error  # tests/pipeline is on sys.path (rootdir, no __init__.py)

STEEL = {"material": "steel", "radius": 0.01, "length": 0.1}
#: a packet of 1 nm in a steel cradle, damped, in SI
DESK = {"N": 16, "bc": "free", "cradle": STEEL, "units": "si",
        "initial": {"kind": "packet", "amplitude": 1e-9, "width": 6},
        "exact": {"method": "dop853_numba", "rtol": 1e-9}, "t_end": 0.5, "store": {"every": 0.01}}


@pytest.fixture(scope="module")
def raw():
    return yaml.safe_load(CONFIG.read_text())


def with_scene(raw, scene, name="desk"):
    cfg = copy.deepcopy(raw)
    cfg["scenes"][name] = copy.deepcopy(scene)
    return cfg


def test_an_si_scene_is_run_in_nc_units(raw):
    """t = omega_0 s: the SI times of the scene become (nc)'s, the damping rate gamma = rate / omega_0 and the
    Kuwabara-Kono eta = A omega_0; the resolved scene keeps its cradle and drops `units`."""
    scene = dict(DESK, damping={"onsite": 0.5, "contact": 1e-6})
    spec = cc.scene(with_scene(raw, scene), "desk")
    w0 = math.sqrt(physical.STANDARD_GRAVITY / 0.1)
    assert spec.units is None and spec.cradle is not None and spec.cradle.material == "steel"
    assert spec.t_end == pytest.approx(0.5 * w0, rel=1e-15)
    assert spec.store.every == pytest.approx(0.01 * w0, rel=1e-15)
    assert spec.damping is not None
    assert spec.damping.onsite == pytest.approx(0.5 / w0, rel=1e-15)
    assert spec.damping.contact == pytest.approx(1e-6 * w0, rel=1e-15)
    assert len(spec.times) == 51
    X = physical.scales(physical.real_cradle("steel", 0.01, length=0.1)).X
    assert spec.initial.amplitude == pytest.approx(1e-9 / X, rel=1e-15)


def test_an_si_amplitude_is_divided_by_the_length_scale(raw):
    scene = {"N": 16, "cradle": STEEL, "units": "si", "t_end": 1.0, "store": {"every": 0.5},
             "initial": {"kind": "travelling", "q": "pi", "a": 1e-6}}
    spec = cc.scene(with_scene(raw, scene), "desk")
    X = physical.scales(physical.real_cradle("steel", 0.01, length=0.1)).X
    assert spec.initial.a == pytest.approx(1e-6 / X, rel=1e-15)


def test_a_scene_without_the_new_keys_resolves_as_before(raw):
    """No `damping`, `cradle` or `units`: the scene's plain parameters (its jobs' identity) hold none of them."""
    from cradle.specs.declare import plain

    p = plain(cc.scene(raw, "tw-weak"))
    assert not {"damping", "cradle", "units"} & set(p)


@pytest.mark.parametrize("change, parts", [
    (lambda s: s.pop("cradle"), ("scenes.desk.units = 'si'", "needs the scene's `cradle:`")),
    (lambda s: s["cradle"].update(material="stell"), ("scenes.desk.cradle.material = 'stell'", "steel")),
    (lambda s: s.update(damping={"onsite": -0.1}), ("scenes.desk.damping.onsite = -0.1", "must be >= 0")),
    (lambda s: s.update(damping={"contact": 1e-6}, exact={"method": "srkn6c"}),
     ("scenes.desk.exact.method = 'srkn6c'", "dop853_numba with damping")),
    (lambda s: s.update(alpha=2.0), ("scenes.desk.alpha = 2", "must be 1.5")),
    (lambda s: s["cradle"].update(omega0=10.0), ("scenes.desk.cradle", "one of them (given: both)")),
    # (a time in SI beyond the longest run once in (nc)'s units: said before the budget's estimate)
    (lambda s: s.update(t_end=1e6), ("scenes.desk.t_end: is 9.90285e+06 in (nc)'s time units", "4194304")),
    (lambda s: s.update(units="metric"), ("scenes.desk.units = 'metric'", "must be one of nc, si")),
])
def test_bad_physical_input_is_one_line(raw, change, parts):
    scene = copy.deepcopy(DESK)
    change(scene)
    one_error(with_scene(raw, scene), *parts)


def test_an_unknown_material_from_python_is_one_line():
    with pytest.raises(ConfigError, match=r"^material = 'stel': unknown; did you mean 'steel'\?"):
        physical.real_cradle("stel", 0.01, length=0.1)
