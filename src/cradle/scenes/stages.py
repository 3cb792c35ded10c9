"""The pipeline's four stages as functions: resolved parameters in, xarray Datasets out.

homoclinic / map orbits  ->  initial data  ->  exact and DpS runs  ->  metrics
(then figures, :mod:`cradle.figures`).

Each function takes the resolved spec of one config entry (a frozen instance of
:mod:`cradle.scenes.spec`, as :func:`cradle.pipeline.config.scene`,
:func:`~cradle.pipeline.config.homoclinic` and :func:`~cradle.pipeline.config.map_entry` build it)
and the Datasets of the stage before, and returns a self-describing Dataset (see
:mod:`cradle.data.variables`, :mod:`cradle.data.io`) that stores the spec's plain values
(:func:`cradle.specs.declare.plain`) as its parameters, and names itself (kind and name,
:func:`cradle.data.provenance.identity`). No file paths and no Snakemake:
the workflow scripts and the command line are thin adapters around these.
A run that fails (no convergence, NaN, drift above the bound) raises
:class:`StageFailure` carrying what was computed, for diagnosis.
"""
from __future__ import annotations

import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np
import xarray as xr

from cradle.data.io import make_dataset
from cradle.measurements import breathers, compare, interactions, sidebands
from cradle.models import damping, dps, initial, lattice
from cradle.scenes.failure import StageFailure
from cradle.scenes.spec import Breather, HomoclinicEntry, Kick, MapEntry, Packet, Pair, Scene, Travelling
from cradle.specs.declare import plain

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from cradle.integrators.dps_solver import DpsSolution
    from cradle.models.dps_sites import DpsSites
    from cradle.models.inhomogeneity import Sites
    from cradle.models.lattice_terms import Terms
    from cradle.models.physical import Cradle

# ---------------------------------------------------------------- stationary DpS

def homoclinic_solution(spec: HomoclinicEntry, name: str = "") -> xr.Dataset:
    """Solve (dpsstn) for one ``homoclinic:`` entry; a(n), residual(n), attributes."""
    # scipy.optimize: only the homoclinic stage needs it
    from cradle.models import homoclinic, homoclinic_continuation, homoclinic_tails

    t0 = time.perf_counter()
    alpha, N, bc, mu = spec.alpha, spec.N, spec.bc, spec.mu
    # the paper's Powell start, or continuation in alpha from 3/2 where it fails (alpha far from 3/2)
    sol = homoclinic_continuation.solve_kind(N, spec.guess, alpha, bc, mu=mu, amplitude=spec.amplitude,
                                             centre=spec.centre, separation=spec.separation)
    a = sol.a
    scale = mu ** (1.0 / (alpha - 1.0))  # (dpsst) solution = scale * (dpsstn) solution
    r = homoclinic.residual(a, alpha, bc, sign=mu)
    sum_a2, sum_d = homoclinic.energy_balance(a, alpha, bc)
    attrs = {
        "name": name, "alpha": alpha, "mu": mu, "bc": bc, "N": N, "guess": spec.guess,
        "guess_amplitude": spec.amplitude, "solver": "scipy.optimize.root hybr (MINPACK) + Newton",
        "residual": sol.residual, "converged": sol.converged, "n_function_evals": sol.n_iterations,
        "max_abs_a": float(np.max(np.abs(a))), "log10_max_abs_a": sol.log10_amplitude, "method": sol.method,
        "sum_a2": sum_a2, "sum_abs_da_pow": sum_d, "wall_time_s": time.perf_counter() - t0,
    }
    if spec.guess == "double":
        attrs["separation"] = spec.separation
    else:  # site: a_{c-n} = a_{c+n}; bond: a_{c-n} = -a_{c+n+1}
        attrs["symmetry_error"] = homoclinic.symmetry_error(a, spec.guess, spec.centre)
    # tails far below machine precision: exact (dpsstn) recursion in log variables (periodic ends)
    log10a = (homoclinic_tails.log10_abs(a / scale, alpha) + np.log10(scale) if bc == "periodic"
              else np.log10(np.abs(a)))
    attrs["log10_tail_min"] = float(np.min(log10a))
    ds = make_dataset({"a": a, "residual_n": r, "log10_abs_a": log10a}, coords={"n": np.arange(N)}, attrs=attrs,
                      params=plain(spec), title=f"solution '{name}' of the stationary DpS equation (dpsstn)",
                      identity=("homoclinic", name))
    if not sol.converged or not np.all(np.isfinite(a)):
        raise StageFailure(f"homoclinic '{name}': Powell hybrid did not converge "
                           f"(residual {sol.residual:.3e}, {sol.message})", ds)
    if attrs["max_abs_a"] < 1e-6 * 10.0 ** (-0.61 / (alpha - 1.0)) * scale:  # mu = 1 amplitude ~ 4^(-1/(alpha-1))
        raise StageFailure(f"homoclinic '{name}': converged to the trivial solution a = 0 "
                           f"(max|a_n| = {attrs['max_abs_a']:.3e}); change the guess", ds)
    return ds


MARKED_ORBITS = ("period2", "period3", "period4")   # keys of stationary.explicit_periodic_orbits stored by map_orbits


def map_orbits(spec: MapEntry, name: str = "") -> xr.Dataset:
    """Orbits of the map G (comp1)-(comp2) for one ``map:`` entry (traj3, traj2)."""
    from cradle.models import stationary

    t0 = time.perf_counter()
    line = spec.line
    starts = stationary.starting_points(spec.starts, None if line is None else (line.from_, line.to, line.count))
    U = stationary.orbits(starts, spec.iterations, spec.alpha, box=spec.box)
    data = {"map_a": U[..., 0], "map_b": U[..., 1]}
    coords = {"orbit": np.arange(len(starts)), "iterate": np.arange(U.shape[1])}
    if spec.marks:  # traj2: the explicit period-2, -3, -4 orbits of its caption, marked on the panel
        explicit = stationary.explicit_periodic_orbits(spec.alpha)
        marks = [(int(key[len("period"):]), explicit[key]) for key in MARKED_ORBITS]
        data.update({"mark_a": np.concatenate([U_p[:, 0] for _, U_p in marks]),
                     "mark_b": np.concatenate([U_p[:, 1] for _, U_p in marks]),
                     "mark_period": np.concatenate([np.full(len(U_p), period) for period, U_p in marks])})
        coords["mark"] = np.arange(data["mark_a"].size)
    attrs = {"name": name, "alpha": spec.alpha, "box": spec.box, "iterations": spec.iterations,
             "marks": spec.marks, "wall_time_s": time.perf_counter() - t0}
    return make_dataset(data, coords=coords, attrs=attrs, params=plain(spec),
                        title=f"orbits '{name}' of the map G (comp1)-(comp2)", identity=("map", name))


# ---------------------------------------------------------------- initial data

def _scene_attrs(spec: Scene, name: str) -> dict:
    """The parameters that define a scene, flattened into netCDF attributes."""
    ini = spec.initial
    noise = ini.noise if isinstance(ini, Travelling) else None
    attrs = {"scene": name, "alpha": spec.alpha, "N": spec.N, "bc": spec.bc,
             "initial_kind": ini.kind, "t_end": spec.t_end,
             "noise": noise.kind if noise else "none", "noise_amplitude": noise.amplitude if noise else 0.0,
             "seed": noise.seed if noise else "none"}
    if isinstance(ini, Travelling):
        attrs.update({"q": ini.wavenumber, "q_expr": ini.q_expr, "phi": ini.phi})
    elif isinstance(ini, Breather):
        attrs.update({"homoclinic": ini.homoclinic})
    if spec.damping is not None:
        attrs.update({"damping_onsite": spec.damping.onsite, "damping_contact": spec.damping.contact})
    if spec.terms is not None:
        attrs.update(terms_attrs(spec.terms))
    if spec.cradle is not None:
        attrs.update(physical_attrs(spec.cradle))
    return attrs


def terms_attrs(terms: Terms) -> dict:
    """The terms of the imperfect cradle (ncimperfect) as attributes (the explicit site values, if any, are in the
    file's parameters and in its ``omega_n``, ``mass_n``, ``stiffness_n``)."""
    inh, pre, on = terms.inhomogeneity, terms.precompression, terms.onsite
    return {"disorder_sigma": inh.sigma, "disorder_distribution": inh.distribution, "mass_sigma": inh.mass_sigma,
            "disorder_seed": inh.seed, "precompression_delta0": pre.delta0, "onsite_potential": on.potential,
            "onsite_beta": on.beta, "onsite_scale": on.scale}


def scene_sites(spec: Scene) -> Sites | None:
    """The site coefficients (m_n, omega_n, k_n) of a scene with active terms, else None."""
    if spec.terms is None or not spec.terms.active:
        return None
    from cradle.models.inhomogeneity import sites

    return sites(spec.terms.inhomogeneity, spec.N)


def dps_sites_of(spec: Scene, s: Sites, eps: float) -> DpsSites:
    """The coefficients of (dpsimperfect) for a scene with active terms and sites ``s``, at its eps."""
    from cradle.models.dps_sites import dps_sites

    on = spec.terms.onsite
    return dps_sites(s.mass, s.omega, s.stiffness, alpha=spec.alpha, eps=eps,
                     beta=on.beta if on.potential == "quartic" else 0.0,
                     pendulum_scale=on.scale if on.potential == "pendulum" else 0.0,
                     delta0=spec.terms.precompression.delta0)


def physical_attrs(cradle: Cradle) -> dict:
    """The real cradle a scene models and the SI value of one unit of each of (nc)'s variables
    (:func:`cradle.models.physical.scales`, under the names :data:`cradle.data.si.SCALES` reads them by): a reader
    converts any stored value to SI with them."""
    from cradle.data.si import SCALES
    from cradle.models import physical

    s = physical.scales(cradle)
    out = {"cradle_material": cradle.material, "cradle_radius_m": cradle.radius, "cradle_omega0_rad_s": s.omega0}
    if cradle.length is not None:
        out.update({"cradle_length_m": cradle.length, "cradle_g_m_s2": cradle.g})
    out.update({attr: getattr(s, physical.QUANTITIES[quantity][0]) for quantity, (attr, _) in SCALES.items()})
    out.update({"sphere_mass_kg": s.m, "hertz_k": s.k, "hertz_k_units": "N m-1.5"})
    return out


def initial_data(spec: Scene, name: str = "", homoclinic_ds: xr.Dataset | None = None) -> xr.Dataset:
    """Initial data of one scene: x0, v0, A0 (and the noise realisation)."""
    ini = spec.initial
    alpha, N, bc = spec.alpha, spec.N, spec.bc
    if isinstance(ini, Travelling):
        noise = ini.noise
        data = initial.travelling_wave(N, ini.wavenumber, alpha, a=ini.a, omega_tw=ini.omega_tw, phi=ini.phi, bc=bc,
                                       noise_kind=noise.kind if noise else "none",
                                       noise_amplitude=noise.amplitude if noise else 0.0,
                                       seed=noise.seed if noise else None)
    elif isinstance(ini, Breather):
        if homoclinic_ds is None:
            raise ValueError(f"scene '{name}': a breather needs the homoclinic solution '{ini.homoclinic}'")
        data = initial.breather(homoclinic_ds["a"].values, alpha, omega_sw=ini.omega_sw, amplitude=ini.amplitude,
                                site=ini.site, bc=bc)
    elif isinstance(ini, Packet):  # loc1 (left): modulated binary oscillation at rest
        data = initial.packet(N, alpha, amplitude=ini.amplitude, width=ini.width, envelope_kind=ini.envelope,
                              centre=ini.centre, bc=bc)
    elif isinstance(ini, Pair):  # loc1 (right): two static breathers at rest, profile solved in-process
        data = initial.pair(N, alpha, amplitude=ini.amplitude, separation=ini.separation, profile=ini.profile,
                            sign=ini.sign, centre=ini.centre, bc=bc)
    elif isinstance(ini, Kick):  # JKC 2013: one bead kicked from rest
        data = initial.kick(N, alpha, velocity=ini.velocity, site=ini.site, bc=bc)
    else:
        raise TypeError(f"scene '{name}': not an initial condition of a known kind: {ini!r}")
    fields = {"x0": data.x0, "v0": data.v0, "A0_re": data.A0.real, "A0_im": data.A0.imag}
    if data.rho1 is not None:
        fields.update({"rho1": data.rho1, "rho2": data.rho2})
    attrs = _scene_attrs(spec, name) | data.info
    s = scene_sites(spec)
    if s is None:
        attrs["energy0"] = float(lattice.hamiltonian(data.x0, data.v0, alpha, bc))
    else:   # the generalised (ham) of (ncimperfect), and the sites the runs use
        from cradle.models import lattice_terms

        attrs["energy0"] = float(lattice_terms.hamiltonian(data.x0, data.v0, alpha, spec.terms, s, bc))
        fields.update({"omega_n": s.omega, "mass_n": s.mass, "stiffness_n": s.stiffness})
    return make_dataset(fields, coords={"n": np.arange(N)}, attrs=attrs,
                        params=plain(spec), title=f"initial data of scene '{name}'", identity=("initial", name))


# ---------------------------------------------------------------- integration

def check_finite(name: str, model: str, arrays: dict[str, np.ndarray], partial: xr.Dataset | None,
                 offset: int = 0) -> None:
    """StageFailure at the first stored time (index ``offset`` + row: a block of a streamed run) where an
    array is not finite."""
    for label, arr in arrays.items():
        bad = ~np.isfinite(arr)
        if bad.any():
            ti = offset + int(np.argwhere(bad)[0][0])
            raise StageFailure(f"scene '{name}' ({model}): {label} is not finite from stored time index {ti} on "
                               "(blow-up or NaN)", partial)


def steps_taken(times: ArrayLike, dt: float, t0: float | None = None) -> tuple[float, float]:
    """(largest, smallest) step a fixed-step splitting takes to reach ``times`` from ``t0`` (default
    times[0]) with nominal step ``dt``: each interval between output times is covered by
    ceil(length/dt) equal steps (:func:`cradle.integrators.integrate_lattice`), so a store finer than
    dt makes every step the store spacing, not dt."""
    t = np.asarray(times, dtype=float)
    if t0 is not None and t.size and t0 < t[0]:
        t = np.concatenate(([t0], t))
    lengths = np.diff(t)
    lengths = lengths[lengths > 0]
    if lengths.size == 0:
        return float(dt), float(dt)
    h = lengths / np.maximum(1.0, np.ceil(lengths / dt * (1.0 - 1e-12)))
    return float(h.max()), float(h.min())


def exact_title(name: str) -> str:
    return f"exact solution of (nc), scene '{name}'"


def exact_attrs(spec: Scene, init_ds: xr.Dataset, method: str, dt_taken: float | None, dt_nominal: float | None,
                rtol: float | None, atol: float | None, stats: dict) -> dict:
    """Global attributes of a scene's exact run: the initial data's, the integrator and its accuracy
    (``dt`` the largest step taken, ``dt_nominal`` its bound, from which the step grid follows and with
    which ``cradle extend`` continues the run; "adaptive" for an adaptive method) and the run's
    ``stats`` (energy_drift, n_steps, n_force_evals, max_compression, wall_time_s, n_onset_corrections)."""
    attrs = dict(init_ds.attrs)  # make_dataset replaces the inherited CF and provenance attributes
    attrs.update({"model": "exact lattice (nc), V = V0", "integrator": method,
                  "dt": dt_taken if dt_nominal is not None else "adaptive",
                  "dt_nominal": dt_nominal if dt_nominal is not None else "adaptive",
                  "rtol": rtol if rtol is not None else "none",
                  "atol": atol if atol is not None else "none",
                  "energy_drift": stats["energy_drift"], "max_energy_drift_allowed": spec.max_energy_drift,
                  **{k: stats[k] for k in ("n_steps", "n_force_evals", "max_compression", "wall_time_s",
                                           "n_onset_corrections")}})
    return attrs


def exact_run(spec: Scene, init_ds: xr.Dataset, name: str = "",
              progress: Callable[[float, float], None] | None = None) -> xr.Dataset:
    """Integrate the lattice (nc) from the scene's initial data; x, v, forces, energy at stored times."""
    from cradle.integrators import SPLITTING_METHODS, integrate_lattice

    alpha, bc = spec.alpha, spec.bc
    times = np.asarray(spec.times, dtype=float)
    ex = spec.exact
    x0, v0 = init_ds["x0"].values, init_ds["v0"].values
    # a fixed-step splitting takes dt_factor, an adaptive method rtol (atol scales with the amplitude)
    accuracy: dict[str, Any] = {"dt_factor": ex.dt_factor} if ex.method in SPLITTING_METHODS else {"rtol": ex.rtol}
    damped = spec.damping is not None and spec.damping.active
    if damped:   # only then: a conservative scene's call, and so its file, stays as it was
        accuracy["damping"] = spec.damping
    s = scene_sites(spec)
    if s is not None:   # likewise: a scene of (nc) calls as before
        accuracy["terms"] = spec.terms
    sol = integrate_lattice(x0, v0, times, alpha=alpha, bc=bc, method=ex.method, progress=progress, **accuracy)
    # the force on each bond, as the run felt it: with contact damping, g_n of (ncdamped); with terms, k_n F_n
    if s is not None:
        from cradle.models import lattice_terms

        force = lattice_terms.bond_forces(sol.x, alpha, spec.terms, s, bc, v=sol.v,
                                          eta=spec.damping.contact if damped else 0.0)
    elif damped:
        force = damping.bond_forces(sol.x, sol.v, alpha, spec.damping.contact, bc)
    else:
        force = lattice.bond_forces(sol.x, alpha, bc)
    attrs = exact_attrs(spec, init_ds, sol.method, steps_taken(times, sol.dt)[0] if sol.dt is not None else None,
                        sol.dt, sol.rtol, sol.atol, {"energy_drift": sol.energy_drift, "n_steps": sol.n_steps,
                                                     "n_force_evals": sol.n_force_evals,
                                                     "max_compression": sol.max_compression,
                                                     "wall_time_s": sol.wall_time_s,
                                                     "n_onset_corrections": getattr(sol, "n_onset_corrections", 0)})
    if damped:
        attrs["model"] = "damped lattice (ncdamped), V = V0"
        attrs["energy_drift_comment"] = "max |H + D - H(0)| / |H(0)|, D the dissipated energy"
    if s is not None:
        attrs["model"] = ("damped " if damped else "") + "imperfect cradle (ncimperfect)"
        attrs["energy_comment"] = "the generalised (ham) of (ncimperfect) (cradle.models.lattice_terms.hamiltonian)"
    fields = {"x": sol.x, "v": sol.v, "force": force, "energy": sol.energy}
    if damped:
        fields["dissipated"] = sol.dissipated
    ds = make_dataset(fields, coords={"t": times, "n": np.arange(spec.N)}, attrs=attrs,
                      params=plain(spec), title=exact_title(name), identity=("exact", name))
    check_finite(name, "exact", {"x": sol.x, "v": sol.v}, ds)
    if not sol.energy_drift <= spec.max_energy_drift:
        raise StageFailure(f"scene '{name}' (exact): relative energy drift {sol.energy_drift:.3e} exceeds "
                           f"max_energy_drift = {spec.max_energy_drift:.1e} ({sol.method}, dt={attrs['dt']})", ds)
    return ds


def dps_dataset(spec: Scene, init_ds: xr.Dataset, name: str, times: np.ndarray, sol: DpsSolution) -> xr.Dataset:
    """The DpS run's Dataset at ``times`` from its solution ``sol`` (:class:`cradle.integrators.DpsSolution`
    at tau = eps^(alpha-1) t): A, the approximate displacement (ansatz), its forces and the drifts."""
    alpha, bc = spec.alpha, spec.bc
    eps = float(init_ds.attrs["eps"])
    x_app = compare.approximate_displacement(sol.A, times, eps)
    s = scene_sites(spec)
    if s is None:
        force = lattice.bond_forces(x_app, alpha, bc)
    else:   # the lattice's bond forces k_n F_n of (ncimperfect) along the approximate displacement
        from cradle.models import lattice_terms

        force = lattice_terms.bond_forces(x_app, alpha, spec.terms, s, bc)
    attrs = dict(init_ds.attrs)  # make_dataset replaces the inherited CF and provenance attributes
    damped = getattr(sol, "damping", None) is not None
    model = "damped DpS (dpsdamped)" if damped else "DpS (dpsimperfect)" if s is not None else "DpS (dfnls)"
    attrs.update({"model": model + " + ansatz (ansatz)",
                  "integrator": sol.method, "rtol": sol.rtol,
                  "atol": sol.atol, "tau0": dps.tau0(alpha), "max_l2_drift": sol.max_l2_drift,
                  "max_dps_energy_drift": sol.max_energy_drift, "n_steps": sol.n_steps,
                  "wall_time_s": sol.wall_time_s})
    if damped:
        attrs.update({"dps_damping_gamma": sol.damping.gamma, "dps_damping_eta": sol.damping.eta,  # type: ignore[union-attr]  # damped: set
                      "drift_comment": "with damping the drifts are the residuals of the balance laws of "
                                       "(dpsdamped): docs/damped-dps.md"})
    return make_dataset({"A_re": sol.A.real, "A_im": sol.A.imag, "x": x_app, "force": force,
                         "l2_drift": sol.l2_drift, "dps_energy_drift": sol.energy_drift, "P_drift": sol.P_drift},
                        coords={"t": times, "n": np.arange(spec.N), "tau": sol.tau}, attrs=attrs,
                        params=plain(spec), title=f"DpS approximation (dfnls)/(ansatz), scene '{name}'",
                        identity=("dps", name))


def dps_run(spec: Scene, init_ds: xr.Dataset, name: str = "",
            progress: Callable[[float, float], None] | None = None) -> xr.Dataset:
    """Integrate the DpS equation (dfnls) and rebuild the approximate solution (ansatz) at stored times."""
    from cradle.integrators import integrate_dps

    alpha, bc = spec.alpha, spec.bc
    times = np.asarray(spec.times, dtype=float)
    eps = float(init_ds.attrs["eps"])
    tau = eps ** (alpha - 1.0) * times
    A0 = init_ds["A0_re"].values + 1j * init_ds["A0_im"].values
    extra = {}
    if spec.damping is not None and spec.damping.active:   # (dpsdamped): docs/damped-dps.md
        from cradle.models.dps_damped import slow_damping

        extra["damping"] = slow_damping(spec.damping, eps, alpha)
    s = scene_sites(spec)
    if s is not None:   # (dpsimperfect): docs/imperfect-dps.md
        extra["sites"] = dps_sites_of(spec, s, eps)
    sol = integrate_dps(A0, tau, alpha=alpha, bc=bc, method=spec.dps.method, rtol=spec.dps.rtol, progress=progress,
                        **extra)
    ds = dps_dataset(spec, init_ds, name, times, sol)
    check_finite(name, "dps", {"A": sol.A}, ds)
    return ds


# ---------------------------------------------------------------- metrics

#: loc1 (left): the packet has no omega_sw of its own; its peak compression is binned by the period of
#: omega_sw ~ 1.1, the paper's value for both loc1 experiments
PACKET_OMEGA = 1.1
LOCALISED_KINDS = ("breather", "pair", "packet")


def travelling_metrics(exact_ds: xr.Dataset, dps_ds: xr.Dataset, k: np.ndarray, spectra: dict) -> dict:
    """Per stored time, for a travelling-wave scene: the sideband ratio and the wavenumber of the largest
    sideband of each spectrum (fft106, fftseuil, fft344), the carrier's share of the power of each
    profile (fft344) and the linear wave a cos(q n - t + phi) (plotcomplin)."""
    q, a = float(exact_ds.attrs["q"]), float(exact_ds.attrs["a"])
    out = {}
    for model, ds in (("exact", exact_ds), ("dps", dps_ds)):
        ratio, k_peak = sidebands.sideband_peak(k, spectra[model], q)
        out[f"sideband_ratio_{model}"], out[f"sideband_k_{model}"] = ratio, k_peak
        # every stored profile in one FFT (a row-by-row loop costs seconds on long scenes; the two agree to
        # the last bit or one ulp)
        out[f"carrier_share_{model}"] = sidebands.carrier_share(ds["x"].values, q)
    out["x_linear"] = compare.linear_wave(exact_ds["n"].values, exact_ds["t"].values, a, q,
                                          float(exact_ds.attrs.get("phi", 0.0)))
    return out


def localised_metrics(exact_ds: xr.Dataset, dps_ds: xr.Dataset) -> tuple[dict, dict]:
    """Breather measurements of a localised scene (plot18, loc1, fini): (data, coords).

    Every localised scene: the peak compression of every bond per breather period (loc1's
    diagrams). A breather: its frequency in both models at the site of largest |x_n(0)| and the
    half-period shift (plot18, fini), and the amplitude radiated beyond 6 sites of its core at
    every stored time (plot18). A pair: the outcome (merge, bound, repel, ...) and the merging
    time of the two breathers under both definitions (final single breather, first coalescence) in both
    models (loc1), by :func:`cradle.measurements.interactions.classify`.
    """
    kind = exact_ds.attrs["initial_kind"]
    periodic = exact_ds.attrs["bc"] == "periodic"
    omega = float(exact_ds.attrs["omega_sw"]) if "omega_sw" in exact_ds.attrs else PACKET_OMEGA
    period = 2.0 * np.pi / omega
    t = exact_ds["t"].values
    data: dict[str, Any] = {"breather_omega": omega}
    for model, ds in (("exact", exact_ds), ("dps", dps_ds)):
        starts, P = breathers.peak_compression(t, ds["force"].values, period)
        data[f"peak_compression_{model}"] = P
    coords = {"t_window": starts}
    if kind == "pair":
        # the outcome measure on the site profile max_t |x_n| per period (interactions.classify): the bond
        # forces cannot resolve two breathers one site apart
        for model, ds in (("exact", exact_ds), ("dps", dps_ds)):
            oc = interactions.classify(t, ds["x"].values, period, periodic=periodic)
            data[f"merging_time_{model}"] = oc.merge_period
            data[f"first_coalescence_{model}"] = oc.first_coalescence
            data[f"outcome_{model}"] = np.int64(oc.code)
    elif kind == "breather":
        x = exact_ds["x"].values
        site = int(np.argmax(np.abs(x[0])))
        sh = breathers.half_period_shift(t, x[:, site], dps_ds["x"].values[:, site], omega)
        data.update({"breather_site": site, "omega_exact": sh["omega_exact"], "omega_approx": sh["omega_approx"],
                     "half_shift_periods": sh["half_shift_periods"]})
        core = 0.5 * (int(np.argmax(x[0])) + int(np.argmin(x[0])))
        data["radiated_exact"] = np.array([breathers.dispersive_amplitude(row, core, periodic=periodic)
                                           for row in x])
    return data, coords


def metrics(spec: Scene | None, exact_ds: xr.Dataset, dps_ds: xr.Dataset, name: str = "") -> xr.Dataset:
    """Exact against approximate: E(t) (plot4-5) and the spectra |x_hat_k(t)| on Gamma*; what the
    figures show of the scene (:func:`travelling_metrics`, :func:`localised_metrics`). Everything is
    read from the two runs; ``spec`` is only stored (None: two runs not made from a scene spec)."""
    if exact_ds.attrs.get("initial_kind") == "kick":   # starts at x = 0: the kicked bead's amplitude v/omega_0
        a_scale = abs(float(exact_ds.attrs["velocity"]))
    else:
        a_scale = float(exact_ds.attrs.get("a", np.max(np.abs(exact_ds["x"].isel(t=0).values))))
    E = compare.relative_error(exact_ds["x"].values, dps_ds["x"].values, a_scale)
    k, xh_exact = compare.spatial_dft(exact_ds["x"].values)
    _, xh_dps = compare.spatial_dft(dps_ds["x"].values)
    attrs = {key: exact_ds.attrs[key] for key in ("scene", "alpha", "N", "bc", "q", "a", "eps", "omega_tw",
                                                   "noise", "noise_amplitude", "seed") if key in exact_ds.attrs}
    attrs.update({"E_scale": a_scale, "E_max": float(np.max(E)), "E_final": float(E[-1]),
                  "t_final": float(exact_ds["t"].values[-1])})
    data = {"E": E, "spectrum_exact": np.abs(xh_exact), "spectrum_dps": np.abs(xh_dps)}
    coords = {"t": exact_ds["t"].values, "k": k}
    kind = exact_ds.attrs.get("initial_kind")
    if kind == "travelling":
        data.update(travelling_metrics(exact_ds, dps_ds, k, {"exact": data["spectrum_exact"],
                                                             "dps": data["spectrum_dps"]}))
        coords["n"] = exact_ds["n"].values
        attrs["sideband_exclude_bins"] = sidebands.EXCLUDE_BINS
    elif kind in LOCALISED_KINDS:
        extra, extra_coords = localised_metrics(exact_ds, dps_ds)
        data.update(extra)
        coords.update(extra_coords)
    return make_dataset(data, coords=coords, attrs=attrs, params=None if spec is None else plain(spec),
                        title=f"exact vs DpS comparison metrics, scene '{name}'", identity=("metrics", name))
