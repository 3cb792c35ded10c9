"""Compile every kernel a scene's job uses, once, before the jobs that use them start.

On an empty compiled-kernel cache (:mod:`cradle.integrators._cache`) the first jobs that
integrate would each compile the same kernels at the same time, one per core. The workflow's
``kernels`` job calls :func:`compile_kernels` first instead (while the other core solves the
stage-1 problems), and the scene jobs then load the compiled code. What it compiles: the default
splitting for (nc) (``srkn6c``, with its onset correction) on a ring and on a free chain, and the
DpS integrator (``dop853_numba``, dfnls) on both; one step each on a few beads.
"""
from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np


def compile_kernels(progress: Callable[[str], object] | None = None) -> str:
    """Run each kernel once on tiny data (compiling it, or loading it from the cache); returns the
    cache key of the kernels' sources (:func:`cradle.integrators._cache.cache_key`). ``progress``, if
    given, gets one line before and one after each kernel: what it is, how far along, how long it took."""
    from cradle.integrators import _cache, integrate_dps, integrate_lattice

    n = np.arange(8)
    x0, v0, a0 = 0.1 * np.cos(np.pi / 4 * n), 0.1 * np.sin(np.pi / 4 * n), 0.1 * np.exp(1j * np.pi / 4 * n)

    def lattice() -> None:
        for bc in ("periodic", "free"):
            integrate_lattice(x0, v0, [0.0, 0.5], alpha=1.5, bc=bc)

    def dps() -> None:
        for bc in ("periodic", "free"):
            integrate_dps(a0, [0.0, 0.5], alpha=1.5, bc=bc)

    steps = [("the lattice (nc), splitting srkn6c with its onset correction", lattice),
             ("DpS (dfnls), dop853_numba", dps)]
    for i, (what, run) in enumerate(steps, 1):
        if progress:
            progress(f"kernel {i}/{len(steps)}: {what}: compiling on first use (the slow step of a first build), "
                     "or loading from the cache")
        start = time.perf_counter()
        run()
        if progress:
            progress(f"kernel {i}/{len(steps)} ready in {time.perf_counter() - start:.1f} s")
    return _cache.cache_key()[0]
