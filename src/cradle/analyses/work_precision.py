"""Work-precision of the lattice integrators: error and energy drift against wall time.

For each scene of ``beyond: work-precision: scenes:`` in config.yaml (the initial data of a
``scenes:`` entry, results/initial/<scene>.nc, whose alpha and bc the file states, run to the
section's own ``t_end``):

1. **Reference.** Two runs of the reference method (default srkn6c) at
   ``dt_factor`` and at twice it, stored on the comparison grid
   ``t = 0, compare_every, 2 compare_every, ..., t_end``. Their difference
   D(t) = max_n max(|x_n - x'_n|, |v_n - v'_n|) / a estimates the error of the
   coarser run (the finer one is 2^4-2^5 times better). The reference *holds*
   up to ``t_valid``, the last grid time before D first exceeds
   ``tolerance``: on chaotic scenes (strongly nonlinear waves, modulational
   instability) two runs of any accuracy separate exponentially, and
   pointwise errors mean something only before ``t_valid``.
2. **Ladders.** Every method of ``work-precision.methods`` at every setting of
   its ladder (``dt_factor`` for the splittings, ``rtol`` with
   ``atol = rtol * a`` for the adaptive methods):

   * ``error``: max over grid times t <= t_valid of max_n max(|x_n - x_ref|,
     |v_n - v_ref|) / a, a the wave amplitude (max |x_n(0)|, |v_n(0)| for
     non-travelling data);
   * ``energy_drift``: max over every step up to t_end of |H - H(0)| / H(0)
     (the invariant, meaningful also beyond t_valid);
   * ``statistic_error`` (only if t_valid < t_end): relative difference of
     the time average over the grid times in (t_valid, t_end] of the contact
     energy sum_n V0(x_{n+1} - x_n) / H(0) against the reference's - a
     statistic, for the chaotic part of the run;
   * ``wall_time``: of the whole :func:`cradle.integrators.integrate_lattice`
     call (JIT caches warm; a run shorter than ``repeat_time`` is repeated
     up to 5 times and the fastest kept), and ``n_force_evals``, ``n_steps``,
     ``dt``.

Output: one batch per scene (:func:`measure_scene`: a Dataset with dims ``method``, ``setting``, the
reference difference D on ``t_compare``; results/work-precision/batch/<form>/<scene>.nc), gathered by
:func:`compute` into one file of one group per scene, results/work-precision/work-precision.nc (the
full form: results/work-precision/full/), drawn as results/figures/work-precision.{pdf,png}
(:mod:`cradle.figures.work_precision`). A batch of the full form takes every core given to Snakemake
(``threads: "all"``), so no other job runs beside it and its times are the machine's; the reduced
form's batches take one core each and run beside the other jobs of ``all`` (their times are those of
a shared machine: the full form is the measurement).
"""
from __future__ import annotations

import datetime as _dt
import json
import platform
import subprocess
import time
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.protocol import Analysis, Batches, Read
from cradle.data.variables import Var
from cradle.models import lattice
from cradle.scenes.spec import LATTICE_ADAPTIVE, SPLITTINGS
from cradle.specs.declare import REQUIRED, declared, param, plain
from cradle.specs.values import DT_FACTOR_FLOOR, MAX_T_END, RTOL_FLOOR, ConfigError, did_you_mean

if TYPE_CHECKING:
    from collections.abc import Iterable

    import xarray as xr
    from numpy.typing import ArrayLike, NDArray

    from cradle.analyses.protocol import Log
    from cradle.integrators.lattice_solver import LatticeSolution
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors

#: Variables of one scene's group (and of its batch file), declared beside the analysis:
#: :func:`cradle.data.io.make_dataset` takes their dims, long names and units from here.
SCENE_VARIABLES: dict[str, Var] = {
    "method": Var(("method",), "integration method of the lattice (nc)"),
    "setting": Var(("setting",), "index of the accuracy setting on the method's ladder"),
    "t_compare": Var(("t_compare",), "time of the comparison grid"),
    "accuracy_parameter": Var(("method", "setting"), "dt_factor (splittings) or rtol (adaptive methods) of the run"),
    "dt": Var(("method", "setting"), "nominal fixed step of a splitting (NaN for adaptive methods)"),
    "error": Var(("method", "setting"),
                 "max over t <= t_valid of max_n max(|x_n - x_ref,n|, |v_n - v_ref,n|) / a"),
    "energy_drift": Var(("method", "setting"), "max over every step of |H(t) - H(0)| / H(0) up to t_end"),
    "statistic_error": Var(("method", "setting"),
                           "relative error of the mean contact energy / H(0) over (t_valid, t_end]"),
    "wall_time": Var(("method", "setting"), "wall time of the integration", "s"),
    "n_force_evals": Var(("method", "setting"), "number of evaluations of the contact forces"),
    "n_steps": Var(("method", "setting"), "number of (accepted) steps"),
    "reference_difference": Var(("t_compare",),
                                "max_n max(|x_n - x'_n|, |v_n - v'_n|) / a between the two reference runs"),
}

#: the stored variables of the `work-precision` file: one group per measured scene, named by the scene
#: (``/tw-weak``), each holding that scene's batch; the root holds the spec and the scene names
VARIABLES = {"/": {}, "/{scene}": SCENE_VARIABLES}

ADAPTIVE_KEY, SPLITTING_KEY = "rtol", "dt_factor"
MAX_REPEATS = 5


# --------------------------------------------------------------------------- the spec (`beyond: work-precision:`)

def _ladder(method: str) -> dict:
    """The schema of one method's ladder of settings in work-precision.methods."""
    key, top, what = (("dt_factor", 1, "splitting step = dt_factor * 2 pi / omega_max") if method in SPLITTINGS
                      else ("rtol", 0.01, "relative tolerances (atol = rtol * a)"))
    floor = RTOL_FLOOR if key == "rtol" else DT_FACTOR_FLOOR
    return {"description": f"Ladder of {method}: {what}.", "type": "object", "additionalProperties": False,
            "required": [key], "properties": {key: {
                "description": f"The settings ({key}), each >= {floor:g}.", "type": "array", "minItems": 1,
                "items": {"type": "number", "maximum": top, "minimum": floor}}}}


@declared(doc="The ladder of settings of one method: dt_factor for a splitting, rtol for an adaptive method.")
class WorkPrecisionLadder:
    dt_factor: list[float] = param(None, "Step factors of a splitting (step = dt_factor * 2 pi / omega_max).")
    rtol: list[float] = param(None, "Relative tolerances of an adaptive method (atol = rtol * a).")


@declared(doc="One measured scene.")
class WorkPrecisionScene:
    t_end: float = param(REQUIRED, "End of every run; in (0, 1e6] (as a scene's t_end).", exclusiveMinimum=0,
                         maximum=MAX_T_END)


@declared(doc="Reference: two runs of a splitting at dt_factor and 2 dt_factor; it holds up to the last comparison "
              "time before their difference (relative to a) exceeds tolerance.")
class WorkPrecisionReference:
    method: str = param("srkn6c", "Splitting used for the reference.", enum=list(SPLITTINGS))
    dt_factor: float = param(0.0002, f"Step factor of the finer reference run; >= {DT_FACTOR_FLOOR:g}.",
                             minimum=DT_FACTOR_FLOOR, maximum=1)
    # at most 1e-2: two references that differ by 1 % of a are no reference, and a larger tolerance would
    # silently compare every method with a wrong one
    tolerance: float = param(1e-10, "Largest difference between the two reference runs, relative to a, for the "
                             "reference to hold; in (0, 1e-2].", exclusiveMinimum=0, maximum=0.01)


#: the reduced form's ladders: four methods, the four coarsest settings of config.yaml's ladders
REDUCED_METHODS = {"srkn6c": {"dt_factor": [0.128, 0.064, 0.032, 0.016]},
                   "srkn4c": {"dt_factor": [0.1, 0.04, 0.016, 0.0064]},
                   "srkn6": {"dt_factor": [0.04, 0.016, 0.0064, 0.00256]},
                   "dop853_numba": {"rtol": [1.0e-5, 1.0e-7, 1.0e-9, 1.0e-11]}}


@declared(doc="Work-precision of the lattice integrators (`snakemake -j2 work_precision`): for each scene, a reference "
              "from two runs of different accuracy, then every method on a ladder of settings; error and energy drift "
              "against wall time in results/work-precision/work-precision.nc (one group per scene) and "
              "results/figures/work-precision.{pdf,png}.")
class WorkPrecision:
    scenes: dict[str, WorkPrecisionScene] = param({}, "Scenes measured, by the name of a `scenes:` entry (its initial "
                                                  "data are used, with the N, bc and alpha its file states), each "
                                                  "with its own t_end.")
    compare_every: float = param(1.0, "Spacing of the comparison grid 0, compare_every, ..., t_end on which states "
                                 "are compared; > 0.", exclusiveMinimum=0)
    repeat_time: float = param(0.2, "A run shorter than this many seconds is repeated (at most 5 times) and its "
                               "fastest wall time kept; >= 0.", minimum=0)
    reference: WorkPrecisionReference = param(WorkPrecisionReference(), "Reference: two runs of a splitting at "
                                              "dt_factor and 2 dt_factor; it holds up to the last comparison time "
                                              "before their difference (relative to a) exceeds tolerance.")
    methods: dict[str, WorkPrecisionLadder] = param({}, "The methods measured and the ladder of settings of each: "
                                                    "dt_factor for the splittings, rtol for the adaptive methods; the "
                                                    "reduced form runs srkn6c, srkn4c, srkn6 and dop853_numba on "
                                                    "four settings each.",
                                                    additionalProperties=False,
                                                    properties={m: _ladder(m) for m in (*SPLITTINGS,
                                                                                        *LATTICE_ADAPTIVE)},
                                                    reduced=REDUCED_METHODS)

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """The scenes name `scenes:` entries (their initial data are measured)."""
        scenes = context.given["scenes"]
        for name in self.scenes:
            if name not in scenes:
                out.add(where + ["scenes", name], f"unknown scene: no `scenes:` entry of that "
                                                  f"name{did_you_mean(name, scenes)}")


def _ladder_of(lad: WorkPrecisionLadder) -> list[tuple[str, list[float]]]:
    """(parameter name, settings) of the keys a ladder gives (one, by the schema)."""
    return [(k, list(v)) for k, v in ((SPLITTING_KEY, lad.dt_factor), (ADAPTIVE_KEY, lad.rtol)) if v is not None]


def machine() -> str:
    """CPU model name (``lscpu``), or what :mod:`platform` knows."""
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True, timeout=10).stdout
        for line in out.splitlines():
            if line.strip().startswith("Model name:"):
                return line.split(":", 1)[1].strip()
    except (OSError, subprocess.SubprocessError):
        pass
    return platform.processor() or platform.machine()


def ladder(spec: WorkPrecision, method: str) -> tuple[str, list[float]]:
    """(parameter name, settings) of one method of a spec."""
    (key, values), = _ladder_of(spec.methods[method])
    return key, values


# --------------------------------------------------------------------------- measurements

def compare_grid(t_end: float, every: float) -> np.ndarray:
    """0, every, 2 every, ... and t_end (the last grid point dropped if within 1e-9 of t_end)."""
    n = int(np.floor(t_end / every * (1.0 + 1e-12)))
    t = np.arange(n + 1) * every
    t = t[t < t_end - 1e-9]
    return np.append(t, t_end)


def state_difference(x: NDArray[np.float64], v: NDArray[np.float64], x_ref: NDArray[np.float64],
                     v_ref: NDArray[np.float64], a: float) -> np.ndarray:
    """max_n max(|x_n - x_ref,n|, |v_n - v_ref,n|) / a at every stored time."""
    return np.maximum(np.abs(x - x_ref).max(axis=-1), np.abs(v - v_ref).max(axis=-1)) / a


def valid_until(t: np.ndarray, diff: np.ndarray, tolerance: float) -> float:
    """The last time of ``t`` before ``diff`` first exceeds ``tolerance`` (t[-1] if it never does)."""
    bad = np.nonzero(~(diff <= tolerance))[0]
    if bad.size == 0:
        return float(t[-1])
    return float(t[max(bad[0] - 1, 0)])


def contact_energy(x: ArrayLike, alpha: float, bc: str) -> np.ndarray:
    """sum_n V0(x_{n+1} - x_n) at every stored time."""
    return lattice.V0(lattice.bond_elongations(x, bc), alpha).sum(axis=-1)


def _kwargs(method: str, value: float, a: float) -> dict:
    from cradle.integrators import SPLITTING_METHODS

    if method in SPLITTING_METHODS:
        return {"dt_factor": value}
    return {"rtol": value, "atol": value * a}


def run_once(x0: ArrayLike, v0: ArrayLike, t: NDArray[np.float64], alpha: float, bc: str, method: str,
             value: float, a: float, repeat_time: float = 0.0) -> tuple[LatticeSolution, float]:
    """One integration (repeated while short, the fastest wall time kept); returns (solution, wall time)."""
    from cradle.integrators import integrate_lattice

    best = np.inf
    spent = 0.0
    sol = None
    for _ in range(MAX_REPEATS):
        t0 = time.perf_counter()
        sol = integrate_lattice(x0, v0, t, alpha=alpha, bc=bc, method=method, **_kwargs(method, value, a))
        wall = time.perf_counter() - t0
        best = min(best, wall)
        spent += wall
        if spent >= repeat_time:
            break
    return sol, best  # type: ignore[return-value]  # MAX_REPEATS >= 1 runs


def warm_up(methods: Iterable[str], alpha: float, bc: str) -> None:
    """Load (or compile) every method's kernels on a tiny chain, so that timings exclude the JIT."""
    from cradle.integrators import integrate_lattice

    x0 = 0.1 * np.cos(np.arange(8) * np.pi / 2)
    for method in methods:
        integrate_lattice(x0, np.zeros(8), [0.0, 0.5], alpha=alpha, bc=bc, method=method,
                          **_kwargs(method, 1e-3, 0.1))


def measure(spec: WorkPrecision, scene: str, x0: ArrayLike, v0: ArrayLike, alpha: float, bc: str,
            a: float | None = None, log: Log | None = None) -> xr.Dataset:
    """The work-precision Dataset of ``scene`` of ``spec`` (see module docstring) from its initial state
    x0, v0 on a chain with exponent ``alpha`` and boundary conditions ``bc``; ``a`` the amplitude errors
    are relative to (default max |x_n(0)|, |v_n(0)|). Methods in the order of ``spec.methods``."""
    from cradle.integrators import SPLITTING_METHODS, integrate_lattice

    say = log or (lambda *a: None)
    t_end = spec.scenes[scene].t_end
    x0 = np.asarray(x0, dtype=float)
    v0 = np.asarray(v0, dtype=float)
    if a is None:
        a = max(float(np.abs(x0).max()), float(np.abs(v0).max()))
    t = compare_grid(t_end, spec.compare_every)
    methods = list(spec.methods)
    ref_spec = spec.reference
    warm_up(sorted(set(methods) | {ref_spec.method}), alpha, bc)

    wall0 = time.perf_counter()
    fine = integrate_lattice(x0, v0, t, alpha=alpha, bc=bc, method=ref_spec.method,
                             dt_factor=ref_spec.dt_factor)
    check = integrate_lattice(x0, v0, t, alpha=alpha, bc=bc, method=ref_spec.method,
                              dt_factor=2.0 * ref_spec.dt_factor)
    ref_wall = time.perf_counter() - wall0
    D = state_difference(check.x, check.v, fine.x, fine.v, a)
    t_valid = valid_until(t, D, ref_spec.tolerance)
    upto = t <= t_valid + 1e-9
    after = t > t_valid + 1e-9
    H0 = float(fine.energy[0])
    stat_ref = float(contact_energy(fine.x[after], alpha, bc).mean() / H0) if after.any() else np.nan
    say(f"{scene}: reference {ref_spec.method} dt_factor={ref_spec.dt_factor:g} ({ref_wall:.2f} s for both "
        f"runs): difference {float(D[upto].max()):.2e} at t_valid={t_valid:g} (max {float(D.max()):.2e} over "
        f"[0, {t_end:g}]), energy drift {fine.energy_drift:.1e}")

    S = max(len(ladder(spec, m)[1]) for m in methods) if methods else 0
    shape = (len(methods), S)
    out = {name: np.full(shape, np.nan) for name in ("accuracy_parameter", "dt", "error", "energy_drift",
                                                      "statistic_error", "wall_time", "n_force_evals", "n_steps")}
    kinds: list[str] = []
    for i, method in enumerate(methods):
        key, values = ladder(spec, method)
        kinds.append(key)
        expected = SPLITTING_KEY if method in SPLITTING_METHODS else ADAPTIVE_KEY
        if key != expected:
            raise ValueError(f"work-precision.methods.{method}: a ladder of {expected!r} is expected, got {key!r}")
        for j, value in enumerate(values):
            sol, wall = run_once(x0, v0, t, alpha, bc, method, value, a, spec.repeat_time)
            err = float(state_difference(sol.x[upto], sol.v[upto], fine.x[upto], fine.v[upto], a).max())
            stat = np.nan
            if after.any():
                stat = abs(float(contact_energy(sol.x[after], alpha, bc).mean() / H0) - stat_ref) / abs(stat_ref)
            row = {"accuracy_parameter": value, "dt": sol.dt if sol.dt is not None else np.nan, "error": err,
                   "energy_drift": sol.energy_drift, "statistic_error": stat, "wall_time": wall,
                   "n_force_evals": sol.n_force_evals, "n_steps": sol.n_steps}
            for name, val in row.items():
                out[name][i, j] = val
            say(f"{scene}: {method:<12s} {key}={value:<8.3g} error {err:.2e}  energy drift {sol.energy_drift:.2e}  "
                f"wall {wall:.4f} s  {int(sol.n_force_evals)} force evals")

    attrs = {"scene": scene, "alpha": alpha, "N": int(x0.size), "bc": bc, "t_end": t_end, "a": a,
             "compare_every": spec.compare_every, "t_valid": t_valid,
             "reference_method": ref_spec.method, "reference_dt_factor": ref_spec.dt_factor,
             "reference_check_dt_factor": 2.0 * ref_spec.dt_factor, "reference_dt": fine.dt,
             "reference_tolerance": ref_spec.tolerance, "reference_error": float(D[upto].max()),
             "reference_energy_drift": fine.energy_drift, "reference_wall_time_s": ref_wall,
             "statistic": "time mean of sum_n V0(x_{n+1} - x_n) / H(0) over grid times in (t_valid, t_end]",
             "statistic_reference": stat_ref,
             "parameter_kind": json.dumps(dict(zip(methods, kinds, strict=True))), "repeat_time_s": spec.repeat_time,
             "machine": machine(), "date": _dt.date.today().isoformat(), "numba_version": _version("numba"),
             "scipy_version": _version("scipy")}
    return _dataset(out, methods, S, t, D, attrs, title=f"work-precision of the lattice integrators, scene "
                                                          f"'{scene}'")


def _version(pkg: str) -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version(pkg)
    except PackageNotFoundError:
        return "unknown"


def _dataset(fields: dict, methods: list[str], S: int, t: NDArray[np.float64],
             D: NDArray[np.float64], attrs: dict, title: str) -> xr.Dataset:
    """A self-describing Dataset (:func:`cradle.data.io.make_dataset`, :data:`SCENE_VARIABLES`) from the
    measured arrays."""
    from cradle.data.io import make_dataset

    coords = {"method": np.array(methods, dtype=object), "setting": np.arange(S),
              "t_compare": np.asarray(t, dtype=float)}
    data = {**fields, "reference_difference": np.asarray(D, dtype=float)}
    return make_dataset(data, coords=coords, attrs=attrs, title=title, variables=SCENE_VARIABLES)


def scene_dataset(spec: WorkPrecision, scene: str, initial: xr.Dataset, log: Log | None = None) -> xr.Dataset:
    """:func:`measure` on the initial data of ``scene`` (results/initial/<scene>.nc): its state, and the
    alpha, bc and amplitude a its file states."""
    a = initial.attrs.get("a")
    return measure(spec, scene, initial["x0"].values, initial["v0"].values, float(initial.attrs["alpha"]),
                   str(initial.attrs["bc"]), None if a is None else float(a), log=log)


def summary(ds: xr.Dataset) -> list[str]:
    """One line per method: the ranges of error, energy drift and wall time on its ladder."""
    lines = []
    for i, m in enumerate(ds["method"].values):
        row = ds.isel(method=i)
        ok = np.isfinite(row["error"].values)
        if not ok.any():
            continue
        e, d, w = (row[v].values[ok] for v in ("error", "energy_drift", "wall_time"))
        lines.append(f"{ds.attrs['scene']:10s} {str(m):13s} error {e.min():.1e}..{e.max():.1e} "
                     f"({np.log10(e.max() / max(e.min(), 1e-300)):.1f} decades)  drift {d.min():.1e}..{d.max():.1e}  "
                     f"wall {w.min():.3g}..{w.max():.3g} s")
    return lines


# --------------------------------------------------------------------------- the analysis protocol

def scenes_of(spec: WorkPrecision) -> list[str]:
    """The scenes one form measures, in the order of their names: one batch and one group each."""
    if not spec.scenes:
        raise ConfigError("config error: beyond.work-precision.scenes: no scene to measure in this form (name "
                          "`scenes:` entries under work-precision.scenes, and those of reduced.scenes for the "
                          "reduced form)")
    return sorted(spec.scenes)


def scene_reads(spec: WorkPrecision, scene: str) -> dict[str, Read]:
    """A batch reads the initial data of its scene."""
    return {"initial": Read.of("initial", scene=scene)}


def measure_scene(spec: WorkPrecision, scene: str, inputs: dict, log: Log | None = None) -> xr.Dataset:
    """One batch: the Dataset of ``scene`` (:func:`scene_dataset`), its summary in the log."""
    ds = scene_dataset(spec, scene, inputs["initial"], log=log)
    for line in summary(ds):
        (log or (lambda *a: None))(line)
    return ds


def compute(spec: WorkPrecision, inputs: dict, log: Log | None = None) -> xr.DataTree:
    """The `work-precision` file: the batch of every scene (``inputs["batch/<scene>"]``) as its group
    ``/<scene>``, values and attributes as measured; the spec and the scene names on the root."""
    import xarray as xr

    from cradle.data.io import make_dataset

    names = scenes_of(spec)
    root = make_dataset({}, attrs={"scene_names": ", ".join(names)}, params=plain(spec), variables={},
                        title="work-precision of the lattice integrators: error and energy drift against wall "
                              "time, one group per scene")
    # the batches as read (their own attributes, no file encoding: the writer sets it)
    groups = {f"/{name}": inputs[f"batch/{name}"].drop_encoding() for name in names}
    return xr.DataTree.from_dict({"/": root, **groups})


ANALYSIS = Analysis(
    name="work-precision", spec=WorkPrecision, compute=compute, variables=VARIABLES,
    # a batch of the full form has the machine to itself: its wall times are the measurement
    batches=Batches(keys=scenes_of, run=measure_scene, reads=scene_reads, threads={"full": "all"}),
    title="Work-precision of the lattice integrators: error and energy drift against wall time")
