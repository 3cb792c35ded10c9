"""Every stored variable and coordinate, declared once: dimensions, long name, units.

Writers never type a ``long_name`` or ``units``: :func:`cradle.io.make_dataset`
looks them up here (the xarray-simlab way), so all outputs agree. Everything in
the model is dimensionless (time in units of 1/omega_0 of the pendula,
displacements in units of the Hertz length), hence units "1".
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Var:
    dims: tuple[str, ...]
    long_name: str
    units: str = "1"


VARIABLES: dict[str, Var] = {
    # coordinates
    "n": Var(("n",), "bead index (bond n joins beads n and n+1)"),
    "t": Var(("t",), "dimensionless time t of (nc)"),
    "tau": Var(("t",), "slow time tau = eps^(alpha-1) t of (dfnls)"),
    "k": Var(("k",), "wavenumber k in Gamma* of the spatial DFT"),
    "iterate": Var(("iterate",), "iteration index j of the map G (comp1)-(comp2)"),
    "orbit": Var(("orbit",), "orbit number"),
    # lattice (nc)
    "x": Var(("t", "n"), "bead displacement x_n(t)"),
    "v": Var(("t", "n"), "bead velocity dx_n/dt"),
    "force": Var(("t", "n"), "contact force V0'(x_{n+1}-x_n) on bond n"),
    "energy": Var(("t",), "lattice Hamiltonian (ham)"),
    # DpS (dfnls)
    "A_re": Var(("t", "n"), "real part of the DpS amplitude A_n(tau)"),
    "A_im": Var(("t", "n"), "imaginary part of the DpS amplitude A_n(tau)"),
    "l2_drift": Var(("t",), "relative drift of sum |A_n|^2 since tau = 0"),
    "dps_energy_drift": Var(("t",), "relative drift of the DpS Hamiltonian H since tau = 0"),
    "P_drift": Var(("t",), "drift of P = sum A_n since tau = 0, relative to max |A_n(0)|"),
    # initial data
    "x0": Var(("n",), "initial displacement x_n(0)"),
    "v0": Var(("n",), "initial velocity dx_n/dt(0)"),
    "A0_re": Var(("n",), "real part of A_n(0)"),
    "A0_im": Var(("n",), "imaginary part of A_n(0)"),
    "rho1": Var(("n",), "noise rho_n^(1) of (perturb)"),
    "rho2": Var(("n",), "noise rho_n^(2) of (perturb)"),
    # stationary DpS (dpsstn) and the map G
    "a": Var(("n",), "solution a_n of the stationary DpS equation (dpsstn)"),
    "residual_n": Var(("n",), "residual of (dpsstn) at site n"),
    "map_a": Var(("orbit", "iterate"), "a_j along an orbit of G"),
    "map_b": Var(("orbit", "iterate"), "b_{j+1} along an orbit of G"),
    # comparison metrics
    "E": Var(("t",), "relative error E(t) = ||x^app(t) - x(t)||_inf / a (plot4-5)"),
    "spectrum_exact": Var(("t", "k"), "|x_hat_k(t)| of the exact solution"),
    "spectrum_dps": Var(("t", "k"), "|x_hat_k(t)| of the approximate solution"),
}


def declared(name: str) -> Var:
    """The declaration of ``name``; a KeyError names the undeclared variable."""
    try:
        return VARIABLES[name]
    except KeyError:
        raise KeyError(f"variable {name!r} is not declared in cradle.variables.VARIABLES") from None
