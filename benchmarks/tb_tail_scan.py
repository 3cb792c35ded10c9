"""The signed tail of the lattice's travelling breathers along their branch in c (travelling-breathers.md, "where
the lattice's tail vanishes").

    python benchmarks/tb_tail_scan.py FULL.nc N MEMBER LOW HIGH STEP
    e.g. ... results/travelling-breathers/full/travelling-breathers.nc 24 eps 0.0015 0 0.0001
         ... results/travelling-breathers/full/travelling-breathers.nc 24 family -0.003 0.003 0.0002

From a stored TB of a full form's /lattice_rings (MEMBER ``eps``: the one at lattice_zero_eps on the ring of N;
``family``: the continuation's member at lattice_zero_step), Newton at its period (converged at once: the tangent),
then the continuation in c (plain corrector) down to c1 (1 + LOW) and up to c1 (1 + HIGH) in steps of STEP, c1 its
velocity; one line per member: c, its relative change, T, eps, the residual, the max-based tail, the signed tail
sigma of cradle.integrators.lattice_tail with its phase defect, and the largest multiplier modulus. CPU: about 3 s a
member on 24 sites, 15 s on 48, on the shared machine; run under nice.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from cradle.analyses import travelling_breathers as tb  # noqa: E402
from cradle.integrators import lattice_tail as LTail, lattice_travelling as LT  # noqa: E402
from cradle.models import dps_travelling as M  # noqa: E402
from cradle.specs.declare import from_plain  # noqa: E402


def start(path: str, N: int, member: str) -> tuple[LT.LatticeTB, tb.TravellingBreathers]:
    """The stored TB (MEMBER of the module docstring) on the ring of N, re-solved at its period for its tangent, and
    the spec of the declared defaults (the full form's keys)."""
    import xarray as xr

    tree = xr.open_datatree(path)
    spec = from_plain(tb.TravellingBreathers, {})
    r = tree["lattice_rings"].to_dataset()
    i = [int(n) for n in r["ring"].values].index(N)
    if member == "eps":
        j = [float(e) for e in r["eps_lattice"].values].index(float(spec.lattice_zero_eps))
        x, v, T = r["x"].values[i, j, :N], r["v"].values[i, j, :N], float(r["period"].values[i, j])
    else:
        j = [float(s) for s in r["c_step"].values].index(float(spec.lattice_zero_step))
        x, v, T = r["x_family"].values[i, j, :N], r["v_family"].values[i, j, :N], float(r["period_family"].values[i, j])
    b = LT.newton(np.concatenate([x, v]), T, spec.alpha, tol=spec.newton_tol)
    if not b.converged:
        raise SystemExit(f"the stored TB does not solve (tbnc) to newton_tol: residual {b.residual:.2g}")
    return b, spec


def main(argv: list[str]) -> None:
    path, N, member = argv[0], int(argv[1]), argv[2]
    low, high, step = (float(a) for a in argv[3:6])
    b, spec = start(path, N, member)
    members = [b]
    for grid in (np.arange(-step, low - 1e-12, -step), np.arange(step, high + 1e-12, step)):
        fam, _ = LT.continue_family(b, b.c * (1.0 + grid), spec.newton_tol, min_step=step / 8)
        members += fam
    print("c             rel       T           eps       residual  tail       sigma       phase     max|mu|")
    for m in sorted(members, key=lambda m: m.c):
        s = LTail.signed_tail(m.z, m.T, m.alpha)
        print(f"{m.c:.10f} {m.c / b.c - 1:+.5f} {m.T:.6f} {m.eps:.6f} {m.residual:.2e}  "
              f"{M.tail_amplitude(m.envelope):.3e}  {s.sigma:+.3e}  {s.phase_defect:+.1e}  "
              f"{float(np.max(np.abs(m.multipliers))):.6f}")


if __name__ == "__main__":
    main(sys.argv[1:])
