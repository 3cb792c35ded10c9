"""A scene's job: initial data, the (nc) and DpS runs and their metrics, written as one set of files.

:func:`run_scene` is what the workflow's ``simulate`` rule and ``cradle run`` both call. A scene
whose store fits in memory runs as a chain of :mod:`cradle.scenes.stages`
(:func:`cradle.pipeline.runner.run_chain`: every file written after every step succeeded); a
larger one (:func:`cradle.pipeline.budget.streams`) block by block in bounded memory
(:func:`cradle.scenes.streamed.simulate_streamed`), with the same values in its files. Either
way a failure leaves none of the scene's files at their targets.
"""
from __future__ import annotations

import logging
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from cradle.pipeline import budget
from cradle.pipeline.runner import Progress, run_chain, setup_logging
from cradle.scenes import stages
from cradle.scenes.spec import Scene

if TYPE_CHECKING:
    import xarray as xr

log = logging.getLogger("cradle")


def _initial(spec: Scene, name: str, homoclinic: xr.Dataset | None) -> xr.Dataset:
    """The scene's initial data; a warning (one line) when its amplitude is outside DpS's measured range."""
    from cradle.measurements.dps_range import outside_range

    init = stages.initial_data(spec, name, homoclinic)
    note = outside_range(name, init["x0"].values, init["v0"].values)
    if note is not None:
        log.warning("warning: %s", note)
    return init


def run_scene(spec: Scene, name: str, outs: dict, log_path: str | None = None,
              homoclinic: Callable[[], xr.Dataset] | xr.Dataset | None = None) -> None:
    """Compute scene ``name`` (resolved ``spec``, :func:`cradle.pipeline.config.scene`) into ``outs``
    (initial, exact, dps, metrics paths, and homoclinic when ``homoclinic`` is a callable computing it;
    else ``homoclinic`` is its Dataset or None)."""
    estimate = budget.long_run(spec, name)
    steps = [("homoclinic", lambda done: homoclinic())] if callable(homoclinic) else []
    hom = (lambda done: done.get("homoclinic")) if callable(homoclinic) else (lambda done: homoclinic)
    steps.append(("initial", lambda done: _initial(spec, name, hom(done))))
    if not budget.streams(spec):
        steps += [
            ("exact", lambda done: stages.exact_run(spec, done["initial"], name,
                                                    progress=Progress(f"exact {name}", estimate=estimate))),
            ("dps", lambda done: stages.dps_run(spec, done["initial"], name, progress=Progress(f"dps {name}"))),
            ("metrics", lambda done: stages.metrics(spec, done["exact"], done["dps"], name)),
        ]
        run_chain(steps, outs, log_path, label=name)
        return
    from cradle.data.io import write_netcdf
    from cradle.scenes import streamed

    setup_logging(log_path)
    t0 = time.perf_counter()
    done: dict[str, Any] = {}
    for key, compute in steps:
        done[key] = compute(done)
    log.info("%s: %s; streamed block by block", name, budget.spec_estimate(spec, name).describe())
    streamed.simulate_streamed(spec, done["initial"], name, outs,
                               progress=Progress(f"exact+dps {name}", estimate=estimate), log=log)
    if "homoclinic" in done:
        write_netcdf(done["homoclinic"], outs["homoclinic"])
    log.info("%s: all done in %.2f s -> %s", name, time.perf_counter() - t0, ", ".join(map(str, outs.values())))
