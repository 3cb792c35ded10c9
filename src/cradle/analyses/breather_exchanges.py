"""Where the exact breathers of (nc) exchange stability: zeros in omega_b of the pinning exponent.

The pinning (symmetry-breaking) Floquet pair of a breather is either real, mu = e^{+-lambda T} (unstable,
growth lambda), or on the unit circle, mu = e^{+-i nu T} (stable). The signed quantity

    sigma(omega_b) = +lambda^2  or  -nu^2

is smooth through a stability exchange (the pair passes through +1), so its zeros between grid points
of a family are found by regula falsi, each new breather continued (Newton, DpS-scaled predictor) from
the nearer grid breather. DpS (dfnls) is homogeneous and has no exchange: sigma_DpS keeps its sign.
"""
from __future__ import annotations

import numpy as np

from cradle.analyses.breathers_spec import Breathers
from cradle.data.variables import Var

VARIABLES = {
    "/exchanges": {
        "exchange": Var(("exchange",), "index of a stability exchange (pinning pair through +1)"),
        "omega_exchange": Var(("exchange",), "omega_b of the stability exchange"),
        "omega_halfwidth": Var(("exchange",), "half-width of the final bracket of omega_exchange"),
        "family_exchange": Var(("exchange",), "family index of the exchange (names in family_names)"),
    },
}


def sigma(fl, T) -> float:
    """+lambda^2 (real pinning pair) or -nu^2 (pair on the unit circle), per unit t squared."""
    if fl.mu_odd.size == 0:
        return float("nan")
    z = np.log(fl.mu_odd[int(np.argmin(np.abs(fl.mu_odd - 1.0)))])
    return float((z.real / T) ** 2 - (z.imag / T) ** 2)


def locate(fam, floquets, name, kind, centre, spec: Breathers, say, steps: int):
    """Zeros of sigma along one family (list of Breathers on the grid), refined by ``steps`` regula falsi steps
    (each breather solved with the spec's newton_tol and rtol). Returns a list of (omega, half-width)."""
    from cradle.integrators import lattice_breathers as lb

    rtol, tol = spec.rtol, spec.newton_tol
    sig = [sigma(floquets[(name, b.omega)], b.T) for b in fam]
    out = []
    for i in range(len(fam) - 1):
        if not (np.isfinite(sig[i]) and np.isfinite(sig[i + 1]) and sig[i] * sig[i + 1] < 0):
            continue
        lo, hi, slo, shi = fam[i], fam[i + 1], sig[i], sig[i + 1]
        for _ in range(steps):
            om = lo.omega + (hi.omega - lo.omega) * slo / (slo - shi)
            om = min(max(om, lo.omega + 0.02 * (hi.omega - lo.omega)), hi.omega - 0.02 * (hi.omega - lo.omega))
            near = lo if om - lo.omega < hi.omega - om else hi
            guess = ((om - 1.0) / (near.omega - 1.0)) ** (1.0 / (lo.alpha - 1.0)) * near.x0
            b = lb.newton(guess, om, lo.alpha, lo.bc, kind, centre, tol, rtol=rtol)
            if not b.converged:
                break
            s = sigma(lb.floquet(b, kind, centre, rtol), b.T)
            if s * slo < 0:
                hi, shi = b, s
            else:
                lo, slo = b, s
        out.append((0.5 * (lo.omega + hi.omega), 0.5 * (hi.omega - lo.omega)))
        say(f"breathers: {name}: stability exchange at omega_b = {out[-1][0]:.6f} +- {out[-1][1]:.1g}")
    return out
