"""The continuum limit alpha -> 1+: DpS breathers against the log-NLS Gaussian, Hertz solitary waves against the
log-KdV Gaussian (issue 37, item 5).

For each eps = alpha - 1 of ``dps_eps`` this analysis computes the site- and bond-centred breathers of (dpsst) at
unit amplitude (:func:`cradle.models.continuum.dps_breather`: the unit-amplitude solve of
:mod:`cradle.models.homoclinic_continuation` on a ring sized from the Gaussian) and measures the distance of the
staggered envelope b_n / max b to exp(-eps (n - n_c)^2) in the max norm over the ring; for each eps of ``hertz_eps``
the solitary wave of the Hertz chain without on-site potential with force exponent 1 + eps at speed 1
(:func:`cradle.models.continuum.hertz_wave`) and the distance of R / max R to exp(-3 eps xi^2) on its grid. The
power of eps at which each distance vanishes is fitted over eps <= ``fit_below``
(:func:`cradle.measurements.continuum.fit_power`); the first-order constants of the limit, (nu - 4)/eps -> 4 ln 2 - 2
and ln max R -> 1/2 at c = 1, are stored beside. The limits and their derivation: :mod:`cradle.models.continuum`.
Near p = 2 the breathers are also compared with the compactons of :mod:`cradle.models.compacton`, and DpS travelling
breathers (:mod:`cradle.integrators.dps_travelling`) at c = K sqrt(eps) / tau0 with the travelling profiles of
:mod:`cradle.models.travelling_continuum` (:func:`travelling`, group "/travelling").
"""
from __future__ import annotations

import math
import time as _time
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.claims_table import GROUP_VARIABLES, Row, group
from cradle.analyses.protocol import Analysis
from cradle.data.variables import Var
from cradle.specs.declare import declared, param, plain
from cradle.specs.values import key_path

if TYPE_CHECKING:
    import xarray as xr
    from numpy.typing import NDArray

    from cradle.analyses.protocol import Log
    from cradle.measurements.continuum import PowerFit
    from cradle.models.continuum import DpsLimit
    from cradle.models.dps_mobility import UnstableBreather
    from cradle.models.solitary import SolitaryWave
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors

_EPS = {"type": "number", "exclusiveMinimum": 0, "minimum": 1e-4, "maximum": 1.0,
        "description": "An eps = alpha - 1 (alpha the Hertz exponent)."}

#: the sources of the limits (stored with the file and in the claims rows)
JS_2014 = ("G. James and Y. Starosvetsky, Breather solutions of the discrete p-Schroedinger equation, in Localized "
           "Excitations in Nonlinear Complex Systems (Springer, 2014), doi 10.1007/978-3-319-02057-0_4")
JP_2014 = ("G. James and D. Pelinovsky, Gaussian solitary waves and compactons in Fermi-Pasta-Ulam lattices with "
           "Hertzian potentials, Proc. R. Soc. A 470 (2014) 20130462, arXiv 1307.3837")


@declared(doc="The continuum limit alpha -> 1+ (issue 37): DpS breathers against the log-NLS Gaussian, solitary "
              "waves of the Hertz chain without on-site potential against the log-KdV Gaussian, the fitted power of "
              "alpha - 1; the unstable DpS breather perturbed, travelling or pinned against alpha; DpS travelling "
              "breathers against the boosted Gaussian and compactons -> "
              "results/continuum-limit/continuum-limit.nc and results/figures/continuum-limit.{pdf,png}.")
class ContinuumLimit:
    dps_eps: list[float] = param([0.5, 0.2, 0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001, 5e-4, 3e-4],
                                 "The eps = alpha - 1 at which the DpS breathers (site and bond) are solved; the ring "
                                 "grows as eps^(-1/2) and the dense solve as its cube (3e-4: 710 sites, ~3 s each).",
                                 minItems=4, maxItems=20, items=_EPS, reduced=[0.1, 0.05, 0.02, 0.01, 0.005])
    hertz_eps: list[float] = param([0.5, 0.2, 0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001],
                                   "The eps = alpha - 1 at which the solitary wave of the Hertz chain is solved "
                                   "(Petviashvili's iteration needs about 20/eps iterations: 1e-3 takes 3 s).",
                                   minItems=4, maxItems=20, items={**_EPS, "minimum": 5e-4},
                                   reduced=[0.1, 0.05, 0.02, 0.01])
    fit_below: float = param(0.05, "The power of eps is fitted over the eps <= fit_below (at least 4 of each list).",
                             exclusiveMinimum=0, maximum=1.0, reduced=0.1)
    decades: float = param(16.0, "Each ring (box) is as wide as the Gaussian's fall by this many decades on each "
                           "side, plus 4 sites.", minimum=4, maximum=30)
    points: int = param(8, "Grid points per site of the solitary wave's box (an integer: the shifts are exact).",
                        minimum=2, maximum=64)
    mobility_alphas: list[float] = param([1.5, 1.75, 2.0, 2.25, 2.5, 3.0], "The alpha at which the unstable "
                                         "site-centred DpS breather is perturbed and run (its growth rate must be "
                                         "resolved: >= 1.5; 1.4 grows e-fold in 3400 time units).", minItems=2,
                                         maxItems=12, items={"type": "number", "minimum": 1.3, "maximum": 3.0},
                                         reduced=[1.75, 2.0, 2.5, 3.0])
    deltas: list[float] = param([1e-3, 1e-2], "Sizes of the perturbation along the growing mode, relative to the "
                                "breather's amplitude.", minItems=1, maxItems=6,
                                items={"type": "number", "exclusiveMinimum": 0, "maximum": 0.3}, reduced=[1e-2])
    seeds: int = param(2, "Runs with seeded complex noise added (seeds 0 .. seeds-1), each with the largest delta.",
                       minimum=0, maximum=16, reduced=1)
    noise: float = param(1e-3, "Size of the seeded noise per site (standard normal real and imaginary parts), "
                         "relative to the breather's amplitude.", exclusiveMinimum=0, maximum=0.1)
    mobility_N: int = param(128, "Sites of the ring of the mobility runs (the discretisation check doubles it).",
                            minimum=32, maximum=1024, reduced=64)
    growth_times: float = param(40.0, "A run lasts (ln(1/delta) + growth_times) / lambda (lambda the growth rate), "
                                "at most tau_max.", minimum=5, maximum=200)
    tau_max: float = param(20000.0, "Longest run (units of tau).", exclusiveMinimum=0, maximum=1e6)
    rtol: float = param(1e-10, "Relative tolerance of the DpS runs (dop853_numba); the check divides it by 10.",
                        minimum=1e-13, maximum=1e-6)
    lattice_alphas: list[float] = param([1.75, 2.0, 3.0], "The alpha at which the same start (largest delta) is run "
                                        "in the lattice (nc) through the ansatz, x_n = 2 eps Re A_n, v_n = -2 eps "
                                        "Im A_n (each run is tens of seconds: none in the reduced form).",
                                        maxItems=6, items={"type": "number", "minimum": 1.3, "maximum": 3.0},
                                        reduced=[])
    lattice_eps: float = param(0.1, "Amplitude eps of the ansatz of the lattice runs (max |x_n| = eps at the start).",
                               exclusiveMinimum=0, maximum=0.5)
    lattice_small_alphas: list[float] = param([1.75, 2.0], "The alpha at which the same start is run in the "
                                              "lattice at the smaller amplitudes lattice_small_eps (full form).",
                                              maxItems=6, items={"type": "number", "minimum": 1.3, "maximum": 2.5},
                                              reduced=[])
    lattice_small_eps: list[float] = param([0.05, 0.04, 0.03, 0.02, 0.01], "Smaller amplitudes eps of the lattice "
                                           "runs; a run lasts tau_end / eps^(alpha - 1), longer as eps falls (0.01 "
                                           "at alpha = 2: about 25 s).", maxItems=10,
                                           items={"type": "number", "minimum": 1e-3, "maximum": 0.5})
    stability_alphas: list[float] = param([1.75, 2.0, 2.5, 3.0], "The alpha at which the exact site breather of the "
                                          "lattice is solved at each stability_eps and its pinning mode compared "
                                          "with DpS's unstable one (about 0.5 s each).", maxItems=8,
                                          items={"type": "number", "minimum": 1.5, "maximum": 3.0},
                                          reduced=[2.0])
    stability_eps: list[float] = param([0.2, 0.1, 0.05, 0.04, 0.03, 0.02, 0.01, 0.005, 0.002, 0.001],
                                       "Amplitudes eps of the exact lattice breathers of the stability check.",
                                       maxItems=16, items={"type": "number", "minimum": 1e-3, "maximum": 0.3},
                                       reduced=[0.1, 0.05, 0.02, 0.01, 0.002])
    tb_eps: list[float] = param([0.2, 0.1, 0.05, 0.02, 0.01, 0.005, 0.002], "The eps = alpha - 1 at which DpS "
                                "travelling breathers are computed and compared with the continuum's travelling "
                                "solutions (ring sized by tb_decades: 0.002 takes 200 sites and about a minute); the "
                                "powers are fitted when at least 4 of them are <= fit_below.", maxItems=12,
                                items=_EPS, reduced=[0.2, 0.1])
    tb_boosts: list[float] = param([0.5, 1.0], "Boosts K of the TBs in the log-NLS's units: a phase gradient kappa = "
                                   "K sqrt(eps) per site, velocity c = K sqrt(eps) / tau0 (increasing).", minItems=1,
                                   maxItems=6, items={"type": "number", "exclusiveMinimum": 0, "maximum": 3},
                                   reduced=[1.0])
    tb_decades: float = param(8.0, "The TBs' ring is as wide as the Gaussian's fall by this many decades on each "
                              "side, plus 4 sites.", minimum=4, maximum=30)
    tb_samples: int = param(16, "Instants over one period T of each TB at which its distance to each travelling "
                            "profile is measured (the largest is kept).", minimum=1, maximum=256)
    thresholds: list[float] = param([1.5, 5.0], "A run travels when its peak moves farther than this (sites) at "
                                    "some time; each threshold gives its own verdicts and crossover.", minItems=1,
                                    maxItems=4, items={"type": "number", "exclusiveMinimum": 0, "maximum": 100})

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Each form: no eps twice, at least 4 eps of each list at or below fit_below; mobility alphas increasing."""
        if list(self.mobility_alphas) != sorted(set(self.mobility_alphas)):
            out.add(where + ["mobility_alphas"], "must increase strictly (the crossover is read along them)",
                    self.mobility_alphas)
        if list(self.tb_boosts) != sorted(set(self.tb_boosts)):
            out.add(where + ["tb_boosts"], "must increase strictly (the family is continued along them)",
                    self.tb_boosts)
        if len(set(self.tb_eps)) != len(self.tb_eps):
            out.add(where + ["tb_eps"], "lists a value twice", self.tb_eps)
        if self.tb_eps and max(self.tb_boosts) * math.sqrt(max(self.tb_eps)) >= 1.0:
            out.add(where + ["tb_boosts"], f"times sqrt(max {key_path(where + ['tb_eps'])}) must be < 1 (the "
                    "phase gradient kappa = K sqrt(eps) of a carrier whose lattice group velocity sin(kappa) / tau0 "
                    "is c)", self.tb_boosts)
        short = []
        for key in ("dps_eps", "hertz_eps"):
            values = getattr(self, key)
            if len(set(values)) != len(values):
                out.add(where + [key], "lists a value twice", values)
            if sum(e <= self.fit_below for e in values) < 4:
                short.append(key)
        if len(short) == 2:   # neither list reaches it: the bound is what is wrong
            out.add(where + ["fit_below"], "leaves fewer than 4 values of dps_eps and of hertz_eps at or below it "
                    "(the power fit has three parameters)", self.fit_below)
        for key in short if len(short) == 1 else ():
            out.add(where + [key], f"needs at least 4 values <= {key_path(where + ['fit_below'])} = "
                    f"{self.fit_below:g} (the power fit has three parameters)", getattr(self, key))


_E = ("eps",)
_FAMILY = {
    "eps": Var(_E, "eps = alpha - 1"),
    "distance": Var(_E, "max-norm distance of the scaled profile to the Gaussian of the limit (both of unit maximum)"),
    "residual": Var(_E, "max residual of the profile's equation relative to its amplitude"),
    "sites": Var(_E, "sites of the ring (DpS) or of the periodic box (Hertz)"),
}
#: the stored variables, per group: a family against eps and each profile of it in its own group (its own grid)
VARIABLES = {
    "/": {},
    "/dps_site": {**_FAMILY, "nu_first_order": Var(_E, "(nu - 4)/eps, nu the mu of (dpsst) of the unit-amplitude "
                                                   "breather; the limit 4 ln 2 - 2")},
    "/dps_bond": {**_FAMILY, "nu_first_order": Var(_E, "(nu - 4)/eps, nu the mu of (dpsst) of the unit-amplitude "
                                                   "breather; the limit 4 ln 2 - 2")},
    "/hertz": {**_FAMILY, "log_amplitude": Var(_E, "ln max R of the wave at c = 1; the limit 1/2"),
               "iterations": Var(_E, "iterations of Petviashvili's iteration")},
    "/dps_site/{k}": {"X": Var(("site",), "sqrt(eps) (n - n_c)"),
                      "envelope": Var(("site",), "staggered envelope b_n / max b of the breather"),
                      "gaussian": Var(("site",), "the log-NLS Gaussian exp(-eps (n - n_c)^2), unit maximum")},
    "/dps_bond/{k}": {"X": Var(("site",), "sqrt(eps) (n - n_c)"),
                      "envelope": Var(("site",), "staggered envelope b_n / max b of the breather"),
                      "gaussian": Var(("site",), "the log-NLS Gaussian exp(-eps (n - n_c)^2), unit maximum")},
    "/hertz/{k}": {"Y": Var(("point",), "sqrt(3 eps) xi"),
                   "strain": Var(("point",), "strain R / max R of the solitary wave at c = 1"),
                   "gaussian": Var(("point",), "the log-KdV Gaussian exp(-3 eps xi^2)")},
    "/mobility": {
        "alpha": Var(("alpha",), "Hertz exponent alpha"),
        "delta": Var(("delta",), "size of the perturbation along the growing mode, relative to the amplitude"),
        "seed": Var(("seed",), "seed of the noise added to the largest delta's start"),
        "threshold": Var(("threshold",), "distance (sites) beyond which a run travels"),
        "sample": Var(("sample",), "index of a stored time"),
        "growth_rate": Var(("alpha",), "growth rate lambda of the site-centred breather's unstable mode (per tau)"),
        "tau_end": Var(("alpha",), "length of the runs (tau)"),
        "displacement": Var(("alpha", "delta"), "largest distance of the peak from its start (sites)"),
        "displacement_noise": Var(("alpha", "seed"), "largest distance of the peak from its start, noise added "
                                  "(sites)"),
        "l2_drift": Var(("alpha", "delta"), "largest relative drift of sum |A_n|^2 over the run"),
        "energy_drift": Var(("alpha", "delta"), "largest relative drift of the DpS Hamiltonian H over the run"),
        "travels": Var(("threshold", "alpha", "delta"), "1 if the run travels beyond the threshold, else 0"),
        "track": Var(("alpha", "sample"), "peak position minus its start (sites), largest delta"),
        "growth": Var(("alpha", "sample"), "lambda tau at the stored times, largest delta"),
    },
    "/lattice": {
        "lattice_alpha": Var(("lattice_alpha",), "Hertz exponent alpha of the lattice runs"),
        "displacement": Var(("lattice_alpha",), "largest distance of the peak of x_n^2 + v_n^2 from its start "
                            "(sites), lattice (nc)"),
        "t_end": Var(("lattice_alpha",), "length of the lattice run, tau_end / eps^(alpha - 1) (units of t)"),
        "energy_drift": Var(("lattice_alpha",), "relative energy drift of the lattice run"),
    },
    "/lattice_small": {
        "small_alpha": Var(("small_alpha",), "Hertz exponent alpha of the small-amplitude lattice runs"),
        "small_eps": Var(("small_eps",), "amplitude eps of the ansatz (max |x_n| at the start)"),
        "displacement": Var(("small_alpha", "small_eps"), "largest distance of the peak of x_n^2 + v_n^2 from its "
                            "start (sites), lattice (nc)"),
        "t_end": Var(("small_alpha", "small_eps"), "length of the lattice run, tau_end / eps^(alpha - 1) (units of t)"),
        "energy_drift": Var(("small_alpha", "small_eps"), "relative energy drift of the lattice run"),
        "dps_displacement": Var(("small_alpha",), "largest distance of the peak from its start (sites), the same "
                                "start run in DpS on the same ring"),
    },
    "/lattice_stability": {
        "stability_alpha": Var(("stability_alpha",), "Hertz exponent alpha"),
        "stability_eps": Var(("stability_eps",), "amplitude eps of the exact site breather of (nc)"),
        "lam": Var(("stability_alpha",), "growth rate lambda of DpS's site breather (per tau), the limit eps -> 0"),
        "sigma_ratio": Var(("stability_alpha", "stability_eps"), "sigma / lambda^2, sigma = Re z^2, z = ln m / "
                           "(T eps^(alpha-1)), m the odd (pinning) Floquet multiplier nearest 1: > 0 unstable along "
                           "the translation, < 0 an oscillating pinned mode; 1 in DpS"),
        "rate": Var(("stability_alpha", "stability_eps"), "largest growth rate over the non-trivial Floquet "
                    "multipliers divided by eps^(alpha-1) (per tau)"),
        "amplitude": Var(("stability_alpha", "stability_eps"), "max |x_n(0)| of the exact breather"),
        "residual": Var(("stability_alpha", "stability_eps"), "half-period residual of the exact breather"),
        "trivial": Var(("stability_alpha", "stability_eps"), "distance of the trivial Floquet pair to +1"),
        "converged": Var(("stability_alpha", "stability_eps"), "1 if Newton converged, else 0"),
    },
    "/compacton_dps": {
        "form": Var(("form",), "degenerate form of the staggered stationary DpS (models.compacton: A, B, C)"),
        "eps": Var(("eps",), "eps = alpha - 1"),
        "distance_site": Var(("form", "eps"), "max-norm distance of the site breather's envelope b_n / max b to the "
                             "compacton of unit maximum"),
        "distance_bond": Var(("form", "eps"), "the same for the bond-centred breather"),
        "nu_error": Var(("form", "eps"), "(nu of the compacton - nu of the site breather) / eps^2"),
        "half_width": Var(("form", "eps"), "half the support of the compacton, pi / (2 kappa) (sites)"),
    },
    "/compacton_hertz": {
        "eps": Var(("eps",), "eps = alpha - 1"),
        "distance": Var(("eps",), "max-norm distance of the strain R / max R at c = 1 to the compacton"),
        "log_amplitude_error": Var(("eps",), "(ln max R of the wave - ln max R of the compacton at c = 1) / eps"),
        "half_width": Var(("eps",), "half the support of the compacton, pi / (2 kappa) (sites)"),
    },
    "/mobility_checks": {
        "alpha": Var(("alpha",), "Hertz exponent alpha"),
        "variant": Var(("variant",), "the discretisation: the runs', N doubled, rtol / 10"),
        "displacement": Var(("alpha", "variant"), "largest distance of the peak from its start (sites), largest "
                            "delta"),
    },
    "/travelling": {
        "tb_eps": Var(("tb_eps",), "eps = alpha - 1 of the travelling breathers"),
        "boost": Var(("boost",), "boost K: phase gradient kappa = K sqrt(eps) per site, c = K sqrt(eps) / tau0"),
        "model": Var(("model",), "travelling profile (models.travelling_continuum.MODELS): the boosted log-NLS "
                     "Gaussian and static compactons of forms A, B, C, then each narrowed by the lattice's carrier"),
        "equation": Var(("equation",), "continuum equation (log-NLS, A, B, C) of the boost residual"),
        "sites": Var(("tb_eps",), "sites of the ring"),
        "c": Var(("tb_eps", "boost"), "velocity c = 1/T of the TB (sites per unit tau)"),
        "kappa": Var(("tb_eps", "boost"), "the boost's phase gradient tau0 c (per site)"),
        "carrier_narrowing": Var(("tb_eps", "boost"), "a / eps of the carrier-narrowed Gaussian exp(-a (n - n_c)^2) at "
                                 "the lattice's carrier asin(tau0 c): (1 + cos) / (2 cos) of it "
                                 "(models.travelling_continuum.carrier_width)"),
        "theta": Var(("tb_eps", "boost"), "phase theta of (tb) of the TB, wrapped into (-pi, pi]"),
        "theta_boost": Var(("tb_eps", "boost"), "theta of the boosted Gaussian of the same c and amplitude: kappa/2 + "
                           "nu/(2 kappa) - pi (mod 2 pi)"),
        "theta_error": Var(("tb_eps", "boost"), "theta - theta_boost, wrapped into (-pi, pi]"),
        "residual": Var(("tb_eps", "boost"), "shift-map residual max|R| / max|A| of the TB"),
        "tail": Var(("tb_eps", "boost"), "max |A_n| over the far quarter ring relative to max |A|"),
        "amplitude": Var(("tb_eps", "boost"), "max |A_n| of the TB (its norm is the unit-amplitude static one's)"),
        "distance": Var(("model", "tb_eps", "boost"), "largest over one period of the max-norm distance of the "
                        "envelope B_n / max|B| (global phase fitted) to the travelling profile, phase included"),
        "distance_modulus": Var(("model", "tb_eps", "boost"), "the same for the moduli |B_n| / max|B| only"),
        "static_distance": Var(("model", "tb_eps"), "the same measurement on the static site breather (c = 0) on "
                               "the same ring: the limit c -> 0"),
        "boost_residual": Var(("equation", "tb_eps", "boost"), "max |residual| / max |U| of the boosted "
                              "unit-amplitude travelling solution in its equation (exact for log-NLS; the boosted "
                              "static compacton for A, B, C), at the TB's kappa"),
        "power": Var(("model", "boost"), "fitted power of eps of the distance (NaN: fewer than 4 eps <= fit_below)"),
        "power_uncertainty": Var(("model", "boost"), "its uncertainty (the larger of stderr and leave-one-end-out)"),
        "constant": Var(("model", "boost"), "K of distance ~ K eps^power"),
        "theta_power": Var(("boost",), "fitted power of eps of |theta_error|"),
        "theta_power_uncertainty": Var(("boost",), "its uncertainty"),
    },
    "/travelling/{k}": {
        "X": Var(("site",), "sqrt(eps) (n - n_c), n_c the TB's centre at tau = 0"),
        "envelope": Var(("boost", "site"), "|B_n| / max|B| of the TB at tau = 0"),
        "X_static": Var(("site",), "sqrt(eps) (n - n_c) of the static site breather"),
        "static": Var(("site",), "the static site breather's envelope b_n / max b on the same ring"),
    },
    "/claims": GROUP_VARIABLES,
}


def dps_family(spec: ContinuumLimit, kind: str) -> list:
    """The breathers of one parity at every eps of the spec."""
    from cradle.models.continuum import dps_breather

    return [dps_breather(e, kind, spec.decades) for e in spec.dps_eps]


def hertz_family(spec: ContinuumLimit) -> list:
    """The solitary waves at c = 1 at every eps of the spec."""
    from cradle.models.continuum import hertz_wave

    return [hertz_wave(e, spec.decades, spec.points) for e in spec.hertz_eps]


def _run(br: UnstableBreather, A0: NDArray[np.complex128], tau_end: float, rtol: float,
         samples: int = 801) -> tuple[NDArray[np.float64], NDArray[np.float64], float, float, float]:
    """One DpS run from A0 to tau_end: (tau, peak track, displacement, l2 drift, H drift)."""
    from cradle.integrators.dps_solver import integrate_dps
    from cradle.measurements.travel import peak_position

    tau = np.linspace(0.0, tau_end, samples)
    sol = integrate_dps(A0, tau, alpha=br.alpha, rtol=rtol)
    x = peak_position(sol.A)
    x = x - x[0]
    return tau, x, float(np.max(np.abs(x))), float(sol.max_l2_drift), float(sol.max_energy_drift)


def crossover(alphas: list[float], travels: list[bool]) -> float:
    """The midpoint between the largest alpha that travels and the next alpha of the list (NaN if none travels;
    the last alpha if all of them do)."""
    idx = [i for i, t in enumerate(travels) if t]
    if not idx:
        return float("nan")
    i = idx[-1]
    return float(alphas[i]) if i == len(alphas) - 1 else 0.5 * (alphas[i] + alphas[i + 1])


def mobility(spec: ContinuumLimit, say: Log) -> tuple[tuple[dict, dict], tuple[dict, dict], dict]:
    """The mobility runs (issue 37, item 4): the unstable site breather perturbed along its growing mode by each
    delta (and, at the largest delta, seeded noise added), run in DpS; the displacement of its peak, the
    verdicts under each threshold, the crossover alpha over perturbations, and the discretisation check (N
    doubled, rtol / 10) at the largest delta. Returns the groups "/mobility", "/mobility_checks" and attributes."""
    from cradle.models.dps_mobility import start, unstable_site

    al = list(spec.mobility_alphas)
    nd, ns = len(spec.deltas), spec.seeds
    disp, l2, H = np.zeros((len(al), nd)), np.zeros((len(al), nd)), np.zeros((len(al), nd))
    disp_noise = np.zeros((len(al), ns))
    lam, tau_end = np.zeros(len(al)), np.zeros(len(al))
    samples = 801
    track, growth = np.zeros((len(al), samples)), np.zeros((len(al), samples))
    checks = np.zeros((len(al), 3))
    for i, alpha in enumerate(al):
        br = unstable_site(alpha, spec.mobility_N)
        lam[i] = br.lam
        if not br.lam > 0:
            raise RuntimeError(f"continuum-limit: the site breather at alpha = {alpha} has no resolved growth rate")
        big = max(spec.deltas)
        tau_end[i] = min((math.log(1.0 / big) + spec.growth_times) / br.lam, spec.tau_max)
        for j, d in enumerate(spec.deltas):
            T = min((math.log(1.0 / d) + spec.growth_times) / br.lam, spec.tau_max)
            tau, x, disp[i, j], l2[i, j], H[i, j] = _run(br, start(br, d), T, spec.rtol, samples)
            if d == big:
                track[i], growth[i] = x, br.lam * tau
                checks[i, 0] = disp[i, j]
        for k in range(ns):
            disp_noise[i, k] = _run(br, start(br, big, spec.noise, k), tau_end[i], spec.rtol, samples)[2]
        wide = unstable_site(alpha, 2 * spec.mobility_N)
        A0 = start(wide, big)
        checks[i, 1] = _run(wide, np.roll(A0, 0), tau_end[i], spec.rtol, samples)[2]
        checks[i, 2] = _run(br, start(br, big), tau_end[i], spec.rtol / 10.0, samples)[2]
        say(f"continuum-limit: mobility alpha = {alpha:g}: lambda = {br.lam:.4g}, displacement "
            f"{', '.join(f'{v:.3g}' for v in disp[i])} sites (deltas), noise "
            f"{', '.join(f'{v:.3g}' for v in disp_noise[i])}; checks {', '.join(f'{v:.3g}' for v in checks[i])}")
    th = list(spec.thresholds)
    travels = np.array([[[disp[i, j] > t for j in range(nd)] for i in range(len(al))] for t in th])
    attrs: dict = {}
    for t_i, t in enumerate(th):
        cross = [crossover(al, list(travels[t_i, :, j])) for j in range(nd)]
        cross += [crossover(al, [disp_noise[i, k] > t for i in range(len(al))]) for k in range(ns)]
        finite = [c for c in cross if np.isfinite(c)]
        attrs[f"crossover_threshold_{t:g}"] = ", ".join(f"{c:g}" for c in cross)
        attrs[f"crossover_min_threshold_{t:g}"] = min(finite) if finite else float("nan")
        attrs[f"crossover_max_threshold_{t:g}"] = max(finite) if finite else float("nan")
        for v, name in ((1, "N doubled"), (2, "rtol / 10")):
            attrs[f"verdicts_unchanged_{name.replace(' ', '_').replace('/', 'over')}_threshold_{t:g}"] = int(
                all((checks[i, v] > t) == (checks[i, 0] > t) for i in range(len(al))))
    attrs.update({"mobility_max_l2_drift": float(np.max(l2)), "mobility_max_energy_drift": float(np.max(H))})
    mob = ({"growth_rate": lam, "tau_end": tau_end, "displacement": disp, "displacement_noise": disp_noise,
            "l2_drift": l2, "energy_drift": H, "travels": travels.astype(np.int8), "track": track,
            "growth": growth},
           {"alpha": al, "delta": list(spec.deltas), "seed": np.arange(ns), "threshold": th,
            "sample": np.arange(samples)})
    chk = ({"displacement": checks},
           {"alpha": al, "variant": np.array(["runs", "N doubled", "rtol / 10"], dtype=object)})
    return mob, chk, attrs


def _fit(eps: list[float], D: list[float], below: float) -> PowerFit:
    from cradle.measurements.continuum import fit_power

    e, d = np.asarray(eps), np.asarray(D)
    keep = e <= below
    return fit_power(e[keep], d[keep])


def claims(fits: dict[str, PowerFit]) -> list[Row]:
    """The cited papers' statements on the limit against ours: qualitative rows (the papers print no number for
    it), judged by the fitted power (a distance that vanishes: power > 0 beyond its uncertainty)."""
    rows = []
    for key, what, src in (("dps_site", "site-centred DpS breathers", JS_2014),
                           ("dps_bond", "bond-centred DpS breathers", JS_2014),
                           ("hertz", "solitary waves of the Hertz chain without on-site potential", JP_2014)):
        f = fits[key]
        ok = f.power - 3 * f.uncertainty > 0
        paper = ("breathers correspond asymptotically to Gaussian homoclinic solutions as alpha -> 1+ (qualitative)"
                 if key != "hertz" else "solitary waves become Gaussian as alpha -> 1+ (log-KdV; qualitative)")
        rows.append(Row(src.split(",")[0] + " 2014", f"{what} against the Gaussian of the limit", paper,
                        f"distance ~ {f.K:.3g} (alpha-1)^{f.power:.4f} +- {f.uncertainty:.1g}",
                        "agrees" if ok else "disagrees",
                        "max-norm distance of the profile scaled to unit maximum to the Gaussian, power fitted over "
                        "the smallest alpha - 1 (continuum-limit)", "power > 0 beyond 3 uncertainties",
                        "analyses/continuum-limit.md", qualitative=True))
    return rows


def lattice_runs(spec: ContinuumLimit, say: Log) -> tuple[dict, dict]:
    """The DpS start of the largest delta through the ansatz in the lattice (nc) (srkn6c, periodic), run for the
    DpS run's length tau_end / eps^(alpha - 1); the displacement of the peak of x_n^2 + v_n^2."""
    from cradle.integrators import integrate_lattice
    from cradle.measurements.travel import displacement
    from cradle.models.dps_mobility import start, unstable_site

    al = list(spec.lattice_alphas)
    disp, t_end, drift = np.zeros(len(al)), np.zeros(len(al)), np.zeros(len(al))
    e = spec.lattice_eps
    big = max(spec.deltas)
    for i, alpha in enumerate(al):
        br = unstable_site(alpha, spec.mobility_N)
        tau = min((math.log(1.0 / big) + spec.growth_times) / br.lam, spec.tau_max)
        t_end[i] = tau / e ** (alpha - 1.0)
        A0 = start(br, big)
        sol = integrate_lattice(2 * e * A0.real, -2 * e * A0.imag, np.linspace(0.0, t_end[i], 801), alpha=alpha)
        disp[i] = displacement(np.sqrt(sol.x**2 + sol.v**2))
        drift[i] = float(sol.energy_drift)
        say(f"continuum-limit: lattice alpha = {alpha:g}, eps = {e:g}: displacement {disp[i]:.3g} sites over "
            f"t = {t_end[i]:.4g}")
    return {"displacement": disp, "t_end": t_end, "energy_drift": drift}, {"lattice_alpha": al}


JAMES_2018 = ("G. James, Travelling breathers and solitary waves in strongly nonlinear lattices, Phil. Trans. R. Soc. "
              "A 376 (2018) 20170138")


def compacton_claims(cfits: dict[str, PowerFit]) -> list[Row]:
    """The two abstracts' statements on compactons near p = 2 against ours (qualitative rows: the abstracts print no
    number): James 2018's degenerate NLS compactons approximating DpS's breathers (here the static ones), and James
    & Pelinovsky's compactons of the fractional KdV tending to the Gaussian (here: against the waves themselves).
    Each agrees when the fitted power of the distance is positive beyond three uncertainties."""
    rows = []
    dps = [cfits[f"compacton_{f}_site"] for f in ("A", "B", "C")]
    ok = all(f.power - 3 * f.uncertainty > 0 for f in dps)
    rows.append(Row("James 2018", "compactons of degenerate NLS equations against DpS breathers near p = 2",
                    "degenerate NLS equations with compacton solutions approximate DpS's (travelling) breathers as "
                    "p -> 2+ (qualitative)",
                    "static site breathers: distance ~ " + ", ".join(f"{f.K:.3g} (alpha-1)^{f.power:.3f}"
                                                                     for f in dps) + " (forms A, B, C)",
                    "agrees" if ok else "disagrees",
                    "max-norm distance of the envelope to the compacton of each degenerate form (continuum-limit); "
                    "the travelling breathers: James 2018's row on them (full form)",
                    "power > 0 beyond 3 uncertainties",
                    "analyses/continuum-limit.md", qualitative=True))
    f = cfits["compacton_hertz"]
    rows.append(Row("James and Pelinovsky 2014", "compactons of the fractional KdV against the Hertz chain's waves",
                    "compactons converge pointwise to the limiting Gaussian as alpha -> 1+ (qualitative)",
                    f"distance of the waves to the compacton ~ {f.K:.3g} (alpha-1)^{f.power:.4f} +- "
                    f"{f.uncertainty:.1g}", "agrees" if f.power - 3 * f.uncertainty > 0 else "disagrees",
                    "max-norm distance of R / max R at c = 1 to the compacton (continuum-limit)",
                    "power > 0 beyond 3 uncertainties", "analyses/continuum-limit.md", qualitative=True))
    return rows


def travelling_claims(spec: ContinuumLimit, tb: dict) -> list[Row]:
    """James 2018's comparison of three continuum models with the TBs as p -> 2+ (qualitative: the abstract prints
    no number), when the TB distances are fitted (at least 4 tb_eps <= fit_below): agrees when the distance of the
    TBs to the boosted Gaussian and to each boosted compacton vanishes (fitted power positive beyond three
    uncertainties) at every boost."""
    P, U = np.asarray(tb["power"]), np.asarray(tb["power_uncertainty"])
    if not np.all(np.isfinite(P)):
        return []
    from cradle.models import travelling_continuum as TC

    ok = bool(np.all(P - 3 * U > 0))
    K = list(spec.tb_boosts)[-1]
    def fits(models: tuple[str, ...]) -> str:
        return ", ".join(f"{tb['constant'][m, -1]:.3g} (alpha-1)^{P[m, -1]:.3f}"
                         for m in (TC.MODELS.index(x) for x in models))

    ours = (f"TBs at c = K sqrt(alpha-1) / tau0, K = {', '.join(f'{k:g}' for k in spec.tb_boosts)}; at K = {K:g} "
            f"distance ~ {fits(('gaussian', 'A', 'B', 'C'))} (boosted Gaussian; boosted compactons A, B, C); "
            f"narrowed by the lattice's carrier {fits(('gaussian carrier', 'B carrier'))} (Gaussian, B)")
    return [Row("James 2018", "continuum models against DpS travelling breathers near p = 2",
                "the log-NLS (Gaussian) and degenerate NLS (compacton) models compared with travelling breathers as "
                "p -> 2+ (qualitative)", ours, "agrees" if ok else "disagrees",
                "max-norm distance of the TB's complex envelope over one period to the boosted profiles "
                "(continuum-limit, /travelling)", "power > 0 beyond 3 uncertainties at every boost",
                "analyses/continuum-limit.md", qualitative=True)]


def lattice_small(spec: ContinuumLimit, say: Log) -> tuple[dict, dict]:
    """The lattice runs of :func:`lattice_runs` at each alpha of ``lattice_small_alphas`` and amplitude of
    ``lattice_small_eps``, and the same start run in DpS on the same ring (its limit eps -> 0)."""
    from cradle.integrators import integrate_lattice
    from cradle.measurements.travel import displacement
    from cradle.models.dps_mobility import start, unstable_site

    al, es = list(spec.lattice_small_alphas), list(spec.lattice_small_eps)
    disp, t_end, drift = (np.zeros((len(al), len(es))) for _ in range(3))
    dps_disp = np.zeros(len(al))
    big = max(spec.deltas)
    for i, alpha in enumerate(al):
        br = unstable_site(alpha, spec.mobility_N)
        tau = min((math.log(1.0 / big) + spec.growth_times) / br.lam, spec.tau_max)
        A0 = start(br, big)
        dps_disp[i] = _run(br, A0, tau, spec.rtol)[2]
        for j, e in enumerate(es):
            t_end[i, j] = tau / e ** (alpha - 1.0)
            sol = integrate_lattice(2 * e * A0.real, -2 * e * A0.imag, np.linspace(0.0, t_end[i, j], 801),
                                    alpha=alpha)
            disp[i, j] = displacement(np.sqrt(sol.x**2 + sol.v**2))
            drift[i, j] = float(sol.energy_drift)
            say(f"continuum-limit: lattice alpha = {alpha:g}, eps = {e:g}: displacement {disp[i, j]:.3g} sites over "
                f"t = {t_end[i, j]:.4g} (DpS {dps_disp[i]:.3g})")
    return ({"displacement": disp, "t_end": t_end, "energy_drift": drift, "dps_displacement": dps_disp},
            {"small_alpha": al, "small_eps": es})


def lattice_stability(spec: ContinuumLimit, say: Log) -> tuple[dict, dict]:
    """The pinning mode of the exact site breather of (nc) at each alpha and amplitude of the spec against DpS's
    unstable mode (:func:`cradle.integrators.lattice_pinning.exact_site`)."""
    from cradle.integrators.lattice_pinning import exact_site

    al, es = list(spec.stability_alphas), list(spec.stability_eps)
    out = {k: np.zeros((len(al), len(es))) for k in ("sigma_ratio", "rate", "amplitude", "residual", "trivial")}
    conv = np.zeros((len(al), len(es)), dtype=np.int8)
    lam = np.zeros(len(al))
    for i, alpha in enumerate(al):
        for j, e in enumerate(es):
            m = exact_site(alpha, spec.mobility_N, e)
            lam[i] = m.lam
            for k in out:
                out[k][i, j] = getattr(m, k)
            conv[i, j] = int(m.converged)
        say(f"continuum-limit: exact lattice site breather at alpha = {alpha:g}: sigma / lambda^2 = "
            f"{', '.join(f'{v:.3g}' for v in out['sigma_ratio'][i])} at eps = {', '.join(f'{e:g}' for e in es)}")
    return {**out, "converged": conv, "lam": lam}, {"stability_alpha": al, "stability_eps": es}


def compactons(spec: ContinuumLimit, fams: dict[str, list[DpsLimit]], waves: list[SolitaryWave]) -> tuple[
        tuple[dict, dict], tuple[dict, dict], dict[str, PowerFit]]:
    """The compactons of :mod:`cradle.models.compacton` against the breathers and waves of the spec (groups
    "/compacton_dps", "/compacton_hertz") and the fitted power of each distance."""
    from cradle.measurements.continuum import sup_distance
    from cradle.models import compacton as K

    eps = list(spec.dps_eps)
    nf = len(K.FORMS)
    D = {kind: np.zeros((nf, len(eps))) for kind in ("site", "bond")}
    nu_error, half = np.zeros((nf, len(eps))), np.zeros((nf, len(eps)))
    fits: dict[str, PowerFit] = {}
    for f_i, form in enumerate(K.FORMS):
        for kind in ("site", "bond"):
            for k, b in enumerate(fams[kind]):
                C = K.dps_compacton(b.n, b.centre, b.eps, form)
                D[kind][f_i, k] = sup_distance(b.envelope, C / np.max(C))
            fits[f"compacton_{form}_{kind}"] = _fit(eps, list(D[kind][f_i]), spec.fit_below)
        for k, b in enumerate(fams["site"]):
            nu_error[f_i, k] = (K.dps_nu(b.eps, form) - b.nu) / b.eps**2
            half[f_i, k] = K.dps_half_width(b.eps, form)
    he = list(spec.hertz_eps)
    DH = [sup_distance(w.strain, K.hertz_compacton(w.xi, e)) for w, e in zip(waves, he, strict=True)]
    fits["compacton_hertz"] = _fit(he, DH, spec.fit_below)
    dps_group = ({"distance_site": D["site"], "distance_bond": D["bond"], "nu_error": nu_error, "half_width": half},
                 {"form": np.array(K.FORMS, dtype=object), "eps": eps})
    hertz_group = ({"distance": DH,
                    "log_amplitude_error": [(math.log(w.strain_max) - K.hertz_log_amplitude(e)) / e
                                            for w, e in zip(waves, he, strict=True)],
                    "half_width": [0.5 * math.pi / K.hertz_kappa(e) for e in he]}, {"eps": he})
    return dps_group, hertz_group, fits


#: the boost K of the push that starts each TB family, if no smaller boost is asked for: Newton converges from it at
#: every eps tried (a push of K = 1 at eps = 0.2 stalls), and the continuation in c goes on from there
START_BOOST = 0.5


def travelling(spec: ContinuumLimit, say: Log) -> dict[str, tuple[dict, dict]]:
    """DpS travelling breathers near alpha = 1 against the continuum's travelling solutions (groups "/travelling" and
    "/travelling/eNN"). At each eps of ``tb_eps``: the unit-amplitude static site breather
    (:func:`cradle.models.continuum.dps_breather` on a ring of ``tb_decades``) pushed by the phase gradient
    min(K, START_BOOST) sqrt(eps), K the smallest boost (:func:`cradle.integrators.dps_travelling.start`), solved at
    its own c and continued at its norm to c = K sqrt(eps) / tau0 for every K of ``tb_boosts``; each member's
    envelope B_n = (-1)^n A_n at ``tb_samples`` instants of one period, against each travelling profile of
    :func:`cradle.models.travelling_continuum.travelling_profile` centred at its centroid
    (:func:`cradle.models.dps_travelling.centre`); theta against the boost's (theta)."""
    from cradle.integrators import dps_travelling as DT, integrate_dps
    from cradle.measurements.continuum import complex_distance, sup_distance
    from cradle.models import dps, dps_travelling as M, travelling_continuum as TC
    from cradle.models.continuum import dps_breather

    es, ks = list(spec.tb_eps), list(spec.tb_boosts)
    ne, nk, nm = len(es), len(ks), len(TC.MODELS)
    shape = (ne, nk)
    out = {key: np.full(shape, np.nan) for key in ("c", "kappa", "carrier_narrowing", "theta", "theta_boost",
                                                   "theta_error", "residual", "tail", "amplitude")}
    D, Dm = np.full((nm, ne, nk), np.nan), np.full((nm, ne, nk), np.nan)
    Ds = np.full((nm, ne), np.nan)
    R = np.full((len(TC.EQUATIONS), ne, nk), np.nan)
    sites = np.zeros(ne, dtype=np.int64)
    subs: dict[str, tuple[dict, dict]] = {}
    for i, e in enumerate(es):
        alpha = 1.0 + e
        t0 = dps.tau0(alpha)
        st = dps_breather(e, "site", spec.tb_decades)
        N = st.n.size
        sites[i] = N
        n = st.n
        sign = (-1.0) ** n
        for m_i, model in enumerate(TC.MODELS):
            Ds[m_i, i] = complex_distance(sign * st.profile, TC.travelling_profile(model, n, M.centre(st.profile), e,
                                                                                   0.0, t0))
        targets = [K * math.sqrt(e) / t0 for K in ks]
        P = float(np.sum(st.profile**2))
        A, T, th = DT.start(st.profile.astype(complex), min(ks[0], START_BOOST) * math.sqrt(e), alpha)
        first = DT.newton(A, T, th, alpha, P)
        if not first.converged:
            raise RuntimeError(f"continuum-limit: no travelling breather at eps = {e:g} from the pushed breather "
                               f"(c = {1 / T:.4g}, residual {first.residual:.2g})")
        fam, last = DT.continue_family(first, targets)
        if len(fam) < nk:
            raise RuntimeError(f"continuum-limit: the travelling breathers at eps = {e:g} end near c = {last:.4g} "
                               f"before c = {targets[-1]:.4g}")
        env = np.zeros((nk, N))
        x0 = np.zeros(N)
        for j, b in enumerate(fam):
            amp = float(np.max(np.abs(b.A)))
            kap = TC.boost_kappa(b.c, t0)
            pred = TC.boost_theta(b.c, t0, TC.nu_gaussian(e, amp))
            out["c"][i, j], out["kappa"][i, j], out["theta"][i, j] = b.c, kap, TC.wrap(b.theta)
            out["carrier_narrowing"][i, j] = TC.carrier_width(e, TC.carrier_kappa(b.c, t0)) / e
            out["theta_boost"][i, j], out["theta_error"][i, j] = pred, TC.wrap(b.theta - pred)
            out["residual"][i, j], out["tail"][i, j], out["amplitude"][i, j] = b.residual, M.tail_amplitude(b.A), amp
            run = integrate_dps(b.A, np.linspace(0.0, b.T, spec.tb_samples + 1)[:-1], alpha=alpha, rtol=DT.RTOL)
            for As in run.A:
                cen = M.centre(As)
                for m_i, model in enumerate(TC.MODELS):
                    prof = TC.travelling_profile(model, n, cen, e, b.c, t0)
                    D[m_i, i, j] = np.fmax(D[m_i, i, j], complex_distance(sign * As, prof))
                    Dm[m_i, i, j] = np.fmax(Dm[m_i, i, j], sup_distance(np.abs(As), np.abs(prof)))
            for q, eq in enumerate(TC.EQUATIONS):
                R[q, i, j] = TC.boost_residual(eq, e, kap)
            cen = M.centre(b.A)
            env[j] = np.abs(b.A) / amp
            if j == 0:
                x0 = math.sqrt(e) * (((n - cen + N / 2) % N) - N / 2)
        def row(v: NDArray[np.float64], f: str = ".4g") -> str:
            return ", ".join(f"{x:{f}}" for x in v)

        g, gc = TC.MODELS.index("gaussian"), TC.MODELS.index("gaussian carrier")
        say(f"continuum-limit: travelling breathers at eps = {e:g} ({N} sites): c = {row(out['c'][i])}; distance / "
            f"eps to the boosted Gaussian {row(D[g, i] / e)}, carrier Gaussian {row(D[gc, i] / e)} (static "
            f"{Ds[g, i] / e:.4g}); theta - theta_boost {row(out['theta_error'][i], '.2g')}")
        subs[f"/travelling/e{i:02d}"] = ({"X": x0, "envelope": env, "X_static": math.sqrt(e) * (n - st.centre),
                                          "static": st.envelope / np.max(st.envelope)}, {})
    fit = {key: np.full((nm, nk), np.nan) for key in ("power", "power_uncertainty", "constant")}
    tp, tu = np.full(nk, np.nan), np.full(nk, np.nan)
    if sum(e <= spec.fit_below for e in es) >= 4:
        for j in range(nk):
            for m_i in range(nm):
                f = _fit(es, list(D[m_i, :, j]), spec.fit_below)
                fit["power"][m_i, j], fit["power_uncertainty"][m_i, j], fit["constant"][m_i, j] = (
                    f.power, f.uncertainty, f.K)
            f = _fit(es, list(np.abs(out["theta_error"][:, j])), spec.fit_below)
            tp[j], tu[j] = f.power, f.uncertainty
    group = ({**out, "distance": D, "distance_modulus": Dm, "static_distance": Ds, "boost_residual": R,
              "sites": sites, **fit, "theta_power": tp, "theta_power_uncertainty": tu},
             {"tb_eps": es, "boost": ks, "model": np.array(TC.MODELS, dtype=object),
              "equation": np.array(TC.EQUATIONS, dtype=object)})
    return {"/travelling": group, **subs}


def mobility_claim(spec: ContinuumLimit, mob: dict, attrs: dict) -> Row:
    """James & Starosvetsky's "a perturbation of an unstable breather generally results in a translational motion
    (traveling breather) when alpha is close to unity, whereas pinning becomes predominant for larger values of
    alpha" against the runs under the first threshold: agrees when the runs travel at the smallest alpha (more than
    half of them) and none does at the largest."""
    t = spec.thresholds[0]
    runs = np.concatenate([np.asarray(mob["displacement"]), np.asarray(mob["displacement_noise"])], axis=1)
    low, high = runs[0] > t, runs[-1] > t
    ok = bool(np.mean(low) > 0.5 and not np.any(high))
    al = spec.mobility_alphas
    ours = (f"{int(np.sum(low))} of {low.size} runs travel beyond {t:g} sites at alpha = {al[0]:g}, "
            f"{int(np.sum(high))} of {high.size} at alpha = {al[-1]:g}; crossover alpha "
            f"{attrs[f'crossover_min_threshold_{t:g}']:g} to {attrs[f'crossover_max_threshold_{t:g}']:g}")
    return Row("James and Starosvetsky 2014", "perturbed unstable DpS breather: travelling or pinned against alpha",
               "travels for alpha close to 1, pinning predominant for larger alpha (qualitative)", ours,
               "agrees" if ok else "disagrees",
               "site-centred breather perturbed along its growing mode and by seeded noise, DpS runs (continuum-limit)",
               f"most runs travel at the smallest alpha, none at the largest (threshold {t:g} sites)",
               "analyses/continuum-limit.md", qualitative=True)


def compute(spec: ContinuumLimit, inputs: dict | None = None, log: Log | None = None) -> xr.DataTree:
    """The `continuum-limit` analysis as a tree of groups (:data:`VARIABLES`); it reads no file."""
    from cradle.data.io import make_tree
    from cradle.measurements.continuum import sup_distance
    from cradle.models import solitary
    from cradle.models.continuum import LOG_NLS_M, kdv_gaussian

    say = log or (lambda *a: None)
    t0 = _time.perf_counter()
    groups: dict = {"/": ({}, {})}
    variables = {k: v for k, v in VARIABLES.items() if "{" not in k}
    fits: dict[str, PowerFit] = {}
    seconds: dict[str, float] = {}
    fams: dict[str, list[DpsLimit]] = {}
    for kind in ("site", "bond"):
        t1 = _time.perf_counter()
        fams[kind] = fam = dps_family(spec, kind)
        seconds[kind] = _time.perf_counter() - t1
        bad = [b.eps for b in fam if not b.converged]
        if bad:
            raise RuntimeError(f"continuum-limit: the {kind} breather did not converge at eps = {bad}")
        D = [sup_distance(b.envelope, b.gaussian) for b in fam]
        path = f"/dps_{kind}"
        groups[path] = ({"distance": D, "residual": [b.residual for b in fam], "sites": [b.n.size for b in fam],
                         "nu_first_order": [(b.nu - 4.0) / b.eps for b in fam]}, {"eps": list(spec.dps_eps)})
        for k, b in enumerate(fam):
            sub = f"{path}/e{k:02d}"
            groups[sub] = ({"X": math.sqrt(b.eps) * (b.n - b.centre), "envelope": b.envelope / np.max(b.envelope),
                            "gaussian": b.gaussian}, {})
            variables[sub] = VARIABLES[path + "/{k}"]
        fits[f"dps_{kind}"] = f = _fit(spec.dps_eps, D, spec.fit_below)
        say(f"continuum-limit: DpS {kind}: distance ~ {f.K:.4g} eps^{f.power:.5f} (+- {f.uncertainty:.2g}); "
            f"(nu - 4)/eps = {(fam[-1].nu - 4) / fam[-1].eps:.6f} at eps = {fam[-1].eps:g} (limit {LOG_NLS_M:.6f})")
    t1 = _time.perf_counter()
    waves = hertz_family(spec)
    seconds["hertz"] = _time.perf_counter() - t1
    D = [sup_distance(w.strain, kdv_gaussian(w.xi, e)) for w, e in zip(waves, spec.hertz_eps, strict=True)]
    groups["/hertz"] = ({"distance": D, "residual": [solitary.residual(w) for w in waves],
                         "sites": [w.xi.size // spec.points for w in waves],
                         "log_amplitude": [math.log(w.strain_max) for w in waves],
                         "iterations": [w.iterations for w in waves]}, {"eps": list(spec.hertz_eps)})
    for k, (w, e) in enumerate(zip(waves, spec.hertz_eps, strict=True)):
        sub = f"/hertz/e{k:02d}"
        groups[sub] = ({"Y": math.sqrt(3.0 * e) * w.xi, "strain": w.strain / w.strain_max,
                        "gaussian": kdv_gaussian(w.xi, e)}, {})
        variables[sub] = VARIABLES["/hertz/{k}"]
    fits["hertz"] = f = _fit(spec.hertz_eps, D, spec.fit_below)
    say(f"continuum-limit: Hertz: distance ~ {f.K:.4g} eps^{f.power:.5f} (+- {f.uncertainty:.2g}); ln max R = "
        f"{math.log(waves[-1].strain_max):.6f} at eps = {spec.hertz_eps[-1]:g} (limit 0.5)")
    t1 = _time.perf_counter()
    groups["/compacton_dps"], groups["/compacton_hertz"], cfits = compactons(spec, fams, waves)
    seconds["compactons"] = _time.perf_counter() - t1
    for key in ("compacton_A_site", "compacton_B_site", "compacton_C_site", "compacton_hertz"):
        f = cfits[key]
        say(f"continuum-limit: {key}: distance ~ {f.K:.4g} eps^{f.power:.5f} (+- {f.uncertainty:.2g})")
    groups["/mobility"], groups["/mobility_checks"], mob_attrs = mobility(spec, say)
    groups["/lattice"] = lattice_runs(spec, say)
    t1 = _time.perf_counter()
    groups["/lattice_stability"] = lattice_stability(spec, say)
    seconds["lattice_stability"] = _time.perf_counter() - t1
    t1 = _time.perf_counter()
    groups["/lattice_small"] = lattice_small(spec, say)
    seconds["lattice_small"] = _time.perf_counter() - t1
    t1 = _time.perf_counter()
    tb = travelling(spec, say)
    seconds["travelling"] = _time.perf_counter() - t1
    groups.update(tb)
    variables["/travelling"] = VARIABLES["/travelling"]
    for sub in tb:
        if sub != "/travelling":
            variables[sub] = VARIABLES["/travelling/{k}"]
    table = claims(fits) + [mobility_claim(spec, groups["/mobility"][0], mob_attrs)] + compacton_claims(cfits)
    table += travelling_claims(spec, tb["/travelling"][0])
    groups["/claims"] = group(table)
    attrs: dict = {"nu_first_order_limit": LOG_NLS_M, "log_amplitude_limit": 0.5, "fit_below": spec.fit_below}
    for key, f in {**fits, **cfits}.items():
        attrs.update({f"{key}_power": f.power, f"{key}_power_stderr": f.stderr, f"{key}_power_spread": f.spread,
                      f"{key}_power_uncertainty": f.uncertainty, f"{key}_constant": f.K,
                      f"{key}_correction": f.k, f"{key}_fit_points": f.points})
    attrs.update({
        "dps_limit": "nu b_n = g(b_n + b_{n+1}) + g(b_n + b_{n-1}) -> b_XX + 4 b ln(2b) - m b = 0, X = sqrt(eps) n, "
                     "nu = 4 + eps m: b_n / max b = exp(-eps (n - n_c)^2), m = 4 ln 2 - 2 at unit amplitude",
        "hertz_limit": "c^2 R'' = f(R(xi+1)) - 2 f(R) + f(R(xi-1)), f = R^(1+eps) -> (c^2 - 1)/eps R = R ln R + "
                       "R_YY/12, Y = sqrt(eps) xi: R / max R = exp(-3 eps xi^2), c^2 = 1 + eps (ln max R - 1/2)",
        "distance_norm": "max over the ring (box) of |profile / max profile - Gaussian / max Gaussian| on the lattice "
                         "sites (DpS: the staggered envelope b_n = (-1)^(n - n_pin) a_n; Hertz: the strain on the "
                         "grid); centre n_c the central site (site) or the middle of the central bond (bond)",
        "fit": "least squares of ln D = p ln eps + ln K + k eps over eps <= fit_below; uncertainty the larger of the "
               "standard error of p and the change of p when the smallest or the largest eps is left out",
        "dps_source": JS_2014, "hertz_source": JP_2014,
        "dps_site_seconds": seconds["site"], "dps_bond_seconds": seconds["bond"], "hertz_seconds": seconds["hertz"],
        "compactons_seconds": seconds["compactons"], "lattice_stability_seconds": seconds["lattice_stability"],
        "lattice_small_seconds": seconds["lattice_small"],
        "travelling_seconds": seconds["travelling"],
        "compacton_dps": "b / max b = cos^(2/eps)(kappa (n - n_c)) on |n - n_c| <= pi/(2 kappa), 0 beyond; kappa = "
                         "eps/(1+eps) (A: nu u = 4 g(u) + (g(u))''), eps/sqrt(1+eps) (B: nu u = 4 g(u) + g'(u) u''), "
                         "eps sqrt(2/((2+eps)(1+eps))) (C: nu u = 4 g(u) + g'(u) u'' + g''(u) u'^2/2), u = 2b",
        "compacton_hertz": "R / max R = cos^(2/eps)(kappa xi), kappa = sqrt(3) eps/(1+eps), of c^2 R = v + v''/12, "
                           "v = R^(1+eps); (max R)^eps = 2 c^2 (1+eps)/(2+eps)",
        **mob_attrs,
        "mobility_definitions": "the site-centred breather (max |A| = 1/2) perturbed by delta (u + i w), u + i w its "
                                "growing mode (max |u| = 1), run to (ln(1/delta) + growth_times)/lambda (at most "
                                "tau_max); its position the parabola-refined peak of |A_n|^2; it travels when the "
                                "largest distance from its start exceeds the threshold; the crossover is the "
                                "midpoint between the largest travelling alpha and the next one",
        "wall_time_s": _time.perf_counter() - t0,
    })
    return make_tree(groups, variables, attrs=attrs, params=plain(spec),
                     title="The continuum limit alpha -> 1+: DpS breathers and Hertz solitary waves against Gaussians")


ANALYSIS = Analysis(
    name="continuum-limit", spec=ContinuumLimit, compute=compute, variables=VARIABLES, claims="/claims",
    title="The continuum limit alpha -> 1+: DpS breathers and Hertz solitary waves against Gaussians")
