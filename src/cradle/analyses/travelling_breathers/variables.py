"""The variables of ``results/travelling-breathers/travelling-breathers.nc``, group by group, each with its
dimensions, long name and units (:class:`cradle.data.variables.Var`).
"""
from __future__ import annotations

from cradle.analyses.claims_table import GROUP_VARIABLES
from cradle.data.variables import Var

_C = ("c",)
VARIABLES = {
    "/": {
        "c": Var(_C, "velocity c = 1/T of the travelling breather (sites per unit tau at the family's norm)"),
    },
    "/family": {
        "period": Var(_C, "period T of (tb): one site per T"),
        "theta": Var(_C, "phase theta of (tb), in (-pi, pi]"),
        "energy": Var(_C, "DpS Hamiltonian H = -sum |A_{n+1} - A_n|^(alpha+1) / ((alpha+1) tau0)"),
        "dH_dc": Var(_C, "dH/dc along the family at fixed norm (centred differences on the grid)"),
        "tail": Var(_C, "max |A_n| on the quarter ring farthest from the centre / max |A_n| (the oscillatory tail)"),
        "residual": Var(_C, "shift-map residual max_n |e^{-i theta} A_{n+1}(T) - A_n(0)| / max |A|"),
        "iterations": Var(_C, "Newton iterations from the tangent predictor"),
        "trivial_defect": Var(_C, "largest |mu - 1| of the four trivial multipliers modulo shift (exactly 0)"),
        "growth_rate": Var(_C, "ln max |mu| / T over the non-trivial multipliers modulo shift (per unit tau)"),
        "unstable": Var(_C, "1 if growth_rate > stability_threshold"),
        "real_mode": Var(_C, "1 if unstable through a real multiplier > 1 (the dH/dc kind), not a complex quartet"),
        "unstable_rtol": Var(_C, "the verdict re-solved at check_rtol"),
        "growth_rate_rtol": Var(_C, "growth_rate re-solved at check_rtol"),
        "unstable_N": Var(_C, "the verdict on the ring of check_N sites (-1: member not reached there)"),
        "growth_rate_N": Var(_C, "growth_rate on the ring of check_N sites (NaN: not reached)"),
        "tail_N": Var(_C, "tail on the ring of check_N sites (NaN: not reached)"),
        "static_distance_site": Var(_C, "min over one period and shifts of max_n ||A_n(tau)| - phi_n^site| / max phi"),
        "static_distance_bond": Var(_C, "the same against the bond-centred static breather"),
    },
    "/profiles": {
        "n": Var(("n",), "site index on the ring"),
        "A_re": Var(("c", "n"), "Re A_n(0) of the travelling breather"),
        "A_im": Var(("c", "n"), "Im A_n(0) of the travelling breather"),
        "static_site": Var(("n",), "phi_n of the site-centred static breather at the family's norm"),
        "static_bond": Var(("n",), "phi_n of the bond-centred static breather at the family's norm"),
    },
    "/multipliers": {
        "m": Var(("m",), "index of a Floquet multiplier modulo shift"),
        "mu_re": Var(("c", "m"), "real part of a multiplier of e^{-i theta} S^{-1} DPhi_T"),
        "mu_im": Var(("c", "m"), "imaginary part of a multiplier of e^{-i theta} S^{-1} DPhi_T"),
    },
    "/direct": {
        "k": Var(("k",), "periods of the direct run"),
        "residual": Var(("k",), "max_n |A_n(kT) - e^{i k theta} A_{n-k}(0)| / max |A|"),
    },
    "/lattice": {
        "c_lattice": Var(("c_lattice",), "velocity c = 1/T of the lattice's TB (sites per unit t), the continuation "
                         "from the TB at the first lattice_eps"),
        "period": Var(("c_lattice",), "period T of (tbnc): x_n(t + T) = x_{n-1}(t)"),
        "eps": Var(("c_lattice",), "eps of the ansatz at the TB's amplitude: sqrt(sum |xi_n|^2 / norm)"),
        "energy": Var(("c_lattice",), "energy (ham) of the lattice's TB"),
        "residual": Var(("c_lattice",), "shift-map residual max |S^{-1} Phi_T(z) - z| / max |z|"),
        "tail": Var(("c_lattice",), "max |xi_n| on the quarter ring farthest from the centre / max |xi_n|, "
                    "xi_n = (x_n - i v_n)/2"),
        "trivial_defect": Var(("c_lattice",), "largest |mu - 1| of the four multipliers modulo shift nearest 1 (time "
                              "shift and energy; the carrier's phase and the wave action)"),
        "growth_rate": Var(("c_lattice",), "ln max |mu| / T over the other multipliers modulo shift (per unit t)"),
        "unstable": Var(("c_lattice",), "1 if growth_rate > stability_threshold"),
        "reciprocal_defect": Var(("c_lattice",), "max over mu of the distance of 1/mu to the nearest multiplier"),
        "smallest_singular": Var(("c_lattice",), "smallest singular value of the bordered Jacobian over its largest "
                                 "(the near-symmetry's direction)"),
    },
    "/lattice_eps": {
        "eps_lattice": Var(("eps_lattice",), "eps of the ansatz that started the solve (lattice_eps)"),
        "period": Var(("eps_lattice",), "period T of (tbnc) of the exact TB"),
        "c_tb": Var(("eps_lattice",), "its velocity 1/T (sites per unit t)"),
        "eps_tb": Var(("eps_lattice",), "eps at the TB's own amplitude: sqrt(sum |xi_n|^2 / norm)"),
        "ansatz_period": Var(("eps_lattice",), "time per site T_d eps^(1-alpha) of the DpS member at eps_lattice"),
        "start_residual": Var(("eps_lattice",), "shift-map residual of the ansatz at T (the closest return)"),
        "residual": Var(("eps_lattice",), "shift-map residual max |S^{-1} Phi_T(z) - z| / max |z| of the TB"),
        "iterations": Var(("eps_lattice",), "Newton iterations from the ansatz"),
        "energy": Var(("eps_lattice",), "energy (ham) of the TB"),
        "tail": Var(("eps_lattice",), "max |xi_n| on the far quarter ring / max |xi_n|"),
        "trivial_defect": Var(("eps_lattice",), "largest |mu - 1| of the four multipliers modulo shift nearest 1"),
        "growth_rate": Var(("eps_lattice",), "ln max |mu| / T over the other multipliers modulo shift (per unit t)"),
        "unstable": Var(("eps_lattice",), "1 if growth_rate > stability_threshold"),
        "reciprocal_defect": Var(("eps_lattice",), "max over mu of the distance of 1/mu to the nearest multiplier"),
        "smallest_singular": Var(("eps_lattice",), "smallest singular value of the bordered Jacobian over its "
                                 "largest"),
        "dps_c": Var(("eps_lattice",), "velocity of the DpS TB through the ansatz: 1 / (T eps_tb^(alpha-1))"),
        "resonance": Var(("eps_lattice",), "theta + T of that DpS TB, modulo 2 pi into (-pi, pi] (0: the ansatz's "
                         "resonance)"),
        "ansatz_distance": Var(("eps_lattice",), "min over the DpS time, site shift and phase of max |z - "
                               "z_ansatz(A, eps_tb)| / max |z|, A that DpS TB"),
        "dps_speed": Var(("eps_lattice",), "the DpS member launched in (nc) through (ansatz): speed over c "
                         "eps^(alpha-1)"),
        "exact_speed": Var(("eps_lattice",), "the exact TB launched the same way: speed over c eps^(alpha-1)"),
        "dps_radiation": Var(("eps_lattice",), "the DpS launch: energy outside the window / total, at the end"),
        "exact_radiation": Var(("eps_lattice",), "the exact TB's launch: energy outside the window / total, at the "
                               "end"),
        "exact_radiation_max": Var(("eps_lattice",), "the exact TB's launch: largest such fraction over the run"),
        "dps_energy_drift": Var(("eps_lattice",), "the DpS launch: max |H(t) - H(0)| / H(0)"),
        "exact_energy_drift": Var(("eps_lattice",), "the exact TB's launch: max |H(t) - H(0)| / H(0)"),
    },
    "/lattice_states": {
        "eps_lattice": Var(("eps_lattice",), "eps of the ansatz that started the solve (lattice_eps)"),
        "site": Var(("site",), "bead index n on the ring"),
        "mode": Var(("mode",), "index of a Floquet multiplier modulo shift"),
        "x": Var(("eps_lattice", "site"), "x_n(0) of the lattice's TB"),
        "v": Var(("eps_lattice", "site"), "v_n(0) of the lattice's TB"),
        "mu_re": Var(("eps_lattice", "mode"), "real part of a multiplier of S^{-1} DPhi_T"),
        "mu_im": Var(("eps_lattice", "mode"), "imaginary part of a multiplier of S^{-1} DPhi_T"),
        "dps_A_re": Var(("eps_lattice", "site"), "Re A_n(0) of the DpS TB through the ansatz (dps_c, the norm)"),
        "dps_A_im": Var(("eps_lattice", "site"), "Im A_n(0) of that DpS TB"),
        "source_A_re": Var(("site",), "Re A_n(0) of the DpS TB whose ansatz started the lattice's TBs"),
        "source_A_im": Var(("site",), "Im A_n(0) of the DpS TB whose ansatz started the lattice's TBs"),
    },
    "/lattice_rings": {
        "ring": Var(("ring",), "sites N of the ring (the first: lattice_N, the members of /lattice_eps and /lattice)"),
        "eps_lattice": Var(("eps_lattice",), "eps of the ansatz that started the TB on the ring of lattice_N"),
        "c_step": Var(("c_step",), "relative change s of the velocity: c = c0 (1 + s), c0 that of the member at the "
                      "first eps_lattice on the same ring"),
        "ring_site": Var(("ring_site",), "site n (up to the largest ring; NaN beyond each ring)"),
        **{f"{k}{suffix}": Var(dims, f"{text} ({which})", units)
           for suffix, dims, which in (("", ("ring", "eps_lattice"), "the TB at eps_lattice on that ring"),
                                       ("_family", ("ring", "c_step"), "the continuation in c on that ring"))
           for k, (text, units) in {
               "period": ("period T of (tbnc), x_n(t + T) = x_{n-1}(t), in units of t", "1"),
               "eps_tb": ("eps at the TB's amplitude: sqrt(sum |xi_n|^2 / norm)", "1"),
               "dps_c": ("velocity of the DpS TB through (ansatz), 1 / (T eps_tb^(alpha-1)), sites per unit tau", "1"),
               "residual": ("shift-map residual max |S^{-1} Phi_T(z) - z| / max |z|", "1"),
               "iterations": ("Newton iterations", "1"),
               "tail": ("max |xi_n| on the far quarter ring / max |xi_n|, xi_n = (x_n - i v_n)/2", "1"),
               "energy": ("energy (ham) of the TB", "1"),
               "trivial_defect": ("largest |mu - 1| of the four multipliers modulo shift nearest 1", "1"),
               "growth_rate": ("ln max |mu| / T over the other multipliers modulo shift, per unit t", "1"),
               "unstable": ("1 if growth_rate > stability_threshold", "1"),
               "reciprocal_defect": ("max over mu of the distance of 1/mu to the nearest multiplier", "1"),
               "smallest_singular": ("smallest singular value of the bordered Jacobian over its largest", "1"),
           }.items()},
        "c_family": Var(("ring", "c_step"), "velocity c = 1/T of the member of the continuation, sites per unit t"),
        "x": Var(("ring", "eps_lattice", "ring_site"), "x_n(0) of the TB at eps_lattice"),
        "v": Var(("ring", "eps_lattice", "ring_site"), "v_n(0) of the TB at eps_lattice"),
        "x_family": Var(("ring", "c_step", "ring_site"), "x_n(0) of the member of the continuation in c"),
        "v_family": Var(("ring", "c_step", "ring_site"), "v_n(0) of the member of the continuation in c"),
    },
    "/lattice_large": {
        "eps_large": Var(("eps_large",), "eps of the ansatz (lattice_large_eps) on the ring of lattice_N"),
        "site": Var(("site",), "site n of the ring of lattice_N"),
        **{k: Var(("eps_large",), text) for k, text in {
            "period": "period T of (tbnc): the time of the ansatz's closest return to its shifted start, in units of t",
            "eps_tb": "eps at the TB's amplitude: sqrt(sum |xi_n|^2 / norm)",
            "dps_c": "velocity of the DpS TB through (ansatz), 1 / (T eps_tb^(alpha-1)), sites per unit tau",
            "residual": "shift-map residual max |S^{-1} Phi_T(z) - z| / max |z| at the end",
            "iterations": "Newton iterations of the second stage (all unknowns)",
            "tail": "max |xi_n| on the far quarter ring / max |xi_n|",
            "energy": "energy (ham) of the TB",
            "trivial_defect": "largest |mu - 1| of the four multipliers modulo shift nearest 1",
            "growth_rate": "ln max |mu| / T over the other multipliers modulo shift, per unit t",
            "unstable": "1 if growth_rate > stability_threshold",
            "reciprocal_defect": "max over mu of the distance of 1/mu to the nearest multiplier",
            "smallest_singular": "smallest singular value of the bordered Jacobian over its largest",
            "ansatz_period": "time per site T_d eps^(1-alpha) of the DpS member in units of t",
            "start_residual": "shift-map residual of the ansatz at T",
            "core_residual": "shift-map residual after the first stage (the core's unknowns alone)",
            "converged": "1 if the residual reached newton_tol",
        }.items()},
        "x": Var(("eps_large", "site"), "x_n(0) of the TB"),
        "v": Var(("eps_large", "site"), "v_n(0) of the TB"),
    },
    "/lattice_zeros": {
        "zero_ring": Var(("zero_ring",), "sites N of the ring (lattice_zero_rings)"),
        "minimum": Var(("minimum",), "the minimum followed: 0 the branch of the TB at lattice_zero_eps, 1 that of the "
                       "continuation's member at lattice_zero_step"),
        "zero_step": Var(("zero_step",), "relative change s of the velocity on the fine grid: c = c1 (1 + s), c1 that "
                         "of the minimum's member"),
        "iterate": Var(("iterate",), "iterate of the regula falsi"),
        "zero_site": Var(("zero_site",), "site n (up to the largest ring; NaN beyond each ring)"),
        **{f"{k}{suffix}": Var(dims, f"{text} ({which})", units)
           for suffix, dims, which in (("_grid", ("zero_ring", "minimum", "zero_step"), "the fine grid's member"),
                                       ("", ("zero_ring", "minimum"), "the TB where the signed tail vanishes"))
           for k, (text, units) in {
               "c_tb": ("velocity c = 1/T, sites per unit t", "1"),
               "period": ("period T of (tbnc), x_n(t + T) = x_{n-1}(t), in units of t", "1"),
               "eps_tb": ("eps at the TB's amplitude: sqrt(sum |xi_n|^2 / norm)", "1"),
               "dps_c": ("velocity of the DpS TB through (ansatz), 1 / (T eps_tb^(alpha-1)), sites per unit tau", "1"),
               "residual": ("shift-map residual max |S^{-1} Phi_T(z) - z| / max |z|", "1"),
               "sigma": ("signed tail Re(B / xi_n0) |xi_n0| / max |xi_n| at the symmetric time, B the far field's "
                         "plane wave at the antipode (cradle.integrators.lattice_tail)", "1"),
               "tail": ("max |xi_n| on the far quarter ring / max |xi_n| at t = 0", "1"),
               "phase_defect": ("Im(B / xi_n0) |xi_n0| / max |xi_n|: the part of the far field off the symmetric "
                                "phase", "1"),
           }.items()},
        "c_error": Var(("zero_ring", "minimum"), "uncertainty of c: max(|sigma|, residual) over the bracket's slope "
                       "d sigma / dc, sites per unit t"),
        "symmetry_defect": Var(("zero_ring", "minimum"), "distance of eta_n = xi_n / xi_n0 to conj(eta_{2 n0 - n}), "
                               "weighted by |xi_n| / max, at the symmetric time"),
        "trivial_defect": Var(("zero_ring", "minimum"), "largest |mu - 1| of the four multipliers modulo shift nearest "
                              "1"),
        "growth_rate": Var(("zero_ring", "minimum"), "ln max |mu| / T over the other multipliers modulo shift, "
                           "per unit t"),
        "unstable": Var(("zero_ring", "minimum"), "1 if growth_rate > stability_threshold"),
        "reciprocal_defect": Var(("zero_ring", "minimum"), "max over mu of the distance of 1/mu to the nearest "
                                 "multiplier"),
        "bracket_low": Var(("zero_ring", "minimum"), "c of the grid member at the bracket's lower end, sites per "
                           "unit t"),
        "bracket_high": Var(("zero_ring", "minimum"), "c of the grid member at the bracket's upper end, sites per "
                            "unit t"),
        "iterations": Var(("zero_ring", "minimum"), "iterates of the regula falsi"),
        "c_iterate": Var(("zero_ring", "minimum", "iterate"), "velocity c of each iterate of the regula falsi, sites "
                         "per unit t"),
        "sigma_iterate": Var(("zero_ring", "minimum", "iterate"), "signed tail of each iterate"),
        "x": Var(("zero_ring", "minimum", "zero_site"), "x_n(0) of the TB where the signed tail vanishes"),
        "v": Var(("zero_ring", "minimum", "zero_site"), "v_n(0) of the TB where the signed tail vanishes"),
    },
    "/lattice_motion": {
        "eps_lattice": Var(("eps_lattice",), "eps of the launch"),
        "s_lattice": Var(("s_lattice",), "tau / T of the DpS member (the lattice time t = s T / eps^(alpha-1))"),
        "dps_distance": Var(("eps_lattice", "s_lattice"), "the DpS member launched in (nc): position minus start"),
        "exact_distance": Var(("eps_lattice", "s_lattice"), "the exact TB launched the same way: position minus "
                              "start"),
    },
    "/motion": {
        "eps": Var(("eps",), "small parameter eps of (ansatz) of the lattice run (tau = eps^(alpha-1) t)"),
        "s": Var(("s",), "tau / T: the sites the DpS TB travels (lattice time t = s T / eps^(alpha-1))"),
        "speed_ratio": Var(("eps",), "lattice velocity over the DpS TB's c eps^(alpha-1) (least squares, whole run)"),
        "speed_early": Var(("eps",), "the same over the first half of the run"),
        "speed_late": Var(("eps",), "the same over the second half of the run"),
        "deficit": Var(("eps",), "1 - speed_ratio: the lattice's speed deficit against DpS"),
        "radiation_end": Var(("eps",), "energy outside the window around the breather over the total, at the end"),
        "energy_drift": Var(("eps",), "max over every step of |H(t) - H(0)| / H(0) of the lattice run (ham)"),
        "distance": Var(("eps", "s"), "lattice: position of the breather minus its start (sites)"),
        "radiation": Var(("eps", "s"), "lattice: energy outside the window around the breather over the total"),
        "dps_distance": Var(("s",), "DpS (same start, same ring): position minus start (sites)"),
        "dps_radiation": Var(("s",), "DpS: norm outside the window around the breather over the norm"),
    },
    "/robustness": {
        "ring": Var(("ring",), "sites of the ring (N, then check_N)"),
        "rtol": Var(("rtol",), "DOP853 relative tolerance (rtol, then check_rtol), on the ring of N"),
        "growth_rate": Var(("ring", "c"), "ln max |mu| / T over the non-trivial multipliers modulo shift (per unit "
                                          "tau; NaN: member not reached on that ring)"),
        "unstable": Var(("ring", "c"), "1 if growth_rate > stability_threshold (-1: not reached)"),
        "tail": Var(("ring", "c"), "max |A_n| on the far quarter ring / max |A_n|"),
        "theta": Var(("ring", "c"), "phase theta of (tb)"),
        "tail_q": Var(("ring", "c"), "wavenumber q of the tail as a plane wave: arg sum A_{n+1} conj(A_n) on the far "
                                     "quarter ring (q = theta mod 2 pi for a tail of small amplitude)"),
        "tail_mi_rate": Var(("ring", "c"), "largest MI growth rate of the plane wave of the tail's q and rms amplitude "
                                           "on the infinite lattice (per unit tau; 0 for |q| <= pi/2)"),
        "mode_extent": Var(("ring", "c"), "participation ratio of the most unstable mode's |v_n|^2 over N (NaN: "
                                          "stable)"),
        "growth_rate_tol": Var(("rtol", "c"), "growth_rate on the ring of N at that tolerance (NaN: not converged)"),
        "unstable_tol": Var(("rtol", "c"), "the verdict on the ring of N at that tolerance (-1: not converged)"),
        "settled": Var(_C, "1 unstable and 0 stable on every ring and at every tolerance; -1 the verdict depends on "
                           "the ring or the tolerance"),
    },
    "/robustness_limit": {
        "limit_ring": Var(("limit_ring",), "sites of a ring of the fine scan (limit_N)"),
        "c_fine": Var(("c_fine",), "velocity c of the fine scan (c +- limit_halfwidth around every member)"),
        "growth_rate": Var(("limit_ring", "c_fine"), "ln max |mu| / T over the non-trivial multipliers modulo shift "
                                                     "(per unit tau; NaN: not reached on that ring)"),
        "unstable": Var(("limit_ring", "c_fine"), "1 if growth_rate > stability_threshold (-1: not reached)"),
        "theta": Var(("limit_ring", "c_fine"), "phase theta of (tb), in (-pi, pi]"),
        "tail": Var(("limit_ring", "c_fine"), "max |A_n| on the far quarter ring / max |A_n|"),
        "tail_mi_rate": Var(("limit_ring", "c_fine"), "largest MI growth rate of the tail's plane wave on the "
                                                      "infinite lattice (per unit tau; 0 for |q| <= pi/2)"),
        "krein_gap": Var(("limit_ring", "c_fine"), "smallest angle between non-trivial multipliers of opposite "
                                                   "Krein signature on the unit circle (pi: no such pair)"),
        "quartet_defect": Var(("limit_ring", "c_fine"), "largest distance from 1/conj(mu) or conj(mu) to the "
                                                        "nearest multiplier (0 for a symplectic spectrum)"),
        "top_arg": Var(("limit_ring", "c_fine"), "arg of the most unstable multiplier (pi: through -1, 0: through "
                                                 "+1; NaN: stable)"),
        "mode_participation": Var(("limit_ring", "c_fine"), "participation ratio 1 / sum w_n^2 over N of the mode "
                                                            "of the largest non-trivial multiplier (w_n its weight "
                                                            "per site, summing to 1)"),
        "mode_core_fraction": Var(("limit_ring", "c_fine"), "weight of that mode on the core, the sites where "
                                                            "|A_n| > 1e-2 max |A_n|"),
        "mode_core_fraction_norm": Var(("limit_ring", "c_fine"), "weight of that mode on the core, the sites "
                                                                 "nearest the centre that hold 1 - 1e-6 of the "
                                                                 "norm"),
        "unstable_fraction": Var(("c", "limit_ring"), "fraction of the member's fine neighbourhood that is unstable "
                                                      "on that ring (NaN: none reached)"),
        "typical_growth": Var(("c", "limit_ring"), "median growth rate over the member's fine neighbourhood"),
        "largest_growth": Var(("c", "limit_ring"), "largest growth rate over the member's fine neighbourhood"),
        "reached": Var(("c", "limit_ring"), "fraction of the member's fine neighbourhood reached on that ring"),
        "decay": Var(_C, "k: least-squares slope of -ln typical_growth against ln N over the rings where it "
                         "exceeds the threshold (NaN: fewer than two; reported, not used by the rule)"),
        "envelope_decay": Var(_C, "the same slope for largest_growth (the windows' envelope)"),
        "verdict": Var(_C, "limit verdict of limit_rule: 1 unstable, 0 stable, -1 undecided"),
        "windows": Var(("limit_ring",), "runs of consecutive unstable points of the fine grid on that ring"),
        "window_width": Var(("limit_ring",), "mean width in c of those runs (points times limit_step)"),
        "ring_largest_growth": Var(("limit_ring",), "largest growth rate over the whole fine grid on that ring"),
        "ring_unstable_fraction": Var(("limit_ring",), "fraction of the reached fine grid that is unstable"),
    },
    "/limit_tail": {
        "fit_ring": Var(("fit_ring",), "sites of a ring of the tail rule's fit (limit_N, then limit_large_N)"),
        "tail_q": Var(_C, "wavenumber q of the tail's plane wave: theta modulo 2 pi, in (-pi, pi]", "rad"),
        "tail_mi_unstable": Var(_C, "1 if the tail's plane wave is modulationally unstable (cos q < 0: at every "
                                    "amplitude), else 0"),
        "theta_spread": Var(_C, "largest |theta - theta on the ring of N| (modulo 2 pi) over the rings of "
                                "/robustness and the tolerances of check_rtol", "rad"),
        "unit_amplitude_mi_rate": Var(_C, "largest MI growth rate of the plane wave e^{i q n} of unit amplitude, "
                                          "closed form (per unit tau; times R^(alpha-1) at amplitude R)"),
        "fastest_sideband": Var(_C, "sideband wavenumber p of that largest rate (NaN: stable)", "rad"),
        "unstable_band_low": Var(_C, "lower edge of the unstable sideband band in [0, pi] (NaN: stable)", "rad"),
        "unstable_band_high": Var(_C, "upper edge of the unstable sideband band in [0, pi] (NaN: stable)", "rad"),
        "tail_mi_rate_min": Var(_C, "smallest MI growth rate of the tail measured on the rings of /robustness (per "
                                    "unit tau: its amplitude changes with N)"),
        "tail_mi_rate_max": Var(_C, "largest MI growth rate of the tail measured on those rings (per unit tau)"),
        "envelope": Var(("c", "fit_ring"), "largest growth rate over the member's neighbourhood, on the points of "
                                           "the member's tail kind common to every ring (per unit tau; NaN: none "
                                           "reached)"),
        "fit_g_inf": Var(_C, "g_inf of envelope = g_inf + b N^-k over the rings (per unit tau; NaN: fewer than 4)"),
        "fit_g_inf_error": Var(_C, "error of fit_g_inf: the larger of its standard error and its change when the "
                                   "smallest or the largest ring is left out (per unit tau)"),
        "fit_g_inf_stderr": Var(_C, "standard error of fit_g_inf from the residuals (per unit tau)"),
        "fit_b": Var(_C, "b of that fit (per unit tau times sites^k)"),
        "fit_k": Var(_C, "exponent k of that fit"),
        "fit_points": Var(_C, "rings in that fit"),
        "fit_degenerate": Var(_C, "1 if k ended on a bound of its range (the error is then no error of g_inf; NaN: "
                                  "no fit)"),
        "verdict": Var(_C, "limit verdict of tail_rule: 1 unstable, 0 stable, -1 undecided"),
        "member_growth": Var(("c", "fit_ring"), "growth rate of the member itself, at c, on each ring (per unit "
                                                "tau; NaN: not reached or c not on that ring's grid)"),
        "member_fit_g_inf": Var(_C, "g_inf of member_growth = g_inf + b N^-k over the rings (per unit tau; NaN: "
                                    "fewer than 4)"),
        "member_fit_g_inf_error": Var(_C, "error of member_fit_g_inf, as fit_g_inf_error (per unit tau)"),
        "member_fit_k": Var(_C, "exponent k of that fit"),
        "member_fit_degenerate": Var(_C, "1 if k ended on a bound of its range (NaN: no fit)"),
        "member_verdict": Var(_C, "limit verdict of the member itself (member_rule): 1 unstable, 0 stable, -1 "
                                  "undecided"),
        "member_participation": Var(("c", "fit_ring"), "participation ratio over N of the member's mode of largest "
                                                       "non-trivial multiplier, at c, on each ring (NaN: not "
                                                       "reached)"),
        "member_core_fraction": Var(("c", "fit_ring"), "weight of that mode on the core (|A_n| > 1e-2 max |A_n|), "
                                                       "at c, on each ring"),
        "member_core_fraction_norm": Var(("c", "fit_ring"), "weight of that mode on the core (the sites nearest "
                                                            "the centre holding 1 - 1e-6 of the norm), at c, on "
                                                            "each ring"),
        "mode_reading": Var(("mode_reading",), "a reading of mode_rule: the tolerance delta on the core fraction's "
                                               "slope, and whether the growth's fall must be resolved"),
        "mode_verdict_readings": Var(("c", "mode_reading"), "limit verdict of mode_rule under each reading (0 "
                                                             "stable, 1 unstable, -1 undecided)"),
        "mode_verdict": Var(_C, "limit verdict of mode_rule, read from the unstable mode's core fraction and "
                                "growth against N (tail MI-unstable: 1, as tail_rule): 1 unstable, 0 stable, -1 "
                                "undecided"),
        "mode_growth_slope": Var(_C, "power s of N in member_growth ~ N^s over the rings where the member is "
                                     "unstable (NaN: fewer than 3, or tail MI-unstable)"),
        "mode_growth_slope_error": Var(_C, "standard error of mode_growth_slope"),
        "mode_core_slope": Var(_C, "power s of N in member_core_fraction ~ N^s over the same rings (-1: an "
                                   "extended mode)"),
        "mode_core_slope_error": Var(_C, "standard error of mode_core_slope"),
    },
    "/limit_fold": {
        "fold_ring": Var(("fold_ring",), "sites of a ring of the fold scan (limit_fold_N)"),
        "arc": Var(("arc",), "index along the family: the first member, the natural continuation's, then the "
                             "pseudo-arclength's"),
        "velocity": Var(("fold_ring", "arc"), "velocity c = 1/T (sites per unit tau; NaN: past the last member)"),
        "energy": Var(("fold_ring", "arc"), "Hamiltonian H of (dfnls) at unit norm"),
        "theta": Var(("fold_ring", "arc"), "phase theta of (tb), in (-pi, pi]", "rad"),
        "growth": Var(("fold_ring", "arc"), "ln max |mu| / T over the non-trivial multipliers modulo shift (per "
                                            "unit tau)"),
        "real_growth": Var(("fold_ring", "arc"), "ln mu / T of the largest real non-trivial multiplier mu > 1 (per "
                                                 "unit tau; 0: none)"),
        "tail": Var(("fold_ring", "arc"), "max |A_n| on the far quarter ring / max |A_n|"),
        "residual": Var(("fold_ring", "arc"), "shift-map residual max |R| / max |A|"),
        "fold_site": Var(("fold_site",), "site n of the ring (NaN beyond the ring's own sites)"),
        "A_re": Var(("fold_ring", "arc", "fold_site"), "Re A_n(0) of the member"),
        "A_im": Var(("fold_ring", "arc", "fold_site"), "Im A_n(0) of the member"),
    },
    "/limit_large": {
        "large_ring": Var(("large_ring",), "sites of a larger ring of the tail rule (limit_large_N)"),
        "c_large": Var(("c_large",), "velocity c of its scan (around the members whose tail is MI-stable)"),
        "growth_rate": Var(("large_ring", "c_large"), "ln max |mu| / T over the non-trivial multipliers modulo "
                                                      "shift (per unit tau; NaN: not reached)"),
        "unstable": Var(("large_ring", "c_large"), "1 if growth_rate > stability_threshold (-1: not reached)"),
        "theta": Var(("large_ring", "c_large"), "phase theta of (tb), in (-pi, pi]", "rad"),
        "tail": Var(("large_ring", "c_large"), "max |A_n| on the far quarter ring / max |A_n|"),
        "tail_mi_rate": Var(("large_ring", "c_large"), "largest MI growth rate of the tail's plane wave on the "
                                                       "infinite lattice (per unit tau)"),
        "quartet_defect": Var(("large_ring", "c_large"), "largest distance from 1/conj(mu) or conj(mu) to the "
                                                         "nearest multiplier (0 for a symplectic spectrum)"),
        "mode_participation": Var(("large_ring", "c_large"), "participation ratio over N of the mode of the largest "
                                                             "non-trivial multiplier"),
        "mode_core_fraction": Var(("large_ring", "c_large"), "weight of that mode on the core (|A_n| > 1e-2 max "
                                                             "|A_n|)"),
        "mode_core_fraction_norm": Var(("large_ring", "c_large"), "weight of that mode on the core (the sites "
                                                                  "nearest the centre holding 1 - 1e-6 of the "
                                                                  "norm)"),
    },
    "/claims": GROUP_VARIABLES,
}
