"""Every stored variable and coordinate, declared once: dimensions, long name, units.

Writers never type a ``long_name`` or ``units``: :func:`cradle.pipeline.io.make_dataset`
looks them up here (the xarray-simlab way), so all outputs agree. Everything in
the model is dimensionless (time in units of 1/omega_0 of the pendula,
displacements in units of the Hertz length), hence units "1".

CF-1.10 notes: the time coordinates are ``t`` and ``tau``, never ``time``
(a ``time`` coordinate would need calendar units such as "days since ...");
complex amplitudes are stored as ``_re``/``_im`` pairs; ``attrs`` holds any
further CF attributes of a variable (``comment``, ``flag_values``, ...), also
written by :func:`cradle.pipeline.io.make_dataset`.
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Var:
    dims: tuple[str, ...]
    long_name: str
    units: str = "1"
    attrs: tuple[tuple[str, str], ...] = ()  # further CF attributes, as (name, value) pairs


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
    "merging_time_exact": Var((), "merging time of the two breathers in breather periods, exact (NaN: none)"),
    "merging_time_dps": Var((), "merging time of the two breathers in breather periods, approximate (NaN: none)"),
    "breather_site": Var((), "bead n of largest |x_n(0)|, where the frequencies are measured"),
    "omega_exact": Var((), "frequency of x_n(t) at breather_site from zero crossings, exact solution"),
    "omega_approx": Var((), "frequency of x_n(t) at breather_site from zero crossings, approximate solution"),
    "half_shift_periods": Var((), "breather periods after which exact and approximate drift half a period apart"),
    "radiated_exact": Var(("t",), "max |x_n(t)| beyond 6 sites of the breather core, exact solution"),
    # beyond the paper: theorem1, mi-diagram
    "t1_alpha": Var(("t1_alpha",), "Hertz exponent alpha of the exact travelling waves"),
    "t1_q": Var(("t1_q",), "wavenumber q of the travelling wave", "rad"),
    "t1_a": Var(("t1_a",), "amplitude a: first sine coefficient of u (ansatzu)"),
    "t1_xi": Var(("t1_xi",), "moving-frame coordinate xi = q n - omega t", "rad"),
    "t1_modes": Var(("t1_modes",), "number J of sine modes of the discretisation"),
    "t1_scene": Var(("t1_scene",), "index of a travelling-wave scene of the paper (names in attribute scene_names)"),
    "t1_omega": Var(("t1_alpha", "t1_q", "t1_a"), "frequency omega_a of the exact travelling wave of (ad)"),
    "t1_omega_dps": Var(("t1_alpha", "t1_q", "t1_a"), "DpS frequency (wleadingorder) without o(): omega_tw of (freq)"),
    "t1_lambda": Var(("t1_alpha", "t1_q", "t1_a"), "lambda = (omega_a^2 - 1) / a^(alpha-1) (adcentral)"),
    "t1_rel_correction": Var(("t1_alpha", "t1_q", "t1_a"), "relative correction (omega_a - omega_DpS)/(omega_DpS - 1)"),
    "t1_residual": Var(("t1_alpha", "t1_q", "t1_a"), "max residual of the discrete (ad), scale-free units"),
    "t1_newton_iterations": Var(("t1_alpha", "t1_q", "t1_a"), "Newton iterations"),
    "t1_profile_error": Var(("t1_alpha", "t1_q", "t1_a"), "max_xi |v_a - K_h P_h N0(sin)|: remainder R_a of (va)"),
    "t1_u_max": Var(("t1_alpha", "t1_q", "t1_a"), "max_xi u(xi) of the exact wave"),
    "t1_correction_slope": Var(("t1_alpha", "t1_q"), "log-log slope of the relative frequency correction in a"),
    "t1_decay_rate": Var(("t1_alpha", "t1_q"), "exponent s of the algebraic decay |v_j| ~ j^-s"),
    "t1_v_small": Var(("t1_alpha", "t1_q", "t1_xi"), "profile correction v_a(xi) at the smallest amplitude"),
    "t1_v_large": Var(("t1_alpha", "t1_q", "t1_xi"), "profile correction v_a(xi) at the largest amplitude"),
    "t1_va_leading": Var(("t1_alpha", "t1_q", "t1_xi"), "leading term K_h P_h N0(sin) of v_a (va), by quadrature"),
    "t1_conv_omega_error": Var(("t1_alpha", "t1_q", "t1_modes"), "|omega_J - omega_ref| against twice the largest J"),
    "t1_conv_profile_error": Var(("t1_alpha", "t1_q", "t1_modes"), "max_xi |v_J - v_ref| against twice the largest J"),
    "t1_pi_omega_quadrature": Var(("t1_alpha", "t1_a"), "q = pi: 2 pi / period of (inteq) at amplitude max u, by quadrature"),
    "t1_scene_a": Var(("t1_scene",), "amplitude a of the scene (from its omega_tw by (freq))"),
    "t1_scene_q": Var(("t1_scene",), "wavenumber q of the scene", "rad"),
    "t1_scene_alpha": Var(("t1_scene",), "Hertz exponent of the scene"),
    "t1_scene_t": Var(("t1_scene",), "time span of the scene"),
    "t1_scene_omega": Var(("t1_scene",), "exact travelling-wave frequency omega_a at the scene's amplitude"),
    "t1_scene_omega_dps": Var(("t1_scene",), "DpS frequency omega_tw (freq) at the scene's amplitude"),
    "t1_scene_drift": Var(("t1_scene",), "phase drift |omega_a - omega_tw| t over the scene's time span", "rad"),
    "t1_scene_residual": Var(("t1_scene",), "max residual of the discrete (ad) at the scene's amplitude"),
    "mi_alpha": Var(("mi_alpha",), "exponent alpha of the DpS equation (dfnls)"),
    "mi_q": Var(("mi_q",), "wavenumber q of the plane wave (ansatz3)", "rad"),
    "mi_p": Var(("mi_p",), "wavenumber p of the perturbation sidebands", "rad"),
    "mi_check": Var(("mi_check",), "index of a direct-simulation check"),
    "mi_growth": Var(("mi_alpha", "mi_q", "mi_p"), "scaled growth rate lambda tau0 R^(1-alpha) of the sidebands +-p"),
    "mi_max_growth": Var(("mi_alpha", "mi_q"), "max over p of the scaled growth rate"),
    "mi_argmax_p": Var(("mi_alpha", "mi_q"), "|p| of the fastest-growing perturbation (NaN where stable)", "rad"),
    "mi_q_threshold": Var(("mi_alpha",), "smallest q with an unstable perturbation", "rad"),
    "mi_p_first": Var(("mi_alpha",), "|p| of the first unstable perturbation at the threshold", "rad"),
    "mi_growth_pi": Var(("mi_alpha",), "max over p of the scaled growth rate at q = pi"),
    "mi_p_max_pi": Var(("mi_alpha",), "|p| of the fastest-growing perturbation at q = pi", "rad"),
    "mi_fixed_point_residual": Var(("mi_alpha",), "max |rotating-frame right-hand side| at the plane wave, N = check_N"),
    "mi_check_q": Var(("mi_alpha", "mi_check"), "q = 2 pi k_q / N of a direct DpS check", "rad"),
    "mi_check_p": Var(("mi_alpha", "mi_check"), "p = 2 pi m_p / N of a direct DpS check", "rad"),
    "mi_check_theory": Var(("mi_alpha", "mi_check"), "scaled growth rate from the linear stability matrix"),
    "mi_check_simulated": Var(("mi_alpha", "mi_check"), "scaled growth rate fitted on a direct DpS run"),
    "mi_check_rel_error": Var(("mi_alpha", "mi_check"), "simulated / theoretical growth rate - 1"),
    # beyond the paper: mi-statistics (cradle.analyses.mistatistics)
    "mis_N": Var(("mis_N",), "number N of beads on the ring"),
    "mis_model": Var(("mis_model",), "model index: 0 exact lattice (nc), 1 DpS approximation (dfnls)/(ansatz)",
                      attrs=(("comment", "names in the global attribute model_names"),)),
    "mis_q": Var(("mis_q",), "carrier wavenumber q of the travelling wave", "rad"),
    "mis_seed": Var(("mis_seed",), "seed of numpy.random.default_rng drawing the noise of (perturb)"),
    "mis_t": Var(("mis_t",), "dimensionless time t of (nc) at which the spectrum is sampled"),
    "mis_ratio": Var(("mis_N", "mis_model", "mis_q", "mis_seed", "mis_t"),
                     "sideband-to-carrier ratio of the spatial spectrum |x_hat_k(t)|"),
    "mis_crossing_time": Var(("mis_N", "mis_model", "mis_q", "mis_seed"),
                             "first time t the sideband ratio reaches the fraction (NaN: not by t_end)",
                             attrs=(("comment", "see mis_crossed; fraction in the global attribute `fraction`"),)),
    "mis_crossed": Var(("mis_N", "mis_model", "mis_q", "mis_seed"), "run unstable by t_end (ratio reached fraction)",
                       attrs=(("comment", "1: the ratio reached fraction by t_end, 0: it did not"),)),
    "mis_k_peak": Var(("mis_N", "mis_model", "mis_q", "mis_seed"),
                      "wavenumber k of the largest sideband at the crossing (at the maximum if none)", "rad"),
    "mis_drift": Var(("mis_N", "mis_model", "mis_q", "mis_seed"),
                     "max relative drift of the lattice energy (exact) or of sum |A_n|^2 (dps)"),
    "mis_k_index": Var(("mis_N", "mis_q"), "integer k with q = 2 pi k / N"),
    "mis_a": Var(("mis_N", "mis_q"), "wave amplitude a from (freq) at omega_tw"),
    "mis_fraction_unstable": Var(("mis_N", "mis_model", "mis_q"), "fraction of seeds unstable by t_end"),
    "mis_fraction_low": Var(("mis_N", "mis_model", "mis_q"), "Wilson 95 % lower bound of the unstable fraction"),
    "mis_fraction_high": Var(("mis_N", "mis_model", "mis_q"), "Wilson 95 % upper bound of the unstable fraction"),
    "mis_median_crossing_time": Var(("mis_N", "mis_model", "mis_q"), "median crossing time over unstable seeds"),
    "mis_threshold": Var(("mis_N", "mis_model"), "threshold q: the unstable fraction crosses 1/2", "rad"),
    "mis_threshold_low": Var(("mis_N", "mis_model"), "lower end of the threshold interval (Wilson 95 %)", "rad"),
    "mis_threshold_high": Var(("mis_N", "mis_model"), "upper end of the threshold interval (Wilson 95 %)", "rad"),
    # beyond the paper: mi-growth (cradle.analyses.migrowth)
    "mig_scene": Var(("mig_scene",), "index of a scene (names in the global attribute scene_names)"),
    "mig_model": Var(("mig_model",), "model index: 0 exact lattice (nc), 1 DpS approximation (dfnls)/(ansatz)",
                      attrs=(("comment", "names in the global attribute model_names"),)),
    "mig_m": Var(("mig_m",), "index m of the perturbation wavenumber p = 2 pi m / N"),
    "mig_t": Var(("mig_t",), "dimensionless time t of (nc)"),
    "mig_q": Var(("mig_scene",), "carrier wavenumber q of the scene", "rad"),
    "mig_N": Var(("mig_scene",), "number N of beads of the scene"),
    "mig_eps": Var(("mig_scene",), "small parameter eps = a/2 of (ansatz); tau = eps^(alpha-1) t"),
    "mig_p": Var(("mig_scene", "mig_m"), "perturbation wavenumber p = 2 pi m / N (NaN past N/2)", "rad"),
    "mig_theory_p": Var(("mig_scene", "mig_m"), "linear DpS growth rate lambda(q, p) eps^(alpha-1), per unit t"),
    "mig_rate_p": Var(("mig_scene", "mig_model", "mig_m"),
                      "slope of log sideband-pair amplitude at p over the fit window, per unit t"),
    "mig_rate": Var(("mig_scene", "mig_model"), "measured growth rate of the dominant sideband pair, per unit t"),
    "mig_rate_stderr": Var(("mig_scene", "mig_model"), "standard error of the fitted growth rate, per unit t"),
    "mig_r2": Var(("mig_scene", "mig_model"), "coefficient of determination of the log-linear fit"),
    "mig_rate_theory": Var(("mig_scene", "mig_model"),
                           "linear DpS growth rate at the scene's q and the measured p*, per unit t"),
    "mig_rate_theory_max": Var(("mig_scene",), "max over p of the linear DpS growth rate, per unit t"),
    "mig_p_star": Var(("mig_scene", "mig_model"), "|p| of the sideband pair that grows (fit target)", "rad"),
    "mig_window_start": Var(("mig_scene", "mig_model"), "start of the fit window in t"),
    "mig_window_end": Var(("mig_scene", "mig_model"), "end of the fit window in t"),
    "mig_exponential": Var(("mig_scene", "mig_model"), "an exponential growth phase was found",
                           attrs=(("comment", "1: exponential phase found (growth over the window >= decades, r2 >= r2_min), 0: not"),)),
    "mig_pair": Var(("mig_scene", "mig_model", "mig_t"),
                    "sideband-pair amplitude at p* over the carrier, |A_hat| spectrum (NaN past t_end)"),
    "mig_envelope": Var(("mig_scene", "mig_model", "mig_t"), "largest sideband-pair amplitude over the carrier"),
    "mig_theory_q": Var(("mig_theory_q",), "wavenumber q of the linear DpS growth-rate diagram", "rad"),
    "mig_theory_max": Var(("mig_theory_q",), "max over p of the scaled linear DpS growth rate lambda tau0 R^(1-alpha)"),
    "mig_rate_scale": Var(("mig_scene",), "tau0 / eps^(alpha-1): a rate per unit t times this is lambda tau0 R^(1-alpha)"),
    "mig_sim_check": Var(("mig_scene", "mig_model"),
                         "max |x - x_sim| / a against results/sim/<scene>/<model>.nc up to the window end"),
    # beyond the paper: floquet (spectral stability of the exact travelling waves)
    "fq_q": Var(("fq_q",), "wavenumber q of the exact travelling wave", "rad"),
    "fq_p": Var(("fq_p",), "Bloch wavenumber p of the perturbation (DpS sideband p)", "rad"),
    "fq_q_profile": Var(("fq_q_profile",), "wavenumber q of a growth-against-p profile", "rad"),
    "fq_omega_tw": Var(("fq_omega_tw",), "omega_tw of (freq) fixing the amplitude of a threshold search"),
    "fq_small_q": Var(("fq_small_q",), "wavenumber q of a small-amplitude check against DpS", "rad"),
    "fq_a": Var(("fq_q",), "amplitude a (first sine coefficient of u) from (freq) at omega_tw"),
    "fq_omega": Var(("fq_q",), "frequency omega_a of the exact wave"),
    "fq_growth": Var(("fq_q", "fq_p"), "lattice growth rate g(p): max Re lambda of the central Bloch pair", "1",
                     attrs=(("comment", "per unit lattice time t; 0 where stable; p = 0 (trivial pair) set to 0"),)),
    "fq_dps_growth": Var(("fq_q", "fq_p"), "DpS growth rate of sideband p in lattice time (R = a/2)"),
    "fq_max_growth": Var(("fq_q",), "max over p of the lattice growth rate"),
    "fq_argmax_p": Var(("fq_q",), "p of the fastest-growing lattice mode (NaN where stable)", "rad"),
    "fq_dps_max_growth": Var(("fq_q",), "max over p of the DpS growth rate in lattice time"),
    "fq_dps_argmax_p": Var(("fq_q",), "p of the fastest-growing DpS sideband (NaN where stable)", "rad"),
    "fq_trivial_defect": Var(("fq_q",), "max |lambda| of the central pair at p = 0 (exactly 0; numerical error)"),
    "fq_profile_growth": Var(("fq_q_profile", "fq_p"), "lattice growth rate against p at a selected q"),
    "fq_profile_dps_growth": Var(("fq_q_profile", "fq_p"), "DpS growth rate (lattice time) against p at a selected q"),
    "fq_profile_max_growth": Var(("fq_q_profile",), "max over p of the lattice growth rate at a selected q"),
    "fq_profile_argmax_p": Var(("fq_q_profile",), "p of the fastest-growing lattice mode at a selected q", "rad"),
    "fq_profile_max_growth_fine": Var(("fq_q_profile",), "the same with the finer numerics (convergence check)"),
    "fq_profile_dps_max_growth": Var(("fq_q_profile",), "max over p of the DpS growth rate at a selected q"),
    "fq_threshold": Var(("fq_omega_tw",), "lattice instability threshold: smallest unstable q", "rad"),
    "fq_threshold_bisection": Var(("fq_omega_tw",), "half-width of the final bisection bracket of the threshold",
                                  "rad"),
    "fq_threshold_p": Var(("fq_omega_tw",), "p of the first unstable lattice mode at the threshold", "rad"),
    "fq_small_growth": Var(("fq_small_q",), "max lattice growth rate at the small amplitude"),
    "fq_small_dps_growth": Var(("fq_small_q",), "max DpS growth rate (lattice time) at the small amplitude"),
    "fq_small_rel_error": Var(("fq_small_q",), "lattice / DpS max growth rate - 1 at the small amplitude"),
}


def declared(name: str) -> Var:
    """The declaration of ``name``; a KeyError names the undeclared variable."""
    try:
        return VARIABLES[name]
    except KeyError:
        raise KeyError(f"variable {name!r} is not declared in cradle.pipeline.variables.VARIABLES") from None
