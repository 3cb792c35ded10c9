"""cradle: the numerical results of G. James, *Nonlinear waves in Newton's cradle
and the discrete p-Schrödinger equation*, rebuilt and extended.

Modules, each named after what it computes:

* :mod:`cradle.lattice`     - the lattice (nc), Hertz potential (vhertz), energy (ham)
* :mod:`cradle.dps`         - the DpS equation (dfnls), tau0 (tau0), plane waves (ansatz3)/(ds)/(freq)
* :mod:`cradle.stationary`  - the map G (comp1)-(comp2) of the stationary DpS equation (dpsstn)
* :mod:`cradle.homoclinic`  - homoclinic (breather) solutions of (dpsstn)
* :mod:`cradle.initial`     - initial conditions (ansatzapprox), (perturb), (ansatzapproxst2)
* :mod:`cradle.integrators` - time integration of (nc) and (dfnls)
* :mod:`cradle.compare`     - the approximate solution (ansatz), E(t), spatial DFT on Gamma*
* :mod:`cradle.variables`   - names, long names and units of every stored variable
* :mod:`cradle.io`          - self-describing netCDF output
* :mod:`cradle.config`      - config schema and physical validation
* :mod:`cradle.figures`     - one function per paper figure
"""
from importlib.metadata import PackageNotFoundError, version as _version

try:
    __version__ = _version("cradle")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0.0.0+unknown"


def __getattr__(name):
    # cradle.open_scene without importing xarray at `import cradle` (the Snakefile imports cradle.config)
    if name == "open_scene":
        from .io import open_scene

        return open_scene
    raise AttributeError(f"module 'cradle' has no attribute {name!r}")
