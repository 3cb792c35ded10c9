"""Lifetimes and frequency drift of the paper's breather and travelling waves in the damped cradle (ncdamped).

Each damping term of (ncdamped) (:mod:`cradle.models.damping`) is switched on alone, on a grid of values: the
on-site gamma, then the Kuwabara-Kono eta. For every family of initial data and every value, both models run:
the damped lattice (``integrate_lattice(..., damping=Damping(...), method="dop853_numba")``) and the damped DpS
(dpsdamped) (``integrate_dps(..., damping=slow_damping(...))``, docs/damped-dps.md), from the same A_n(0).

Families (:func:`families`): the small breather of plot18 (the bond-centred homoclinic of (dpsstn) on N beads,
built by :func:`cradle.models.initial.breather` at the initial amplitude of the scene breather-small) and the
travelling waves (ansatzapprox) q = 2 pi k / N of :func:`cradle.models.initial.travelling_wave` at the given
omega_tw (tw-weak: 1.01, tw-moderate: 1.1).

Lifetime: the first time the energy falls to a fraction f of its start, f = 1/2 and f = 1/e (the result depends
on the definition: both are stored), read by log-linear interpolation between samples (NaN: not reached by
t_end). The lattice's energy is (ham) H(t); the DpS one is the leading order 2 eps^2 sum |A_n|^2 of (ham) on
the ansatz (docs/damped-dps.md, balance laws), so its fraction is that of sum |A_n|^2.

Closed forms, where one exists:

* on-site damping alone, DpS: d/dtau sum |A_n|^2 = -gamma~ sum |A_n|^2 exactly, so sum |A_n|^2 falls to f at
  t = -ln(f) / gamma (tau = -ln(f) / gamma~): exact. On the lattice the same holds to first order (the on-site
  force removes gamma sum v_n^2, twice the kinetic energy, which is H to O(eps^(alpha-1)) on average);
* contact damping alone on a plane wave, DpS: R^(1-alpha) = 1 + (alpha-1) Im(kappa) Omega tau (docs/damped-dps.md),
  energy ~ R^2, so tau_f = (f^((1-alpha)/2) - 1) / ((alpha-1) Im(kappa) Omega), t_f = tau_f eps^(1-alpha): exact
  for (dpsdamped), and to leading order for the lattice wave;
* contact damping on the breather: none (the p-Laplacian diffusion changes its profile): measured only.

Frequency drift (the breather): over windows of length ``window``, the lattice frequency from the zero
crossings of the breather's largest bead (:func:`cradle.measurements.breathers.frequency_from_crossings`) and
its amplitude max |x|; the DpS frequency 1 + d arg(A_n)/dt (least squares over the window) and amplitude
2 |A_n|. The adiabatic DpS prediction from an amplitude: omega = 1 + (omega_sw(0) - 1) (amp / amp(0))^(alpha-1)
(the mu = 1 family of (breatherdps): mu ~ amp^(alpha-1)); for on-site damping alone the exact reduction of
(dpsdamped) (A = e^{-gamma~ tau/2} B(s(tau))) gives omega(t) - 1 = (omega_sw(0) - 1) e^{-(alpha-1) gamma t/2},
averaged over each window.

Validity: as dps-validity, sup_{t <= T eps^(1-alpha)} max_n |x_n - x_n^app| of the damped lattice against the damped
DpS (:func:`cradle.measurements.damped_validity.sup_error`) for the plane wave at several eps, each term alone
(gamma = gamma~ eps^(alpha-1) at fixed gamma~; eta fixed), with its power of eps against alpha.

The steel cradle (:func:`steel_cradle`): for the cradle of :func:`cradle.models.physical.real_cradle` (steel,
radius, pendulum length), eta from a coefficient of restitution e at an impact speed v through the two-bead
collision of (ncdamped) itself (:func:`cradle.models.restitution.restitution`: 1 - e = f(A kappa^(2/5) v^(1/5)),
kappa = 2 k / m, f(b) = C1 b + O(b^2) with Schwager & Poeschel's C1), and gamma from Stokes' drag of air,
6 pi mu_air R v; both are stated assumptions, not measurements (the spec's param docs and docs/dissipation.md say
which).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.protocol import Analysis
from cradle.data.variables import Var
from cradle.models.restitution import first_order_coefficient, restitution, scaled_for
from cradle.models.restitution_data import STEEL_ASSUMED
from cradle.specs.declare import declared, param, plain
from cradle.specs.values import RTOL_FLOOR

if TYPE_CHECKING:
    import xarray as xr
    from numpy.typing import NDArray

    from cradle.analyses.protocol import Log
    from cradle.integrators.dps_solver import DpsSolution
    from cradle.integrators.lattice_solver import LatticeSolution
    from cradle.models.damping import Damping
    from cradle.models.initial import InitialData
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors

#: Hertz's exponent of (vhertz) for spheres: the damped cradle of a real (steel) cradle
ALPHA = 1.5
TERMS = ("onsite", "contact")
#: the fractions of the initial energy whose first crossing defines a lifetime
LEVELS = (0.5, math.exp(-1.0))
LEVEL_NAMES = ("half", "1/e")

_GAMMA = {"description": "An on-site damping gamma of (ncdamped).", "type": "number", "exclusiveMinimum": 0,
          "maximum": 1}
_ETA = {"description": "A Kuwabara-Kono constant eta of (ncdamped).", "type": "number", "exclusiveMinimum": 0,
        "maximum": 100}
_OMEGA = {"description": "omega_tw of (freq) of a travelling wave (> 1).", "type": "number", "exclusiveMinimum": 1,
          "maximum": 1.5}
_VEPS = {"description": "An eps of (ansatz) for the validity runs.", "type": "number", "exclusiveMinimum": 0,
         "maximum": 0.1}
_TS = {"description": "A slow time T = eps^(alpha-1) t (> 0).", "type": "number", "exclusiveMinimum": 0,
       "maximum": 20}

# ----------------------------------------------------------------- the spec (config `beyond: dissipation:`)


@declared(doc="Lifetimes (time to half and to 1/e of the energy) and frequency drift of the small breather of plot18 "
              "and of travelling waves under each damping term of (ncdamped) alone, on a grid of values, in the "
              "damped lattice, the damped DpS (dpsdamped) and the closed forms; the sup error of the damped DpS "
              "against the damped lattice at several eps; the damping of a steel cradle -> "
              "results/dissipation/dissipation.nc and results/figures/dissipation.{pdf,png}.")
class Dissipation:
    N: int = param(50, "Ring size of every run (plot18 and tw-weak: 50).", minimum=8, maximum=400)
    breather_amplitude: float = param(9.7e-3, "Initial |x| of the breather's largest bead (scene breather-small, "
                                      "plot18: 9.7e-3, omega_sw ~ 1.1).", exclusiveMinimum=0, maximum=0.5)
    wave_mode: int = param(5, "k of the travelling waves' wavenumber q = 2 pi k / N (5 on N = 50: q = pi/5, as "
                           "tw-weak).", minimum=1, maximum=200)
    waves: list[float] = param([1.01, 1.1], "omega_tw of the travelling waves (tw-weak: 1.01, a ~ 0.021; "
                               "tw-moderate: 1.1, a ~ 2.1).", minItems=0, maxItems=4, items=_OMEGA,
                               reduced=[1.01])
    onsite: list[float] = param([1e-3, 2e-3, 5e-3, 1e-2, 2e-2, 5e-2, 0.1], "On-site damping values gamma (each "
                                "run has eta = 0).", minItems=2, maxItems=20, items=_GAMMA,
                                reduced=[0.01, 0.03, 0.1])
    contact: list[float] = param([0.1, 0.3, 1.0, 3.0, 10.0], "Kuwabara-Kono values eta (each run has gamma = 0).",
                                 minItems=2, maxItems=20, items=_ETA,
                                 reduced=[0.3, 1.0, 3.0])
    t_end: float = param(1500.0, "Length of every run (units of (nc)); a lifetime longer than this is NaN.",
                         minimum=10, maximum=20000,
                         reduced=300.0)
    sample_every: float = param(0.1, "Spacing of the stored samples (the frequencies are read from zero crossings: "
                                "tens of samples per period).", exclusiveMinimum=0, maximum=0.5)
    window: float = param(50.0, "Length of the windows of the frequency drift.", minimum=10, maximum=10000)
    rtol: float = param(1e-10, "Relative tolerance of the lattice (dop853_numba) and DpS runs.", minimum=RTOL_FLOOR,
                        maximum=1e-6)
    validity_eps: list[float] = param([0.01, 0.0025], "eps of (ansatz) of the validity runs (the plane wave of "
                                      "wave_mode, A_n(0) = e^{-iqn}).", minItems=2, maxItems=6, items=_VEPS)
    validity_T: list[float] = param([0.5, 1.0, 2.0], "Slow times T of the validity errors.", minItems=1, maxItems=12,
                                    items=_TS,
                                    reduced=[0.5, 1.0])
    validity_gamma: float = param(1.0, "gamma~ = gamma eps^(1-alpha) of the on-site validity runs.",
                                  exclusiveMinimum=0, maximum=10)
    validity_eta: float = param(0.1, "eta of the contact validity runs.", exclusiveMinimum=0, maximum=10)
    steel_radius: float = param(0.01, "Radius of the steel cradle's balls (m).", exclusiveMinimum=0, maximum=1)
    steel_length: float = param(0.1, "Pendulum length of the steel cradle (m).", exclusiveMinimum=0, maximum=100)
    steel_restitution: float = param(STEEL_ASSUMED.e,
                                     "Coefficient of restitution e of two of its balls at steel_speed: a "
                                     "STATED ASSUMPTION (no measured value for 1 cm steel balls at cradle speeds "
                                     "was found in the sources available to us; docs/dissipation.md).",
                                     exclusiveMinimum=0, exclusiveMaximum=1)
    steel_speed: float = param(STEEL_ASSUMED.v,
                               "Relative impact speed (m/s) at which steel_restitution holds (assumed).",
                               exclusiveMinimum=0, maximum=100)
    air_viscosity: float = param(1.7894e-5, "Dynamic viscosity of air (Pa s): ISO 2533:1975 Standard Atmosphere, "
                                 "sea level (15 C); the on-site gamma of the steel cradle is Stokes' drag "
                                 "6 pi mu R v on a ball (a lower bound: the Reynolds number of a swinging ball is "
                                 "10^2-10^3, where the drag is larger).", exclusiveMinimum=0, maximum=1)

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Each form: the wave fits the ring below the zone edge; the grids have distinct values."""
        if not 2 * self.wave_mode < self.N:
            out.add(where + ["wave_mode"], f"must be below N / 2 (N = {self.N}; q < pi)", self.wave_mode)
        for key in ("waves", "onsite", "contact", "validity_eps"):
            values = getattr(self, key)
            if len(set(values)) != len(values):
                out.add(where + [key], "lists a value twice", values)


# ----------------------------------------------------------------- initial data


def families(spec: Dissipation) -> list[tuple[str, InitialData]]:
    """(name, InitialData) of every family: ``breather`` (plot18's small breather) and ``wave-<omega_tw>``."""
    from cradle.models import homoclinic_continuation, initial

    sol = homoclinic_continuation.solve_kind(spec.N, "bond", ALPHA, "periodic")
    if not sol.converged:
        raise ValueError(f"dissipation: bond homoclinic on N = {spec.N} did not converge (residual {sol.residual:.3e})")
    out: list[tuple[str, InitialData]] = [("breather", initial.breather(np.asarray(sol.a), ALPHA,
                                                                   amplitude=spec.breather_amplitude))]
    q = 2.0 * np.pi * spec.wave_mode / spec.N
    for w in spec.waves:
        out.append((f"wave-{w:g}", initial.travelling_wave(spec.N, q, ALPHA, omega_tw=float(w))))
    return out


# ----------------------------------------------------------------- measurements on one run


def lifetime(t: NDArray[np.float64], ratio: NDArray[np.float64], level: float) -> float:
    """First time the decreasing ``ratio`` (energy over its start) reaches ``level``, interpolated linearly in
    log(ratio) between the two samples around it; NaN if it never does."""
    t, r = np.asarray(t, dtype=float), np.asarray(ratio, dtype=float)
    below = np.flatnonzero(r <= level)
    if below.size == 0:
        return float("nan")
    i = int(below[0])
    if i == 0:
        return float(t[0])
    la, lb, lv = math.log(r[i - 1]), math.log(r[i]), math.log(level)
    return float(t[i - 1] + (t[i] - t[i - 1]) * (la - lv) / (la - lb))


def closed_lifetime(term: str, value: float, level: float, family: str, info: dict, q: float) -> float:
    """The closed-form lifetime (module docstring) of a family under one term; NaN where there is none."""
    from cradle.models import dps
    from cradle.models.dps_damped import contact_factor

    if term == "onsite":
        return -math.log(level) / value
    if family.startswith("wave"):
        kap = contact_factor(value, ALPHA)
        Om = dps.plane_wave_frequency(1.0, q, ALPHA)
        tau_f = (level ** ((1.0 - ALPHA) / 2.0) - 1.0) / ((ALPHA - 1.0) * kap.imag * Om)
        return float(tau_f * info["eps"] ** (1.0 - ALPHA))
    return float("nan")


def drift_windows(t: NDArray[np.float64], x_site: NDArray[np.float64], v_site: NDArray[np.float64],
                  A_site: NDArray[np.complex128], eps: float,
                  window: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Per window [k window, (k+1) window): (starts, lattice omega, lattice amplitude, DpS omega, DpS amplitude).

    The amplitudes are window means of the envelopes: sqrt(x^2 + v^2) of the bead (its amplitude for a frequency
    near 1) and 2 eps |A_n|, so that they are averaged as the frequencies are."""
    from cradle.measurements.breathers import frequency_from_crossings

    t = np.asarray(t, dtype=float)
    K = int(np.floor((t[-1] - t[0]) / window + 1e-9))
    starts = t[0] + window * np.arange(K)
    out = np.full((4, K), np.nan)
    phase = np.unwrap(np.angle(A_site))
    for k in range(K):
        m = (t >= starts[k]) & (t <= starts[k] + window)
        out[0, k] = frequency_from_crossings(t[m], x_site[m])
        out[1, k] = np.mean(np.hypot(x_site[m], v_site[m]))
        out[2, k] = 1.0 + np.polyfit(t[m], phase[m], 1)[0]
        out[3, k] = 2.0 * eps * np.mean(np.abs(A_site[m]))
    return starts, out


def run_pair(init: InitialData, damping: Damping, t: NDArray[np.float64],
             rtol: float) -> tuple[LatticeSolution, DpsSolution]:
    """The damped lattice and damped DpS runs of one family: (lattice solution, DpS solution)."""
    from cradle.integrators import integrate_dps, integrate_lattice
    from cradle.models.dps_damped import slow_damping

    lat = integrate_lattice(init.x0, init.v0, t, alpha=ALPHA, method="dop853_numba", rtol=rtol, damping=damping)
    sol = integrate_dps(init.A0, init.eps ** (ALPHA - 1.0) * t, alpha=ALPHA, rtol=rtol,
                        damping=slow_damping(damping, init.eps, ALPHA))
    return lat, sol


# ----------------------------------------------------------------- validity (as dps-validity, damped)


def validity(spec: Dissipation, term: str, eps: float) -> dict:
    """sup errors (:func:`cradle.measurements.damped_validity.sup_error`) of the plane wave of ``wave_mode`` at
    ``eps`` with one damping term (on-site: gamma = validity_gamma eps^(alpha-1); contact: validity_eta)."""
    from cradle.integrators import integrate_dps, integrate_lattice
    from cradle.measurements.damped_validity import sup_error
    from cradle.models import dps_damped
    from cradle.models.damping import Damping

    q = 2.0 * np.pi * spec.wave_mode / spec.N
    A0 = np.exp(-1j * q * np.arange(spec.N))
    damping = (Damping(onsite=spec.validity_gamma * eps ** (ALPHA - 1.0)) if term == "onsite"
               else Damping(contact=spec.validity_eta))
    slow = dps_damped.slow_damping(damping, eps, ALPHA)
    x0, v0 = dps_damped.lattice_state(A0, eps, ALPHA, slow)
    t_max = max(spec.validity_T) * eps ** (1.0 - ALPHA)
    # samples a twentieth of a period apart: the sampled sup within a few per cent (damped_validity)
    t = np.linspace(0.0, t_max, int(np.ceil(t_max / 0.05)) + 1)
    lat = integrate_lattice(x0, v0, t, alpha=ALPHA, method="dop853_numba", rtol=spec.rtol, damping=damping)
    sol = integrate_dps(A0, eps ** (ALPHA - 1.0) * t, alpha=ALPHA, rtol=spec.rtol, damping=slow)
    r = sup_error(t, lat.x, sol.A, eps, ALPHA, spec.validity_T, v=lat.v)
    r["energy_drift"] = lat.energy_drift
    return r


# ----------------------------------------------------------------- the steel cradle


#: C1 of 1 - e = C1 A kappa^(2/5) v^(1/5) + ... for xi'' + kappa (xi^(3/2) + A xi^(1/2) xi') = 0 (the series of
#: Ramirez, Poeschel, Brilliantov & Schwager, Phys. Rev. E 60 (1999) 4465; Schwager & Poeschel, Phys. Rev. E 78
#: (2008) 051304), in closed form from the undamped collision (cradle.models.restitution.first_order_coefficient)
SCHWAGER_C1 = first_order_coefficient()


def steel_cradle(spec: Dissipation) -> dict:
    """eta and gamma of (ncdamped) for the steel cradle of the spec, and what they are made of (module docstring)."""
    from cradle.models import physical
    from cradle.models.damping import contact_eta, onsite_gamma

    cr = physical.real_cradle("steel", spec.steel_radius, length=spec.steel_length)
    s = physical.scales(cr)
    kappa = s.k / (s.m / 2.0)
    b = scaled_for(spec.steel_restitution)
    A = b / (kappa**0.4 * spec.steel_speed**0.2)
    rho = physical.MATERIALS["steel"].rho
    rate = 4.5 * spec.air_viscosity / (rho * spec.steel_radius**2)  # 6 pi mu R / m, m = (4/3) pi R^3 rho
    small = 1e-4
    return {"eta": contact_eta(A, s.omega0), "gamma": onsite_gamma(rate, s.omega0), "A_seconds": A,
            "rate_per_second": rate, "omega0": s.omega0, "X": s.X, "kk_b": b,
            "C1_measured": (1.0 - restitution(small)) / small}


# ----------------------------------------------------------------- the pipeline stage

_FAM = Var(("family",), "family of initial data (breather, wave-<omega_tw>)")
_TERM = Var(("term",), "damping term of (ncdamped): onsite (gamma) or contact (eta)")
_CASE = Var(("case",), "index of a damped case: one term of (ncdamped) at one value (term_of_case, damping)")
_LEVEL = Var(("level",), "fraction f of the initial energy whose first crossing is the lifetime",
             attrs=(("comment", "f = 1/2 and 1/e"),))
_LT = ("family", "case", "level")

#: the stored variables of the `dissipation` file, per group: "/lifetimes" (family, case, level), "/drift" the
#: breather's frequency over windows (case, window), "/validity" (term, i_eps, T), "/steel" the steel cradle
VARIABLES = {
    "/": {},
    "/lifetimes": {
        "family": _FAM, "case": _CASE, "level": _LEVEL,
        "term_of_case": Var(("case",), "damping term of the case: 0 on-site gamma, 1 Kuwabara-Kono eta"),
        "damping": Var(("case",), "value of the case's damping term (gamma or eta of (ncdamped))"),
        "lifetime_lattice": Var(_LT, "first time t at which H(t) of (ncdamped) falls to f H(0)",
                                attrs=(("comment", "NaN: not reached by t_end"),)),
        "lifetime_dps": Var(_LT, "first time t at which sum |A_n|^2 of (dpsdamped) falls to f of its start"),
        "lifetime_closed": Var(_LT, "closed-form lifetime: -ln f / gamma (on-site), the plane wave's contact law "
                               "(waves); NaN where none"),
        "energy_left_lattice": Var(("family", "case"), "H(t_end) / H(0) of the lattice run"),
        "energy_left_dps": Var(("family", "case"), "sum |A_n|^2 at t_end over its start (DpS run)"),
        "balance_drift": Var(("family", "case"), "max |H + D - H(0)| / |H(0)| of the lattice run (integrator error)"),
        "dps_l2_drift": Var(("family", "case"), "residual of the l2 balance of the DpS run (integrator error)"),
        "eps": Var(("family",), "small parameter eps of (ansatz) of the family"),
        "omega0_family": Var(("family",), "frequency of the family: omega_sw (breather) or omega_tw (waves)"),
        "exponent_lattice": Var(("family", "term", "level"), "fitted power p of lifetime ~ damping^p, lattice"),
        "exponent_dps": Var(("family", "term", "level"), "fitted power p of lifetime ~ damping^p, DpS"),
        "term": _TERM,
    },
    "/drift": {
        "window": Var(("window",), "index of a time window of length window_length"),
        "window_start": Var(("window",), "start time of the window"),
        "omega_lattice": Var(("case", "window"), "breather frequency of the lattice (zero crossings of its largest "
                             "bead)"),
        "amplitude_lattice": Var(("case", "window"), "window mean of sqrt(x^2 + v^2) of the breather's largest bead"),
        "omega_dps": Var(("case", "window"), "breather frequency of (dpsdamped): 1 + d arg(A_n)/dt at that bead"),
        "amplitude_dps": Var(("case", "window"), "window mean of 2 eps |A_n| at that bead"),
        "omega_adiabatic": Var(("case", "window"), "window mean of 1 + (omega_sw(0) - 1) (a(t) / a(0))^(alpha-1), a "
                               "the lattice bead's envelope: the DpS breather at the lattice's amplitude"),
        "omega_closed": Var(("case", "window"), "on-site alone: 1 + (omega_sw(0) - 1) e^{-(alpha-1) gamma t/2} "
                            "averaged over the window (exact for (dpsdamped)); NaN for the contact term"),
    },
    "/validity": {
        "i_eps": Var(("i_eps",), "index of eps of the validity runs"),
        "term": _TERM,
        "T": Var(("T",), "slow time T = tau up to which the error is taken (dfnls)"),
        "validity_eps": Var(("i_eps",), "eps of (ansatz) of the validity run"),
        "abs_error": Var(("term", "i_eps", "T"), "sup_{t <= T eps^(1-alpha)} max_n |x_n - x_n^app|, damped lattice "
                         "against damped DpS"),
        "rel_error": Var(("term", "i_eps", "T"), "abs_error / (2 eps)"),
        "envelope_error": Var(("term", "i_eps", "T"), "sup_t max_n |x_n - x_n^app| / (2 eps max_n |A_n(tau)|)"),
        "law_ratio": Var(("term", "i_eps", "T"), "abs_error / eps^alpha: constant where the consistency law holds"),
        "exponent": Var(("term", "T"), "power of eps of abs_error between the smallest and largest eps"),
        "validity_energy_drift": Var(("term", "i_eps"), "max |H + D - H(0)| / |H(0)| of the validity lattice run"),
    },
    "/steel": {
        "cradle": Var(("cradle",), "the real cradle (one: the spec's steel cradle)"),
        "family": _FAM, "term": _TERM, "level": _LEVEL,
        "eta_steel": Var(("cradle",), "eta of (ncdamped) of the steel cradle (from the assumed restitution)"),
        "gamma_steel": Var(("cradle",), "gamma of (ncdamped) of the steel cradle (Stokes drag of air)"),
        "A_steel": Var(("cradle",), "Kuwabara-Kono constant A of the steel cradle", units="s"),
        "rate_steel": Var(("cradle",), "on-site damping rate of the steel cradle (Stokes drag per unit mass and speed)",
                          units="s-1"),
        "omega0": Var(("cradle",), "pendulum angular frequency omega_0 = sqrt(g / L)", units="rad s-1"),
        "length_scale": Var(("cradle",), "length X of one unit of displacement of (nc)", units="m"),
        "restitution_C1": Var(("cradle",), "1 - e over b at b = 1e-4 for the collision of (ncdamped): C1 of Schwager & "
                              "Poeschel's 1 - e = C1 b + ..."),
        "lifetime_closed_steel": Var(("family", "term", "level"), "closed-form lifetime at the steel cradle's "
                                     "damping (NaN where none)"),
        "lifetime_closed_steel_si": Var(("family", "term", "level"), "the same in seconds", units="s"),
    },
}


def _power(x: NDArray[np.float64], y: NDArray[np.float64]) -> float:
    """Least-squares power p of y ~ x^p over the finite positive points (NaN with fewer than 2)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    ok = np.isfinite(y) & (y > 0)
    if ok.sum() < 2:
        return float("nan")
    return float(np.polyfit(np.log(x[ok]), np.log(y[ok]), 1)[0])


def compute(spec: Dissipation, inputs: dict | None = None, log: Log | None = None) -> xr.DataTree:
    """The `dissipation` analysis as a tree of groups (module docstring, :data:`VARIABLES`); reads no file."""
    import time

    from cradle.data.io import make_tree
    from cradle.models.damping import Damping

    t_start = time.perf_counter()
    say = log or (lambda *a: None)
    fams = families(spec)
    q = 2.0 * np.pi * spec.wave_mode / spec.N
    cases = [(0, float(g)) for g in spec.onsite] + [(1, float(e)) for e in spec.contact]
    n_f, n_c, n_l = len(fams), len(cases), len(LEVELS)
    life_lat, life_dps, life_cf = (np.full((n_f, n_c, n_l), np.nan) for _ in range(3))
    left_lat, left_dps, bal, l2d = (np.full((n_f, n_c), np.nan) for _ in range(4))
    t = np.linspace(0.0, spec.t_end, int(round(spec.t_end / spec.sample_every)) + 1)
    n_w = int(np.floor(spec.t_end / spec.window + 1e-9))
    drift = np.full((4, n_c, n_w), np.nan)
    w_adiab, w_closed = np.full((n_c, n_w), np.nan), np.full((n_c, n_w), np.nan)
    starts = spec.window * np.arange(n_w)
    for jf, (name, init) in enumerate(fams):
        info = init.info
        site = int(np.argmax(np.abs(init.x0)))
        for jc, (term, value) in enumerate(cases):
            damping = Damping(**{TERMS[term]: value})
            lat, sol = run_pair(init, damping, t, spec.rtol)
            H = np.asarray(lat.energy)
            l2 = np.sum(np.abs(sol.A) ** 2, axis=1)
            for k, f in enumerate(LEVELS):
                life_lat[jf, jc, k] = lifetime(t, H / H[0], f)
                life_dps[jf, jc, k] = lifetime(t, l2 / l2[0], f)
                life_cf[jf, jc, k] = closed_lifetime(TERMS[term], value, f, name, info, q)
            left_lat[jf, jc], left_dps[jf, jc] = H[-1] / H[0], l2[-1] / l2[0]
            bal[jf, jc], l2d[jf, jc] = lat.energy_drift, sol.max_l2_drift
            if name == "breather" and n_w:
                _, d = drift_windows(t, lat.x[:, site], lat.v[:, site], sol.A[:, site], init.eps,
                                     spec.window)
                drift[:, jc] = d
                w0, a0 = info["omega_sw"], abs(init.x0[site])
                env = np.hypot(lat.x[:, site], lat.v[:, site]) / a0
                w_adiab[jc] = [1.0 + (w0 - 1.0) * np.mean(env[(t >= s0) & (t <= s0 + spec.window)] ** (ALPHA - 1.0))
                               for s0 in starts]
                if term == 0:
                    r = 0.5 * (ALPHA - 1.0) * value
                    mean = (np.exp(-r * starts) - np.exp(-r * (starts + spec.window))) / (r * spec.window)
                    w_closed[jc] = 1.0 + (w0 - 1.0) * mean
            say(f"dissipation: {name} {TERMS[term]}={value:g}: lifetime (half) lattice {life_lat[jf, jc, 0]:.4g}, "
                f"DpS {life_dps[jf, jc, 0]:.4g}, closed {life_cf[jf, jc, 0]:.4g}")
    terms = np.array([c[0] for c in cases])
    values = np.array([c[1] for c in cases])
    expo_lat, expo_dps = np.full((n_f, 2, n_l), np.nan), np.full((n_f, 2, n_l), np.nan)
    for jf in range(n_f):
        for term in range(2):
            m = terms == term
            for k in range(n_l):
                expo_lat[jf, term, k] = _power(values[m], life_lat[jf, m, k])
                expo_dps[jf, term, k] = _power(values[m], life_dps[jf, m, k])
    # validity
    Ts = np.sort(np.asarray(spec.validity_T, dtype=float))
    veps = np.asarray(spec.validity_eps, dtype=float)
    vabs, vrel, venv = (np.full((2, veps.size, Ts.size), np.nan) for _ in range(3))
    vdrift = np.full((2, veps.size), np.nan)
    for term in range(2):
        for ie, eps in enumerate(veps):
            res = validity(spec, TERMS[term], float(eps))
            vabs[term, ie], vrel[term, ie], venv[term, ie] = res["abs_error"], res["rel_error"], res["envelope_error"]
            vdrift[term, ie] = res["energy_drift"]
        say(f"dissipation: validity {TERMS[term]}: E_abs/eps^alpha at T = {Ts[-1]:g}: "
            + " ".join(f"{e:.3g}" for e in vabs[term, :, -1] / veps**ALPHA))
    lo, hi = int(np.argmin(veps)), int(np.argmax(veps))
    vexp = np.log(vabs[:, hi] / vabs[:, lo]) / math.log(veps[hi] / veps[lo])
    # the steel cradle
    st = steel_cradle(spec)
    steel_life = np.full((n_f, 2, n_l), np.nan)
    for jf, (name, init) in enumerate(fams):
        for term, value in ((0, st["gamma"]), (1, st["eta"])):
            for k, f in enumerate(LEVELS):
                steel_life[jf, term, k] = closed_lifetime(TERMS[term], value, f, name, init.info, q)
    names = [n for n, _ in fams]
    groups = {
        "/lifetimes": ({"term_of_case": terms, "damping": values, "lifetime_lattice": life_lat,
                        "lifetime_dps": life_dps, "lifetime_closed": life_cf, "energy_left_lattice": left_lat,
                        "energy_left_dps": left_dps, "balance_drift": bal, "dps_l2_drift": l2d,
                        "eps": np.array([i.eps for _, i in fams]),
                        "omega0_family": np.array([i.info.get("omega_sw", i.info.get("omega_tw"))
                                                   for _, i in fams]),
                        "exponent_lattice": expo_lat, "exponent_dps": expo_dps},
                       {"family": names, "case": np.arange(n_c), "level": np.asarray(LEVELS), "term": list(TERMS)}),
        "/drift": ({"window_start": starts, "omega_lattice": drift[0], "amplitude_lattice": drift[1],
                    "omega_dps": drift[2], "amplitude_dps": drift[3], "omega_adiabatic": w_adiab,
                    "omega_closed": w_closed}, {"window": np.arange(n_w)}),
        "/validity": ({"validity_eps": veps, "abs_error": vabs, "rel_error": vrel, "envelope_error": venv,
                       "law_ratio": vabs / veps[None, :, None] ** ALPHA, "exponent": vexp,
                       "validity_energy_drift": vdrift}, {"i_eps": np.arange(veps.size), "T": Ts, "term": list(TERMS)}),
        "/steel": ({"eta_steel": [st["eta"]], "gamma_steel": [st["gamma"]], "A_steel": [st["A_seconds"]],
                    "rate_steel": [st["rate_per_second"]], "omega0": [st["omega0"]], "length_scale": [st["X"]],
                    "restitution_C1": [st["C1_measured"]], "lifetime_closed_steel": steel_life,
                    "lifetime_closed_steel_si": steel_life / st["omega0"]},
                   {"cradle": ["steel"], "family": names, "term": list(TERMS), "level": np.asarray(LEVELS)}),
    }
    attrs = {
        "family_names": ", ".join(names),
        "level_names": ", ".join(LEVEL_NAMES),
        "term_names": ", ".join(TERMS),
        "alpha": ALPHA,
        "families": f"breather: plot18's small breather, bond-centred homoclinic of (dpsstn) on N = {spec.N}, "
                    f"initial amplitude {spec.breather_amplitude:g} (initial.breather); wave-<omega_tw>: "
                    f"(ansatzapprox) q = 2 pi {spec.wave_mode} / {spec.N}, a from (freq)",
        "window_length": spec.window,
        "breather_amplitude": spec.breather_amplitude,
        "t_end": spec.t_end,
        "lattice_integrator": f"dop853_numba, rtol = {spec.rtol:g}",
        "dps_integrator": f"dop853_numba, rtol = {spec.rtol:g}",
        "validity": f"plane wave q = 2 pi {spec.wave_mode} / {spec.N}; on-site: gamma~ = {spec.validity_gamma:g} "
                    f"(gamma = gamma~ eps^(alpha-1)); contact: eta = {spec.validity_eta:g}",
        "steel_cradle": f"steel (physical.MATERIALS), radius {spec.steel_radius:g} m, length {spec.steel_length:g} m; "
                        f"contact: ASSUMED restitution e = {spec.steel_restitution:g} at {spec.steel_speed:g} m/s "
                        "converted through the collision of (ncdamped) itself (cradle.models.restitution.restitution); "
                        "on-site: Stokes "
                        f"drag 6 pi mu R v, mu = {spec.air_viscosity:g} Pa s (ISO 2533), a lower bound",
        "schwager_C1": SCHWAGER_C1,
        "max_balance_drift": float(np.nanmax(bal)),
        "wall_time_s": time.perf_counter() - t_start,
    }
    return make_tree(groups, VARIABLES, attrs=attrs, params=plain(spec),
                     title="Lifetimes and frequency drift of breathers and travelling waves in the damped cradle "
                           "(ncdamped) and (dpsdamped)")


ANALYSIS = Analysis(
    name="dissipation", spec=Dissipation, compute=compute, variables=VARIABLES,
    title="Lifetimes and frequency drift of breathers and travelling waves under each damping term, lattice and DpS")
