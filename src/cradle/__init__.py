"""cradle: the numerical results of G. James, *Nonlinear waves in Newton's cradle
and the discrete p-Schrödinger equation*, rebuilt and extended.

Sub-packages, one layer each, each importing only from the layers before it (docs/developing.md):

* :mod:`cradle.specs`        - the declaration kit of typed specs: parameters, shared types, one-line errors
* :mod:`cradle.data`         - self-describing netCDF: declared variables, atomic writes, checksummed reads
* :mod:`cradle.models`       - the paper's objects: the lattice (nc)/(ham), the DpS equation (dfnls),
  the stationary problem (dpsstn) and its map G (comp1)-(comp2), homoclinics, initial data
  (ansatzapprox)/(perturb)/(ansatzapproxst2), the exact travelling waves of (ad)
* :mod:`cradle.integrators`  - time integration of (nc) and (dfnls), compiled kernels
* :mod:`cradle.measurements` - measurements on runs: (ansatz), E(t), spectra on Gamma*, breathers
* :mod:`cradle.scenes`       - a scene: its spec (where it is validated) and its stages, from the homoclinic
  solution to the exact and DpS runs and their comparison
* :mod:`cradle.analyses`     - beyond the paper, one module per analysis (and the paper's claims table)
* :mod:`cradle.figures`      - drawing functions, from stored data
* :mod:`cradle.pipeline`     - config loading, results layout, jobs, budgets, code dependencies, CLI
"""
from cradle.data.provenance import VERSION as __version__

__all__ = ["__version__", "open_scene"]


def __getattr__(name):
    # cradle.open_scene without importing xarray at `import cradle` (the Snakefile imports cradle.pipeline.config)
    if name == "open_scene":
        from cradle.pipeline.outputs import open_scene

        return open_scene
    raise AttributeError(f"module 'cradle' has no attribute {name!r}")
