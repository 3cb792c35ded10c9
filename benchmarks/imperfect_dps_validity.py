"""The sup error of (dpsimperfect) against the imperfect lattice (ncimperfect), as dps-validity defines it, for a
disordered ring (detuning, masses, stiffnesses, quartic on-site) and a precompressed one, at a few eps; writes the
table of docs/imperfect-dps.md. Run:

    PYTHONPATH=src python benchmarks/imperfect_dps_validity.py [eps ...]

Lattice: integrate_lattice(..., terms=Terms(...)) (DOP853 in numba, rtol 1e-11), samples every 0.05. The
DpS coefficients are held fixed in slow units (delta_n, delta~) as eps varies, so that every eps describes the same
(dpsimperfect); masses, stiffnesses and the lattice's quartic beta are eps-independent (beta~ = omega_n^2 beta
eps^(3-alpha) shrinks with eps, as it must).
"""
import sys
import time

import numpy as np

from cradle.integrators import integrate_dps, integrate_lattice
from cradle.measurements.damped_validity import sup_error
from cradle.models import dps_sites as S
from cradle.models.inhomogeneity import Inhomogeneity
from cradle.models.lattice_terms import Terms
from cradle.models.onsite import OnSite
from cradle.models.precompression import Precompression
from doctable import publish

ALPHA, N, T = 1.5, 16, [0.5, 1.0, 2.0]
EPS = [float(e) for e in sys.argv[1:]] or [0.01, 0.005, 0.0025, 0.00125]
SEED = 2025
n = np.arange(N)
A0 = (1.0 + 0.3 * np.cos(2 * np.pi * n / N)) * np.exp(-1j * np.pi / 4 * n)
A0 /= np.max(np.abs(A0))
_rng = np.random.default_rng(SEED)
DETUNING = 0.3 * _rng.normal(size=N)          # delta_n, slow units: sigma = 0.3 eps^(alpha-1) in omega_n - 1
MASS = 1.0 + 0.1 * _rng.normal(size=N)
STIFFNESS = 1.0 + 0.2 * _rng.normal(size=N)
BETA = 20.0                                   # quartic W of the lattice (beta~ = 20 eps^(3/2) omega_n^2)
DELTA_SLOW = 1.0                              # precompression delta~ = delta0 / eps: contacts open and close

CASES = {
    "disordered": lambda eps: dict(omega=1.0 + DETUNING * eps ** (ALPHA - 1), mass=MASS, stiffness=STIFFNESS,
                                   beta=BETA, delta0=0.0),
    "precompressed": lambda eps: dict(omega=np.ones(N), mass=np.ones(N), stiffness=np.ones(N), beta=0.0,
                                      delta0=DELTA_SLOW * eps),
}


def terms_of(c) -> Terms:
    return Terms(inhomogeneity=Inhomogeneity(omega=tuple(c["omega"]), mass=tuple(c["mass"]),
                                             stiffness=tuple(c["stiffness"])),
                 precompression=Precompression(delta0=c["delta0"]),
                 onsite=OnSite(potential="quartic", beta=c["beta"]) if c["beta"] else OnSite())


rows = []
for case, build in CASES.items():
    for eps in EPS:
        c0 = time.perf_counter()
        c = build(eps)
        sites = S.dps_sites(c["mass"], c["omega"], c["stiffness"], alpha=ALPHA, eps=eps, beta=c["beta"],
                            delta0=c["delta0"])
        # well-prepared data: x = eps (A + c.c.), v = eps (i A + eps^(alpha-1) dA/dtau) + c.c.
        x0 = 2.0 * eps * A0.real
        v0 = 2.0 * eps * (1j * A0 + eps ** (ALPHA - 1) * S.rhs(A0, ALPHA, sites)).real
        t_end = max(T) * eps ** (1 - ALPHA)
        t = np.linspace(0.0, t_end, int(np.ceil(t_end / 0.05)) + 1)
        lat = integrate_lattice(x0, v0, t, alpha=ALPHA, method="dop853_numba", rtol=1e-11, terms=terms_of(c))
        dps = integrate_dps(A0, eps ** (ALPHA - 1) * t, alpha=ALPHA, rtol=1e-11, sites=sites)
        m = sup_error(t, lat.x, dps.A, eps, ALPHA, T, v=lat.v)
        plain = sup_error(t, lat.x, integrate_dps(A0, eps ** (ALPHA - 1) * t, alpha=ALPHA, rtol=1e-11).A, eps,
                          ALPHA, T)
        for i, Ti in enumerate(m["T"]):
            rows.append((case, eps, Ti, m["abs_error"][i], m["abs_error"][i] / eps**ALPHA, m["rel_error"][i],
                         m["velocity_abs_error"][i], plain["abs_error"][i],
                         max(dps.max_l2_drift, dps.max_energy_drift), float(lat.energy_drift)))
        print(f"{case} eps = {eps}: {time.perf_counter() - c0:.1f} s", flush=True)

head = ("| ring | eps | T | E_abs | E_abs / eps^alpha | E_rel = E_abs/(2 eps) | velocity E_abs | E_abs, (dfnls) | "
        "DpS invariants drift | lattice energy drift |\n|---|---|---|---|---|---|---|---|---|---|\n")
body = "".join(f"| {r} | {e:g} | {Ti:g} | {a:.3e} | {a_s:.3f} | {rel:.3e} | {ve:.3e} | {u:.3e} | {d:.1e} | "
               f"{ld:.1e} |\n" for r, e, Ti, a, a_s, rel, ve, u, d, ld in rows)
powers = []
for case in CASES:
    last = [r for r in rows if r[0] == case and r[2] == T[-1]]
    if len(last) > 1:
        for (_, e1, _, a1, *_), (_, e2, _, a2, *_) in zip(last[:-1], last[1:], strict=True):
            powers.append(f"{case}: {np.log(a1 / a2) / np.log(e1 / e2):.3f} between eps = {e1:g} and {e2:g}")
text = head + body + (f"\nPower of eps at T = {T[-1]:g} (alpha = {ALPHA}): " + "; ".join(powers) + ".\n")
print(text)
publish("imperfect-dps.md", "imperfect-dps-validity", text)
