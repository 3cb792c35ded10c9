"""Compile every kernel a scene's job uses, once, before the jobs that use them start.

On an empty compiled-kernel cache (:mod:`cradle.integrators._cache`) the first jobs that
integrate would each compile the same kernels at the same time, one per core. The workflow's
``kernels`` job calls :func:`compile_kernels` first instead (while the other core solves the
stage-1 problems), and the scene jobs then load the compiled code. What it compiles: the default
splitting for (nc) (``srkn6c``, with its onset correction) on a ring and on a free chain, and the
DpS integrator (``dop853_numba``, dfnls) on both; one step each on a few beads.
"""
from __future__ import annotations

import numpy as np


def compile_kernels() -> str:
    """Run each kernel once on tiny data (compiling it, or loading it from the cache); returns the
    cache key of the kernels' sources (:func:`cradle.integrators._cache.cache_key`)."""
    from cradle.integrators import _cache, integrate_dps, integrate_lattice

    n = np.arange(8)
    for bc in ("periodic", "free"):
        integrate_lattice(0.1 * np.cos(np.pi / 4 * n), 0.1 * np.sin(np.pi / 4 * n), [0.0, 0.5], alpha=1.5, bc=bc)
        integrate_dps(0.1 * np.exp(1j * np.pi / 4 * n), [0.0, 0.5], alpha=1.5, bc=bc)
    return _cache.cache_key()[0]
