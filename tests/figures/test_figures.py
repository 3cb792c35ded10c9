"""Every paper figure of sections 4.1-4.2 draws from real (small) pipeline outputs:
space-time diagrams are raster images on one colour scale for both models, spectra
are the paper's DFT of the stored displacements."""
import numpy as np
import pytest
from matplotlib.collections import QuadMesh
from matplotlib.image import AxesImage

from cradle.figures import drawer, registry, spectra
from cradle.measurements import compare
from cradle.pipeline import config as cc
from cradle.scenes import stages

TIMES = [0.0, 5.0, 10.0, 15.0, 20.0]
CFG = {
    "defaults": {"exact": {"method": "srkn6"}},
    "scenes": {
        "small": {"N": 20, "bc": "periodic",
                  "initial": {"kind": "travelling", "q": "4pi/5", "omega_tw": 1.1,
                              "noise": {"kind": "gaussian", "amplitude": 0.05, "seed": 1}},
                  "t_end": 20.0, "store": {"snapshots": TIMES, "every": 0.5}},
    },
    "figures": {},
}


@pytest.fixture(scope="module")
def sim():
    cfg = cc.validate(CFG)
    spec = cc.scene(cfg, "small")
    init = stages.initial_data(spec, "small")
    ex, ap = stages.exact_run(spec, init, "small"), stages.dps_run(spec, init, "small")
    return {"small": {"exact": ex, "dps": ap, "metrics": stages.metrics(spec, ex, ap, "small")}}


SPACETIME = {"plot6-7": [], "plot2-3": TIMES[1:3], "plot1v5st": [], "plot1v5": TIMES[2:3], "plot8-11": TIMES[:2],
             "plot9-10": [], "plot29-30": TIMES[:2], "plot26-27": [], "plot28": []}


@pytest.mark.parametrize("label, times", SPACETIME.items())
def test_spacetime_figures_are_raster_on_a_shared_scale(sim, label, times):
    fig = drawer(label)(sim, {"scenes": ["small"], "times": times})
    images = [im for ax in fig.axes for im in ax.get_images()]
    # no vector mesh outside colour bars (a 3000 x 200 pcolormesh PDF takes 44 s to write)
    assert not any(isinstance(c, QuadMesh) for ax in fig.axes if ax.get_label() != "<colorbar>"
                   for c in ax.collections)
    if images:
        assert all(isinstance(im, AxesImage) for im in images)
        lims = {im.get_clim() for im in images}
        assert len(lims) == 1                              # exact and approximate on one scale
        vmin, vmax = lims.pop()
        assert vmax == 0.0 and vmin < 0.0                  # white: beads apart; black: most negative
    assert len(fig.axes) >= 1


def test_spectra_are_the_papers_dft(sim):
    fig = spectra.draw_fft106(sim, {"scenes": ["small"], "times": TIMES})
    assert len(fig.axes) == 8
    line = fig.axes[0].get_lines()[0]
    x = sim["small"]["exact"]["x"].sel(t=TIMES[0]).values
    k, xh = compare.spatial_dft(x)
    order = np.argsort(line.get_xdata())
    assert np.allclose(np.asarray(line.get_ydata())[order], np.abs(xh)[np.argsort(k)])
    fig = spectra.draw_fftseuil({n: sim["small"] for n in "abc"}, {"scenes": list("abc"), "times": [20.0]})
    assert len(fig.axes) == 6
    fig = spectra.draw_fft344(sim, {"scenes": ["small"], "times": TIMES[2:5]})
    assert len(fig.axes) >= 5


def test_every_label_has_one_drawing_function():
    labels = set(registry())
    paper = {"traj3", "traj2", "bcsc", "plot4-5", "plotcomplin", "plot6-7", "plot2-3", "plot1v5st", "plot1v5",
             "plot8-11", "plot9-10", "plot29-30", "plot26-27", "plot28", "fft106", "fftseuil", "fft344",
             "plot18", "loc1", "fini"}
    assert paper <= labels


def test_module_lookup_by_source_agrees_with_the_imported_registry():
    """The Snakefile finds a label's module by reading sources (module_of, labels); the
    imported FIGURES dicts say the same, and a figure job imports only that module."""
    import importlib
    import subprocess
    import sys

    from cradle import figures
    from cradle.analyses.registry import ANALYSES

    reg = registry()
    assert sorted(figures.labels()) == sorted(reg)
    for label, func in reg.items():
        assert func.__module__ == f"cradle.figures.{figures.module_of(label)}"
        assert figures.drawer(label) is func
    for a in ANALYSES.values():   # a drawing, or the tables an analysis declares (the claims table)
        module = importlib.import_module(f"cradle.figures.{a.module}")
        assert callable(module.tables if a.tables else module.draw), a.name
    with pytest.raises(KeyError, match="'no-such-figure'"):
        figures.module_of("no-such-figure")
    code = ("import sys; from cradle.figures import drawer; drawer('bcsc'); "
            "print(sorted(m for m in sys.modules if m.startswith('cradle.figures.')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["['cradle.figures.homoclinic']"]


def _run(x0, v0, t0=0.0):
    import xarray as xr

    t = np.array([t0, t0 + 1.0])
    x, v = np.array([x0, x0]), np.array([v0, v0])
    return xr.Dataset({"x": (("t", "n"), x), "v": (("t", "n"), v)}, coords={"t": t}, attrs={"N": len(x0)})


def test_a_scene_outside_dps_s_measured_range_is_marked_in_its_caption():
    """The amplitude max_n sqrt(x_n^2 + v_n^2) at t = 0 against 2 eps_max of dps-validity (0.2): above it the
    caption carries a second line that says so, at or below it the caption is the one line it was; the figures
    and the run's warning (cradle.measurements.dps_range.outside_range) tell the same states outside."""
    from cradle.figures import dps_range_note, scene_caption
    from cradle.measurements.dps_range import measured_amplitude

    top = measured_amplitude()
    inside = _run([0.6 * top, 0.0, 0.0], [0.0, 0.8 * top, 0.0])        # amplitude exactly top: inside
    outside = _run([0.6 * top, 0.0, 0.0], [0.0, 0.0, 1.01 * top])
    assert dps_range_note("s", inside) == "" and "\n" not in scene_caption("s", inside)
    note = dps_range_note("s", outside)
    assert f"amplitude {1.01 * top:.3g} > {top:g}" in note and "outside DpS's measured range" in note
    assert scene_caption("s", outside).split("\n")[1] == note
    assert dps_range_note("s", _run([0.0, 0.0, 0.0], [0.0, 0.0, 2.0], t0=5.0)) == ""   # no state at t = 0
    from cradle.measurements.dps_range import outside_range

    for ds in (inside, outside):
        x0, v0 = ds["x"].values[0], ds["v"].values[0]
        assert (outside_range("s", x0, v0) is None) == (dps_range_note("s", ds) == "")


def test_a_comparison_figure_marks_a_scene_outside_dps_s_range(sim, monkeypatch):
    """The scene's amplitude a against the measured range: a range above a leaves the title as it was, one below
    a (the module's eps_max lowered) marks it."""
    from cradle.measurements.dps_range import amplitude_of
    from cradle.specs import values

    ex = sim["small"]["exact"]
    a = amplitude_of(ex["x"].values[0], ex["v"].values[0])
    for eps_max, marked in ((a, False), (0.4 * a, True)):     # the range's top 2 eps_max: 2a (inside), 0.8a
        monkeypatch.setattr(values, "DPS_EPS_MEASURED", eps_max)
        fig = drawer("plot2-3")(sim, {"scenes": ["small"], "times": TIMES[1:3]})
        assert ("outside DpS's measured range" in fig.get_suptitle()) == marked
