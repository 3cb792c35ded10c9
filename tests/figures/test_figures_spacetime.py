"""Figures of sections 4.1-4.2 (cradle.figures.spacetime) on synthetic datasets shaped
like the pipeline's outputs: the expected panels, raster (imshow) space-time diagrams,
exact and approximate on one grey scale vmin = the most negative force of both, vmax = 0."""
import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.collections import QuadMesh
from matplotlib.image import AxesImage

from cradle.data.io import make_dataset
from cradle.figures import drawer, registry, spacetime

N = 16
T = np.round(np.arange(0.0, 60.0 + 1e-9, 0.5), 9)       # a stored grid, every 0.5 on [0, 60]
EXACT_MIN, DPS_MIN = -3.0, -2.0                          # the exact run compresses harder


def _forces(x):
    d = np.roll(x, -1, axis=1) - x                       # periodic bonds: n joins n and n+1
    return -np.abs(np.minimum(d, 0.0)) ** 1.5


def _scene(seed):
    rng = np.random.default_rng(seed)
    n = np.arange(N)
    x = np.cos(0.8 * n[None, :] - 1.1 * T[:, None]) + 0.05 * rng.standard_normal((len(T), N))
    xa = np.cos(0.8 * n[None, :] - 1.05 * T[:, None])
    fe, fa = _forces(x), _forces(xa)
    fe *= EXACT_MIN / fe.min()
    fa *= DPS_MIN / fa.min()
    fe[:, 5] = 0.0                                       # one bond always open: white column
    coords = {"t": T, "n": n}
    exact = make_dataset({"x": x, "v": np.zeros_like(x), "force": fe, "energy": np.ones(len(T))}, coords,
                         {"energy_drift": 1e-10})
    dps = make_dataset({"A_re": xa, "A_im": 0 * xa, "x": xa, "force": fa, "tau": 0.1 * T}, coords)
    metrics = make_dataset({"E": np.abs(x - xa).max(axis=1)}, {"t": T})
    return {"exact": exact, "dps": dps, "metrics": metrics}


@pytest.fixture(scope="module")
def data():
    return {"synthetic": _scene(1)}


# label -> (times shown, number of axes including colour bars, number of space-time images)
EXPECTED = {
    "plot6-7": ([], 3, 2),
    "plot2-3": ([10.0, 55.5], 2, 0),
    "plot1v5st": ([], 3, 2),
    "plot1v5": ([50.0], 3, 1),
    "plot8-11": ([0.0, 40.0], 2, 0),
    "plot9-10": ([], 3, 2),
    "plot29-30": ([0.0, 30.0], 2, 0),
    "plot26-27": ([], 3, 2),
    "plot28": ([], 2, 1),
}


def test_every_label_is_registered_here():
    reg = registry()
    assert {label for label, func in reg.items() if func.__module__ == spacetime.__name__} == set(EXPECTED)


@pytest.mark.parametrize("label", EXPECTED)
def test_panels_raster_and_one_grey_scale(data, label):
    times, n_axes, n_images = EXPECTED[label]
    fig = drawer(label)(data, {"scenes": ["synthetic"], "times": times})
    try:
        assert len(fig.axes) == n_axes
        panels = [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]
        images = [im for ax in panels for im in ax.get_images()]
        assert len(images) == n_images
        assert all(isinstance(im, AxesImage) for im in images)
        assert not any(isinstance(c, QuadMesh) for ax in panels for c in ax.collections)
        assert all(im.get_cmap().name == "gray" for im in images)          # vmin black, 0 white
        if n_images == 2 or label == "plot1v5":                             # plot1v5: plot1v5st's scale
            assert {im.get_clim() for im in images} == {(EXACT_MIN, 0.0)}
        for ax in panels:
            if ax.get_images():
                assert ax.get_xlabel() == "$n$" and ax.get_ylabel() in ("$t$", "")
            else:                                                           # profiles: 2 lines each
                assert ax.get_xlabel() == "$n$" and ax.get_ylabel() == "$x_n(t)$"
                assert len(ax.get_lines()) == 2
    finally:
        plt.close(fig)


def test_image_extent_puts_stored_samples_at_cell_centres(data):
    fig = drawer("plot6-7")(data, {"scenes": ["synthetic"]})
    try:
        im = fig.axes[0].get_images()[0]
        assert im.origin == "lower"
        assert im.get_extent() == pytest.approx([-0.5, N - 0.5, -0.25, 60.25])
        assert im.get_array().shape == (len(T), N)
        assert np.all(im.get_array()[:, 5] == 0.0)                         # the open bond is white
    finally:
        plt.close(fig)


def test_plot28_window_is_the_most_active_bonds_late(data):
    ex = data["synthetic"]["exact"]
    (t0, t1), (n0, n1) = spacetime.plot28_window(ex, beads=4, span=20.0)
    assert (t0, t1) == (40.0, 60.0)
    var = ex["force"].sel(t=slice(40.0, 60.0)).var("t").values
    best = max(range(N), key=lambda i: var[np.arange(i, i + 4) % N].sum())
    assert (n0, n1) == (best, (best + 3) % N)
    # a window wrapping around the periodic chain is drawn in order and labelled mod N
    fig, ax = plt.subplots()
    try:
        im = spacetime.spacetime(ax, ex, -3.0, t_range=(40.0, 60.0), n_range=(N - 2, 1))
        assert im.get_array().shape == (41, 4)
        np.testing.assert_array_equal(im.get_array()[:, 0], ex["force"].sel(t=slice(40.0, 60.0)).values[:, N - 2])
        assert ax.xaxis.get_major_formatter()(N + 1, 0) == "1"
    finally:
        plt.close(fig)


def test_common_vmin_over_both_models(data):
    sim = data["synthetic"]
    assert spacetime.common_vmin(sim["exact"], sim["dps"]) == EXACT_MIN
    assert spacetime.common_vmin(sim["dps"]) == DPS_MIN
    apart = sim["dps"].assign(force=0.0 * sim["dps"]["force"])
    assert spacetime.common_vmin(apart) < 0.0                                # all white, still valid
