"""Figures fft106, fftseuil, fft344 (section 4.2) on small synthetic datasets in the pipeline's
shapes, and the sideband-to-carrier ratio they print."""
import matplotlib.pyplot as plt
import numpy as np
import pytest

from cradle.data.io import make_dataset
from cradle.figures import spectra
from cradle.measurements import compare, sidebands
from cradle.scenes import stages

N = 40                                   # q N / (2 pi) = 16 for q = 4 pi/5: q on Gamma*
Q = 4 * np.pi / 5
TIMES = [0.0, 1.5, 3.0, 4.5, 6.0]


# --------------------------------------------------------------------------- sideband_ratio

def _carrier(N, q, amp=1.0):
    return amp * np.cos(q * np.arange(N))


def _ratio(x, q, **kw):
    k, xh = compare.spatial_dft(x)
    return float(sidebands.sideband_ratio(k, np.abs(xh), q, **kw))


def test_pure_carrier_has_no_sideband():
    for N, q in ((200, 4 * np.pi / 5), (200, 57 * np.pi / 100), (200, np.pi / 2), (40, Q)):
        assert _ratio(_carrier(N, q, 0.3), q) < 1e-12


@pytest.mark.parametrize("offset_bins, h", [(10, 0.25), (-7, 0.6), (4, 0.01)])
def test_carrier_plus_sideband_gives_its_relative_height(offset_bins, h):
    N, q = 200, 4 * np.pi / 5
    n = np.arange(N)
    p = q + 2 * np.pi * offset_bins / N
    x = 0.7 * np.cos(q * n) + h * 0.7 * np.cos(p * n + 0.3)
    assert _ratio(x, q) == pytest.approx(h, rel=1e-9)


def test_window_around_carrier_and_wrap_at_pi():
    N, q = 200, 4 * np.pi / 5
    n = np.arange(N)
    x = np.cos(q * n) + 0.5 * np.cos((q + 3 * 2 * np.pi / N) * n)      # 3 bins away: inside the window
    assert _ratio(x, q) < 1e-12
    assert _ratio(x, q, exclude_bins=2) == pytest.approx(0.5, rel=1e-9)
    # q = pi - 2 bins: its window wraps round k = pi onto -pi + bins
    q2 = np.pi - 2 * 2 * np.pi / N
    x = np.cos(q2 * n) + 0.4 * np.cos((-np.pi + 2 * np.pi / N) * n)      # 3 bins from q2 across pi
    assert _ratio(x, q2) < 1e-12


def test_harmonics_are_left_out_only_when_asked():
    from cradle.measurements.sidebands import harmonics
    N, q = 200, 57 * np.pi / 100                # fft344: 2(q - pi) = -0.86 pi, 3q - 2pi = -0.29 pi
    n = np.arange(N)
    second, third = 2 * (q - np.pi), 3 * q - 2 * np.pi
    x = np.cos(q * n) + 0.2 * np.cos(second * n) + 0.1 * np.cos(third * n)
    assert _ratio(x, q) < 1e-12
    assert _ratio(x, q, exclude_harmonics=False) == pytest.approx(0.2, rel=1e-9)
    h = harmonics(q)
    assert sorted(h["2(q-pi)"]) == pytest.approx(sorted([second, -second]))
    assert sorted(h["3q-2pi"]) == pytest.approx(sorted([third, -third]))
    # q = 4 pi/5 (fft106): both harmonics fall on k = +-2 pi/5; q = pi/2: 2(q - pi) = pi, 3q - 2pi = -q
    h = harmonics(4 * np.pi / 5)
    assert sorted(h["2(q-pi)"]) == pytest.approx([-0.4 * np.pi, 0.4 * np.pi])
    assert sorted(h["3q-2pi"]) == pytest.approx([-0.4 * np.pi, 0.4 * np.pi])
    h = harmonics(np.pi / 2)
    assert np.pi in h["2(q-pi)"] and sorted(h["3q-2pi"]) == pytest.approx([-np.pi / 2, np.pi / 2])


def test_ratio_is_vectorised_over_time_and_rejects_other_grids():
    N, q = 200, 4 * np.pi / 5
    n = np.arange(N)
    x = np.stack([np.cos(q * n), np.cos(q * n) + 0.3 * np.cos((q - 0.5) * n)])
    # q - 0.5 is not on Gamma*: its leakage still tops out below 0.3 outside the window
    k, xh = compare.spatial_dft(x)
    r = sidebands.sideband_ratio(k, np.abs(xh), q)
    assert r.shape == (2,) and r[0] < 1e-12 and 0.1 < r[1] < 0.3
    with pytest.raises(ValueError, match="Gamma"):
        sidebands.sideband_ratio(np.linspace(-3, 3, N), np.abs(xh), q)


# --------------------------------------------------------------------------- drawing

def _scene(q=Q, q_expr="4pi/5", seed=0):
    """exact.nc, dps.nc, metrics.nc of one scene, as the pipeline writes them (dims (t, n), (t, k))."""
    rng = np.random.default_rng(seed)
    t, n = np.array(TIMES), np.arange(N)
    a = 0.01
    base = a * np.cos(q * n[None, :] - 1.1 * t[:, None])
    ex = base + 1e-3 * rng.standard_normal((t.size, N))
    ap = base + 1e-3 * rng.standard_normal((t.size, N))
    attrs = {"q": q, "q_expr": q_expr, "a": a, "N": N, "bc": "periodic", "initial_kind": "travelling"}
    exact = make_dataset({"x": ex}, coords={"t": t, "n": n}, attrs=attrs)
    dps = make_dataset({"x": ap}, coords={"t": t, "n": n}, attrs=attrs)
    return {"exact": exact, "dps": dps, "metrics": stages.metrics(None, exact, dps, "s")}


def _curve(ax):
    (line,) = [ln for ln in ax.get_lines() if len(ln.get_xdata()) > 2]      # not the k = +-q markers
    return np.asarray(line.get_xdata()), np.asarray(line.get_ydata())


def _assert_is_dft(ax, ds, t):
    k_plot, y = _curve(ax)
    k, xh = compare.spatial_dft(ds["x"].sel(t=t).values)
    assert np.allclose(k_plot, k) and np.allclose(y, np.abs(xh), rtol=1e-12, atol=0)


def test_fft106_panels_are_the_dft_at_the_right_times():
    sim = _scene()
    fig = spectra.draw_fft106({"s": sim}, {"scenes": ["s"], "times": TIMES})
    assert len(fig.axes) == 8
    axes = np.array(fig.axes).reshape(4, 2)
    for row in range(4):
        _assert_is_dft(axes[row, 0], sim["exact"], TIMES[row])
        _assert_is_dft(axes[row, 1], sim["dps"], TIMES[row] if row < 3 else TIMES[4])
        assert axes[row, 0].get_ylim() == axes[row, 1].get_ylim()        # one linear scale per row
        assert axes[row, 0].get_yscale() == "linear"
    assert axes[0, 0].get_xlabel() == "$k$" and axes[0, 0].get_ylabel() == r"$|\hat{x}_k(t)|$"
    # k = +-q marked
    marks = [ln.get_xdata()[0] for ln in axes[0, 0].get_lines() if len(ln.get_xdata()) == 2]
    assert sorted(marks) == pytest.approx([-Q, Q])
    plt.close(fig)


def test_fftseuil_one_row_per_scene():
    qs = {"a": (52 * np.pi / 100, "52pi/100"), "b": (51 * np.pi / 100, "51pi/100"), "c": (np.pi / 2, "pi/2")}
    # N = 40 puts none of these q on Gamma*: the figure only needs the data's own DFT
    data = {name: _scene(q, expr, seed=i) for i, (name, (q, expr)) in enumerate(qs.items())}
    fig = spectra.draw_fftseuil(data, {"scenes": list(qs), "times": [TIMES[-1]]})
    assert len(fig.axes) == 6
    axes = np.array(fig.axes).reshape(3, 2)
    for row, name in enumerate(qs):
        _assert_is_dft(axes[row, 0], data[name]["exact"], TIMES[-1])
        _assert_is_dft(axes[row, 1], data[name]["dps"], TIMES[-1])
        assert qs[name][1].replace("pi", r"\pi") in axes[row, 0].get_title()
    plt.close(fig)


def test_fft344_spectra_and_profiles():
    sim = _scene()
    t_spec, t1, t2 = TIMES[2:5]
    fig = spectra.draw_fft344({"s": sim}, {"scenes": ["s"], "times": [t_spec, t1, t2]})
    assert len(fig.axes) == 5
    se, sa, x1, x2, xa = fig.axes
    _assert_is_dft(se, sim["exact"], t_spec)
    _assert_is_dft(sa, sim["dps"], t_spec)
    for ax, model, t in ((x1, "exact", t1), (x2, "exact", t2), (xa, "dps", t2)):
        n, x = _curve(ax)
        assert np.array_equal(n, np.arange(N)) and np.array_equal(x, sim[model]["x"].sel(t=t).values)
        assert ax.get_xlabel() == "$n$" and ax.get_ylabel() == "$x_n(t)$"
    plt.close(fig)


def test_metrics_without_the_sideband_peaks_and_missing_times_are_errors():
    sim = _scene()
    stale = sim["metrics"].drop_vars(["sideband_ratio_dps", "sideband_k_dps"])
    with pytest.raises(ValueError, match="rebuild the metrics"):
        spectra.draw_fft106({"s": {**sim, "metrics": stale}}, {"scenes": ["s"], "times": TIMES})
    with pytest.raises(ValueError, match="not stored"):
        spectra.draw_fft344({"s": sim}, {"scenes": ["s"], "times": [1.0, 3.0, 6.0]})
    plt.close("all")


def test_printed_ratios_and_shares_are_the_stored_measurements():
    """The metrics stage stores, per stored time, what the panels print: sideband_peak of the DFT
    of each model and the carrier share of each profile."""
    sim = _scene()
    m, q = sim["metrics"], Q
    for model in ("exact", "dps"):
        k, xh = compare.spatial_dft(sim[model]["x"].values)
        ratio, k_peak = sidebands.sideband_peak(k, np.abs(xh), q)
        assert np.array_equal(m[f"sideband_ratio_{model}"].values, ratio)
        assert np.array_equal(m[f"sideband_k_{model}"].values, k_peak, equal_nan=True)
        for i, x in enumerate(sim[model]["x"].values):
            assert m[f"carrier_share_{model}"].values[i] == pytest.approx(sidebands.carrier_share(x, q), rel=1e-14)
    t = TIMES[3]
    fig = spectra.draw_fft344({"s": sim}, {"scenes": ["s"], "times": [t, TIMES[1], TIMES[2]]})
    r = float(m["sideband_ratio_exact"].sel(t=t))
    assert f"$r = {r:.3g}$" in fig.axes[0].get_title()
    share = float(m["carrier_share_dps"].sel(t=TIMES[2]))
    assert f"carrier share of power {share:.2f}" in fig.axes[4].get_title()
    plt.close(fig)


def test_carrier_share_of_a_profile():
    N, q = 200, 57 * np.pi / 100
    n = np.arange(N)
    assert sidebands.carrier_share(0.02 * np.cos(q * n - 0.7), q) == pytest.approx(1.0, abs=1e-12)
    # carrier a, one sideband of amplitude a/2: share = 1 / (1 + 1/4)
    x = np.cos(q * n) + 0.5 * np.cos((q + 2 * np.pi * 10 / N) * n)
    assert sidebands.carrier_share(x, q) == pytest.approx(0.8, rel=1e-12)
