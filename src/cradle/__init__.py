"""cradle: the numerical results of G. James, *Nonlinear waves in Newton's cradle
and the discrete p-Schrödinger equation*, rebuilt and extended.

Sub-packages, one layer each:

* :mod:`cradle.models`       - the paper's objects: the lattice (nc)/(ham), the DpS equation (dfnls),
  the stationary problem (dpsstn) and its map G (comp1)-(comp2), homoclinics, initial data
  (ansatzapprox)/(perturb)/(ansatzapproxst2), the exact travelling waves of (ad)
* :mod:`cradle.integrators`  - time integration of (nc) and (dfnls), compiled kernels
* :mod:`cradle.measurements` - measurements on runs: (ansatz), E(t), spectra on Gamma*, breathers
* :mod:`cradle.analyses`     - beyond the paper: theorem1, modulational instability, Floquet,
  work-precision, and the paper's claims table
* :mod:`cradle.pipeline`     - config, stages, runner, netCDF io, provenance, code dependencies, CLI
* :mod:`cradle.figures`      - one drawing function per figure label, from stored data
"""
from cradle.data.provenance import VERSION as __version__


def __getattr__(name):
    # cradle.open_scene without importing xarray at `import cradle` (the Snakefile imports cradle.pipeline.config)
    if name == "open_scene":
        from cradle.pipeline.outputs import open_scene

        return open_scene
    raise AttributeError(f"module 'cradle' has no attribute {name!r}")
