"""Declarations of the entries a job computes from: scenes (one lattice (nc) + DpS (dfnls) run, its initial
condition one class per ``kind``), homoclinic and map entries, defaults; each ``check`` what no key says alone."""
from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import Any, cast

from cradle.models.damping import Damping
from cradle.models.lattice_terms import Terms
from cradle.models.physical import HERTZ_ALPHA, Cradle, scales
from cradle.specs.declare import NULL, REQUIRED, declared, param
from cradle.specs.schema import register_union
from cradle.specs.values import (
    DT_FACTOR_FLOOR,
    INTEGER_TOL,
    MAX_T_END,
    SEED_MAX,
    T_END_WHY,
    TIME_TOL,
    ConfigError,
    Errors,
    angle_expr,
    parse_angle,
    show,
)

from .times import store_times

#: a key path: ``["scenes", "tw-weak", "store", "snapshots", 1]``
Where = list[str | int]

#: the name-keyed sections whose entries a figure reads, in the order their names are claimed
ENTRY_SECTIONS = ("map", "homoclinic", "scenes")


@dataclass(frozen=True)
class Context:
    """The entries one entry's check may refer to: ``given`` every name of each of :data:`ENTRY_SECTIONS` (one
    with problems too), ``scenes`` and ``homoclinic`` the resolved entries that passed."""

    given: Mapping[str, tuple[str, ...]]
    scenes: Mapping[str, Scene]
    homoclinic: Mapping[str, HomoclinicEntry]

    @cached_property
    def names(self) -> dict[str, str]:
        """Every map, homoclinic and scene name -> its section (the first that uses it)."""
        out: dict[str, str] = {}
        for section in ENTRY_SECTIONS:
            for name in self.given.get(section, ()):
                out.setdefault(name, section)
        return out


SPLITTINGS = ("srkn6c", "srkn4c", "srkn6", "srkn4", "strang")   # fixed step: dt_factor
LATTICE_ADAPTIVE = ("dop853_numba", "dop853", "rk45", "lsoda", "radau")   # error control: rtol
DPS_METHODS = ("dop853", "dop853_numba", "rk45")


@declared("exactIntegrator", doc="Integrator of the lattice (nc).", partial=True)
class ExactIntegrator:
    method: str = param("srkn6c", "srkn6c (default: Blanes-Moan order-6 splitting, harmonic part exact, with the "
                        "contact-onset correction) | srkn4c | srkn6 | srkn4 | strang (plain splittings) | "
                        "dop853_numba (adaptive, compiled) | dop853 | rk45 | lsoda | radau (scipy).",
                        enum=[*SPLITTINGS, *LATTICE_ADAPTIVE])
    # at most 1: a step longer than the shortest linearised period 2 pi / omega_max resolves no oscillation
    dt_factor: float | None = param(NULL, f"Splitting step = dt_factor * 2 pi / omega_max; in [{DT_FACTOR_FLOOR:g}, "
                                    "1], or null for the method's default.", minimum=DT_FACTOR_FLOOR, maximum=1)
    rtol: float = param(1e-10, "Relative tolerance of the adaptive (scipy) methods, in [1e-14, 1e-2].", ref="rtol")


@declared("dpsIntegrator", doc="Integrator of the DpS equation (dfnls).", partial=True)
class DpsIntegrator:
    method: str = param("dop853_numba", "dop853_numba (default: DOP853 with error control, compiled) | dop853 "
                        "(scipy, compiled right-hand side) | rk45.", enum=list(DPS_METHODS))
    rtol: float = param(1e-10, "Relative tolerance, in [1e-14, 1e-2]; atol = rtol * max |A_n(0)|.", ref="rtol")


@declared(doc="Settings every scene, homoclinic and map entry inherits unless it overrides them.")
class Defaults:
    alpha: float = param(1.5, "Hertz exponent in V0(x) = |x|^(1+alpha) H(-x)/(1+alpha) (vhertz); > 1.", ref="alpha")
    exact: ExactIntegrator = param(ExactIntegrator(), "Integrator of the lattice (nc) used by every scene that does "
                                   "not override it.",
                                   fill={"method": "Default lattice integrator.",
                                         "dt_factor": "Default splitting step factor (null = the method's default).",
                                         "rtol": "Default relative tolerance of the adaptive (scipy) methods."})
    dps: DpsIntegrator = param(DpsIntegrator(), "Integrator of the DpS equation (dfnls) used by every scene that "
                               "does not override it.",
                               fill={"method": "Default DpS integrator.",
                                     "rtol": "Default relative tolerance; atol = rtol * max |A_n(0)|."})
    max_energy_drift: float = param(1e-6, "An exact run whose max_t |H(t)-H(0)|/H(0) exceeds this fails.",
                                    ref="maxEnergyDrift")


@declared("noise", doc="Perturbation (perturb): A_n(0) = (1 + rho1_n) cos(q n + phi) - i (1 + rho2_n) sin(q n + "
                       "phi).")
class Noise:
    kind: str = param("uniform", "Law of rho1_n, rho2_n: uniform on [-amplitude, amplitude] or gaussian with "
                      "standard deviation amplitude.", enum=["uniform", "gaussian"])
    # at most 1: rho is relative to the wave's amplitude; a noise larger than the wave leaves no wave of (perturb)
    amplitude: float = param(REQUIRED, "Half-width (uniform) or standard deviation (gaussian) of the noise, relative "
                             "to the wave's amplitude; in [0, 1].", minimum=0, maximum=1)
    seed: int = param(REQUIRED, "Seed of numpy.random.default_rng (PCG64); recorded so the run is reproducible; "
                      "integer in [0, 2^62].", minimum=0, maximum=SEED_MAX)


@declared("travelling", doc="Approximate travelling wave (ansatzapprox) x_n(0) = a cos(q n + phi), optionally "
                            "perturbed (perturb).")
class Travelling:
    kind: str = param(REQUIRED, "travelling", const="travelling")
    q: float | str = param(REQUIRED, "Wavenumber q in (-pi, pi] (radians or 'pi/5'-like); with periodic ends "
                           "q N / (2 pi) must be an integer.", ref="angle")
    a: float = param(None, "Amplitude a = 2 eps of the wave; > 0. Give exactly one of a and omega_tw.",
                     exclusiveMinimum=0)
    omega_tw: float = param(None, "Frequency of the wave; a follows from (freq), which needs omega_tw > 1 and q != 0. "
                            "Give exactly one of a and omega_tw.", exclusiveMinimum=1)
    phi: float = param(0.0, "Phase phi of the wave (radians).")
    noise: Noise = param(None, "Optional perturbation (perturb); absent = unperturbed wave.")

    @property
    def wavenumber(self) -> float:
        """q in radians."""
        return parse_angle(self.q)

    @property
    def q_expr(self) -> str:
        """q as written ('pi/5'; a number as its repr), kept beside its value in radians."""
        return angle_expr(self.q)

    def check(self, scene: Scene, where: Where, context: Context, out: Errors) -> None:
        """q in (-pi, pi] fitting a ring, exactly one of a and omega_tw, a finite a > 0 from (freq)."""
        path = where + ["initial"]
        q = None
        try:
            q = parse_angle(self.q)
        except ConfigError as err:
            out.add(path + ["q"], "not an angle: " + str(err).split("as an angle: ", 1)[-1], self.q)
        if q is not None:
            if not (-math.pi + 1e-12 < q <= math.pi + 1e-12):
                out.add(path + ["q"], f"must be in (-pi, pi], got q = {q:.10g} rad", self.q)
            elif scene.bc == "periodic":
                m = q * scene.N / (2.0 * math.pi)
                if abs(m - round(m)) > INTEGER_TOL:
                    out.add(path + ["q"], f"with periodic ends q N/(2 pi) must be an integer (the wave must fit the "
                                          f"ring), got q N/(2 pi) = {m:.10g} (N = {scene.N})", self.q)
        a, om = self.a, self.omega_tw
        if a is not None and om is not None:
            out.add(path, f"give exactly one of a and omega_tw, got both (a = {show(a)}, omega_tw = {show(om)})")
        elif a is None and om is None:
            out.add(path, "give exactly one of a and omega_tw, got neither")
        elif om is not None and q is not None:
            if abs(math.sin(q / 2.0)) < 1e-12:
                out.add(path + ["q"], "must not be 0 with omega_tw: (freq) gives omega_tw = 1 for every a when "
                                      "q = 0; give a instead of omega_tw", self.q)
            else:
                from cradle.models import dps  # the amplitude must come out finite and positive
                try:
                    a_derived = dps.amplitude_from_omega(float(om), q, scene.alpha)
                except (ValueError, OverflowError, ZeroDivisionError) as err:
                    out.add(path + ["omega_tw"], f"cannot derive a from (freq): {err}", om)
                else:
                    if not (math.isfinite(a_derived) and a_derived > 0):
                        out.add(path + ["omega_tw"], f"(freq) gives a = {a_derived!r}, not a finite amplitude > 0",
                                om)


@declared("breather", doc="Breather (ansatzapproxst2)/(breatherdps) built from a homoclinic solution of (dpsstn).")
class Breather:
    kind: str = param(REQUIRED, "breather", const="breather")
    homoclinic: str = param(REQUIRED, "Name of the homoclinic entry the breather is built from (same N and bc as "
                            "the scene).", ref="name")
    omega_sw: float = param(None, "Breather frequency; mu = (omega_sw - 1) 2^alpha tau0 > 0 needs omega_sw > 1. Give "
                            "exactly one of omega_sw and amplitude.", exclusiveMinimum=1)
    amplitude: float = param(None, "Initial amplitude |x_site(0)| > 0, from which mu and omega_sw follow. Give "
                             "exactly one of omega_sw and amplitude.", exclusiveMinimum=0)
    site: int = param(None, "Bead where amplitude is measured (0 <= site < N); default: the largest |a_n|.",
                      minimum=0)

    def check(self, scene: Scene, where: Where, context: Context, out: Errors) -> None:
        """Exactly one of omega_sw and amplitude, a site on the chain, a homoclinic entry of the same N, bc, alpha."""
        path = where + ["initial"]
        om, amp = self.omega_sw, self.amplitude
        if om is not None and amp is not None:
            out.add(path, f"give exactly one of omega_sw and amplitude, got both "
                          f"(omega_sw = {show(om)}, amplitude = {show(amp)})")
        elif om is None and amp is None:
            out.add(path, "give exactly one of omega_sw and amplitude, got neither")
        if self.site is not None and not 0 <= self.site < scene.N:
            out.add(path + ["site"], f"must be a bead index in [0, N-1] = [0, {scene.N - 1}]", self.site)
        name, known = self.homoclinic, context.given.get("homoclinic", ())
        if name not in known:
            out.add(path + ["homoclinic"], f"no homoclinic entry of that name (homoclinic entries: "
                                           f"{', '.join(known) or 'none'})", name)
            return
        h = context.homoclinic.get(name)
        if h is None:  # an entry with schema errors: those are said
            return
        for key, value, theirs in (("N", scene.N, h.N), ("bc", scene.bc, h.bc)):
            if value != theirs:
                out.add(where + [key], f"must equal homoclinic.{name}.{key} = {show(theirs)} "
                                       f"(the breather is built from that solution)", value)
        if scene.alpha != h.alpha:
            out.add(where + ["alpha"], f"must equal the alpha of homoclinic.{name} ({h.alpha!r}): the breather "
                                       f"is built from that solution", scene.alpha)
        elif self.amplitude is not None and self.site is not None and 0 <= self.site < scene.N == h.N \
                and scene.bc == h.bc and h.well_placed():
            from cradle.models.homoclinic_continuation import zero_at

            if zero_at(self.site, h.N, h.guess, h.alpha, h.bc, h.mu, h.amplitude, h.centre, h.separation):
                out.add(path + ["site"], f"the profile of homoclinic.{name} is 0 there (its tails underflow double "
                                         f"precision a few sites from its core): the amplitude must be given at a "
                                         f"bead where a_n != 0", self.site)


@declared("packet", doc="Modulated binary oscillation at rest (figure loc1, left): x_n(0) = amplitude (-1)^n "
                        "env(n - centre), v_n(0) = 0; DpS from A_n(0) = x_n(0)/2, eps = 1 (tau = 0 in (breatherdps)).")
class Packet:
    kind: str = param(REQUIRED, "packet", const="packet")
    amplitude: float = param(REQUIRED, "Peak of the envelope (amplitude of the binary oscillation); > 0.",
                             exclusiveMinimum=0)
    width: float = param(REQUIRED, "Number of sites the envelope (almost) covers; > 0 and <= N. gaussian: "
                         "sigma = width/6; cos2: cos^2(pi s/width) on |s| < width/2.", exclusiveMinimum=0)
    envelope: str = param("gaussian", "Envelope shape: gaussian (almost compactly supported) or cos2 (compactly "
                          "supported).", enum=["gaussian", "cos2"])
    centre: float = param(None, "Centre of the envelope, a site (integer) or a bond (half-integer) in [0, N-1]; "
                          "default (N-1)/2.", minimum=0)

    def check(self, scene: Scene, where: Where, context: Context, out: Errors) -> None:
        """The envelope must fit the chain and be centred on it."""
        path, N = where + ["initial"], scene.N
        if self.width > N:
            out.add(path + ["width"], f"must be <= N = {N} (the envelope must fit the chain)", self.width)
        if self.centre is not None and not 0 <= self.centre <= N - 1:
            out.add(path + ["centre"], f"must be in [0, N-1] = [0, {N - 1}]", self.centre)
        elif not out.within(path):
            from cradle.models.initial import envelope_peak

            if not envelope_peak(N, self.envelope, self.width, self.centre) * self.amplitude > 0:
                out.add(path + ["width"], "too narrow: the envelope is 0 at every bead (the packet would be x = 0; "
                                          "a Gaussian's sigma is width/6)", self.width)


@declared("pair", doc="Two static breathers at rest (figure loc1, right): two copies of a homoclinic profile of "
                      "(dpsstn), separation sites apart, each of amplitude `amplitude`; v_n(0) = 0; DpS from "
                      "A_n(0) = x_n(0)/2, eps = 1.")
class Pair:
    kind: str = param(REQUIRED, "pair", const="pair")
    amplitude: float = param(REQUIRED, "|x_n(0)| of one copy alone at its largest site; > 0 (mu and omega_sw of one "
                             "breather follow).", exclusiveMinimum=0)
    separation: int = param(REQUIRED, "Distance in sites between the centres of the two copies; integer in "
                            "[1, N-1].", minimum=1)
    profile: str = param("bond", "Homoclinic profile of each copy, solved from the paper's start on the scene's N "
                         "and bc: site or bond.", enum=["site", "bond"])
    sign: int = param(1, "Relative sign of the second copy: 1 (in phase) or -1 (in antiphase).", enum=[1, -1])
    centre: int = param(None, "Site the profile is centred on before the copies are shifted (0 <= centre < N); "
                        "default N // 2.", minimum=0)

    def check(self, scene: Scene, where: Where, context: Context, out: Errors) -> None:
        """The two copies must be distinct and the centre a site."""
        path, N = where + ["initial"], scene.N
        if not 1 <= self.separation < N:
            out.add(path + ["separation"], f"must be in [1, N-1] = [1, {N - 1}]", self.separation)
        if self.centre is not None and not 0 <= self.centre < N:
            out.add(path + ["centre"], f"must be a site index in [0, N-1] = [0, {N - 1}]", self.centre)


@declared("kick", doc="One bead kicked from rest (James, Kevrekidis & Cuevas 2013): x_n(0) = 0, v_n(0) = velocity "
                      "at `site`; DpS from A_n(0) = -i velocity/2 there, eps = 1.")
class Kick:
    kind: str = param(REQUIRED, "kick", const="kick")
    velocity: float = param(REQUIRED, "Velocity given to the kicked bead; nonzero, |velocity| <= 1e3.", minimum=-1e3,
                            maximum=1e3)
    site: int = param(0, "The kicked bead (0 <= site < N); default 0, the first bead of the chain.", minimum=0)

    def check(self, scene: Scene, where: Where, context: Context, out: Errors) -> None:
        """A nonzero kick on a bead of the chain."""
        path = where + ["initial"]
        if self.velocity == 0:
            out.add(path + ["velocity"], "must be nonzero (a chain at rest does not move)", self.velocity)
        if not 0 <= self.site < scene.N:
            out.add(path + ["site"], f"must be a bead index in [0, N-1] = [0, {scene.N - 1}]", self.site)


INITIAL_KINDS = {"travelling": Travelling, "breather": Breather, "packet": Packet, "pair": Pair, "kick": Kick}
INITIAL_DOC = "Initial condition of a scene: kind travelling, breather, packet or pair."
KIND_DOC = ("travelling (ansatzapprox), breather (ansatzapproxst2), packet (a modulated binary oscillation at rest), "
            "pair (two static breathers at rest) or kick (one bead kicked from rest).")
register_union("initial", INITIAL_DOC, KIND_DOC, INITIAL_KINDS)


@declared("store", doc="What a scene stores: profiles at `snapshots` and/or every `every` time units on [0, t_end] "
                       "(0 and t_end are always stored).", any_of=[("snapshots",), ("every",)])
class Store:
    snapshots: list[float] = param(None, "Strictly increasing times in [0, t_end] whose profiles are stored.",
                                   items={"type": "number", "minimum": 0})
    every: float = param(None, "Spacing of the stored time grid on [0, t_end]; > 0.", exclusiveMinimum=0)


@declared("scene", doc="One lattice (nc) + DpS (dfnls) run.")
class Scene:
    N: int = param(REQUIRED, "Number of beads; >= 2.", ref="N")
    bc: str = param("periodic", "Boundary conditions (periodic | free).", ref="bc")
    alpha: float = param(None, "Per-scene Hertz exponent; default defaults.alpha.", ref="alpha")
    exact: ExactIntegrator = param(None, "Per-scene lattice integrator settings, merged over defaults.exact.")
    dps: DpsIntegrator = param(None, "Per-scene DpS integrator settings, merged over defaults.dps.")
    max_energy_drift: float = param(None, "Per-scene energy drift bound; default defaults.max_energy_drift.",
                                    ref="maxEnergyDrift")
    initial: Travelling | Breather | Packet | Pair | Kick = param(REQUIRED, "Initial condition: its kind "
                                                                  "(travelling, breather, packet, pair, kick) and "
                                                                  "parameters.", ref="initial")
    # at most MAX_T_END: stored times are told apart to TIME_TOL, finer than float64 resolves beyond it
    t_end: float = param(REQUIRED, "Final time of the run (lattice time t); in (0, 4194304] (float64 tells stored "
                         "times 1e-9 apart only below 2^22); the budget's estimate bounds it too.", exclusiveMinimum=0,
                         maximum=MAX_T_END)
    store: Store = param(REQUIRED, "Times at which the state is stored.")
    damping: Damping = param(None, "Dissipation (ncdamped): on-site and Kuwabara-Kono contact damping; absent: the "
                             "conservative (nc).")
    terms: Terms = param(None, "The imperfect cradle (ncimperfect): inhomogeneity (site masses, on-site "
                         "frequencies, contact stiffnesses), precompression and the on-site potential; absent: (nc).")
    cradle: Cradle = param(None, "The real cradle the scene models: its spheres and strings give the scales of (nc) "
                           "(cradle.models.physical); the outputs store them, and `units: si` reads the scene's "
                           "values in SI.")
    units: str = param(None, "Units of the scene's times, amplitudes and damping: nc (default: those of (nc)) or si "
                       "(times in s, amplitudes a and amplitude in m, omega_tw and omega_sw in rad/s, damping.onsite a "
                       "rate in 1/s, damping.contact the Kuwabara-Kono time A in s, a kick's velocity in m/s, "
                       "terms.precompression.delta0 and terms.inhomogeneity.length and radius in m; needs "
                       "`cradle:`).",
                       enum=["nc", "si"])

    @cached_property
    def times(self) -> tuple[float, ...]:
        """The stored times: 0, the grid of ``store.every``, the snapshots and t_end (:func:`store_times`)."""
        return tuple(store_times(self.store.snapshots, self.store.every, self.t_end))

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Snapshots increasing within [0, t_end], damping and terms with their integrator, the initial kind's."""
        t_end, prev = self.t_end, None
        for i, t in enumerate(self.store.snapshots or []):
            p = where + ["store", "snapshots", i]
            if t > t_end + TIME_TOL:
                out.add(p, f"must be <= t_end = {show(t_end)}", t)
            elif prev is not None and not t > prev:
                out.add(p, f"must be > the previous snapshot {show(prev)} (snapshots must be strictly "
                           f"increasing)", t)
            prev = t
        if self.damping is not None and self.damping.active and self.exact.method not in DAMPED_METHODS:
            out.add(where + ["exact", "method"], f"must be one of {', '.join(DAMPED_METHODS)} with damping (a "
                                                 "splitting is not symplectic for a damped cradle: "
                                                 "docs/dissipation.md)", self.exact.method)
        self._check_terms(where, out)
        self.initial.check(self, where, context, out)

    def check_cradle(self, where: Where, out: Errors) -> None:
        """A cradle of one on-site frequency and Hertz's exponent, a swing below its string, SI values only with a
        cradle, t_end within MAX_T_END in (nc)'s units: run when the scene is read, before the budget."""
        c = self.cradle
        if c is not None:
            if (c.length is None) == (c.omega0 is None):
                out.add(where + ["cradle"], "give the pendulum length or omega0, one of them (given: "
                                            f"{'both' if c.length is not None else 'neither'})")
            elif c.length is not None:
                self._check_swing(c, where, out)
            if self.alpha != HERTZ_ALPHA:
                out.add(where + ["alpha"], f"must be {HERTZ_ALPHA} for a cradle of spheres (Hertz's exponent)",
                        self.alpha)
        if self.units == "si" and c is None:
            out.add(where + ["units"], "needs the scene's `cradle:` (its scales convert SI values to (nc)'s)",
                    self.units)
        elif self.t_end > MAX_T_END:   # only an SI time can get here: the schema bounds t_end in (nc)'s units
            out.add(where + ["t_end"], f"is {self.t_end:.6g} in (nc)'s time units (t omega_0), more than "
                                       f"{MAX_T_END:.0f} ({T_END_WHY})")   # the value given is in SI

    def _check_swing(self, c: Cradle, where: Where, out: Errors) -> None:
        """A pendulum's initial displacement (in (nc)'s units here: times X) below its string length."""
        X = scales(c).X
        for key in ("a", "amplitude"):
            value = getattr(self.initial, key, None)
            if isinstance(value, (int, float)) and not abs(value) * X < c.length:   # type: ignore[operator]
                out.add(where + ["initial", key], f"a displacement of {abs(value) * X:.3g} m: must be below the "
                                                  f"string length {c.length:g} m (a bead swings within its string)",
                        float(f"{value * X:.12g}"))

    def _check_terms(self, where: Where, out: Errors) -> None:
        """Active terms need DOP853 in numba, precompression a ring, site values one per bead, a positive draw."""
        terms = self.terms
        if terms is None:
            return
        path, inh = where + ["terms"], terms.inhomogeneity
        given = {key: getattr(inh, key) for key in ("omega", "mass", "stiffness", "length", "radius", "material")
                 if getattr(inh, key) is not None}
        for key, values in given.items():
            if len(values) != self.N:
                out.add(path + ["inhomogeneity", key], f"must have N = {self.N} values (one per "
                                                       f"{'bond' if key == 'stiffness' else 'bead'}), got "
                                                       f"{len(values)}")
        if inh.omega is not None and inh.length is not None:
            out.add(path + ["inhomogeneity", "length"], "give omega or length, not both (length sets omega_n = "
                                                        "(l_0/l_n)^(1/2))")
        if not terms.active:
            return
        if self.exact.method not in DAMPED_METHODS:
            out.add(where + ["exact", "method"], f"must be one of {', '.join(DAMPED_METHODS)} with active terms "
                                                 "(the imperfect cradle (ncimperfect) is integrated by DOP853 in "
                                                 "numba: docs/imperfect-cradles.md)", self.exact.method)
        if self.damping is not None and self.damping.active:
            out.add(where + ["damping"], "cannot go with active terms in a scene: its DpS run would need the damped "
                                         "(dpsimperfect), which is not derived (the lattice takes both: "
                                         "integrate_lattice(..., damping=, terms=))")
        if terms.precompression.delta0 > 0.0 and self.bc != "periodic":
            out.add(path + ["precompression", "delta0"], f"needs bc = periodic (a precompressed chain with bc = "
                                                         f"{self.bc} flies apart: walls are not modelled)",
                    terms.precompression.delta0)
        if all(len(v) == self.N for v in given.values()):
            from cradle.models.inhomogeneity import sites

            try:
                sites(inh, self.N)
            except ConfigError as e:   # a draw with a non-positive frequency or mass: its key, value and why
                head, why = str(e).split(": ", 1)
                key = head.split(" = ", 1)[0].rsplit(".", 1)[-1]
                out.add(path + ["inhomogeneity", key], why, getattr(inh, key))


_POINT = {"type": "number"}


@declared(doc="`count` starting points equally spaced on the segment from `from` to `to` (both ends included); "
              "added after `starts`.")
class MapLine:
    from_: list[float] = param(REQUIRED, "First point [a_0, b_1] of the segment.", key="from", minItems=2, maxItems=2,
                               items=_POINT)
    to: list[float] = param(REQUIRED, "Last point [a_0, b_1] of the segment.", minItems=2, maxItems=2, items=_POINT)
    count: int = param(REQUIRED, "Number of starting points on the segment; integer >= 2.", minimum=2, maximum=1000)


@declared("mapEntry", doc="Orbits of the map G (comp1)-(comp2).", any_of=[("starts",), ("line",)])
class MapEntry:
    box: float = param(REQUIRED, "Orbits are dropped after they leave ||U||_inf <= box; > 0.", exclusiveMinimum=0)
    iterations: int = param(REQUIRED, "How many times G is applied; integer in [1, 1e7].", minimum=1,
                            maximum=10_000_000)
    marks: bool = param(False, "Mark the explicit period-2, -3 and -4 orbits of the traj2 caption in this panel.")
    starts: list[list[float]] = param(None, "Starting points U_0 = (a_0, b_1), one pair [a_0, b_1] per orbit.",
                                      minItems=1, items={"description": "A starting point [a_0, b_1].",
                                                         "type": "array", "minItems": 2, "maxItems": 2,
                                                         "items": _POINT})
    alpha: float = param(None, "Per-entry Hertz exponent; default defaults.alpha.", ref="alpha")
    line: MapLine = param(None, "`count` starting points equally spaced on the segment from `from` to `to` (both "
                          "ends included); added after `starts`.")

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Every starting point inside the box ||U||_inf <= box."""
        points = [(where + ["starts", i], u) for i, u in enumerate(self.starts or [])]
        if self.line is not None:
            points += [(where + ["line", "from"], self.line.from_), (where + ["line", "to"], self.line.to)]
        for key, u in points:
            if max(abs(x) for x in u) > self.box:
                out.add(key, f"must lie in the box ||U||_inf <= box = {show(self.box)}", u)


@declared("homoclinicEntry", doc="A homoclinic solution of (dpsstn) found by Powell's hybrid method from an initial "
                                 "guess.")
class HomoclinicEntry:
    guess: str = param(REQUIRED, "Initial guess: site (a_{N/2} = -amplitude), bond (a_{N/2} = amplitude, "
                       "a_{N/2+1} = -amplitude) or double (two site humps `separation` sites apart).",
                       enum=["site", "bond", "double"])
    N: int = param(REQUIRED, "Number of sites; >= 2.", ref="N")
    bc: str = param("periodic", "Boundary conditions (periodic | free).", ref="bc")
    amplitude: float = param(0.1, "Amplitude of the initial guess; > 0.", exclusiveMinimum=0)
    separation: int = param(9, "Distance in sites between the two humps of the double guess; integer >= 1 (< N).",
                            minimum=1)
    alpha: float = param(None, "Per-entry Hertz exponent; default defaults.alpha.", ref="alpha")
    mu: float = param(1.0, "mu of (dpsst); the solution is mu^(1/(alpha-1)) times the mu = 1 one; > 0.",
                      exclusiveMinimum=0)
    centre: int = param(None, "Site the guess is centred on (0 <= centre < N); default N // 2.", minimum=0)

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """The centre a site, the humps of a double guess distinct, and max |a_n| = (mu / nu)^(1/(alpha-1)) with
        nu > 4 (docs/extremes.md) within 10^(+-300), the solver's limit."""
        alpha = self.alpha if isinstance(self.alpha, (int, float)) else 1.5
        decades = 300.0 * (alpha - 1.0)   # of mu, for 300 of the amplitude
        excess = math.log10(self.mu / 4.0) if self.mu > 0 else -math.inf
        if abs(excess) > decades:
            word, bound = (">=", -decades) if excess < 0 else ("<=", decades)
            exponent = math.log10(4.0) + bound
            limit = f"{10.0 ** (exponent - math.floor(exponent)):.3g}e{math.floor(exponent):+d}"
            out.add(where + ["mu"], f"must be {word} {limit} at alpha = {show(alpha)}: the solution's amplitude "
                                    f"(mu/nu)^(1/(alpha-1)) with nu > 4 {'under' if excess < 0 else 'over'}flows "
                                    f"double precision beyond", self.mu)
        if self.centre is not None and not 0 <= self.centre < self.N:
            out.add(where + ["centre"], f"must be a site index in [0, N-1] = [0, {self.N - 1}]", self.centre)
        if self.guess == "double" and not 1 <= self.separation < self.N:
            out.add(where + ["separation"], f"must be in [1, N-1] = [1, {self.N - 1}]", self.separation)
        if self.well_placed():
            if not out.within(where):   # a short chain solved as its job solves it
                from cradle.models.homoclinic_continuation import solve_fails

                why = solve_fails(self.N, self.guess, alpha, self.bc, self.mu, self.amplitude, self.centre,
                                  self.separation)
                if why is not None:
                    out.add(where, f"its job's solve fails from this guess ({why}); change the guess, its centre or N")
            return
        if out.has(where + ["centre"]) or out.has(where + ["separation"]):
            return
        from cradle.models.homoclinic import guess_off_chain

        out.add(where + ["centre"], str(guess_off_chain(self.N, self.guess, self.bc, self.centre, self.separation)),
                self.N // 2 if self.centre is None else self.centre)

    def well_placed(self) -> bool:
        """Whether the guess's seeds are beads of the chain: the centre a site, the humps of a double guess
        distinct, neither off a chain with free ends (:func:`cradle.models.homoclinic.guess_off_chain`)."""
        from cradle.models.homoclinic import guess_off_chain

        return (self.centre is None or 0 <= self.centre < self.N) and (
            self.guess != "double" or 1 <= self.separation < self.N) and (
            guess_off_chain(self.N, self.guess, self.bc, self.centre, self.separation) is None)


#: the lattice integrators that take damping and the terms of the imperfect cradle (integrate_lattice)
DAMPED_METHODS = ("dop853_numba",)


#: a scene's SI values (``units: si``): key path -> quantity (cradle.models.physical.QUANTITIES; rate 1/s, A in s)
SI_KEYS = {("t_end",): "time", ("store", "every"): "time", ("store", "snapshots"): "time",
           ("initial", "a"): "displacement", ("initial", "amplitude"): "displacement",
           ("initial", "omega_tw"): "rate", ("initial", "omega_sw"): "rate",
           ("initial", "velocity"): "velocity",
           ("damping", "onsite"): "rate", ("damping", "contact"): "A",
           ("terms", "precompression", "delta0"): "displacement",
           ("terms", "inhomogeneity", "length"): "string", ("terms", "inhomogeneity", "radius"): "radius"}


def in_nc_units(scene: Scene) -> Scene:
    """A scene given in SI (``units: si``) with its values in (nc)'s units (:data:`SI_KEYS`); any other as it is."""
    c = scene.cradle
    if scene.units != "si" or c is None or (c.length is None) == (c.omega0 is None):
        return scene   # nothing to convert, or a cradle the checks refuse
    s = scales(c)
    string = c.length if c.length is not None else c.g / s.omega0**2   # l_0 = g / omega_0^2
    factor = {"time": s.omega0, "displacement": 1.0 / s.X, "velocity": 1.0 / s.V, "rate": 1.0 / s.omega0,
              "A": s.omega0, "string": 1.0 / string, "radius": 1.0 / c.radius}
    out = dataclasses.replace(scene, units=cast(str, None))   # absent: (nc)'s units
    for keys, quantity in SI_KEYS.items():
        out = _scaled(out, keys, factor[quantity])
    return out


def _scaled(obj: Any, keys: tuple[str, ...], factor: float) -> Any:
    """``obj`` with the value at ``keys`` (a number or a list) times ``factor``, where it has one."""
    value = getattr(obj, keys[0], None) if dataclasses.is_dataclass(obj) else None
    if value is None or keys[0] not in {f.name for f in dataclasses.fields(obj)}:
        return obj
    if len(keys) > 1:
        return dataclasses.replace(obj, **{keys[0]: _scaled(value, keys[1:], factor)})
    return dataclasses.replace(obj, **{keys[0]: [v * factor for v in value] if isinstance(value, list)
                                       else value * factor})
