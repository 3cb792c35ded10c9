"""Time integration of Newton's cradle (nc)/(meca) and of the DpS equation (dfnls).

Public API
----------
:func:`integrate_lattice` -> :class:`LatticeSolution`
    (nc) with the Hertz potential (vhertz), or (meca) with kappa = 1
    ("smooth"), by symplectic splittings of the energy (ham) ("srkn6"
    default, "srkn4", "strang"; numba kernels, fixed step), by the same
    with the contact-onset correction ("srkn6c", "srkn4c": the fastest at
    equal accuracy, see :mod:`cradle.integrators._onset`), by scipy's
    adaptive solvers ("dop853", "rk45", "lsoda", "radau"; numba right-hand
    side) or by "dop853_numba" (DOP853 entirely in numba, for references);
    energy monitored after every step. With ``damping=Damping(...)``: the damped (ncdamped) by
    "dop853_numba" only, with its dissipated energy D integrated as a component of the state and
    the drift of H + D monitored (``LatticeSolution.dissipated``).
:func:`integrate_dps` -> :class:`DpsSolution`
    (dfnls) with scipy's DOP853 (numba right-hand side) or "dop853_numba";
    l2 norm, Hamiltonian and P = sum A_n monitored after every step. With
    ``damping=DpsDamping(...)``, the damped (dpsdamped) of
    :mod:`cradle.models.dps_damped` (:mod:`cradle.integrators.dps_damped_solver`),
    the dissipated amounts integrated with the run.

Helpers: :func:`omega_max`, :func:`compression_bounds`, :func:`default_dt`,
``DEFAULT_DT_FACTOR``, ``METHODS``, ``CORRECTED_METHODS``.

The (inteq) reduction x_n = (-1)^n a(t) (N even, periodic) and the plane
waves (ansatz3) of (dfnls) are used as exact references in
tests/test_integrators.py.
"""
from __future__ import annotations

from cradle.integrators.dps_solver import DPS_METHODS, DpsSolution, integrate_dps
from cradle.integrators.lattice_adaptive import ADAPTIVE_METHODS, SCIPY_METHODS
from cradle.integrators.lattice_solver import MAX_RERUNS, METHODS, LatticeSolution, integrate_lattice
from cradle.integrators.lattice_splitting import CORRECTED_METHODS, SPLITTING_METHODS
from cradle.integrators.lattice_step import compression_bounds
from cradle.models.lattice import DEFAULT_DT_FACTOR, default_dt, omega_max

__all__ = [
    "LatticeSolution",
    "DpsSolution",
    "integrate_lattice",
    "integrate_dps",
    "omega_max",
    "compression_bounds",
    "default_dt",
    "DEFAULT_DT_FACTOR",
    "MAX_RERUNS",
    "METHODS",
    "SPLITTING_METHODS",
    "CORRECTED_METHODS",
    "ADAPTIVE_METHODS",
    "SCIPY_METHODS",
    "DPS_METHODS",
]
