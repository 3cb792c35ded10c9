"""Section 4.3 (plot18, loc1, fini): the packet and pair initial kinds, the free-end
homoclinic solution, the pair's outcome in the metrics on synthetic data, and the three drawing functions."""
import copy
from pathlib import Path

import matplotlib
import numpy as np
import pytest
import xarray as xr
import yaml

from cradle.figures import localised, registry
from cradle.measurements import breathers, interactions
from cradle.models import dps, homoclinic, initial, lattice
from cradle.pipeline import config as cc
from cradle.scenes import stages

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import QuadMesh  # noqa: E402
from matplotlib.image import AxesImage  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
ALPHA = 1.5


# ------------------------------------------------------------------ packet

def test_packet_gaussian_on_a_bond():
    d = initial.packet(50, ALPHA, amplitude=0.016, width=12, envelope_kind="gaussian", centre=24.5)
    n = np.arange(50)
    assert d.x0.shape == (50,) and d.eps == 1.0
    assert np.all(d.v0 == 0.0)
    assert np.array_equal(d.A0, d.x0 / 2) and np.all(d.A0.imag == 0)
    expected = 0.016 * (-1.0) ** n * np.exp(-0.5 * ((n - 24.5) / 2.0) ** 2)   # sigma = width / 6
    assert d.x0 == pytest.approx(expected, abs=1e-18)
    assert np.max(np.abs(d.x0)) == pytest.approx(0.016 * np.exp(-0.5 / 16), rel=1e-12)
    inside = np.abs(n - 24.5) < 6                       # the 12 sites n = 19..30
    assert inside.sum() == 12
    assert np.max(np.abs(d.x0[~inside])) < 0.01 * 0.016   # "almost compactly supported"
    assert np.all(np.sign(d.x0[inside]) == (-1.0) ** n[inside])   # binary oscillation
    assert d.x0[24] == pytest.approx(-d.x0[25])         # antisymmetric about the bond


def test_packet_cos2_is_compact_and_wraps_on_a_ring():
    d = initial.packet(20, ALPHA, amplitude=0.01, width=6, envelope_kind="cos2", centre=0)
    nonzero = np.flatnonzero(d.x0)
    assert sorted(nonzero.tolist()) == [0, 1, 2, 18, 19]   # |s| < 3 around site 0, across the seam
    assert d.x0[0] == pytest.approx(0.01) and np.max(np.abs(d.x0)) == pytest.approx(0.01)
    free = initial.packet(20, ALPHA, amplitude=0.01, width=6, envelope_kind="cos2", centre=0, bc="free")
    assert sorted(np.flatnonzero(free.x0).tolist()) == [0, 1, 2]


def test_packet_rejects_bad_input():
    with pytest.raises(ValueError, match="envelope"):
        initial.packet(20, ALPHA, amplitude=0.01, width=6, envelope_kind="box")
    with pytest.raises(ValueError, match="amplitude"):
        initial.packet(20, ALPHA, amplitude=0.0, width=6)


# ------------------------------------------------------------------ pair

def test_pair_of_bond_breathers_with_a_node_between():
    d = initial.pair(50, ALPHA, amplitude=0.01, separation=3, profile="bond", sign=1)
    assert d.x0.shape == (50,) and d.eps == 1.0
    assert np.all(d.v0 == 0.0) and np.array_equal(d.A0, d.x0 / 2)
    # bond profile centred on bond (25, 26), copies shifted by -1 and +2: cores 24-25 and 27-28, node at 26
    assert abs(d.x0[26]) < 1e-15
    assert d.x0[26 - np.arange(1, 10)] == pytest.approx(-d.x0[26 + np.arange(1, 10)], abs=1e-15)
    assert {int(np.argmax(np.abs(d.x0[:26]))), 26 + 1 + int(np.argmax(np.abs(d.x0[27:])))} == {24, 28}
    assert np.max(np.abs(d.x0)) == pytest.approx(0.01, rel=0.02)
    a = homoclinic.solve(homoclinic.initial_guess(50, "bond", ALPHA), ALPHA).a
    mu = (0.01 / np.max(np.abs(a))) ** (ALPHA - 1)
    assert d.info["mu"] == pytest.approx(mu) and d.info["omega_sw"] == pytest.approx(dps.omega_sw_from_mu(mu, ALPHA))


def test_pair_far_apart_is_two_copies_of_the_breather_data():
    a = homoclinic.solve(homoclinic.initial_guess(50, "site", ALPHA), ALPHA).a
    d = initial.pair(50, ALPHA, amplitude=0.01, separation=20, profile="site", sign=-1, a_n=a)
    single = initial.breather(a, ALPHA, amplitude=0.01)
    assert d.x0 == pytest.approx(np.roll(single.x0, -10) - np.roll(single.x0, 10), abs=1e-15)
    assert np.max(np.abs(d.x0)) == pytest.approx(0.01, rel=1e-12)
    assert d.info["omega_sw"] == pytest.approx(single.info["omega_sw"])


def test_pair_rejects_bad_input():
    with pytest.raises(ValueError, match="separation"):
        initial.pair(10, ALPHA, amplitude=0.01, separation=10)
    with pytest.raises(ValueError, match="sign"):
        initial.pair(10, ALPHA, amplitude=0.01, separation=3, sign=2)
    with pytest.raises(ValueError, match="profile"):
        initial.pair(10, ALPHA, amplitude=0.01, separation=3, profile="double")


# ------------------------------------------------------------------ config + stages

def _config_with(scene):
    raw = yaml.safe_load((ROOT / "config.yaml").read_text())
    cfg = {"defaults": copy.deepcopy(raw.get("defaults", {})), "homoclinic": {}, "scenes": {"s": scene},
           "figures": {}}
    return cfg


@pytest.mark.parametrize("ini", [
    {"kind": "packet", "amplitude": 0.016, "width": 12, "envelope": "gaussian", "centre": 9.5},
    {"kind": "packet", "amplitude": 0.016, "width": 6},
    {"kind": "pair", "amplitude": 0.01, "separation": 3},
    {"kind": "pair", "amplitude": 0.01, "separation": 2, "profile": "site", "sign": -1, "centre": 10},
])
def test_initial_data_stage_for_the_new_kinds(ini):
    cfg = _config_with({"N": 20, "bc": "periodic", "initial": ini, "t_end": 1.0, "store": {"every": 0.5}})
    spec = cc.scene(cfg, "s")
    ds = stages.initial_data(spec, "s")
    assert ds.attrs["initial_kind"] == ini["kind"] and ds.attrs["eps"] == 1.0 and "homoclinic" not in ds.attrs
    assert np.all(ds["v0"].values == 0) and np.all(ds["A0_im"].values == 0)
    assert np.array_equal(ds["A0_re"].values, ds["x0"].values / 2)
    energy0 = lattice.hamiltonian(ds["x0"].values, ds["v0"].values, ALPHA, "periodic")
    assert ds.attrs["energy0"] == pytest.approx(energy0)


@pytest.mark.parametrize("ini, path, words", [
    ({"kind": "packet", "amplitude": 0.01, "width": 30}, "scenes.s.initial.width", "must be <= N = 20"),
    ({"kind": "packet", "amplitude": 0.01, "width": 6, "centre": 19.5}, "scenes.s.initial.centre", "[0, 19]"),
    ({"kind": "packet", "amplitude": 0.01}, "scenes.s.initial.width", "missing"),
    ({"kind": "packet", "amplitude": 0.01, "width": 6, "envelope": "box"}, "scenes.s.initial.envelope", "gaussian"),
    ({"kind": "pair", "amplitude": 0.01, "separation": 20}, "scenes.s.initial.separation", "[1, 19]"),
    ({"kind": "pair", "amplitude": 0.01, "separation": 3, "sign": 0}, "scenes.s.initial.sign", "must be one of"),
    ({"kind": "pair", "amplitude": -0.01, "separation": 3}, "scenes.s.initial.amplitude", "must be > 0"),
    ({"kind": "pair", "amplitude": 0.01, "separation": 3, "homoclinic": "bond"}, "scenes.s.initial.homoclinic",
     "unknown key"),
])
def test_config_checks_of_the_new_kinds(ini, path, words):
    cfg = _config_with({"N": 20, "bc": "periodic", "initial": ini, "t_end": 1.0, "store": {"every": 0.5}})
    with pytest.raises(cc.ConfigError) as info:
        cc.validate(cfg)
    lines = info.value.errors
    assert len(lines) == 1, lines
    assert lines[0].startswith(f"config error: {path}") and words in lines[0], lines[0]


def test_real_config_entries_of_section_4_3():
    cfg = cc.load(ROOT / "config.yaml")
    assert cfg["homoclinic"]["free-bond"]["bc"] == "free" and cfg["homoclinic"]["free-bond"]["N"] == 10
    for label in ("plot18", "loc1", "fini"):
        assert label in cfg["figures"] and label in registry()
    assert cfg["scenes"]["loc1-pair"]["initial"]["kind"] == "pair"
    assert cfg["scenes"]["loc1-packet"]["initial"]["kind"] == "packet"


# ------------------------------------------------------------------ free-end homoclinic (fini)

def test_free_end_bond_homoclinic_on_ten_beads():
    guess = homoclinic.initial_guess(10, "bond", ALPHA, 0.1, centre=4)
    sol = homoclinic.solve(guess, ALPHA, "free")
    a = sol.a
    assert sol.converged and sol.residual < 1e-14
    assert np.max(np.abs(homoclinic.residual(a, ALPHA, "free"))) < 1e-14
    assert np.max(np.abs(a)) > 0.04                                       # nontrivial
    k = np.arange(5)
    assert np.max(np.abs(a[4 - k] + a[5 + k])) < 1e-11 * np.max(np.abs(a))  # antisymmetric about bond (4, 5)
    assert np.sum(a[3:7] ** 2) / np.sum(a**2) > 0.98                       # mainly on 4 beads
    s2, sd = homoclinic.energy_balance(a, ALPHA, "free")
    assert s2 == pytest.approx(sd, rel=1e-12)


# ------------------------------------------------------------------ the pair's outcome in the metrics

def _breathers(halves, period=2 * np.pi / 1.1, N=30, dt=0.25):
    """Synthetic displacements and forces of breathers at N/2 -+ half(t), breathing at omega = 2 pi /
    period: ``halves(t)`` gives the half-separation (0: one breather at N/2)."""
    n_periods = 200
    t = np.arange(0, n_periods * period + 1e-9, dt)
    n = np.arange(N)
    half = halves(t)
    bump = lambda x0: np.exp(-0.5 * ((n[None, :] - x0[:, None]) / 0.7) ** 2)  # noqa: E731
    shape = np.where(half[:, None] > 0, bump(N / 2 - half) + bump(N / 2 + half), bump(N / 2 + 0 * half))
    shape /= shape.max(axis=1, keepdims=True)
    x = 1e-2 * (-1.0) ** n[None, :] * shape * np.cos(2 * np.pi / period * t)[:, None]
    force = -np.maximum(np.cos(2 * np.pi / period * t), 0)[:, None] ** 1.5 * 1e-3 * shape
    return {"t": t, "x": x, "force": force}


T = 2 * np.pi / 1.1


def _merge_at(t_merge):
    """Two breathers 6 sites apart until t_merge, one from then on (a known merge)."""
    return _breathers(lambda t: np.where(t < t_merge, 3.0, 0.0))


def test_frequency_and_half_period_shift():
    t = np.arange(0, 600, 0.1)
    assert breathers.frequency_from_crossings(t, np.cos(1.1 * t + 0.3)) == pytest.approx(1.1, rel=1e-6)
    sh = breathers.half_period_shift(t, np.cos(1.09 * t), np.cos(1.1 * t), 1.1)
    assert sh["half_shift_periods"] == pytest.approx((np.pi / 0.01) / (2 * np.pi / 1.1), rel=1e-3)


def _pair_run(t_merge):
    """A synthetic run of kind "pair" (displacements and forces of _merge_at) as the sim files hold it."""
    d = _merge_at(t_merge)
    N = d["force"].shape[1]
    return xr.Dataset({"x": (("t", "n"), d["x"]), "force": (("t", "n"), d["force"])},
                      coords={"t": d["t"], "n": np.arange(N)},
                      attrs={"omega_sw": 1.1, "bc": "periodic", "initial_kind": "pair", "alpha": ALPHA})


def test_metrics_stage_stores_the_outcome_of_the_interaction_measure():
    ex, ap = _pair_run(80.5 * T), _pair_run(60.2 * T)
    m = stages.metrics(None, ex, ap, "pair")
    for model, run in (("exact", ex), ("dps", ap)):
        oc = interactions.classify_run(run)
        assert oc.outcome == "merge"
        assert float(m[f"merging_time_{model}"]) == oc.merge_period
        assert float(m[f"first_coalescence_{model}"]) == oc.first_coalescence <= oc.merge_period
        assert int(m[f"outcome_{model}"]) == interactions.OUTCOMES.index("merge")
        assert m[f"merging_time_{model}"].attrs["units"] == "1" and m[f"merging_time_{model}"].attrs["long_name"]
    # the period holding t_merge still shows both breathers: the merge is the next period
    assert localised.loc1_merging_times({"metrics": m}) == {"exact": 81.0, "dps": 61.0}
    # the peak compression the loc1 diagrams bin by period is the measurement's, on every bond
    starts, P = breathers.peak_compression(ex["t"].values, ex["force"].values, 2.0 * np.pi / 1.1)
    assert np.array_equal(m["t_window"].values, starts)
    assert np.array_equal(m["peak_compression_exact"].values, P, equal_nan=True)


def test_metrics_stage_stores_the_breather_measurements_of_plot18_and_fini():
    sim = _sim(N=40, t_end=120.0)
    ex, ap, m = sim["exact"], sim["dps"], sim["metrics"]
    x = ex["x"].values
    site = int(np.argmax(np.abs(x[0])))
    sh = breathers.half_period_shift(ex["t"].values, x[:, site], ap["x"].values[:, site], 1.1)
    assert int(m["breather_site"]) == site
    assert localised.shift(m) == sh
    core = 0.5 * (int(np.argmax(x[0])) + int(np.argmin(x[0])))
    i = 57
    assert float(m["radiated_exact"][i]) == breathers.dispersive_amplitude(x[i], core, periodic=True)


def test_a_metrics_file_without_the_measurements_is_a_clear_error():
    sim = _sim(kind="pair", t_end=100.0)
    stale = sim["metrics"].drop_vars(["merging_time_exact", "merging_time_dps"])
    with pytest.raises(ValueError, match="rebuild the metrics"):
        localised.loc1_merging_times({**sim, "metrics": stale})


# ------------------------------------------------------------------ drawing functions

def _sim(N=20, t_end=60.0, dt=0.5, omega=1.1, bc="periodic", kind="breather", scale=0.01):
    t = np.round(np.arange(0, t_end + 1e-9, dt), 9)
    n = np.arange(N)
    prof = scale * (-1.0) ** n * np.exp(-0.5 * ((n - N / 2 + 0.5) / 1.2) ** 2)
    attrs = {"omega_sw": omega, "mu": 0.44, "bc": bc, "initial_kind": kind, "alpha": ALPHA}

    def ds(w):
        x = prof[None, :] * np.cos(w * t)[:, None]
        f = lattice.bond_forces(x, ALPHA, bc)
        return xr.Dataset({"x": (("t", "n"), x), "force": (("t", "n"), f)}, coords={"t": t, "n": n}, attrs=attrs)

    ex, ap = ds(omega * 0.995), ds(omega)
    if kind == "packet":  # no omega_sw of its own (the metrics stage bins it by 1.1)
        for part in (ex, ap):
            del part.attrs["omega_sw"]
    return {"exact": ex, "dps": ap, "metrics": stages.metrics(None, ex, ap, kind)}


def _images(fig):
    return [im for ax in fig.axes for im in ax.get_images()]


def _no_mesh(fig):
    """No pcolormesh outside the colourbars (a colourbar draws its own scale as a mesh)."""
    return not any(isinstance(c, QuadMesh) for ax in fig.axes if ax.get_label() != "<colorbar>"
                   for c in ax.collections)


def test_draw_plot18_on_synthetic_data():
    data = {"s": _sim(N=40, t_end=120.0), "l": _sim(N=40, t_end=30.0, omega=1.6, scale=0.3)}
    fig = localised.draw_plot18(data, {"scenes": ["s", "l"], "times": [0.0, 110.0, 120.0, 30.0]})
    assert len(_images(fig)) == 1 and isinstance(_images(fig)[0], AxesImage) and _no_mesh(fig)
    assert len([ax for ax in fig.axes if ax.get_label() != "<colorbar>"]) == 4
    plt.close(fig)


def test_draw_loc1_on_synthetic_data():
    packet = _sim(kind="packet")
    data = {"p": packet, "q": _sim(kind="pair", t_end=100.0)}
    fig = localised.draw_loc1(data, {"scenes": ["p", "q"]})
    ims = _images(fig)
    assert len(ims) == 4 and _no_mesh(fig)
    # row-major: exact packet, exact pair, approx packet, approx pair; exact and approx share a scale
    assert ims[0].get_clim() == ims[2].get_clim() and ims[1].get_clim() == ims[3].get_clim()
    assert ims[0].get_clim()[1] == 0.0 and ims[0].get_cmap().name == "gray"
    titles = " ".join(ax.get_title() for ax in fig.axes)
    assert "merging" in titles
    plt.close(fig)


def test_draw_fini_on_synthetic_data():
    data = {"f": _sim(N=10, t_end=60.0, dt=0.1, bc="free")}
    fig = localised.draw_fini(data, {"scenes": ["f"], "times": [0.0, 10.0, 50.0, 60.0]})
    axes = fig.axes
    assert len(axes) == 4
    assert all(len(ax.get_lines()) == 10 for ax in axes)             # one trace per bead
    y = axes[0].get_lines()[5].get_ydata()   # beads numbered from 0, as everywhere
    assert np.mean(y) == pytest.approx(5.0, abs=0.5)                  # bead n = 5 drawn around 5
    assert axes[0].get_xlim() == (0.0, 10.0) and axes[2].get_xlim() == (50.0, 60.0)
    plt.close(fig)
