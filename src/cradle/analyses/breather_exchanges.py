"""Where the exact breathers of (nc) exchange stability: zeros in omega_b of the pinning exponent.

The pinning (symmetry-breaking) Floquet pair of a breather is either real, mu = e^{+-lambda T} (unstable,
growth lambda), or on the unit circle, mu = e^{+-i nu T} (stable). The signed quantity

    sigma(omega_b) = +lambda^2  or  -nu^2

is smooth through a stability exchange (the pair passes through +1), so its zeros between grid points
of a family are found by regula falsi, each new breather continued (Newton, DpS-scaled predictor) from
the nearer grid breather. DpS (dfnls) is homogeneous and has no exchange: sigma_DpS keeps its sign.

Each exchange rests on the verdicts of the two grid breathers around it, and a verdict on a pinning
multiplier a little off +1: :func:`refine` stores, per exchange and side, the verdict, |mu - 1| of the
pinning multiplier and beside it the trivial pair's defect (exactly 0, so its size is the precision of a
multiplier near +1), then the same re-solved at the finer tolerance ``check_rtol`` on a ring
:data:`REFINE_RING` times larger (a free chain keeps its length: its ends are part of the problem), and
whether the refined verdicts are the same.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.breathers_spec import Breathers
from cradle.data.variables import Var

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from cradle.analyses.protocol import Log
    from cradle.integrators.lattice_breathers import Breather, Floquet

VARIABLES = {
    "/exchanges": {
        "exchange": Var(("exchange",), "index of a stability exchange (pinning pair through +1)"),
        "omega_exchange": Var(("exchange",), "omega_b of the stability exchange"),
        "omega_halfwidth": Var(("exchange",), "half-width of the final bracket of omega_exchange"),
        "family_exchange": Var(("exchange",), "family index of the exchange (names in family_names)"),
        "side": Var(("side",), "grid breather below or above the exchange in omega_b"),
        "omega_side": Var(("exchange", "side"), "omega_b of the grid breather on that side of the exchange"),
        "unstable_side": Var(("exchange", "side"), "stability verdict: 1 if the pinning pair is real (unstable), "
                             "0 if on the unit circle", attrs=(("flag_values", (0.0, 1.0)),
                                                               ("flag_meanings", "stable unstable"))),
        "pinning_offset": Var(("exchange", "side"), "|mu - 1| of the pinning multiplier (symmetry-breaking, "
                              "nearest +1)"),
        "pinning_precision": Var(("exchange", "side"), "trivial-pair defect max |mu - 1| of the same breather",
                                 attrs=(("comment", "the trivial pair is exactly +1: its defect is the precision "
                                                    "of a multiplier near +1, hence of pinning_offset"),)),
        "unstable_refined": Var(("exchange", "side"), "the verdict of the breather re-solved at check_rtol on "
                                "the larger ring (refined_N)", attrs=(("flag_values", (0.0, 1.0)),
                                                                      ("flag_meanings", "stable unstable"))),
        "pinning_offset_refined": Var(("exchange", "side"), "|mu - 1| of the pinning multiplier, refined"),
        "pinning_precision_refined": Var(("exchange", "side"), "trivial-pair defect, refined"),
        "refined_N": Var(("exchange",), "beads of the lattice of the refined check (a ring REFINE_RING times "
                         "larger; a free chain its own length)"),
        "refined_agrees": Var(("exchange",), "1 if the refined check gives both verdicts of the exchange, else 0"),
    },
}

#: the refined check of an exchange's verdicts runs on a ring this many times larger (rounded up to even)
REFINE_RING = 1.5


def sigma(fl: Floquet, T: float) -> float:
    """+lambda^2 (real pinning pair) or -nu^2 (pair on the unit circle), per unit t squared."""
    if fl.mu_odd.size == 0:
        return float("nan")
    z = np.log(fl.mu_odd[int(np.argmin(np.abs(fl.mu_odd - 1.0)))])
    return float((z.real / T) ** 2 - (z.imag / T) ** 2)


def locate(fam: list[Breather], floquets: dict[tuple[str, float], Floquet], name: str, kind: str, centre: int,
           spec: Breathers, say: Log, steps: int) -> list[tuple[float, float]]:
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


def _pinning(fl: Floquet) -> float:
    """|mu - 1| of the symmetry-breaking multiplier nearest +1."""
    return float(np.min(np.abs(fl.mu_odd - 1.0))) if fl.mu_odd.size else float("nan")


def _embedded(b: Breather, kind: str, centre: int, N_new: int, centre_new: int) -> NDArray[np.float64]:
    """The breather's x(0) moved onto a lattice of N_new beads, its centre bead to centre_new, zeros elsewhere
    (the beads beyond the core are below the shooting's core cut)."""
    x = np.zeros(N_new)
    x[np.arange(b.x0.size) + (centre_new - centre)] = b.x0
    return x


def refine(fam: list[Breather], floquets: dict[tuple[str, float], Floquet], name: str, kind: str, centre: int,
           exchanges: list[tuple[float, float]], spec: Breathers, say: Log) -> list[dict]:
    """Per exchange (omega, half-width) of one family: the verdict, pinning offset |mu - 1| and trivial defect
    of the grid breathers on both sides, and the same re-solved (Newton from the embedded x(0)) and measured
    at ``spec.check_rtol`` on a ring REFINE_RING times larger (free chain: same length)."""
    from cradle.integrators import lattice_breathers as lb

    bc = fam[0].bc
    N = fam[0].x0.size
    N_new = N if bc == "free" else 2 * int(np.ceil(REFINE_RING * N / 2))
    c_new = centre + (N_new - N) // 2
    done: dict[float, tuple] = {}

    def refined(b: Breather) -> tuple:
        if b.omega not in done:
            x = _embedded(b, kind, centre, N_new, c_new)
            b2 = lb.newton(x, b.omega, b.alpha, bc, kind, c_new, spec.newton_tol, rtol=spec.check_rtol)
            fl2 = lb.floquet(b2, kind, c_new, spec.check_rtol) if b2.converged else None
            done[b.omega] = ((float(sigma(fl2, b2.T) > 0), _pinning(fl2), fl2.trivial) if fl2 is not None
                             else (np.nan, np.nan, np.nan))
        return done[b.omega]

    out = []
    for om, _hw in exchanges:
        i = max(k for k in range(len(fam) - 1) if fam[k].omega < om)
        row: dict = {"refined_N": N_new}
        for key in ("omega_side", "unstable_side", "pinning_offset", "pinning_precision", "unstable_refined",
                    "pinning_offset_refined", "pinning_precision_refined"):
            row[key] = []
        for b in (fam[i], fam[i + 1]):
            fl = floquets[(name, b.omega)]
            row["omega_side"].append(b.omega)
            row["unstable_side"].append(float(sigma(fl, b.T) > 0))
            row["pinning_offset"].append(_pinning(fl))
            row["pinning_precision"].append(fl.trivial)
            for key, v in zip(("unstable_refined", "pinning_offset_refined", "pinning_precision_refined"),
                              refined(b), strict=True):
                row[key].append(v)
        row["refined_agrees"] = float(row["unstable_side"] == row["unstable_refined"])
        say(f"breathers: {name}: exchange at {om:.6f}: verdicts {row['unstable_side']} with pinning |mu - 1| "
            f"{row['pinning_offset'][0]:.2g}, {row['pinning_offset'][1]:.2g} (trivial defect "
            f"{row['pinning_precision'][0]:.2g}, {row['pinning_precision'][1]:.2g}); refined (N = {N_new}, rtol "
            f"{spec.check_rtol:g}): {row['unstable_refined']}")
        out.append(row)
    return out
