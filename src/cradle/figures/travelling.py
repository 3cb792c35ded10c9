"""Figures plot4-5 and plotcomplin: travelling waves q = pi/5, omega_tw = 1.01 (section 4.1)."""
from __future__ import annotations

from typing import TYPE_CHECKING

from cradle.figures import figure, legend_outside, scene_caption
from cradle.figures.spacetime import _at, _profiles

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: finite points each data panel holds at least (tests/figures/test_figures_render.py): a profile of N beads
MIN_POINTS = {"plot4-5": 20, "plotcomplin": 20}


def draw_plot4_5(data: dict, options: dict) -> Figure:
    """Left: exact and approximate profiles at t = 621.95; right: E(t) = ||x^tw - x||_inf / a."""
    (name,) = options["scenes"]
    sim = data[name]
    fig, (left, right) = figure(1, 2, width=9.0, height=3.6)
    _profiles(left, sim, options["times"][0])
    legend_outside(left)
    fig.suptitle(scene_caption(name, sim["exact"]), fontsize=9)
    m = sim["metrics"]
    right.plot(m["t"].values, m["E"].values, lw=0.6, color="k")
    right.set_xlabel("$t$")
    right.set_ylabel("$E(t)$")
    right.set_title(f"max E = {float(m['E'].max()):.3f}, E(t_end) = {float(m['E'][-1]):.3f}", fontsize=9)
    right.set_xlim(0, float(m["t"][-1]))
    return fig


def draw_plotcomplin(data: dict, options: dict) -> Figure:
    """Left: the plot4-5 experiment with noise (perturb); right: exact, approximate and
    linear wave a cos(q n - t) at t0 = 333.7."""
    noisy, clean = options["scenes"]
    t_noisy, t0 = options["times"]
    fig, (left, right) = figure(1, 2, width=9.0, height=3.8)
    _profiles(left, data[noisy], t_noisy, title="with noise, ")
    legend_outside(left)
    fig.suptitle(scene_caption(noisy, data[noisy]["exact"]) + "\n" + scene_caption(clean, data[clean]["exact"]),
                 fontsize=9)
    sim = data[clean]
    _profiles(right, sim, t0)
    m = sim["metrics"]
    if "x_linear" not in m:
        raise ValueError(f"scene '{clean}': no x_linear in its metrics file: rebuild the metrics")
    lin = _at(m, t0)["x_linear"]          # stored at every t: the time of the exact profile shown
    right.plot(lin["n"].values, lin.values, "--", color="C0", lw=1.0, label="linear wave")
    legend_outside(right)
    return fig
