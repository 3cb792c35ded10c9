"""cradle: the numerical results of G. James, *Nonlinear waves in Newton's cradle
and the discrete p-Schrödinger equation*, rebuilt and extended.

Sub-packages, one layer each, each importing only from the layers before it (docs/developing.md):

* :mod:`cradle.specs`        - the declaration kit of typed specs: parameters, shared types, one-line errors
* :mod:`cradle.data`         - self-describing netCDF: declared variables, atomic writes, checksummed reads
* :mod:`cradle.models`       - the paper's objects: the lattice (nc)/(ham), the DpS equation (dfnls),
  the stationary problem (dpsstn) and its map G (comp1)-(comp2), homoclinics, initial data
  (ansatzapprox)/(perturb)/(ansatzapproxst2), the exact travelling waves of (ad)
* :mod:`cradle.integrators`  - time integration of (nc) and (dfnls), compiled kernels
* :mod:`cradle.measurements` - measurements on runs: (ansatz), E(t), spectra on Gamma*, breathers
* :mod:`cradle.scenes`       - a scene: its spec (where it is validated) and its stages, from the homoclinic
  solution to the exact and DpS runs and their comparison
* :mod:`cradle.analyses`     - beyond the paper, one module per analysis (and the paper's claims table)
* :mod:`cradle.figures`      - drawing functions, from stored data
* :mod:`cradle.pipeline`     - config loading, results layout, jobs, budgets, code dependencies, CLI
"""

from typing import Any

#: the public API, by theme: (name, "module" or "module:attribute", one-line summary). The module docstring's
#: table and ``__all__`` are made from it; each name is imported on first use (:func:`__getattr__`)
_API: tuple[tuple[str, tuple[tuple[str, str, str], ...]], ...] = (
    ("Initial data (section 4)", (
        ("travelling_wave", "cradle.models.initial",
         "travelling-wave data (ansatzapprox), a from (freq), optionally perturbed as in (perturb)"),
        ("breather", "cradle.models.initial", "breather data (ansatzapproxst2) from a solution a_n of (dpsstn)"),
        ("packet", "cradle.models.initial", "a modulated binary oscillation at rest (loc1, left)"),
        ("pair", "cradle.models.initial", "two static breathers at rest (loc1, right)"),
        ("kick", "cradle.models.initial", "one bead kicked from rest (James, Kevrekidis & Cuevas 2013)"),
        ("two_breathers", "cradle.models.pairs",
         "two breathers of chosen profiles, centres, amplitudes and phase (breather-interactions)"),
        ("from_displacements", "cradle.models.initial",
         "your own x_n(0) at rest, with its DpS start A_n(0) = x_n(0)/2, eps = 1"),
        ("lattice_state", "cradle.models.initial", "(x_n(0), v_n(0)) of (ansatz) from your own A_n(0) and eps"),
        ("InitialData", "cradle.models.initial", "what the builders return: A0, eps, x0, v0, noise, derived info"),
    )),
    ("The two models", (
        ("integrate_lattice", "cradle.integrators",
         "integrate the lattice (nc) with the Hertz potential (vhertz) from (x0, v0)"),
        ("integrate_dps", "cradle.integrators", "integrate the DpS equation (dfnls) from A0 in the slow time tau"),
        ("LatticeSolution", "cradle.integrators",
         "what integrate_lattice returns: t, x, v, the energy (ham) and its drift"),
        ("DpsSolution", "cradle.integrators", "what integrate_dps returns: tau, A and the drifts of its invariants"),
    )),
    ("Comparison and measurements", (
        ("compare_models", "cradle.measurements.comparison",
         "both models as one Dataset along model = 'exact', 'dps', with E(t) and the spectra"),
        ("approximate_displacement", "cradle.measurements.compare",
         "x^app_n(t) = eps (A_n e^{it} + c.c.) of (ansatz) from a DpS run"),
        ("relative_error", "cradle.measurements.compare", "E(t) = ||x^app(t) - x(t)||_inf / a of figure plot4-5"),
        ("spatial_dft", "cradle.measurements.compare", "the paper's spectrum x_hat_k(t) for k in Gamma* (fft106)"),
        ("gamma_star", "cradle.measurements.compare", "Gamma* = (2 pi / N) {-N/2 + 1, ..., N/2}, the discrete band"),
    )),
    ("Stationary DpS (section 2.2)", (
        ("G", "cradle.models.stationary", "one step (a_n, b_{n+1}) -> (a_{n+1}, b_{n+2}) of the map G (comp1)-(comp2)"),
        ("G_inverse", "cradle.models.stationary", "the inverse map G^{-1}"),
        ("orbits", "cradle.models.stationary", "orbits of G from several starting points at once (traj3, traj2)"),
        ("solve_homoclinic", "cradle.models.homoclinic_continuation:solve_kind",
         "the site, bond or double homoclinic solution of (dpsstn) for any alpha > 1 (bcsc)"),
        ("Homoclinic", "cradle.models.homoclinic", "what solve_homoclinic returns: a_n, residual, convergence"),
    )),
    ("Physical units (docs/physical-units.md)", (
        ("real_cradle", "cradle.models.physical",
         "a cradle in SI: sphere material and radius, pendulum length or on-site omega_0 (validated)"),
        ("scales", "cradle.models.physical",
         "(nc)'s units in SI for a cradle: T = 1/omega_0, X = (m omega_0^2/k)^2, velocity, force, energy"),
        ("to_si", "cradle.models.physical", "a value of (nc) (displacement, time, velocity, energy, force) in SI"),
        ("from_si", "cradle.models.physical", "an SI value in (nc)'s dimensionless units"),
        ("release_amplitude", "cradle.models.physical",
         "the (nc) amplitude L sin(theta)/X of a pendulum released from theta degrees"),
        ("collision_time", "cradle.models.physical", "Hertz collision time t_c = 2 I delta_max / v of two spheres"),
        ("lookup_material", "cradle.models.physical", "a named sphere material: E, nu, rho and their sources"),
        ("in_si", "cradle.data.si", "a stored run of a real cradle (`cradle:`) in SI: s, m, m s-1, N, J"),
    )),
    ("Dissipation (docs/dissipation.md, docs/damped-dps.md)", (
        ("Damping", "cradle.models.damping",
         "the damping terms of (ncdamped): on-site gamma and Kuwabara-Kono contact eta; integrate_lattice(damping=)"),
        ("DpsDamping", "cradle.models.dps_damped", "their DpS counterpart (dpsdamped); integrate_dps(damping=)"),
        ("slow_damping", "cradle.models.dps_damped", "the DpsDamping of a lattice Damping at small parameter eps"),
    )),
    ("Imperfect cradles (docs/imperfect-cradles.md)", (
        ("Terms", "cradle.models.lattice_terms",
         "the terms of (ncimperfect): inhomogeneity, precompression, on-site potential; integrate_lattice(terms=)"),
        ("Inhomogeneity", "cradle.models.inhomogeneity",
         "per-bead masses and on-site frequencies, per-contact stiffnesses: drawn (sigma, seed) or given"),
        ("Precompression", "cradle.models.precompression", "a uniform static overlap delta0 (> 0, rings) or gaps"),
        ("OnSite", "cradle.models.onsite", "the on-site potential W: harmonic, quartic (beta), pendulum (scale)"),
        ("sites", "cradle.models.inhomogeneity", "the site coefficients (m_n, omega_n, k_n) of an Inhomogeneity"),
        ("contact_stiffness", "cradle.models.inhomogeneity", "Hertz's (4/3) E* sqrt(R*) of two spheres"),
    )),
    ("Stored results", (
        ("open_scene", "cradle.pipeline.outputs",
         "a scene's exact and DpS runs and their metrics as one Dataset along model"),
        ("open_dataset", "cradle.data.io", "open an output netCDF file, every checksum verified"),
        ("open_tree", "cradle.data.io", "open an analysis file (netCDF groups) as a DataTree, checksums verified"),
    )),
    ("Typed specs", (
        ("Scene", "cradle.scenes.spec", "the typed spec of a scene: N, bc, alpha, integrators, initial data, times"),
        ("scene_of", "cradle.scenes.stored", "the Scene that made a stored file, rebuilt from its parameters"),
        ("from_plain", "cradle.specs.declare", "a typed spec from plain values, validated (one-line ConfigError)"),
        ("plain", "cradle.specs.declare", "a typed spec as plain JSON values, as files store it"),
        ("ConfigError", "cradle.specs.values", "a refused value: one line naming the key, the value and why"),
    )),
)
_WHERE = {name: where for _, entries in _API for name, where, _ in entries}

__all__ = ["__version__", *_WHERE]


def _table() -> str:
    width = max(map(len, _WHERE)) + 2
    lines = ["Public API: ``cradle.<name>``, each imported on first use (``import cradle`` loads no numpy).", ""]
    for theme, entries in _API:
        lines += [theme] + [f"    {name:<{width}}{summary}" for name, _, summary in entries] + [""]
    return "\n".join(lines)


__doc__ = f"{__doc__}\n{_table()}"


def __getattr__(name: str) -> Any:
    """A name of the public API (the table above), imported from its module on first use."""
    # the public names on first use: the Snakefile imports cradle.pipeline.config to plan and must not pay for
    # numpy, xarray or numba; and __version__ (importlib.metadata) not in a job's process before it is forked
    # from the warm one (cradle.pipeline.warm)
    where = "cradle.data.provenance:VERSION" if name == "__version__" else _WHERE.get(name)
    if where is None:
        raise AttributeError(f"module 'cradle' has no attribute {name!r}")
    import importlib

    module, _, attr = where.partition(":")
    value = getattr(importlib.import_module(module), attr or name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    """The module's names with the whole public API, imported or not yet."""
    return sorted(set(globals()) | set(__all__))
