"""Exact breathers of the lattice (nc): families in omega_b, Floquet stability, Peierls-Nabarro barrier and
distance to the DpS breathers (ansatzapproxst2), against the DpS predictions.

The breathers and their multipliers are :mod:`cradle.integrators.lattice_breathers` (reversible shooting with
the variational equations, Newton continuation in omega_b from the DpS start); the DpS side is
:mod:`cradle.models.dps_breathers`; the kicked breather and the direct growth check are
:mod:`cradle.analyses.breather_mobility`. :func:`compute` stores them as a tree of netCDF groups
(:data:`VARIABLES`). Its spec is :class:`cradle.analyses.breathers_spec.Breathers` (config ``beyond:
breathers:``, a reduced form for ``all``); it reads no file.

Families (the ``family`` coordinate holds their names, as does the root attribute ``family_names``): site- and
bond-centred on the ring of N beads (plot18) and on the free-end chain of fini. Symmetry classes: (nc) is
invariant under x_n -> -x_{2c-n}; the bond breather has x(t) = -S x(t), the site breather x(t + T/2) = -S x(t).
"""
from __future__ import annotations

import time
from types import ModuleType
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.breather_exchanges import REFINE_RING, VARIABLES as _EXCHANGES
from cradle.analyses.breather_mobility import VARIABLES as _MOBILITY
from cradle.analyses.breathers_spec import Breathers
from cradle.analyses.protocol import Analysis
from cradle.data.variables import Var
from cradle.specs.declare import plain

if TYPE_CHECKING:
    import xarray as xr
    from numpy.typing import NDArray

    from cradle.analyses.protocol import Log

_F = ("family", "omega")
VARIABLES = {
    "/": {
        "family": Var(("family",), "breather family: ring site, ring bond (plot18), free bond (fini)"),
        "omega": Var(("omega",), "breather frequency omega_b of the continuation grid"),
        "N": Var(("family",), "number of beads of the family's lattice"),
    },
    "/families": {
        "converged": Var(_F, "1 where the exact breather was found (Newton converged), else 0"),
        "amplitude": Var(_F, "max_n |x_n(0)| of the exact breather"),
        "energy": Var(_F, "energy (ham) of the exact breather"),
        "action": Var(_F, "action J = int_0^T sum_n v_n^2 dt of the exact breather"),
        "action_check": Var(_F, "action of the breather re-solved with the finer tolerance (resolution check)"),
        "energy_check": Var(_F, "energy of the breather re-solved with the finer tolerance (resolution check)"),
        "profile_change": Var(_F, "max|x0 - x0_check| / max|x0|, x0_check re-solved with the finer tolerance"),
        "residual": Var(_F, "periodic-orbit residual max|z(T) - z(0)| / max|x(0)| over one period"),
        "residual_check": Var(_F, "the period residual of the breather re-solved with the finer tolerance"),
        "newton_iterations": Var(_F, "Newton iterations from the predictor"),
        "trivial_defect": Var(_F, "max |mu - 1| of the trivial Floquet pair (exactly 0; numerical error)"),
        "growth_rate": Var(_F, "max ln|mu| / T over the non-trivial Floquet multipliers (per unit t)",
                           attrs=(("comment", "0 (to round-off) where spectrally stable"),)),
        "unstable": Var(_F, "1 if growth_rate > stability_threshold (unstable), 0 if stable"),
        "odd_growing": Var(_F, "1 if the fastest-growing mode breaks the breather's symmetry (pinning mode)"),
        "pinning_exponent": Var(_F, "ln(mu) / T of the symmetry-breaking multiplier nearest +1: real part",
                                attrs=(("comment", "the pinning (translation) mode; real rate if unstable"),)),
        "pinning_frequency": Var(_F, "|arg mu| / T of the symmetry-breaking multiplier nearest +1"),
        "dps_growth_rate": Var(_F, "max Re lambda of the DpS breather of the same omega_b, per unit t"),
        "dps_pinning_exponent": Var(_F, "Re lambda of the DpS symmetry-breaking eigenvalue nearest 0"),
        "dps_pinning_frequency": Var(_F, "|Im lambda| of the DpS symmetry-breaking eigenvalue nearest 0"),
        "dps_distance": Var(_F, "max_n |x_n(0) - x_n^DpS(0)| / max|x(0)|, DpS breather of the same omega_b"),
        "omega_dps": Var(_F, "frequency of the DpS breather with the same amplitude max|x_n(0)|"),
        "tail_slope": Var(_F, "slope of ln(-ln(max_t|x_n| / max|x|)) against distance from the centre, over the "
                          "beads past the resolved core, in log variables (DpS: ln alpha)"),
    },
    "/profiles": {
        "n": Var(("n",), "bead index (ring families; free chains use the first N_free beads)"),
        "x0": Var(("family", "omega", "n"), "x_n(0) of the exact breather (v_n(0) = 0)"),
        "x0_dps": Var(("family", "omega", "n"), "x_n(0) of the DpS breather of the same omega_b"),
    },
    "/multipliers": {
        "m": Var(("m",), "index of a Floquet multiplier"),
        "mu_re": Var(("family", "omega", "m"), "real part of a Floquet multiplier of the exact breather"),
        "mu_im": Var(("family", "omega", "m"), "imaginary part of a Floquet multiplier of the exact breather"),
    },
    "/tails": {
        "j": Var(("j",), "distance from the breather's centre, beads (right tail)"),
        "log10_amplitude": Var(("family", "j"), "log10 max_t |x_n(t)| of the exact breather at pn_omega",
                               attrs=(("comment", ("from the trajectory where resolved, then the tail recursion "
                                                   "in log variables (cradle.integrators.lattice_breather_tails)")),)),
        "log10_amplitude_dps": Var(("family", "j"),
                                   "log10 |x_n(0)| of the DpS breather at pn_omega (homoclinic_tails)"),
    },
    "/pn": {
        "action_pn": Var(("action_pn",), "action J at which site and bond breathers of the ring are compared"),
        "barrier": Var(("action_pn",), "Peierls-Nabarro barrier E_bond - E_site at equal action, exact lattice"),
        "barrier_dps": Var(("action_pn",), "the DpS prediction of E_bond - E_site at equal action"),
        "barrier_uncertainty": Var(("action_pn",), "|barrier - barrier of the breathers re-solved with the finer "
                                   "tolerance| (resolution check)"),
        "omega_site": Var(("action_pn",), "omega_b of the site breather of that action"),
    },
    **_MOBILITY,
    **_EXCHANGES,
}


#: the refined-check variables of /exchanges and the shape of one exchange's value (per side, or one)
_CHECK_SHAPES: dict[str, tuple[tuple[int, ...], type]] = {
    k: ((2,), float) for k in ("omega_side", "unstable_side", "pinning_offset", "pinning_precision",
                               "unstable_refined", "pinning_offset_refined", "pinning_precision_refined")}
_CHECK_SHAPES.update({"refined_N": ((), int), "refined_agrees": ((), float)})


def _family_names(spec: Breathers) -> list[tuple[str, int, str, str]]:
    names = [(f"ring {k}", spec.N, "periodic", k) for k in spec.kinds]
    if spec.free_N > 0:
        names += [("free bond", spec.free_N, "free", "bond")]   # fini's; no site symmetry on an even chain
    return names


def _centre(N: int, bc: str) -> int:
    """Centre bead c of a family: N // 2 on the ring (as homoclinic.initial_guess), (N - 1) // 2 on a free
    chain (bond (c, c+1) in the middle: the free-bond entry of fini)."""
    return N // 2 if bc == "periodic" else (N - 1) // 2


def _profile(N: int, kind: str, alpha: float, bc: str) -> NDArray[np.float64]:
    from cradle.models import homoclinic

    sol = homoclinic.solve(homoclinic.initial_guess(N, kind, alpha, 0.1, centre=_centre(N, bc)), alpha, bc)
    if not sol.converged:
        raise RuntimeError(f"breathers: no DpS {kind} profile on N = {N} ({bc}), residual {sol.residual:.2g}")
    return sol.a


def _nearest_one(mu: NDArray[np.complex128], T: float) -> tuple[float, float]:
    if mu.size == 0:
        return np.nan, np.nan
    z = mu[int(np.argmin(np.abs(mu - 1.0)))]
    ln = np.log(z)
    return float(abs(ln.real) / T), float(abs(ln.imag) / T)


def compute(spec: Breathers, inputs: dict | None = None, log: Log | None = None) -> xr.DataTree:
    """The `breathers` analysis (:data:`VARIABLES`) from the spec of one form (it reads no file: ``inputs`` is
    empty); the kicked breather and the direct growth check by :func:`cradle.analyses.breather_mobility.compute`,
    the stability exchanges by :func:`cradle.analyses.breather_exchanges.locate`."""
    from cradle.data.io import make_tree
    from cradle.integrators import lattice_breather_tails as lbt, lattice_breathers as lb
    from cradle.models import dps_breathers as db, homoclinic_tails as ht

    t_start = time.perf_counter()
    say = log or (lambda *a: None)
    al = spec.alpha
    omegas = np.asarray(spec.omegas, float)
    fams = _family_names(spec)
    F, W, Nmax = len(fams), omegas.size, spec.N
    out = {k: np.full((F, W), np.nan) for k in VARIABLES["/families"]}
    out["converged"][:] = 0
    x0s, x0d = np.full((F, W, Nmax), np.nan), np.full((F, W, Nmax), np.nan)
    mus = np.full((F, W, 2 * Nmax), np.nan, complex)
    ends, timings, keep, floquets, exchanges = {}, {}, {}, {}, []
    checks: list[dict] = []       # the refined verdicts of each exchange (breather_exchanges.refine)
    n_tails = [(N // 2 - 1 if bc == "periodic" else N - 1 - _centre(N, bc)) for _, N, bc, _ in fams]
    tails, tails_d = np.full((F, max(n_tails)), np.nan), np.full((F, max(n_tails)), np.nan)
    for f, (name, N, bc, kind) in enumerate(fams):
        t0 = time.perf_counter()
        n_tail = n_tails[f]
        a = _profile(N, kind, al, bc)
        sym, c = kind, _centre(N, bc)
        fam, last = lb.continue_family(a, omegas, al, bc, sym, c, tol=spec.newton_tol, log=say)
        ends[name] = last
        odd_basis = None
        if sym is not None:
            S = lb.reflection(N, c + (0.5 if kind == "bond" else 0.0), bc)
            # symmetry-breaking DpS modes: S-odd for the (S-even) site profile, S-even for the bond one
            odd_basis = lb._eigenbasis(S, -1.0 if kind == "site" else 1.0)
        keep[name] = fam
        for b in fam:
            w = int(np.argmin(np.abs(omegas - b.omega)))
            res, J = lb.period_residual(b, spec.rtol)
            # resolution check: the breather re-solved (Newton from x0) and measured at the finer tolerance
            b2 = lb.newton(b.x0, b.omega, al, bc, sym, c, spec.newton_tol / 100, max_iter=3,
                           rtol=spec.check_rtol)
            res2, J2 = lb.period_residual(b2, spec.check_rtol)
            o = out
            o["energy_check"][f, w] = b2.energy()
            o["profile_change"][f, w] = float(np.max(np.abs(b2.x0 - b.x0)) / b.amplitude)
            o["converged"][f, w] = 1
            o["amplitude"][f, w], o["energy"][f, w], o["action"][f, w] = b.amplitude, b.energy(), J
            o["action_check"][f, w] = J2
            o["residual"][f, w], o["residual_check"][f, w], o["newton_iterations"][f, w] = res, res2, b.iterations
            xd = lb.dps_start(a, b.omega, al)
            x0s[f, w, :N], x0d[f, w, :N] = b.x0, xd
            o["dps_distance"][f, w] = float(np.max(np.abs(b.x0 - xd)) / b.amplitude)
            o["omega_dps"][f, w] = db.omega_of_amplitude(a, b.amplitude, al)
            cc_ = c + (0.5 if kind == "bond" else 0.0)
            _, lt_, first = lbt.log10_tail(b, cc_, n_tail, rtol=spec.rtol)
            o["tail_slope"][f, w] = lbt.double_exponential_slope(lt_, np.log10(b.amplitude), first)
            if abs(b.omega - spec.pn_omega) < 1e-9:
                tails[f, :n_tail] = lt_
                sc = np.log10(lb.dps_start(a, b.omega, al)[c] / a[c])
                ld = ht.log10_abs(a, al, centre=c) + sc
                first_d = c + 1                      # bead j = 1 of log10_tail (site and bond)
                seq = [ld[(first_d + i) % N] if bc == "periodic" else ld[first_d + i] for i in range(n_tail)]
                tails_d[f, :n_tail] = seq
            lam, lam_odd = db.stability(a, b.omega, al, bc, odd_basis)
            o["dps_growth_rate"][f, w] = float(np.max(lam.real))
            if lam_odd is not None:
                z = lam_odd[int(np.argmin(np.abs(lam_odd)))]
                o["dps_pinning_exponent"][f, w], o["dps_pinning_frequency"][f, w] = abs(z.real), abs(z.imag)
            if sym is not None:
                fl = lb.floquet(b, kind, c, spec.rtol)
                floquets[(name, b.omega)] = fl
                o["trivial_defect"][f, w], o["growth_rate"][f, w] = fl.trivial, fl.rate
                o["odd_growing"][f, w] = float(fl.odd_growing)
                o["pinning_exponent"][f, w], o["pinning_frequency"][f, w] = _nearest_one(fl.mu_odd, b.T)
                mus[f, w, :fl.mu.size] = fl.mu
                o["unstable"][f, w] = float(fl.rate > spec.stability_threshold)
        if sym is not None and spec.exchange_steps > 0:
            from cradle.analyses.breather_exchanges import locate, refine

            found = locate(fam, floquets, name, kind, c, spec, say, spec.exchange_steps)
            exchanges += [(f, *e) for e in found]
            t_refine = time.perf_counter()
            checks += refine(fam, floquets, name, kind, c, found, spec, say)
            timings[f"{name} refinement"] = time.perf_counter() - t_refine
        timings[name] = time.perf_counter() - t0
        if fam:
            om = [b.omega for b in fam]
            say(f"breathers: {name} (N = {N}): {len(fam)} breathers, omega_b in [{min(om):.4g}, {max(om):.4g}], "
                f"family ends at {last}; max residual {np.nanmax(out['residual'][f]):.2g} (finer "
                f"{np.nanmax(out['residual_check'][f]):.2g}, profile change "
                f"{np.nanmax(out['profile_change'][f]):.2g}), "
                f"max trivial defect "
                f"{np.nanmax(out['trivial_defect'][f]) if sym else float('nan'):.2g}; {timings[name]:.1f} s")

    # dE/dJ = omega_b / (2 pi) along each family: Delta E against Delta J / (2 pi) + int (omega_b - 1) dJ / (2 pi),
    # the integral with omega_b - 1 = c J^p through both ends of each grid interval (a check of E and J)
    dedj = []
    for f in range(F):
        ok = np.isfinite(out["action"][f])
        E, J, w = out["energy"][f][ok], out["action"][f][ok], omegas[ok] - 1.0
        for i in range(E.size - 1):
            p = np.log(w[i + 1] / w[i]) / np.log(J[i + 1] / J[i])
            integral = w[i] / J[i] ** p * (J[i + 1] ** (p + 1) - J[i] ** (p + 1)) / (p + 1)
            dedj.append(abs((J[i + 1] - J[i] + integral) / (2 * np.pi) / (E[i + 1] - E[i]) - 1.0))
    # Peierls-Nabarro barrier on the ring: E_bond - E_site at the site breather's action
    pn = _pn(out, fams, omegas, spec, al, db)
    groups = {
        "/": ({"N": np.array([n for _, n, _, _ in fams])}, {"family": [n for n, *_ in fams], "omega": omegas}),
        "/families": (out, {}),
        "/profiles": ({"x0": x0s, "x0_dps": x0d}, {"n": np.arange(Nmax)}),
        "/multipliers": ({"mu_re": mus.real, "mu_im": mus.imag}, {"m": np.arange(2 * Nmax)}),
        "/pn": pn[0],
        "/tails": ({"log10_amplitude": tails, "log10_amplitude_dps": tails_d}, {"j": np.arange(1, tails.shape[1] + 1)}),
        "/exchanges": ({"omega_exchange": [e[1] for e in exchanges], "omega_halfwidth": [e[2] for e in exchanges],
                        "family_exchange": [e[0] for e in exchanges],
                        **{k: np.array([r[k] for r in checks], dtype).reshape((len(checks), *shape))
                           for k, (shape, dtype) in _CHECK_SHAPES.items()}},
                       {"exchange": np.arange(len(exchanges)), "side": ["below", "above"]}),
    }
    fit = _distance_fit(out, omegas, spec)
    attrs = {"alpha": al, "family_names": ", ".join(n for n, *_ in fams),
             "family_ends": ", ".join(f"{k}: {v}" for k, v in ends.items()),
             "rtol": spec.rtol, "check_rtol": spec.check_rtol,
             "exchange_refinement": "each exchange's grid breathers re-solved from x(0) at check_rtol on a ring "
                                    f"{REFINE_RING:g} times larger (free chain: same length); verdicts by the sign "
                                    "of the pinning pair's sigma (breather_exchanges.sigma)",
             "stability_threshold": spec.stability_threshold,
             "pn_omega": spec.pn_omega, "pn_barrier_at_pn_omega": pn[1], "pn_barrier_dps_at_pn_omega": pn[2],
             "pn_energy_site_at_pn_omega": pn[3], "pn_barrier_uncertainty_at_pn_omega": pn[4],
             "dE_dJ_check": float(max(dedj)) if dedj else np.nan,
             "dE_dJ_check_comment": "max over grid intervals of |(Delta J + int (omega_b - 1) dJ) / (2 pi Delta E) "
                                    "- 1| (omega_b - 1 = c J^p through both ends: exact to O((omega_b - 1)^2) per "
                                    "interval)",
             "dps_distance_exponent": fit[0], "dps_distance_prefactor": fit[1],
             "dps_distance_fit_omega_max": spec.fit_omega_max,
             "tail_slope_dps": float(np.log(al)),
             "method": "reversible shooting (v(0) = 0; v(T/2) = 0 on Fix(-S) for bond, x(T/4) on Fix(S) and v(T/4) "
                       "on Fix(-S) for site) with DOP853 and the variational equations; Newton continuation in "
                       "omega_b from the DpS start; monodromy M = R M(T/2)^-1 R M(T/2) on the core",
             "timings_s": ", ".join(f"{k}={v:.1f}" for k, v in timings.items())}
    from cradle.analyses import breather_mobility
    groups.update(breather_mobility.compute(keep, floquets, spec, al, say, attrs))
    attrs["wall_time_s"] = time.perf_counter() - t_start
    say(f"breathers: done in {attrs['wall_time_s']:.1f} s")
    return make_tree(groups, VARIABLES, attrs=attrs, params=plain(spec),
                     title="Exact breathers of (nc): families, Floquet stability, Peierls-Nabarro barrier, distance "
                           "to the DpS breathers")


def _pn(out: dict, fams: list[tuple], omegas: NDArray[np.float64], spec: Breathers, al: float,
        db: ModuleType) -> tuple[tuple[dict, dict], float, float, float, float]:
    """E_bond - E_site at the site breather's action J_s, from the bond breather of the same omega_b.

    Along a family of periodic orbits dE/dJ = 1/T = omega_b / (2 pi), so the bond breather of action J_s
    has energy E_b + (J_s - J_b) omega_b / (2 pi) + (J_s - J_b)^2 / (4 pi) d omega_b/dJ; J_s - J_b is
    ~1e-7 J here, so the quadratic term (d omega_b/dJ from the family) is below 1e-15 of E and no
    interpolation between grid points is needed. The uncertainty is the change of the barrier when both
    breathers are re-solved with the finer tolerance (errors of x0 off the family enter E - omega J / 2 pi
    at first order).
    """
    names = [n for n, *_ in fams]
    if "ring site" not in names or "ring bond" not in names:
        return ({"barrier": [], "barrier_dps": [], "barrier_uncertainty": [], "omega_site": []}, {"action_pn": []}), \
            np.nan, np.nan, np.nan, np.nan
    fs, fb = names.index("ring site"), names.index("ring bond")

    def barrier(Es: NDArray[np.float64], Js: NDArray[np.float64], Eb: NDArray[np.float64],
                Jb: NDArray[np.float64]) -> NDArray[np.float64]:
        dJ = Js - Jb
        dwdJ = np.gradient(omegas[ok], Jb[ok]) if ok.sum() > 1 else np.zeros(ok.sum())
        return Eb[ok] + dJ[ok] * omegas[ok] / (2 * np.pi) + dJ[ok] ** 2 * dwdJ / (4 * np.pi) - Es[ok]

    ok = np.isfinite(out["action"][fs]) & np.isfinite(out["action"][fb])
    bar = barrier(out["energy"][fs], out["action"][fs], out["energy"][fb], out["action"][fb])
    unc = np.abs(bar - barrier(out["energy_check"][fs], out["action_check"][fs], out["energy_check"][fb],
                               out["action_check"][fb]))
    Js, Es = out["action"][fs], out["energy"][fs]
    N = spec.N
    a_s, a_b = _profile(N, "site", al, "periodic"), _profile(N, "bond", al, "periodic")
    bar_d = db.pn_barrier(a_s, a_b, Js[ok], al)
    om_s = omegas[ok]
    j = np.where(np.abs(om_s - spec.pn_omega) < 1e-9)[0]
    at = (float(bar[j[0]]), float(bar_d[j[0]]), float(Es[ok][j[0]]), float(unc[j[0]])) if j.size else (np.nan,) * 4
    return ({"barrier": bar, "barrier_dps": bar_d, "barrier_uncertainty": unc, "omega_site": om_s},
            {"action_pn": Js[ok]}), *at


def _distance_fit(out: dict, omegas: NDArray[np.float64], spec: Breathers) -> tuple[float, float]:
    """Power law dps_distance ~ C (omega_b - 1)^p over omega_b <= fit_omega_max, all ring families pooled."""
    d = out["dps_distance"]
    x = np.broadcast_to(omegas - 1.0, d.shape)
    sel = np.isfinite(d) & (x <= spec.fit_omega_max - 1.0) & (d > 0)
    if np.unique(x[sel]).size < 2:
        return np.nan, np.nan
    p, c = np.polyfit(np.log(x[sel]), np.log(d[sel]), 1)
    return float(p), float(np.exp(c))


ANALYSIS = Analysis(
    name="breathers", spec=Breathers, compute=compute, variables=VARIABLES,
    title="Exact breathers of (nc): families, Floquet stability, Peierls-Nabarro barrier, distance to DpS")
