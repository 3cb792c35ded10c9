"""One interaction run of two breathers in both models, (nc) and (dfnls)/(ansatz), classified by
:mod:`cradle.measurements.interactions` (figure loc1; the `breather-interactions` analysis and
benchmarks/loc1_readings.py).

Both models start from the same :class:`cradle.models.initial.InitialData` (the DpS
from tau = 0 in (breatherdps)); the bond forces are stored every ``every`` time
units (about 11 samples per breather period at the default 0.5, enough for the
peak compression of each period) and only the outcome is kept.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.measurements import compare, interactions
from cradle.models import lattice

if TYPE_CHECKING:
    from collections.abc import Iterable

    from numpy.typing import NDArray

    from cradle.models.initial import InitialData

MODELS = ("exact", "dps")
EVERY = 0.5          # stored time step of the forces (breather period 2 pi / 1.1 = 5.7)
DPS_RTOL = 1e-9      # DOP853 tolerance of (dfnls): merging times agree with 1e-10 to the period
NEAR = 3             # the largest breather's norm: sites within 3 of its centre


def norm_density(model: str, x: NDArray[np.float64] | None = None, v: NDArray[np.float64] | None = None,
                 A: NDArray[np.complex128] | None = None) -> NDArray[np.float64]:
    """Norm density per site: |A_n|^2 (DpS, conserved sum) or (x_n^2 + v_n^2)/4 for the lattice (the
    same quantity through the ansatz x_n = 2 Re(A_n e^{it}) at leading order)."""
    if model == "dps":
        return np.abs(A) ** 2  # type: ignore[arg-type]  # the DpS model's A given
    return 0.25 * (x ** 2 + v ** 2)  # type: ignore[operator]  # the lattice's x, v given


def largest_share(rho: NDArray[np.float64], centre_site: float, N: int, periodic: bool = True) -> float:
    """Share of sum rho held by the sites within NEAR of ``centre_site``."""
    n = np.arange(N)
    d = np.abs(n - centre_site)
    if periodic:
        d = np.minimum(d, N - d)
    total = float(rho.sum())
    return float(rho[d <= NEAR].sum() / total) if total > 0 else float("nan")


def run_pair(data: InitialData, t_end: float, alpha: float = 1.5, bc: str = "periodic", models: Iterable[str] = MODELS,
             every: float = EVERY, method: str = "srkn6c", dps_rtol: float = DPS_RTOL,
             keep: bool = False) -> dict[str, dict]:
    """Integrate ``data`` (InitialData) to ``t_end`` in each of ``models``; per model a dict with the
    :class:`~cradle.measurements.interactions.Outcome`, the share of the norm held by the largest
    breather at the start and the end (norm_share_0, norm_share_end) and the wall time; with ``keep``
    also t, x and force."""
    from cradle.integrators import integrate_dps, integrate_lattice

    N = data.x0.size
    periodic = bc == "periodic"
    period = 2.0 * np.pi / float(data.info["omega_sw"])
    times = np.arange(0.0, t_end + 1e-9, every)
    out = {}
    for model in models:
        if model == "exact":
            lat = integrate_lattice(data.x0, data.v0, times, alpha=alpha, bc=bc, method=method)
            x = lat.x
            rho0 = norm_density(model, x=x[0], v=lat.v[0])
            rho1 = norm_density(model, x=x[-1], v=lat.v[-1])
            wall = lat.wall_time_s
        else:
            sol = integrate_dps(data.A0, times * data.eps ** (alpha - 1.0), alpha=alpha, bc=bc,
                                method="dop853_numba", rtol=dps_rtol)
            x = compare.approximate_displacement(sol.A, times, data.eps)
            rho0, rho1 = norm_density(model, A=sol.A[0]), norm_density(model, A=sol.A[-1])
            wall = sol.wall_time_s
        oc = interactions.classify(times, x, period, periodic=periodic)
        c0 = oc.centre[0] if oc.centre.size else np.nan
        c1 = oc.centre[-1] if oc.centre.size else np.nan
        res = {"outcome": oc, "norm_share_0": largest_share(rho0, c0, N, periodic),
               "norm_share_end": largest_share(rho1, c1, N, periodic), "wall_time_s": float(wall),
               "periods": float(times[-1] / period)}
        if keep:
            res.update({"t": times, "x": x, "force": lattice.bond_forces(x, alpha, bc)})
        out[model] = res
    return out
