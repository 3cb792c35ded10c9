"""Declarations of the config's sections: figures, work_precision, budget, and the whole file.

Each section is a frozen dataclass whose fields carry description, bounds and
default (:func:`cradle.specs.declare.param`); :class:`Config` is the whole file. The entries a
job computes from (defaults, map, homoclinic, scenes) are declared in :mod:`cradle.scenes.spec`.
The checks that span several keys or sections are the ``check`` methods here, in
:mod:`cradle.scenes.spec` and in :mod:`.beyond`; :func:`check` runs them all in order.
"""
from __future__ import annotations

import math

from cradle.pipeline.budget import Budget
from cradle.scenes.spec import LATTICE_ADAPTIVE, SPLITTINGS, Defaults, HomoclinicEntry, MapEntry, Scene
from cradle.specs.declare import REQUIRED, declared, param
from cradle.specs.values import TIME_TOL, did_you_mean, entries, finite, store_times

from .beyond import Beyond
from .movies import Movies

SECTIONS = ("map", "homoclinic", "scenes")  # the name spaces a figure's `scenes:` list reads from


def _known_figures() -> tuple[str, ...]:
    from cradle.figures import DATASET_FIGURES, FIGURES, OTHER_FIGURES

    return (*FIGURES, *DATASET_FIGURES, *OTHER_FIGURES)


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


def _ladder(method: str) -> dict:
    """The schema of one method's ladder of settings in work_precision.methods."""
    key, top, what = (("dt_factor", 1, "splitting step = dt_factor * 2 pi / omega_max") if method in SPLITTINGS
                      else ("rtol", 0.01, "relative tolerances (atol = rtol * a)"))
    return {"description": f"Ladder of {method}: {what}.", "type": "object", "additionalProperties": False,
            "required": [key], "properties": {key: {
                "description": f"The settings ({key}), each > 0.", "type": "array", "minItems": 1,
                "items": {"type": "number", "exclusiveMinimum": 0, "maximum": top}}}}


@declared(doc="Reference: two runs of a splitting at dt_factor and 2 dt_factor; it holds up to the last comparison "
              "time before their difference (relative to a) exceeds tolerance.")
class WorkPrecisionReference:
    method: str = param("srkn6c", "Splitting used for the reference.", enum=list(SPLITTINGS))
    dt_factor: float = param(0.0002, "Step factor of the finer reference run; > 0.", exclusiveMinimum=0, maximum=1)
    tolerance: float = param(1e-10, "Largest difference between the two reference runs, relative to a, for the "
                             "reference to hold; > 0.", exclusiveMinimum=0)


@declared(doc="The reduced form `snakemake all` builds (results/work-precision/<scene>.nc, "
              "results/figures/work-precision.*); the full one is `snakemake work_precision_full` "
              "(results/work-precision/full/).")
class WorkPrecisionReduced:
    scenes: list[str] = param(["tw-weak"], "The measured scenes kept (names under work_precision.scenes).",
                              minItems=1, items={"$ref": "#/$defs/name"})
    t_end: float = param(100.0, "Runs end at the smaller of this and the scene's t_end; > 0.", exclusiveMinimum=0)
    methods: list[str] = param(["srkn6c", "srkn4c", "srkn6", "dop853_numba"], "The methods kept (those of them "
                               "that work_precision.methods measures).", minItems=1,
                               items={"type": "string", "enum": [*SPLITTINGS, *LATTICE_ADAPTIVE]})
    settings: int = param(4, "The first (coarsest) settings of each ladder kept.", minimum=1, maximum=20)


@declared(doc="Work-precision of the lattice integrators (`snakemake -j2 work_precision`): for each scene, a reference "
              "from two runs of different accuracy, then every method on a ladder of settings; error and energy drift "
              "against wall time in results/work-precision/<scene>.nc and results/figures/work-precision.{pdf,png}.")
class WorkPrecision:
    scenes: dict = param({}, "Scenes measured, by the name of a `scenes:` entry (its initial data, N, bc and alpha "
                         "are used), each with its own t_end.", type="object", propertyNames={"$ref": "#/$defs/name"},
                         additionalProperties={"description": "One measured scene.", "type": "object",
                                               "additionalProperties": False, "required": ["t_end"],
                                               "properties": {"t_end": {"description": "End of every run; > 0.",
                                                                        "type": "number", "exclusiveMinimum": 0}}})
    compare_every: float = param(1.0, "Spacing of the comparison grid 0, compare_every, ..., t_end on which states "
                                 "are compared; > 0.", exclusiveMinimum=0)
    repeat_time: float = param(0.2, "A run shorter than this many seconds is repeated (at most 5 times) and its "
                               "fastest wall time kept; >= 0.", minimum=0)
    reference: WorkPrecisionReference = param(WorkPrecisionReference(), "Reference: two runs of a splitting at "
                                              "dt_factor and 2 dt_factor; it holds up to the last comparison time "
                                              "before their difference (relative to a) exceeds tolerance.")
    methods: dict = param({}, "The methods measured and the ladder of settings of each: dt_factor for the "
                          "splittings, rtol for the adaptive methods.", type="object", additionalProperties=False,
                          properties={m: _ladder(m) for m in (*SPLITTINGS, *LATTICE_ADAPTIVE)})
    reduced: WorkPrecisionReduced = param(WorkPrecisionReduced(), WorkPrecisionReduced.__schema_doc__)

    @staticmethod
    def check(wp, cfg: dict, out) -> None:
        """work_precision.scenes name `scenes:` entries (their initial data are measured); the reduced form
        keeps some of those scenes and methods."""
        if not isinstance(wp, dict) or not isinstance(wp.get("scenes"), dict):
            return
        scenes = entries(cfg, "scenes")
        for name in wp["scenes"]:
            if name not in scenes:
                out.add(["work_precision", "scenes", name], f"unknown scene: no `scenes:` entry of that "
                                                            f"name{did_you_mean(name, scenes)}")
        red = wp.get("reduced") if isinstance(wp.get("reduced"), dict) else {}
        if not wp["scenes"]:  # nothing measured: the reduced form's defaults name nothing to check
            return
        for i, name in enumerate(red.get("scenes") or []):
            if name not in wp["scenes"]:
                out.add(["work_precision", "reduced", "scenes", i], f"not a work_precision scene"
                                                                    f"{did_you_mean(name, list(wp['scenes']))}", name)
        kept = [m for m in red.get("methods") or [] if m in (wp.get("methods") or {})]
        if red.get("methods") and isinstance(wp.get("methods"), dict) and wp["methods"] and not kept:
            out.add(["work_precision", "reduced", "methods"], "names no method of work_precision.methods",
                    red["methods"])

    @staticmethod
    def scenes_of(cfg: dict, form: str) -> list[str]:
        """The scenes measured in one form (full: every work_precision scene)."""
        wp = cfg["work_precision"]
        return list(wp["scenes"]) if form == "full" else [n for n in wp["reduced"]["scenes"] if n in wp["scenes"]]

    @staticmethod
    def resolve(cfg: dict, name: str, scene: dict, form: str = "full") -> dict:
        """The parameters of work-precision scene ``name`` (plain, JSON-serialisable): ``alpha``, ``N``,
        ``bc`` of the resolved ``scene`` of that name, the rest from ``work_precision``; the reduced form
        keeps its methods, the first settings of each ladder, and ends at its t_end."""
        wp = cfg["work_precision"]
        t_end, methods = float(wp["scenes"][name]["t_end"]), wp["methods"]
        ladder = slice(None)
        if form == "reduced":
            red = wp["reduced"]
            t_end = min(t_end, float(red["t_end"]))
            methods = {m: lad for m, lad in methods.items() if m in red["methods"]}
            ladder = slice(0, int(red["settings"]))
        return {"name": name, "alpha": scene["alpha"], "N": scene["N"], "bc": scene["bc"],
                "t_end": t_end, "compare_every": float(wp["compare_every"]),
                "reference": dict(wp["reference"]), "repeat_time": float(wp["repeat_time"]),
                "methods": {m: {k: [float(x) for x in v][ladder] for k, v in lad.items()} for m, lad in methods.items()}}


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
    work_precision: WorkPrecision = param(WorkPrecision(), WorkPrecision.__schema_doc__)
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
    WorkPrecision.check(cfg.get("work_precision"), cfg, out)
    Beyond.check(cfg.get("beyond"), cfg, out)
    figures = cfg.get("figures")
    for label, fig in (figures.items() if isinstance(figures, dict) else ()):
        Figure.check(label, fig, cfg, names, out)
