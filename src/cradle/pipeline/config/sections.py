"""Declarations of figures, ``beyond:`` (one key per analysis, declared by its module) and the whole file."""
from __future__ import annotations

import bisect
from typing import Any

from cradle.figures import FIGURES
from cradle.pipeline.budget import Budget
from cradle.scenes.spec import ENTRY_SECTIONS, Context, Defaults, HomoclinicEntry, MapEntry, Scene, Where
from cradle.specs.declare import REQUIRED, declared, param, schema_doc
from cradle.specs.values import TIME_TOL, Errors, did_you_mean

from .movies import Movies

SECTIONS = ENTRY_SECTIONS  # the name spaces a figure's `scenes:` list reads from
KNOWN_FIGURES = tuple(FIGURES)


def _holds(times: tuple[float, ...], t: float) -> bool:
    """Whether the sorted stored ``times`` hold ``t`` (to TIME_TOL)."""
    i = bisect.bisect_left(times, t - TIME_TOL)
    return i < len(times) and times[i] <= t + TIME_TOL


@declared("figure", doc="What one figure reads.")
class Figure:
    scenes: list[str] = param(REQUIRED, "Names of the map, homoclinic or scene entries the figure reads.", minItems=1,
                              uniqueItems=True, items={"$ref": "#/$defs/name"})
    times: list[float] = param(None, "Times shown by the panels; each >= 0 and stored by one of the figure's scenes.",
                               items={"type": "number", "minimum": 0})

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Names of existing entries, and times stored by the scenes it reads."""
        names = context.names
        for i, n in enumerate(self.scenes):
            if n not in names:
                out.add(where + ["scenes", i], f"unknown scene: no map, homoclinic or scene entry of that "
                                               f"name{did_you_mean(n, names)}", n)
        read = [n for n in self.scenes if n in context.given["scenes"]]
        if not read or self.times is None:
            return
        stored = []
        for n in read:
            scene = context.scenes.get(n)
            if scene is None or out.has(["scenes", n, "store", "every"]):  # its errors are said
                return
            stored.append(scene.times)
        for i, t in enumerate(self.times):
            if not any(_holds(times, t) for times in stored):
                out.add(where + ["times", i], f"not a stored time of {', '.join(read)} "
                                              f"(add it to a store.snapshots list)", t)


BEYOND_DOC = ("Analyses beyond the paper, one section each, keyed by the analysis's name (its module "
              "cradle.analyses.<name>, its targets <name> and <name>_full, its folder results/<name>/); see "
              "docs/analyses.md.")


def _beyond_class() -> Any:
    """The declared class of ``beyond:``: one key per analysis of the registry, its own spec class."""
    from cradle.analyses.registry import ANALYSES

    namespace: dict[str, Any] = {"__annotations__": {}}
    for a in ANALYSES.values():
        namespace["__annotations__"][a.module] = a.spec
        namespace[a.module] = param(a.spec(), schema_doc(a.spec), key=a.name)
    return declared(doc=BEYOND_DOC)(type("Beyond", (), namespace))


Beyond = _beyond_class()


@declared(doc="The experiments of G. James, 'Nonlinear waves in Newton's cradle and the discrete p-Schrodinger "
              "equation': integrator defaults, orbits of the map G, homoclinic solutions of (dpsstn), lattice + DpS "
              "runs (scenes) and the figures that read them. Validated by cradle.pipeline.config.validate.")
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
    beyond: Beyond = param(Beyond(), schema_doc(Beyond))   # type: ignore[valid-type]  # a class made at import
    budget: Budget = param(Budget(), schema_doc(Budget))
    movies: Movies = param(Movies(), schema_doc(Movies))
