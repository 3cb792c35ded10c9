"""Declarations of the config's sections: figures, and the whole file (each analysis's section is declared by
its module, the budget by cradle.pipeline.budget).

Each section is a frozen dataclass whose fields carry description, bounds and
default (:func:`cradle.specs.declare.param`); :class:`Config` is the whole file. The entries a
job computes from (defaults, map, homoclinic, scenes) are declared in :mod:`cradle.scenes.spec`.
The checks that span several keys or sections are the ``check`` methods here, in
:mod:`cradle.scenes.spec` and in :mod:`.beyond`; :func:`check` runs them all in order.
"""
from __future__ import annotations

import math

from cradle.pipeline.budget import Budget
from cradle.scenes.spec import Defaults, HomoclinicEntry, MapEntry, Scene
from cradle.specs.declare import REQUIRED, declared, param
from cradle.specs.values import TIME_TOL, did_you_mean, entries, finite, store_times

from .beyond import Beyond
from .movies import Movies

SECTIONS = ("map", "homoclinic", "scenes")  # the name spaces a figure's `scenes:` list reads from


def _known_figures() -> tuple[str, ...]:
    from cradle.figures import FIGURES

    return tuple(FIGURES)


KNOWN_FIGURES = _known_figures()


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
