"""Every stored variable and coordinate, declared once: dimensions, long name, units.

Writers never type a ``long_name`` or ``units``: :func:`cradle.data.io.make_dataset`
looks them up here (the xarray-simlab way), so all outputs agree. Everything in
the model is dimensionless (time in units of 1/omega_0 of the pendula,
displacements in units of the Hertz length), hence units "1".

CF-1.10 notes: the time coordinates are ``t`` and ``tau``, never ``time``
(a ``time`` coordinate would need calendar units such as "days since ...");
complex amplitudes are stored as ``_re``/``_im`` pairs; ``attrs`` holds any
further CF attributes of a variable (``comment``, ``flag_values``, ...), also
written by :func:`cradle.data.io.make_dataset`.

The analyses beyond the paper declare their own variables beside their code, one dict per netCDF
group (``VARIABLES`` of :mod:`cradle.analyses.theorem1`, ``mi_diagram``, ``migrowth``,
``mistatistics``, ``floquet``; :mod:`cradle.analyses.work_precision` likewise), passed to
:func:`cradle.data.io.make_tree` or ``make_dataset(variables=...)``.
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Var:
    dims: tuple[str, ...]
    long_name: str
    units: str = "1"
    attrs: tuple[tuple[str, object], ...] = ()  # further CF attributes, as (name, value) pairs


VARIABLES: dict[str, Var] = {
    # coordinates
    "n": Var(("n",), "bead index (bond n joins beads n and n+1)"),
    "t": Var(("t",), "dimensionless time t of (nc)"),
    "tau": Var(("t",), "slow time tau = eps^(alpha-1) t of (dfnls)",
               attrs=(("comment", "auxiliary coordinate along t: the DpS time of each stored t"),)),
    "k": Var(("k",), "wavenumber k in Gamma* of the spatial DFT",
             attrs=(("comment", "Gamma* = (2 pi / N) {-N/2+1, ..., N/2}, radians per bead"),)),
    "iterate": Var(("iterate",), "iteration index j of the map G (comp1)-(comp2)"),
    "orbit": Var(("orbit",), "orbit number"),
    # lattice (nc)
    "x": Var(("t", "n"), "bead displacement x_n(t)"),
    "v": Var(("t", "n"), "bead velocity dx_n/dt"),
    "force": Var(("t", "n"), "contact force V0'(x_{n+1}-x_n) on bond n",
                 attrs=(("comment", "with free ends the last bond is absent and its force is 0"),)),
    "energy": Var(("t",), "lattice Hamiltonian (ham)"),
    "dissipated": Var(("t",), "energy dissipated since t = 0 by the damping terms of (ncdamped), D(t) = int_0^t P",
                      attrs=(("comment", "integrated with the run as its own quantity (not H(0) - H(t)); "
                                         "energy + dissipated is conserved to the integrator's accuracy"),)),
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
    # the site coefficients of the imperfect cradle (ncimperfect)
    "omega_n": Var(("n",), "on-site angular frequency omega_n of bead n, in units of omega_0 (ncimperfect)"),
    "mass_n": Var(("n",), "mass m_n of bead n relative to the reference bead (ncimperfect)"),
    "stiffness_n": Var(("n",), "contact stiffness k_n of bond n (beads n, n+1) relative to the reference pair "
                               "(ncimperfect)"),
    "rho1": Var(("n",), "noise rho_n^(1) of (perturb)"),
    "rho2": Var(("n",), "noise rho_n^(2) of (perturb)"),
    # stationary DpS (dpsstn) and the map G
    "a": Var(("n",), "solution a_n of the stationary DpS equation (dpsstn)"),
    "residual_n": Var(("n",), "residual of (dpsstn) at site n"),
    "log10_abs_a": Var(("n",), "log10 |a_n|, tails continued below machine precision in log variables"),
    "map_a": Var(("orbit", "iterate"), "a_j along an orbit of G"),
    "map_b": Var(("orbit", "iterate"), "b_{j+1} along an orbit of G"),
    "mark": Var(("mark",), "point of an explicit periodic orbit of G (traj2 caption)"),
    "mark_a": Var(("mark",), "a_n of an explicit period-2, -3 or -4 orbit of G"),
    "mark_b": Var(("mark",), "b_{n+1} of an explicit period-2, -3 or -4 orbit of G"),
    "mark_period": Var(("mark",), "period of the explicit orbit the point belongs to"),
    # comparison metrics
    "E": Var(("t",), "relative error E(t) = ||x^app(t) - x(t)||_inf / a (plot4-5)"),
    "spectrum_exact": Var(("t", "k"), "|x_hat_k(t)| of the exact solution"),
    "spectrum_dps": Var(("t", "k"), "|x_hat_k(t)| of the approximate solution"),
    # metrics of travelling-wave scenes (fft106, fftseuil, fft344, plotcomplin)
    "sideband_ratio_exact": Var(("t",), "sideband-to-carrier ratio of |x_hat_k(t)|, exact solution",
                                attrs=(("comment", "cradle.measurements.sidebands.sideband_peak; "
                                                   "windows of sideband_exclude_bins bins left out"),)),
    "sideband_ratio_dps": Var(("t",), "sideband-to-carrier ratio of |x_hat_k(t)|, approximate solution",
                              attrs=(("comment", "cradle.measurements.sidebands.sideband_peak; "
                                                 "windows of sideband_exclude_bins bins left out"),)),
    "sideband_k_exact": Var(("t",), "wavenumber k of the largest sideband, exact solution", "rad"),
    "sideband_k_dps": Var(("t",), "wavenumber k of the largest sideband, approximate solution", "rad"),
    "carrier_share_exact": Var(("t",), "share of the carrier k = +-q in sum_k |x_hat_k(t)|^2, exact solution"),
    "carrier_share_dps": Var(("t",), "share of the carrier k = +-q in sum_k |x_hat_k(t)|^2, approximate solution"),
    "x_linear": Var(("t", "n"), "linear wave a cos(q n - t + phi) of (nc) linearised at x = 0 (plotcomplin)"),
    # metrics of localised scenes (plot18, loc1, fini)
    "t_window": Var(("t_window",), "start time t of a breather-period window",
                    attrs=(("comment", "windows [t_0 + j T, t_0 + (j+1) T), T = 2 pi / breather_omega"),)),
    "breather_omega": Var((), "angular frequency whose period bins the peak compression",
                          attrs=(("comment", "omega_sw of the scene; 1.1 for the packet (no omega_sw)"),)),
    "peak_compression_exact": Var(("t_window", "n"), "peak compression max |f_n| over one breather period, exact"),
    "peak_compression_dps": Var(("t_window", "n"), "peak compression max |f_n| over one breather period, approximate"),
    "merging_time_exact": Var((), "merging time of the two breathers in breather periods, exact (NaN: none)",
                              attrs=(("comment", "cradle.measurements.interactions.classify on max_t |x_n| per "
                                                 "period: first period of the final single breather"),)),
    "merging_time_dps": Var((), "merging time of the two breathers in breather periods, approximate (NaN: none)",
                            attrs=(("comment", "cradle.measurements.interactions.classify on max_t |x_n| per "
                                               "period: first period of the final single breather"),)),
    "first_coalescence_exact": Var((), "first coalescence of the two breathers in breather periods, exact (NaN: none)",
                                   attrs=(("comment", "cradle.measurements.interactions.classify on max_t |x_n| per "
                                                      "period: first period of the first single state, which a "
                                                      "breathing bound pair may leave again"),)),
    "first_coalescence_dps": Var((), "first coalescence of the two breathers in breather periods, approximate "
                                     "(NaN: none)",
                                 attrs=(("comment", "cradle.measurements.interactions.classify on max_t |x_n| per "
                                                    "period: first period of the first single state, which a "
                                                    "breathing bound pair may leave again"),)),
    "outcome_exact": Var((), "interaction outcome of the two breathers, exact",
                         attrs=(("flag_values", (0, 1, 2, 3, 4)),
                                ("flag_meanings", "merge bound repel transmit none"))),
    "outcome_dps": Var((), "interaction outcome of the two breathers, approximate",
                       attrs=(("flag_values", (0, 1, 2, 3, 4)), ("flag_meanings", "merge bound repel transmit none"))),
    "breather_site": Var((), "bead n of largest |x_n(0)|, where the frequencies are measured"),
    "omega_exact": Var((), "frequency of x_n(t) at breather_site from zero crossings, exact solution"),
    "omega_approx": Var((), "frequency of x_n(t) at breather_site from zero crossings, approximate solution"),
    "half_shift_periods": Var((), "breather periods after which exact and approximate drift half a period apart"),
    "radiated_exact": Var(("t",), "max |x_n(t)| beyond 6 sites of the breather core, exact solution"),
}

#: the two models along one dimension, by name (``ds.sel(model="exact")``): the analyses that store both
#: models' results in one array declare it in their VARIABLES
MODELS = ("exact", "dps")
MODEL = Var(("model",), "model: exact lattice (nc) or DpS approximation (dfnls)/(ansatz)",
            attrs=(("comment", "'exact' or 'dps'"),))


def declared(name: str) -> Var:
    """The declaration of ``name``; a KeyError names the undeclared variable."""
    try:
        return VARIABLES[name]
    except KeyError:
        raise KeyError(f"variable {name!r} is not declared in cradle.data.variables.VARIABLES") from None
