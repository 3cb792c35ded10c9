"""Work-precision of the lattice integrators: error and energy drift against wall time.

For one scene of the ``work_precision:`` section of config.yaml (the initial
data of a ``scenes:`` entry, run to the section's own ``t_end``):

1. **Reference.** Two runs of the reference method (default srkn6c) at
   ``dt_factor`` and at twice it, stored on the comparison grid
   ``t = 0, compare_every, 2 compare_every, ..., t_end``. Their difference
   D(t) = max_n max(|x_n - x'_n|, |v_n - v'_n|) / a estimates the error of the
   coarser run (the finer one is 2^4-2^5 times better). The reference *holds*
   up to ``t_valid``, the last grid time before D first exceeds
   ``tolerance``: on chaotic scenes (strongly nonlinear waves, modulational
   instability) two runs of any accuracy separate exponentially, and
   pointwise errors mean something only before ``t_valid``.
2. **Ladders.** Every method of ``work_precision.methods`` at every setting of
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

Output: one Dataset per scene (dims ``method``, ``setting``; the reference
difference D on ``t_compare``), written to results/work-precision/<scene>.nc
by ``snakemake work_precision``, which also draws
results/figures/work-precision.{pdf,png} (:mod:`cradle.figures.work_precision`).

Command line (used by workflow/rules/workprecision.smk)::

    python -m cradle.analyses.work_precision scene --spec JSON --initial results/initial/S.nc --out results/work-precision/S.nc
    python -m cradle.analyses.work_precision figure --out results/figures/work-precision results/work-precision/*.nc
"""
from __future__ import annotations

import argparse
import datetime as _dt
import json
import logging
import platform
import subprocess
import sys
import time

import numpy as np

from cradle.models import lattice
from cradle.data.variables import Var

log = logging.getLogger("cradle")

#: Variables of the work-precision files (flat, one per scene), declared beside the analysis:
#: :func:`cradle.data.io.make_dataset` takes their dims, long names and units from here.
VARIABLES: dict[str, Var] = {
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

ADAPTIVE_KEY, SPLITTING_KEY = "rtol", "dt_factor"
MAX_REPEATS = 5


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


def ladder(spec: dict, method: str) -> tuple[str, list[float]]:
    """(parameter name, settings) of one method of a resolved spec."""
    (key, values), = spec["methods"][method].items()
    return key, list(values)


# --------------------------------------------------------------------------- measurements

def compare_grid(t_end: float, every: float) -> np.ndarray:
    """0, every, 2 every, ... and t_end (the last grid point dropped if within 1e-9 of t_end)."""
    n = int(np.floor(t_end / every * (1.0 + 1e-12)))
    t = np.arange(n + 1) * every
    t = t[t < t_end - 1e-9]
    return np.append(t, t_end)


def state_difference(x, v, x_ref, v_ref, a: float) -> np.ndarray:
    """max_n max(|x_n - x_ref,n|, |v_n - v_ref,n|) / a at every stored time."""
    return np.maximum(np.abs(x - x_ref).max(axis=-1), np.abs(v - v_ref).max(axis=-1)) / a


def valid_until(t: np.ndarray, diff: np.ndarray, tolerance: float) -> float:
    """The last time of ``t`` before ``diff`` first exceeds ``tolerance`` (t[-1] if it never does)."""
    bad = np.nonzero(~(diff <= tolerance))[0]
    if bad.size == 0:
        return float(t[-1])
    return float(t[max(bad[0] - 1, 0)])


def contact_energy(x, alpha: float, bc: str) -> np.ndarray:
    """sum_n V0(x_{n+1} - x_n) at every stored time."""
    return lattice.V0(lattice.bond_elongations(x, bc), alpha).sum(axis=-1)


def _kwargs(method: str, value: float, a: float) -> dict:
    from cradle.integrators import SPLITTING_METHODS

    if method in SPLITTING_METHODS:
        return {"dt_factor": value}
    return {"rtol": value, "atol": value * a}


def run_once(x0, v0, t, alpha, bc, method, value, a, repeat_time=0.0):
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
    return sol, best


def warm_up(methods, alpha: float, bc: str) -> None:
    """Load (or compile) every method's kernels on a tiny chain, so that timings exclude the JIT."""
    from cradle.integrators import integrate_lattice

    x0 = 0.1 * np.cos(np.arange(8) * np.pi / 2)
    for method in methods:
        integrate_lattice(x0, np.zeros(8), [0.0, 0.5], alpha=alpha, bc=bc, method=method,
                          **_kwargs(method, 1e-3, 0.1))


def measure(spec: dict, x0, v0, a: float | None = None) -> xr.Dataset:
    """The work-precision Dataset of one scene (see module docstring)."""
    from cradle.integrators import SPLITTING_METHODS, integrate_lattice

    alpha, bc, t_end = spec["alpha"], spec["bc"], spec["t_end"]
    x0 = np.asarray(x0, dtype=float)
    v0 = np.asarray(v0, dtype=float)
    if a is None:
        a = max(float(np.abs(x0).max()), float(np.abs(v0).max()))
    t = compare_grid(t_end, spec["compare_every"])
    methods = list(spec["methods"])
    ref_spec = spec["reference"]
    warm_up(sorted(set(methods) | {ref_spec["method"]}), alpha, bc)

    wall0 = time.perf_counter()
    fine = integrate_lattice(x0, v0, t, alpha=alpha, bc=bc, method=ref_spec["method"],
                             dt_factor=ref_spec["dt_factor"])
    check = integrate_lattice(x0, v0, t, alpha=alpha, bc=bc, method=ref_spec["method"],
                              dt_factor=2.0 * ref_spec["dt_factor"])
    ref_wall = time.perf_counter() - wall0
    D = state_difference(check.x, check.v, fine.x, fine.v, a)
    t_valid = valid_until(t, D, ref_spec["tolerance"])
    upto = t <= t_valid + 1e-9
    after = t > t_valid + 1e-9
    H0 = float(fine.energy[0])
    stat_ref = float(contact_energy(fine.x[after], alpha, bc).mean() / H0) if after.any() else np.nan
    log.info("%s: reference %s dt_factor=%g (%.2f s for both runs): difference %.2e at t_valid=%g "
             "(max %.2e over [0, %g]), energy drift %.1e", spec["name"], ref_spec["method"], ref_spec["dt_factor"],
             ref_wall, float(D[upto].max()), t_valid, float(D.max()), t_end, fine.energy_drift)

    S = max(len(ladder(spec, m)[1]) for m in methods) if methods else 0
    shape = (len(methods), S)
    out = {name: np.full(shape, np.nan) for name in ("accuracy_parameter", "dt", "error", "energy_drift",
                                                      "statistic_error", "wall_time", "n_force_evals", "n_steps")}
    kinds = []
    for i, method in enumerate(methods):
        key, values = ladder(spec, method)
        kinds.append(key)
        expected = SPLITTING_KEY if method in SPLITTING_METHODS else ADAPTIVE_KEY
        if key != expected:
            raise ValueError(f"work_precision.methods.{method}: a ladder of {expected!r} is expected, got {key!r}")
        for j, value in enumerate(values):
            sol, wall = run_once(x0, v0, t, alpha, bc, method, value, a, spec["repeat_time"])
            err = float(state_difference(sol.x[upto], sol.v[upto], fine.x[upto], fine.v[upto], a).max())
            stat = np.nan
            if after.any():
                stat = abs(float(contact_energy(sol.x[after], alpha, bc).mean() / H0) - stat_ref) / abs(stat_ref)
            row = {"accuracy_parameter": value, "dt": sol.dt if sol.dt is not None else np.nan, "error": err,
                   "energy_drift": sol.energy_drift, "statistic_error": stat, "wall_time": wall,
                   "n_force_evals": sol.n_force_evals, "n_steps": sol.n_steps}
            for name, val in row.items():
                out[name][i, j] = val
            log.info("%s: %-12s %s=%-8.3g error %.2e  energy drift %.2e  wall %.4f s  %d force evals",
                     spec["name"], method, key, value, err, sol.energy_drift, wall, sol.n_force_evals)

    attrs = {"scene": spec["name"], "alpha": alpha, "N": int(x0.size), "bc": bc, "t_end": t_end, "a": a,
             "compare_every": spec["compare_every"], "t_valid": t_valid,
             "reference_method": ref_spec["method"], "reference_dt_factor": ref_spec["dt_factor"],
             "reference_check_dt_factor": 2.0 * ref_spec["dt_factor"], "reference_dt": fine.dt,
             "reference_tolerance": ref_spec["tolerance"], "reference_error": float(D[upto].max()),
             "reference_energy_drift": fine.energy_drift, "reference_wall_time_s": ref_wall,
             "statistic": "time mean of sum_n V0(x_{n+1} - x_n) / H(0) over grid times in (t_valid, t_end]",
             "statistic_reference": stat_ref,
             "parameter_kind": json.dumps(dict(zip(methods, kinds))), "repeat_time_s": spec["repeat_time"],
             "machine": machine(), "date": _dt.date.today().isoformat(), "numba_version": _version("numba"),
             "scipy_version": _version("scipy")}
    return _dataset(out, methods, S, t, D, attrs, title=f"work-precision of the lattice integrators, scene "
                                                          f"'{spec['name']}'")


def _version(pkg: str) -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version(pkg)
    except PackageNotFoundError:
        return "unknown"


def _dataset(fields: dict, methods, S, t, D, attrs, title) -> xr.Dataset:
    """A self-describing Dataset (:func:`cradle.data.io.make_dataset`, :data:`VARIABLES`) from the
    measured arrays."""
    from cradle.data.io import make_dataset

    coords = {"method": np.array(methods, dtype=object), "setting": np.arange(S),
              "t_compare": np.asarray(t, dtype=float)}
    data = {**fields, "reference_difference": np.asarray(D, dtype=float)}
    return make_dataset(data, coords=coords, attrs=attrs, title=title, variables=VARIABLES)


def scene_dataset(spec: dict, initial: xr.Dataset) -> xr.Dataset:
    """:func:`measure` on the initial data of a scene (results/initial/<scene>.nc)."""
    a = initial.attrs.get("a")
    return measure(spec, initial["x0"].values, initial["v0"].values, None if a is None else float(a))


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


# --------------------------------------------------------------------------- command line

def main(argv=None) -> int:
    from cradle.data.io import open_dataset
    from cradle.pipeline.runner import run, setup_logging

    parser = argparse.ArgumentParser(prog="python -m cradle.analyses.work_precision", description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("scene", help="measure one scene")
    p.add_argument("--spec", required=True, help="resolved parameters (JSON, cradle.pipeline.config.resolved_work_precision)")
    p.add_argument("--initial", required=True, help="results/initial/<scene>.nc")
    p.add_argument("--out", required=True)
    p.add_argument("--log")
    f = sub.add_parser("figure", help="draw the work-precision figure")
    f.add_argument("--out", required=True, help="output stem (writes .pdf and .png)")
    f.add_argument("--log")
    f.add_argument("inputs", nargs="+")
    args = parser.parse_args(argv)
    if args.command == "scene":
        spec = json.loads(args.spec)

        def compute():
            ds = scene_dataset(spec, open_dataset(args.initial))
            for line in summary(ds):
                log.info("%s", line)
            return ds

        run(compute, args.out, args.log, label=f"work-precision {spec['name']}")
        return 0
    setup_logging(args.log)
    from cradle.figures import save_figure
    from cradle.figures.work_precision import draw

    data = {}
    for path in args.inputs:
        ds = open_dataset(path)
        data[ds.attrs["scene"]] = ds
    for path in save_figure(draw(data), args.out):
        log.info("wrote %s", path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
