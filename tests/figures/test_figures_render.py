"""Every figure of `snakemake all`, rendered from the outputs themselves, is worth printing: no text
outside the figure or on other text, no legend on plotted points, no placeholder text, no tick label
with more than 4 significant digits, and every data panel holds at least the minimum of finite points
its figure module declares (``MIN_POINTS``).

Two sources, both the reduced forms `all` builds:

* in CI (a fresh clone has no results/): the analyses that read no file and compute their reduced form
  in seconds on one core, computed in-process at their declared reduced size (:data:`IN_PROCESS`), and
  the paper figures drawn from map and homoclinic entries (:data:`PAPER_IN_PROCESS`). Left out there:
  the paper figures of scenes (sixteen simulations) and the analyses that read scenes or batches
  (mi-growth, mi-statistics, paper-checks, theorem1, work-precision) or take tens of seconds (floquet);
* every figure of `all` (each paper figure of config.yaml and each analysis's ``draw`` of its reduced
  form), from the results folder ``$CRADLE_RESULTS`` or ./results when it holds them; a figure whose
  files are missing is skipped, naming the file and the command that builds it.

The three frames of the desk-toy movie that docs/analyses/desk-toy.md shows (before, during and after the first
impact) are checked the same way, from the movie's own run computed here.
"""
from __future__ import annotations

import importlib
import os
import re
from pathlib import Path

import numpy as np
import pytest

from cradle.analyses.registry import ANALYSES
from cradle.data.io import open_tree, write_netcdf
from cradle.figures import FIGURES, drawer, figure, module_of
from cradle.pipeline import config as cc, layout

ROOT = Path(__file__).resolve().parents[2]
RESULTS = Path(os.environ.get("CRADLE_RESULTS", ROOT / "results"))
CONFIG = cc.load(ROOT / "config.yaml")

#: analyses whose reduced form reads no file and computes in seconds on one core: rendered in CI
IN_PROCESS = ("breathers", "breather-interactions", "desk-toy", "desk-toy-minute", "dissipation", "dps-validity",
              "continuum-limit",
              "mi-diagram")
#: paper figures of map and homoclinic entries (each well under a second to compute): rendered in CI
PAPER_IN_PROCESS = ("traj3", "traj2", "bcsc")

#: text a finished figure never shows
PLACEHOLDER = re.compile(r"in this form|\btodo\b|placeholder|\bfixme\b|not computed|\btbd\b", re.I)
#: tolerance (pixels) of the bounding-box tests: glyph boxes include some blank margin
TOL = 1.0


# ------------------------------------------------------------------------------------------------ checks

def _texts(fig):
    """(what, artist, its axes or None) for every visible non-empty text outside legends, and every
    legend (one box)."""
    out = [("figure text", t, None) for t in fig.texts]
    for key in ("_suptitle", "_supxlabel", "_supylabel"):
        out.append((key.strip("_"), getattr(fig, key, None), None))
    for i, ax in enumerate(fig.axes):
        if not ax.get_visible():
            continue
        name = f"axes {i} ({ax.get_title() or ax.get_label() or ''})"
        for title in (ax.title, ax._left_title, ax._right_title):
            out.append((f"{name} title", title, ax))
        if ax.axison:
            out.append((f"{name} x label", ax.xaxis.label, ax))
            out.append((f"{name} y label", ax.yaxis.label, ax))
            for axis, which in ((ax.xaxis, "x"), (ax.yaxis, "y")):
                out.append((f"{name} {which} offset", axis.get_offset_text(), ax))
                for tick in axis._update_ticks():  # the ticks drawn: those inside the view
                    for lab in (tick.label1, tick.label2):
                        out.append((f"{name} {which} tick", lab, ax))
        out.extend((f"{name} text", t, ax) for t in ax.texts)
        # every legend of the panel: the last one made, and those kept with add_artist
        out.extend((f"{name} legend", leg, ax) for leg in ax.get_children() if type(leg).__name__ == "Legend")
    out.extend(("figure legend", leg, None) for leg in fig.legends)
    seen: set[int] = set()  # the suptitle is also one of fig.texts
    return [(w, a, ax) for w, a, ax in out if a is not None and a.get_visible() and id(a) not in seen
            and not seen.add(id(a)) and (not hasattr(a, "get_text") or a.get_text().strip())]


def _text_of(artist) -> str:
    if hasattr(artist, "get_texts"):  # a legend
        title = artist.get_title().get_text()
        return " | ".join([title] + [t.get_text() for t in artist.get_texts()])
    return artist.get_text()


def _overlap(a, b) -> bool:
    return (min(a.x1, b.x1) - max(a.x0, b.x0) > TOL) and (min(a.y1, b.y1) - max(a.y0, b.y0) > TOL)


def significant_digits(label: str) -> int:
    """Significant digits of a tick label's mantissa (``-1.85115x10^0`` -> 6, ``0.0025`` -> 2, ``3000`` -> 1)."""
    text = label.replace("\\mathdefault", "").replace("$", "").replace("{", "").replace("}", "")
    text = text.replace("\u2212", "-").replace("\\times", "x").replace("\u00d7", "x")
    mantissa = re.split(r"x|e(?=[-+]?\d)|\^", text)[0]
    digits = re.sub(r"[^0-9.]", "", mantissa)
    if not re.search(r"\d", digits):
        return 0
    if "." in digits:
        return len(digits.replace(".", "").lstrip("0")) or 1
    return len(digits.lstrip("0").rstrip("0")) or 1


def _data_points(ax, along_lines: bool):
    """Display coordinates of the marks of ``ax``: line vertices and scatter offsets, and with
    ``along_lines`` points every pixel along drawn line segments (reference lines such as axvline too)."""
    pts = [np.zeros((0, 2))]
    for line in ax.get_lines():
        if not line.get_visible():
            continue
        xy = np.asarray(line.get_transform().transform(np.asarray(line.get_xydata(), dtype=float).reshape(-1, 2)))
        xy = xy[np.isfinite(xy).all(axis=1)]
        if line.get_marker() not in (None, "None", "", " ") or not along_lines:
            pts.append(xy)
        if along_lines and line.get_linestyle() not in ("None", "", " ") and len(xy) > 1:
            for p, q in zip(xy[:-1], xy[1:], strict=True):
                n = int(min(np.hypot(*(q - p)), 2000)) + 2
                pts.append(p + np.linspace(0, 1, n)[:, None] * (q - p))
    for c in ax.collections:
        if c.get_visible() and hasattr(c, "get_offsets") and len(c.get_offsets()) and len(c.get_paths()) <= 1 \
                and type(c).__name__ == "PathCollection":
            xy = c.get_offset_transform().transform(np.asarray(c.get_offsets(), dtype=float).reshape(-1, 2))
            pts.append(xy[np.isfinite(xy).all(axis=1)])
    return np.concatenate(pts)


def _covered(box, pts) -> int:
    return int(((pts[:, 0] > box.x0 + TOL) & (pts[:, 0] < box.x1 - TOL)
                & (pts[:, 1] > box.y0 + TOL) & (pts[:, 1] < box.y1 - TOL)).sum())


def finite_points(ax) -> int:
    """Finite data points of ``ax``: line vertices, scatter offsets, finite image/mesh cells, bars."""
    n = 0
    for line in ax.get_lines():
        if line.get_transform().contains_branch(ax.transData):
            xy = np.asarray(line.get_xydata(), dtype=float).reshape(-1, 2)
            n += int(np.isfinite(xy).all(axis=1).sum())
    for c in ax.collections:
        arr = c.get_array() if hasattr(c, "get_array") else None
        if arr is not None and np.size(arr) > 1 and not hasattr(c, "get_offsets") or type(c).__name__ == "QuadMesh":
            n += int(np.isfinite(np.ma.filled(np.asarray(arr, dtype=float), np.nan)).sum()) if arr is not None else 0
        elif hasattr(c, "get_offsets") and len(c.get_offsets()) > 1:
            xy = np.asarray(c.get_offsets(), dtype=float).reshape(-1, 2)
            n += int(np.isfinite(xy).all(axis=1).sum())
        else:
            for p in c.get_paths():
                v = np.asarray(p.vertices, dtype=float)
                n += int(np.isfinite(v).all(axis=1).sum())
    for im in ax.get_images():
        n += int(np.isfinite(np.ma.filled(np.asarray(im.get_array(), dtype=float), np.nan)).sum())
    n += len(ax.patches)
    return n


def _marker_radius(artist, renderer) -> float:
    """Half a marker's size in pixels (0 for an artist without markers)."""
    if hasattr(artist, "get_markersize") and artist.get_marker() not in (None, "None", "", " ", ","):
        return renderer.points_to_pixels(artist.get_markersize()) / 2
    if type(artist).__name__ == "PathCollection" and len(artist.get_sizes()):
        return renderer.points_to_pixels(float(np.sqrt(np.max(artist.get_sizes())))) / 2
    return 0.0


def _marks_of(artist):
    """Display coordinates of the points ``artist`` marks (a line's vertices, a scatter's offsets), finite ones."""
    if hasattr(artist, "get_xydata"):
        xy = np.asarray(artist.get_xydata(), dtype=float).reshape(-1, 2)
        xy = artist.get_transform().transform(xy) if len(xy) else xy
    elif hasattr(artist, "get_offsets") and len(artist.get_offsets()):
        xy = artist.get_offset_transform().transform(np.asarray(artist.get_offsets(), dtype=float).reshape(-1, 2))
    else:
        return np.zeros((0, 2))
    return xy[np.isfinite(xy).all(axis=1)]


def clipped_marks(ax, renderer) -> list[str]:
    """Markers of ``ax`` that its frame cuts: centred outside the panel, or closer to an edge than their own
    radius (half a marker drawn); and error bars that leave the panel (a bar to 0 on a log axis)."""
    from matplotlib.container import ErrorbarContainer

    box, found = ax.get_window_extent(renderer), []
    for artist in [*ax.get_lines(), *ax.collections]:
        r = _marker_radius(artist, renderer)
        if not artist.get_visible() or not artist.get_clip_on() or r == 0:
            continue
        xy = _marks_of(artist)
        inside = ((xy[:, 0] > box.x0 + r - TOL) & (xy[:, 0] < box.x1 - r + TOL)
                  & (xy[:, 1] > box.y0 + r - TOL) & (xy[:, 1] < box.y1 - r + TOL))
        if len(xy) and not inside.all():
            found.append(f"{int((~inside).sum())} markers cut by the frame: axes {ax.get_title()!r} "
                         f"({artist.get_label()!r})")
    for container in ax.containers:
        if not isinstance(container, ErrorbarContainer):
            continue
        for bars in container.lines[2]:
            segments = [np.asarray(s, dtype=float).reshape(-1, 2) for s in bars.get_segments()]
            if not segments or not sum(len(s) for s in segments):
                continue
            xy = bars.get_transform().transform(np.concatenate(segments))
            out = (~np.isfinite(xy).all(axis=1) | (xy[:, 0] < box.x0 - TOL) | (xy[:, 0] > box.x1 + TOL)
                   | (xy[:, 1] < box.y0 - TOL) | (xy[:, 1] > box.y1 + TOL))
            if out.any():
                found.append(f"{int(out.sum())} error-bar ends off the panel: axes {ax.get_title()!r} "
                             f"({container.get_label()!r})")
    return found


def _drawn_in_view(artist, renderer) -> bool:
    """Whether ``artist`` (a line, a collection, a patch or a container of them) shows a finite point inside its
    panel."""
    parts = [c for c in artist if c is not None] if isinstance(artist, tuple | list) else [artist]
    if hasattr(artist, "get_children") and type(artist).__name__.endswith("Container"):
        parts = [c for c in artist.get_children() if c is not None]
    for part in parts:
        ax = getattr(part, "axes", None)
        if ax is None or not part.get_visible():
            continue
        box = ax.get_window_extent(renderer)
        if hasattr(part, "get_xydata") and part.get_linestyle() not in ("None", "", " ") \
                and len(part.get_xydata()) > 1:   # a line crossing the panel with its vertices outside
            path = part.get_transform().transform_path(part.get_path())
            if path.intersects_bbox(box, filled=False):
                return True
        if hasattr(part, "get_xydata") or hasattr(part, "get_offsets"):
            xy = _marks_of(part)
            if len(xy) and ((xy[:, 0] >= box.x0 - TOL) & (xy[:, 0] <= box.x1 + TOL)
                            & (xy[:, 1] >= box.y0 - TOL) & (xy[:, 1] <= box.y1 + TOL)).any():
                return True
            if len(xy) or hasattr(part, "get_xydata"):
                continue
        extent = part.get_window_extent(renderer)
        if extent.width > 0 and extent.height > 0 and extent.overlaps(box):
            return True
    return False


def _style(artist) -> tuple:
    """(marker, linestyle) of a legend handle or line ('' where it draws none)."""
    marker = artist.get_marker() if hasattr(artist, "get_marker") else ""
    marker = "" if marker in (None, "None", " ", "") else str(marker)
    line = artist.get_linestyle() if hasattr(artist, "get_linestyle") else ""
    return marker, "" if line in (None, "None", " ", "") else str(line)


def _empty(artist) -> bool:
    """A proxy made for a legend: a line or scatter without a single point."""
    if hasattr(artist, "get_xydata"):
        return not len(artist.get_xydata())
    return type(artist).__name__ == "PathCollection" and not len(artist.get_offsets())


def undrawn_legend_entries(fig, renderer) -> list[str]:
    """Legend entries (of a panel or of the figure) that nothing drawn stands behind: the artists carrying the
    label show no point in their panel; an entry whose handle carries no data (a key: colour or style alone) needs a
    drawn line or marker of its marker (or, without one, its line style)."""
    labelled: dict[tuple, list] = {}   # (axes or None for the whole figure, label) -> artists
    drawn_styles = set()
    for ax in fig.axes:
        for artist in [*ax.get_lines(), *ax.collections, *ax.patches, *ax.containers]:
            for owner in (ax, None):
                labelled.setdefault((owner, artist.get_label()), []).append(artist)
            if hasattr(artist, "get_xydata") and _drawn_in_view(artist, renderer):
                drawn_styles.update(_style(artist))
            elif type(artist).__name__ == "PathCollection" and _drawn_in_view(artist, renderer):
                drawn_styles.add("o")
    found = []
    legends = [leg for ax in fig.axes for leg in ax.get_children() if type(leg).__name__ == "Legend"]
    legends += list(fig.legends)
    for leg in legends:
        for handle, text in zip(leg.legend_handles, leg.get_texts(), strict=False):
            label = text.get_text()
            # a panel's legend speaks for that panel; a figure legend (or a key panel's) for the whole figure
            owner = leg.axes if leg not in fig.legends else None
            owners = [a for a in labelled.get((owner, label), []) if not _empty(a)]
            if owner is not None and not owners:
                owners = [a for a in labelled.get((None, label), []) if not _empty(a)]
            if owners:
                if not any(_drawn_in_view(a, renderer) for a in owners):
                    found.append(f"legend entry with nothing drawn: {label!r}")
                continue
            if handle is None:
                continue
            missing = [style for style in _style(handle) if style and style not in drawn_styles]
            if missing and type(handle).__name__ == "Line2D":
                found.append(f"legend key drawn nowhere ({', '.join(missing)}): {label!r}")
    return found


def problems(fig, min_points: int) -> list[str]:
    """What keeps ``fig`` from print: each problem one line."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    # the figures are drawn outside pyplot (the user's backend is left alone): render them on an Agg canvas,
    # as savefig does; the layout engine places everything on a full draw
    canvas = fig.canvas if hasattr(fig.canvas, "get_renderer") else FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    frame = fig.bbox
    found = []
    texts = [(what, a, a.get_window_extent(renderer), owner) for what, a, owner in _texts(fig)]
    panels = [(i, ax, ax.get_window_extent(renderer)) for i, ax in enumerate(fig.axes) if ax.get_visible()]
    for what, a, box, owner in texts:
        text = _text_of(a)
        if (box.x0 < frame.x0 - TOL or box.y0 < frame.y0 - TOL or box.x1 > frame.x1 + TOL
                or box.y1 > frame.y1 + TOL):
            found.append(f"outside the figure: {what} {text!r}")
        if PLACEHOLDER.search(text):
            found.append(f"placeholder: {what} {text!r}")
        if what.endswith("tick") and significant_digits(text) > 4:
            found.append(f"more than 4 significant digits: {what} {text!r}")
        for j, ax, panel in panels:  # the plotting area of another panel (a colour bar, ...)
            if ax is not owner and _overlap(box, panel):
                found.append(f"on the area of axes {j} ({ax.get_title() or ax.get_label()!r}): {what} {text!r}")
    for i, (w1, a1, b1, _) in enumerate(texts):
        for w2, a2, b2, _ in texts[i + 1:]:
            if _overlap(b1, b2):
                found.append(f"overlap: {w1} {_text_of(a1)!r} and {w2} {_text_of(a2)!r}")
    for i, ax in enumerate(fig.axes):
        if ax.get_visible():
            tight = ax.get_tightbbox(renderer)
            if tight is not None and (tight.x0 < frame.x0 - TOL or tight.y0 < frame.y0 - TOL
                                      or tight.x1 > frame.x1 + TOL or tight.y1 > frame.y1 + TOL):
                found.append(f"outside the figure: axes {i} ({ax.get_title()!r}) or what it draws")
            found.extend(clipped_marks(ax, renderer))
    found.extend(undrawn_legend_entries(fig, renderer))
    for i, ax in enumerate(fig.axes):
        leg = ax.get_legend()
        if leg is not None and leg.get_visible():
            n = _covered(leg.get_window_extent(renderer), _data_points(ax, along_lines=True))
            if n:
                found.append(f"legend covers {n} plotted points: axes {i} ({ax.get_title()!r})")
        marks = _data_points(ax, along_lines=False)
        for t in ax.texts:  # a note inside the panel hides what it covers as a legend would
            n = _covered(t.get_window_extent(renderer), marks) if t.get_visible() and t.get_text() else 0
            if n:
                found.append(f"text covers {n} plotted points: axes {i} {t.get_text()!r}")
        if ax.get_label() == "<colorbar>" or not ax.get_visible():
            continue
        if ax.axison and finite_points(ax) < min_points:
            found.append(f"axes {i} ({ax.get_title()!r}): {finite_points(ax)} finite points < {min_points}")
    return found


def min_points(module: str, label: str) -> int:
    """The minimum of finite points per data panel declared beside the figure (``MIN_POINTS`` of its
    module: a number, or label -> number)."""
    declared = importlib.import_module(f"cradle.figures.{module}").MIN_POINTS
    return declared[label] if isinstance(declared, dict) else declared


def test_the_checks_catch_what_they_look_for():
    fig, ax = figure(1, 2, width=4, height=3)
    x = np.linspace(0, 1, 50)
    ax[0].plot(x, x, "o", label="a long legend entry covering the points")
    ax[0].legend(loc="center")
    ax[0].set_yticks([0.5, 0.9], labels=["0.5", "$-1.85115\\times10^{0}$"])
    ax[0].set_title("a title far too long for its panel, running into the next one and beyond the edge")
    ax[1].text(0.5, 0.5, "no kicked runs in this form")
    found = "\n".join(problems(fig, min_points=5))
    for what in ("outside the figure", "overlap", "legend covers", "placeholder", "significant digits",
                 "finite points < 5"):
        assert what in found, what
    assert significant_digits("$\\mathdefault{-1.85115\\times10^{0}}$") == 6
    assert significant_digits("\u22120.0025") == 2 and significant_digits("3000") == 1
    fig, ax = figure()
    ax.plot(x, x**2, "o-", label="x^2")
    ax.legend(loc="upper left")
    ax.set_title("fine")
    assert problems(fig, min_points=50) == []


# ------------------------------------------------------------------------------------------------ sources

def _paper_cases():
    return [pytest.param(label, id=label) for label in CONFIG["figures"]]


def _analysis_cases():
    return [pytest.param(name, id=name) for name, a in ANALYSES.items() if not a.tables]


def _load_paper(label, root):
    scenes = {}
    for name in CONFIG["figures"][label]["scenes"]:
        scenes[name] = next(s for s in ("map", "homoclinic", "scenes") if name in CONFIG.get(s, {}))
    for name, kind in scenes.items():
        paths = ([layout.path(kind, root, name=name)] if kind in ("map", "homoclinic")
                 else layout.scene_paths(name, root, layout.RUN_PARTS).values())
        for p in paths:
            if not Path(p).exists():
                pytest.skip(f"{p} missing: `snakemake -j2 all` builds it")
    from cradle.pipeline.outputs import load_inputs
    return load_inputs(scenes, root)


def _analysis_note(a) -> str:
    form = a.forms[0]
    return f"reduced form: `snakemake -j2 {a.target}_full` builds the full one" if form != "full" else ""


def _draw_analysis(name, tree):
    a = ANALYSES[name]
    fig = importlib.import_module(f"cradle.figures.{a.module}").draw(tree)
    note = _analysis_note(a)
    if note:  # as cradle.figures.draw_analysis places it
        fig.supxlabel(note, x=0.998, ha="right", fontsize=6, color="0.4")
    return fig


def _check(fig, module, label):
    found = problems(fig, min_points(module, label))
    assert not found, f"{label}:\n  " + "\n  ".join(found)


@pytest.fixture(scope="session")
def in_process(tmp_path_factory):
    """The reduced forms of :data:`IN_PROCESS` and the map and homoclinic entries of
    :data:`PAPER_IN_PROCESS`, computed here and written as `all` writes them."""
    from cradle.scenes import stages

    root = tmp_path_factory.mktemp("results")
    for name in IN_PROCESS:
        a = ANALYSES[name]
        spec = cc.analysis_spec(CONFIG, name, a.forms[0])
        write_netcdf(a.compute(spec, {}, log=lambda *args: None),
                     layout.analysis_output(name, a.forms[0], a.forms[0], root))
    for label in PAPER_IN_PROCESS:
        for name in CONFIG["figures"][label]["scenes"]:
            if name in CONFIG.get("map", {}):
                write_netcdf(stages.map_orbits(cc.map_entry(CONFIG, name), name), layout.path("map", root, name=name))
            else:
                write_netcdf(stages.homoclinic_solution(cc.homoclinic(CONFIG, name), name),
                             layout.path("homoclinic", root, name=name))
    return root


@pytest.mark.slow
@pytest.mark.parametrize("name", IN_PROCESS)
def test_analysis_figure_of_its_reduced_form_computed_here(in_process, name):
    a = ANALYSES[name]
    tree = open_tree(layout.analysis_output(name, a.forms[0], a.forms[0], in_process))
    _check(_draw_analysis(name, tree), a.module, name)


@pytest.mark.slow
@pytest.mark.parametrize("label", PAPER_IN_PROCESS)
def test_paper_figure_of_entries_computed_here(in_process, label):
    _check(drawer(label)(_load_paper(label, in_process), CONFIG["figures"][label]), module_of(label), label)


@pytest.mark.slow
@pytest.mark.parametrize("label", _paper_cases())
def test_paper_figure_from_the_results(label):
    data = _load_paper(label, RESULTS)
    _check(drawer(label)(data, CONFIG["figures"][label]), module_of(label), label)


@pytest.mark.slow
@pytest.mark.parametrize("name", _analysis_cases())
def test_analysis_figure_from_the_results(name):
    a = ANALYSES[name]
    path = Path(layout.analysis_output(name, a.forms[0], a.forms[0], RESULTS))
    if not path.exists():
        pytest.skip(f"{path} missing: `snakemake -j2 {a.target}` builds it")
    _check(_draw_analysis(name, open_tree(path)), a.module, name)


def test_every_figure_of_all_is_covered():
    """Each paper figure and each analysis figure has its declared minimum (and so a case above)."""
    for label in CONFIG["figures"]:
        assert min_points(module_of(label), label) >= 1, label
    for a in ANALYSES.values():
        if not a.tables:
            assert min_points(a.module, a.name) >= 1, a.name
    assert set(FIGURES) >= set(CONFIG["figures"])


@pytest.fixture(scope="module")
def desk_toy_movie_run():
    """The desk-toy movie's run of the desk toy of `all`'s config (5 balls, 1 lifted) over one swing."""
    from cradle.analyses.desk_toy_movie import SlowMotion, movie_run

    spec = cc.analysis_spec(CONFIG, "desk-toy", ANALYSES["desk-toy"].forms[0])
    movies = CONFIG["movies"]
    return movie_run(spec, 5, 1, SlowMotion(**{**movies["desk_toy"], "swings": 1}), movies["fps"])


@pytest.mark.slow
@pytest.mark.parametrize("frame", ["before", "during", "after"])
def test_desk_toy_movie_frames_at_an_impact(desk_toy_movie_run, frame):
    """The frames of the desk-toy movie (cradle.figures.desk_toy_movie) that docs/analyses/desk-toy.md shows pass
    the checks above."""
    from cradle.figures.desk_toy_movie import STILL_LEAD, MovieFigure, impact_frames

    ds, movies = desk_toy_movie_run, CONFIG["movies"]
    mf = MovieFigure(ds, movies["width"], movies["height"])
    mf.show(impact_frames(ds, lead=STILL_LEAD)[frame])
    found = problems(mf.fig, min_points=1)
    assert not found, f"desk-toy movie, {frame}:\n  " + "\n  ".join(found)
