"""The fixed-step drivers of the splittings of (ham) on (nc)/(meca), with or without the onset correction.

One call runs the splitting loop (:func:`cradle.integrators._splitting.split_run`, with the
correction :class:`cradle.integrators._onset.OnsetCorrection` for "srkn6c", "srkn4c") over the output
times in chunks, so that progress can be reported about once per second; the state is stored
exactly at every output time, and a run continued from a stored state takes the same steps.
"""
from __future__ import annotations

import math
import time
from typing import TYPE_CHECKING

import numpy as np

from cradle.integrators import _kernels as K, _onset, _splitting
from cradle.integrators._coefficients import SPLITTINGS
from cradle.integrators._validate import check_steps

if TYPE_CHECKING:
    from collections.abc import Callable

    from cradle.integrators._types import Floats

#: Splittings with the contact-onset correction (:mod:`._onset`) -> the splitting they correct.
CORRECTED_METHODS = {"srkn6c": "srkn6", "srkn4c": "srkn4"}
SPLITTING_METHODS = tuple(SPLITTINGS) + tuple(CORRECTED_METHODS)

#: (variant, n_iter, near) of the onset correction (:mod:`._onset`): variant 2 replaces the
#: quadrature actually taken, 0 refinements of the model's end values, and a bond is treated when
#: |d| < near * h * (|d'(0)| + |d'(h)|) at a step end or d changes sign (benchmarks/onset_correction.py).
ONSET_OPTIONS = (2, 0, _onset.NEAR_DEFAULT)


def run_splitting(x0: Floats, v0: Floats, t_out: Floats, dt: float, method: str, alpha: float, mode: int,
                  periodic: bool, progress: Callable[[float, float], None] | None,
                  onset: tuple[int, int, float] | None = None, t0: float = 0.0,
                  energy0: float | None = None) -> tuple[Floats, Floats, Floats, float, int, int, float, int]:
    """(X, V, E, drift, steps, force evaluations, max compression, onset corrections) of a splitting run
    from (x0, v0) at ``t0`` with step bound ``dt``; ``onset`` overrides :data:`ONSET_OPTIONS`."""
    check_steps(t0, t_out, dt)
    corrected = method in CORRECTED_METHODS
    a, b, _order = SPLITTINGS[CORRECTED_METHODS.get(method, method)]
    N = x0.size
    T = t_out.size
    if t_out[0] == t0:
        tgrid, shift = t_out, 0
    else:
        tgrid, shift = np.concatenate(([t0], t_out)), 1
    X = np.empty((T, N))
    V = np.empty((T, N))
    E = np.empty(T)
    x = x0.copy()
    v = v0.copy()
    F = np.empty(N)
    correction: _splitting.NoCorrection | _onset.OnsetCorrection
    if corrected:
        variant, n_iter, near = ONSET_OPTIONS if onset is None else onset
        correction = _onset.onset_correction(x, v, a, variant, n_iter, near)
        f = correction.fs[-1]
    else:
        correction = _splitting.NoCorrection(np.empty(N))
        f = correction.f
    pot, c0 = K.forces(x, f, F, alpha, mode, periodic)
    H0 = 0.5 * float(np.dot(x, x) + np.dot(v, v)) + pot
    if shift == 0:
        X[0], V[0], E[0] = x, v, H0
    # drift measured from energy0 (the energy at the start of the run being continued) if given
    stats = np.array([H0 if energy0 is None else float(energy0), 0.0, c0, H0])
    counts = np.array([0, 1, 0, 0, 0], dtype=np.int64)
    nint = tgrid.size - 1
    k, j = 0, 0
    t_final = float(tgrid[-1])
    if progress is None:
        budget = np.iinfo(np.int64).max
    else:  # first chunk ~0.2 s at ~4 ns per bond evaluation
        budget = max(1, int(5e7 / (N * a.size)))
    while k < nint:
        t0 = time.perf_counter()
        n_before = counts[0]
        k, j = _splitting.split_run(correction, x, v, F, tgrid, float(dt), k, j, budget, a, b, alpha, mode, periodic,
                                    X, V, E, shift, stats, counts)
        if progress is not None:
            elapsed = time.perf_counter() - t0
            taken = int(counts[0] - n_before)
            if elapsed > 0 and taken > 0:
                budget = max(1, int(taken / elapsed))  # ~1 s per chunk
            if k < nint:
                length = tgrid[k + 1] - tgrid[k]
                nk = max(1, math.ceil(length / dt * (1.0 - 1e-12)))
                t_reached = float(tgrid[k] + j * length / nk)
            else:
                t_reached = t_final
            progress(t_reached, t_final)
    return X, V, E, float(stats[1]), int(counts[0]), int(counts[1]), float(stats[2]), int(counts[2])
