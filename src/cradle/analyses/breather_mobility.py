"""Mobility and instability of the exact breathers of (nc), measured in direct lattice runs.

* Kicked breather: the exact ring breather of the ``kick_family`` at omega_b = ``kick_omega`` is given a
  velocity kick along its pinning mode (the symmetry-breaking Floquet mode with multiplier nearest +1;
  from the real span of that eigenvector, the combination with no displacement part, normalised to
  sum v^2 = 1), v(0) = kick * max|x0| * e, for each kick size; the run (integrate_lattice, srkn6c) gives
  the position of the energy centre X(t) (circular mean of the site energies on the ring), its velocity
  (least-squares slope over the second half of the run) and the radiation loss (fraction of the energy
  farther than ``kick_window`` beads from X at the end).
* Direct growth: the unstable ring breather at ``direct_omega`` (default: the most unstable one) is seeded
  along the eigenvector of its largest multiplier (relative size 1e-6: well above the integration noise
  ~1e-13 per period, well below nonlinearity at the end) and run (dop853_numba) until the
  mode should have grown by ``direct_growth_factor``; the growth rate fitted on the projection of
  z(kT) - z(0) on the left eigenvector is set beside ln|mu| / T (as the floquet analysis does for the
  travelling waves).
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from cradle.analyses.breathers_spec import Breathers
from cradle.data.variables import Var

if TYPE_CHECKING:
    from numpy.typing import ArrayLike, NDArray

    from cradle.analyses.protocol import Log
    from cradle.integrators.lattice_breathers import Breather, Floquet

VARIABLES = {
    "/kick": {
        "kick": Var(("kick",), "kick size: velocity along the pinning mode / max|x(0)|"),
        "velocity": Var(("kick",), "velocity of the kicked breather's energy centre (beads per unit t)"),
        "radiation": Var(("kick",), "fraction of the energy farther than kick_window beads from the centre at the end"),
        "energy_drift": Var(("kick",), "relative energy drift of the kicked run"),
    },
    "/direct": {
        "t_direct": Var(("t_direct",), "time of a sample of the direct run (multiples of T)"),
        "deviation": Var(("t_direct",), "|l . (z(t) - z_breather(t))|: the deviation of the run seeded along the "
                         "unstable mode, projected on its left eigenvector l"),
    },
}


def _centre(e: ArrayLike, N: int) -> NDArray[np.float64]:
    """Circular mean position of the energy density e_n on a ring of N beads."""
    ang = 2 * np.pi * np.arange(N) / N
    return np.angle(np.sum(e * np.exp(1j * ang), axis=-1)) * N / (2 * np.pi)


def _site_energy(x: NDArray[np.float64], v: NDArray[np.float64], alpha: float) -> NDArray[np.float64]:
    d = np.roll(x, -1, axis=-1) - x
    bond = np.maximum(-d, 0.0) ** (alpha + 1) / (alpha + 1)
    return 0.5 * (v**2 + x**2) + 0.5 * (bond + np.roll(bond, 1, axis=-1))


def kicked(b: Breather, fl: Floquet, kicks: list[float], t_end: float, window: float, alpha: float,
           n_out: int = 401) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Velocity, radiation fraction and energy drift of the breather ``b`` kicked along its pinning mode."""
    from cradle.integrators import integrate_lattice

    N, nc = b.x0.size, fl.core.size
    X = fl.pin[:nc]                       # displacement parts of the real span of the pinning eigenvector
    _, _, Vt = np.linalg.svd(X)
    e = fl.pin @ Vt[-1]                   # the combination with the smallest displacement part
    kick_dir = np.zeros(N)
    kick_dir[fl.core] = e[nc:]
    kick_dir /= np.linalg.norm(kick_dir)
    if np.dot(kick_dir, np.arange(N) - N / 2) < 0:
        kick_dir = -kick_dir              # a positive kick pushes towards larger n
    t_out = np.linspace(0.0, t_end, n_out)
    vel, rad, drift = (np.full(len(kicks), np.nan) for _ in range(3))
    for i, k in enumerate(kicks):
        sol = integrate_lattice(b.x0, k * b.amplitude * kick_dir, t_out, alpha=alpha, bc=b.bc, method="srkn6c")
        xs, vs = np.asarray(sol.x), np.asarray(sol.v)
        E = _site_energy(xs, vs, alpha)
        c = np.unwrap(_centre(E, N) * 2 * np.pi / N) * N / (2 * np.pi)
        half = t_out >= 0.5 * t_end
        vel[i] = float(np.polyfit(t_out[half], c[half], 1)[0])
        dist = np.abs((np.arange(N) - c[-1] + N / 2) % N - N / 2)
        rad[i] = float(np.sum(E[-1][dist > window]) / np.sum(E[-1]))
        drift[i] = float(sol.energy_drift) if hasattr(sol, "energy_drift") else np.nan
    return vel, rad, drift


def direct_growth(b: Breather, growth_factor: float, rel_size: float = 1e-6,
                  rtol: float = 1e-13) -> tuple[float, float, np.ndarray, np.ndarray]:
    """(rate fitted on the run, Floquet rate ln|mu| / T, t, |c_k|) for the breather ``b`` seeded along the
    eigenvector of its largest multiplier mu (core monodromy of :func:`lattice_breathers.monodromy`).

    The deviation delta(kT) = z(kT) - z(0) is projected on the left eigenvector l of mu: c_k = l . delta(kT)
    grows like mu^k, free of the secular drift of the trivial (Jordan) pair that |delta| also holds
    (a phase drift from the finite accuracy of omega_b); the rate is fitted on log|c_k| over the second
    half of the samples."""
    from cradle.integrators import integrate_lattice, lattice_breathers as lb

    N = b.x0.size
    M, _, idx = lb.monodromy(b, rtol)
    mu, V = np.linalg.eig(M)
    i = int(np.argmax(np.abs(mu)))
    rate = float(np.log(np.abs(mu[i])) / b.T)
    left = np.linalg.inv(V)[i]
    vec = V[:, i].real if np.linalg.norm(V[:, i].real) > 0.3 else V[:, i].imag
    vec = vec / np.linalg.norm(vec)
    nc = idx.size
    dx, dv = np.zeros(N), np.zeros(N)
    dx[idx], dv[idx] = vec[:nc], vec[nc:]
    s = rel_size * b.amplitude
    n_per = int(np.ceil(np.log(growth_factor) / (rate * b.T)))
    t_out = b.T * np.arange(n_per + 1)
    sol = integrate_lattice(b.x0 + s * dx, s * dv, t_out, alpha=b.alpha, bc=b.bc, method="dop853_numba",
                            rtol=rtol, atol=rtol * b.amplitude * 1e-3)
    xs, vs = np.asarray(sol.x), np.asarray(sol.v)
    delta = np.concatenate([xs[:, idx] - b.x0[idx], vs[:, idx]], axis=1)
    proj = np.abs(delta @ left)
    sel = t_out >= 0.5 * t_out[-1]
    return float(np.polyfit(t_out[sel], np.log(proj[sel]), 1)[0]), rate, t_out, proj


def compute(families: dict, floquets: dict, spec: Breathers, alpha: float, say: Log, attrs: dict) -> dict:
    """The /kick and /direct groups of the `breathers` analysis (``spec``: its kick_* and direct_* keys) from
    the ring families ``families`` (name -> list of Breathers) and their Floquet results ``floquets``
    ((name, omega_b) -> Floquet); the scalar results go into ``attrs``."""
    import time

    groups: dict[str, tuple[dict[str, Any], dict[str, Any]]] = {}   # path -> (data_vars, coords)
    t0 = time.perf_counter()
    kicks = [float(k) for k in spec.kicks]
    fam_name = f"ring {spec.kick_family}"
    fam = [b for b in families.get(fam_name, []) if abs(b.omega - spec.kick_omega) < 1e-9]
    vel = rad = drift = np.full(len(kicks), np.nan)
    if kicks and fam:
        b = fam[0]
        fl = floquets[(fam_name, b.omega)]
        vel, rad, drift = kicked(b, fl, kicks, spec.kick_t_end, spec.kick_window, alpha)
        say(f"breathers: {fam_name} at omega_b = {b.omega}: kicks {kicks} -> velocities {np.round(vel, 6)}, "
            f"radiation {np.round(rad, 6)}")
    groups["/kick"] = ({"velocity": vel, "radiation": rad, "energy_drift": drift}, {"kick": kicks})
    attrs.update(kick_family=fam_name, kick_omega=spec.kick_omega, kick_t_end=spec.kick_t_end,
                 kick_window=spec.kick_window, kick_seconds=time.perf_counter() - t0)

    t0 = time.perf_counter()
    best = None
    for name, fam in families.items():
        if not name.startswith("ring"):
            continue
        for b in fam:
            if spec.direct_omega and abs(b.omega - spec.direct_omega) > 1e-9:
                continue
            fl = floquets[(name, b.omega)]
            if fl.rate > spec.stability_threshold and (best is None or fl.rate > best[1].rate):
                best = (b, fl, name)
    if best is not None and spec.direct_growth_factor > 1:
        b, fl, name = best
        r_run, r_fl, t, dev = direct_growth(b, spec.direct_growth_factor, rtol=spec.rtol)
        attrs.update(direct_family=name, direct_omega_b=b.omega, direct_rate_run=r_run, direct_rate_floquet=r_fl,
                     direct_rel_error=r_run / r_fl - 1.0)
        say(f"breathers: direct run of the {name} breather at omega_b = {b.omega:.4g}: growth {r_run:.6g} vs "
            f"Floquet {r_fl:.6g} ({r_run / r_fl - 1:+.2e})")
        groups["/direct"] = ({"deviation": dev}, {"t_direct": t})
    else:
        groups["/direct"] = ({"deviation": []}, {"t_direct": []})
    attrs["direct_seconds"] = time.perf_counter() - t0
    return groups
