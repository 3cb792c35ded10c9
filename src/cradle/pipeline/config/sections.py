"""Declarations of the config's sections: defaults, map, homoclinic, scenes, figures, beyond.

Each section is a frozen dataclass whose fields carry description, bounds and
default (:func:`.spec.param`); :class:`Config` is the whole file. The checks
that span several keys or sections are the ``check`` methods here and in
:mod:`.scenes` / :mod:`.beyond`; :func:`check` runs them all in order.
"""
from __future__ import annotations

import math
from dataclasses import fields

from .beyond import Beyond
from .movies import Movies
from cradle.scenes.spec import DpsIntegrator, ExactIntegrator, Scene
from cradle.specs.declare import REQUIRED, declared, param
from cradle.specs.values import TIME_TOL, did_you_mean, entries, finite, number, show, store_times

SECTIONS = ("map", "homoclinic", "scenes")  # the name spaces a figure's `scenes:` list reads from


def _known_figures() -> tuple[str, ...]:
    from cradle.figures import DATASET_FIGURES, FIGURES

    return (*FIGURES, *DATASET_FIGURES)


KNOWN_FIGURES = _known_figures()


@declared(doc="Settings every scene, homoclinic and map entry inherits unless it overrides them.")
class Defaults:
    alpha: float = param(1.5, "Hertz exponent in V0(x) = |x|^(1+alpha) H(-x)/(1+alpha) (vhertz); > 1.", ref="alpha")
    exact: ExactIntegrator = param(ExactIntegrator(), "Integrator of the lattice (nc) used by every scene that does "
                                   "not override it.",
                                   fill={"method": "Default lattice integrator.",
                                         "dt_factor": "Default splitting step factor (null = the method's default).",
                                         "rtol": "Default relative tolerance of the adaptive (scipy) methods."})
    dps: DpsIntegrator = param(DpsIntegrator(), "Integrator of the DpS equation (dfnls) used by every scene that "
                               "does not override it.",
                               fill={"method": "Default DpS integrator.",
                                     "rtol": "Default relative tolerance; atol = rtol * max |A_n(0)|."})
    max_energy_drift: float = param(1e-6, "An exact run whose max_t |H(t)-H(0)|/H(0) exceeds this fails.",
                                    ref="maxEnergyDrift")


_POINT = {"type": "number"}


@declared(doc="`count` starting points equally spaced on the segment from `from` to `to` (both ends included); "
              "added after `starts`.")
class MapLine:
    from_: list[float] = param(REQUIRED, "First point [a_0, b_1] of the segment.", key="from", minItems=2, maxItems=2,
                               items=_POINT)
    to: list[float] = param(REQUIRED, "Last point [a_0, b_1] of the segment.", minItems=2, maxItems=2, items=_POINT)
    count: int = param(REQUIRED, "Number of starting points on the segment; integer >= 2.", minimum=2, maximum=1000)


@declared("mapEntry", doc="Orbits of the map G (comp1)-(comp2).", any_of=[("starts",), ("line",)])
class MapEntry:
    box: float = param(REQUIRED, "Orbits are dropped after they leave ||U||_inf <= box; > 0.", exclusiveMinimum=0)
    iterations: int = param(REQUIRED, "How many times G is applied; integer >= 1.", minimum=1)
    marks: bool = param(False, "Mark the explicit period-2, -3 and -4 orbits of the traj2 caption in this panel.")
    starts: list[list[float]] = param(None, "Starting points U_0 = (a_0, b_1), one pair [a_0, b_1] per orbit.",
                                      minItems=1, items={"description": "A starting point [a_0, b_1].",
                                                         "type": "array", "minItems": 2, "maxItems": 2,
                                                         "items": _POINT})
    alpha: float = param(None, "Per-entry Hertz exponent; default defaults.alpha.", ref="alpha")
    line: MapLine = param(None, "`count` starting points equally spaced on the segment from `from` to `to` (both "
                          "ends included); added after `starts`.")

    @staticmethod
    def check(name: str, entry: dict, out) -> None:
        """Every starting point inside the box ||U||_inf <= box."""
        box, starts = entry.get("box"), entry.get("starts")
        points = [(["map", name, "starts", i], u) for i, u in enumerate(starts if isinstance(starts, list) else [])]
        line = entry.get("line")
        if isinstance(line, dict):
            points += [(["map", name, "line", end], line.get(end)) for end in ("from", "to")]
        if number(box):
            for key, u in points:
                if isinstance(u, list) and u and all(number(x) for x in u) and max(abs(x) for x in u) > box:
                    out.add(key, f"must lie in the box ||U||_inf <= box = {show(box)}", u)


@declared("homoclinicEntry", doc="A homoclinic solution of (dpsstn) found by Powell's hybrid method from an initial "
                                 "guess.")
class HomoclinicEntry:
    guess: str = param(REQUIRED, "Initial guess: site (a_{N/2} = -amplitude), bond (a_{N/2} = amplitude, "
                       "a_{N/2+1} = -amplitude) or double (two site humps `separation` sites apart).",
                       enum=["site", "bond", "double"])
    N: int = param(REQUIRED, "Number of sites; >= 2.", ref="N")
    bc: str = param("periodic", "Boundary conditions (periodic | free).", ref="bc")
    amplitude: float = param(0.1, "Amplitude of the initial guess; > 0.", exclusiveMinimum=0)
    separation: int = param(9, "Distance in sites between the two humps of the double guess; integer >= 1 (< N).",
                            minimum=1)
    alpha: float = param(None, "Per-entry Hertz exponent; default defaults.alpha.", ref="alpha")
    mu: float = param(1.0, "mu of (dpsst); the solution is mu^(1/(alpha-1)) times the mu = 1 one; > 0.",
                      exclusiveMinimum=0)
    centre: int = param(None, "Site the guess is centred on (0 <= centre < N); default N // 2.", minimum=0)

    @staticmethod
    def check(name: str, entry: dict, out) -> None:
        """The centre a site of the chain, the two humps of a double guess distinct."""
        path, N = ["homoclinic", name], entry.get("N")
        c = entry.get("centre")
        if number(c) and isinstance(N, int) and not 0 <= c < N:
            out.add(path + ["centre"], f"must be a site index in [0, N-1] = [0, {N - 1}]", c)
        sep = entry.get("separation")
        if entry.get("guess") == "double" and number(sep) and isinstance(N, int) and not 1 <= sep < N:
            out.add(path + ["separation"], f"must be in [1, N-1] = [1, {N - 1}]", sep)


@declared("figure", doc="What one figure reads.")
class Figure:
    scenes: list[str] = param(REQUIRED, "Names of the map, homoclinic or scene entries the figure reads.", minItems=1,
                              uniqueItems=True, items={"$ref": "#/$defs/name"})
    times: list[float] = param(None, "Times shown by the panels; each >= 0 and stored by one of the figure's scenes.",
                               items={"type": "number", "minimum": 0})

    @staticmethod
    def check(label: str, fig: dict, cfg: dict, names: dict, out) -> None:
        """A known label, names of existing entries, and times stored by the scenes it reads."""
        if label not in KNOWN_FIGURES:
            out.add(["figures", label], f"unknown figure label {label!r} (known labels: {', '.join(KNOWN_FIGURES)})")
        if not isinstance(fig, dict) or not isinstance(fig.get("scenes"), list):
            return
        scenes = entries(cfg, "scenes")
        for i, n in enumerate(fig["scenes"]):
            if isinstance(n, str) and n not in names:
                out.add(["figures", label, "scenes", i], f"unknown scene: no map, homoclinic or scene entry of "
                                                         f"that name{did_you_mean(n, names)}", n)
        read = [n for n in fig["scenes"] if isinstance(n, str) and n in scenes]
        times = fig.get("times")
        if not read or not isinstance(times, list):
            return
        stored = []
        for n in read:
            s = scenes[n]
            if not (isinstance(s.get("store"), dict) and finite(s.get("t_end")) and s["t_end"] > 0
                    and not out.has(["scenes", n, "store", "every"])):
                return
            try:
                stored += store_times(s["store"], s["t_end"])
            except (TypeError, ValueError):
                return
        import numpy as np

        stored = np.asarray(stored)
        for i, t in enumerate(times):
            if finite(t) and not np.any(np.abs(stored - t) <= TIME_TOL):
                out.add(["figures", label, "times", i], f"not a stored time of {', '.join(read)} "
                                                        f"(add it to a store.snapshots list)", t)


@declared(doc="Limits every job must fit, checked on estimates before any work starts (cradle.pipeline.budget); "
              "raise them on a bigger machine.")
class Budget:
    """Limits every job must fit (config key ``budget:``); the defaults fit a 2-core, 24 GB machine
    running two jobs side by side."""

    memory_gb: float = param(8.0, "Peak memory one job may use (GB); two jobs run side by side on two cores.",
                             exclusiveMinimum=0)
    disk_gb: float = param(20.0, "Bytes one job may write, and all scenes together (GB).", exclusiveMinimum=0)
    hours: float = param(12.0, "Wall time one job may take (hours), estimated from its steps and beads.",
                         exclusiveMinimum=0)

    @classmethod
    def from_config(cls, cfg: dict) -> "Budget":
        """The budget of a validated config: its ``budget:`` values over the defaults."""
        given = (cfg or {}).get("budget") or {}
        return cls(**{f.name: float(given[f.name]) for f in fields(cls) if given.get(f.name) is not None})


@declared(doc="The experiments of G. James, 'Nonlinear waves in Newton's cradle and the discrete p-Schrodinger "
              "equation': integrator defaults, orbits of the map G, homoclinic solutions of (dpsstn), lattice + DpS "
              "runs (scenes) and the figures that read them. Checked after this schema by "
              "cradle.pipeline.config.validate (physical checks).")
class Config:
    defaults: Defaults = param(Defaults(), "Settings every scene, homoclinic and map entry inherits unless it "
                               "overrides them.")
    map: dict[str, MapEntry] = param({}, "Orbits of the map G (comp1)-(comp2), by entry name (figures traj3, traj2).")
    homoclinic: dict[str, HomoclinicEntry] = param({}, "Solutions of the stationary DpS equation (dpsstn) found by "
                                                   "Powell's hybrid method, by entry name (figure bcsc, breathers).")
    scenes: dict[str, Scene] = param({}, "Lattice (nc) + DpS (dfnls) runs from one initial condition, by scene name.")
    figures: dict[str, Figure] = param({}, "Figures by label (the paper's and the project's): the map/homoclinic/scene "
                                       "entries each reads and the times its panels show.",
                                       propertyNames={"description": "A known figure label.",
                                                      "enum": list(KNOWN_FIGURES)})
    beyond: Beyond = param(Beyond(), Beyond.__schema_doc__)
    budget: Budget = param(Budget(), Budget.__schema_doc__)
    movies: Movies = param(Movies(), Movies.__schema_doc__)


def check_finite(node, out, path=()) -> None:
    """Every float of the config finite: an inf or nan anywhere is one line, at its key (run before the
    schema, whose bounds would otherwise word it as out of range)."""
    path = list(path)
    if isinstance(node, dict):
        for k, v in node.items():
            check_finite(v, out, path + [k])
    elif isinstance(node, list):
        for i, v in enumerate(node):
            check_finite(v, out, path + [i])
    elif isinstance(node, float) and not math.isfinite(node):
        out.add(path, "must be a finite number", node)


def check(cfg: dict, out) -> None:
    """The checks the schema cannot express, section by section (``cfg`` has the schema defaults)."""
    names: dict[str, str] = {}   # unique across the sections a figure reads from
    for section in SECTIONS:
        sec = cfg.get(section)
        for name in sec if isinstance(sec, dict) else ():
            if name in names:
                out.add([section, name], f"name {name!r} is also used by {names[name]}.{name} (map, homoclinic "
                                         f"and scenes names must be unique)")
            else:
                names[name] = section
    for name, entry in entries(cfg, "map").items():
        MapEntry.check(name, entry, out)
    for name, entry in entries(cfg, "homoclinic").items():
        HomoclinicEntry.check(name, entry, out)
    for name, scene in entries(cfg, "scenes").items():
        Scene.check(name, scene, cfg, out)
    Beyond.check(cfg.get("beyond"), cfg, out)
    figures = cfg.get("figures")
    for label, fig in (figures.items() if isinstance(figures, dict) else ()):
        Figure.check(label, fig, cfg, names, out)
