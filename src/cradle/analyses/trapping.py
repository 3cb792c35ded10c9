"""Trapping: how much of an incident wave's energy a chain at rest keeps in static breathers (shock absorbers).

The paper's conclusion (section ``conclu``): granular chains "are interesting devices for the design of shock
absorbers ..., and the possibility might exist to trap a part of the energy of an incident wave into static
breathers in an efficient way". Measured here on (nc) and on the imperfect cradle (ncimperfect) with detuned
strings (:mod:`cradle.models.lattice_terms`), with and without the damping of (ncdamped).

The chain (free ends, alpha = 3/2) is three zones, beads counted from the left:

* ``launch``: the homogeneous beads where the incident wave starts: ``launch`` beads for the striker (bead 0),
  ``back`` + 40 for the breather (its profile on the last 40, the ``back`` beads behind it an absorbing back end
  made of length, checked as the far end is: ``reach_back``);
* ``target``: ``length`` beads, homogeneous (sigma = 0) or disordered: on-site frequencies
  omega_n = 1 + sigma z_n drawn by :func:`cradle.models.inhomogeneity.sites` from the recorded seed (z normal,
  zero mean, unit variance: the string lengths of a real cradle; masses and contacts equal);
* ``lead``: ``lead`` homogeneous beads: an absorbing end made of length. Nothing comes back from the far end:
  each run records the largest energy ever held by its last ``edge`` beads (``reach``, 0 when the wave never got
  there), and the spec's lead is long enough that it is 0 to rounding in every run (docs/analyses.md).

Incident waves (amplitude a):

* ``striker``: bead 0 given the velocity v_0(0) = a, the rest at rest (energy a^2/2). In (nc) it launches one
  travelling breather at ~0.2 a^(1/2) beads per unit time and leaves a slowly spreading wake behind;
* ``breather``: the bond-centred breather of (ansatzapproxst2) (the homoclinic of (dpsstn) on 40 beads,
  :func:`cradle.models.homoclinic_continuation.solve_kind`, at largest |x_n(0)| = a, 20 beads before the target)
  given a velocity along its translation mode: for x_n(t) = (-1)^n f(n - c t) cos(omega t) the velocities at
  t = 0 are -c (-1)^n f'(n); v(0) = kick a e with e = (-1)^n grad((-1)^n x_n(0)) normalised (sum e_n^2 = 1),
  a positive kick sending it into the target. (The breathers analysis kicks along the exact breather's
  pinning mode; the translation mode is its small-amplitude form and needs no Floquet computation.)

Times are slow times tau = a^(alpha-1) t of (dfnls) (the DpS time, with a in place of 2 eps): every incident
crosses the same number of beads per unit tau (~0.2), so one lead length serves every amplitude; a run lasts
t = tau_end a^(1-alpha).

Measured (:mod:`cradle.measurements.trapping`) at each measurement time tau_m and each window W (in tau) and
threshold theta (fraction of the energy put in, H(0)): the static breathers and the fraction of H(0) they hold
(whole chain, and those centred in the target), the energy of each zone and the energy dissipated D (damped
runs: H + D = H(0) is the integrator's check). Every definition the spec lists is reported.

Runs (each a "run" row of /runs): the amplitude scan (every amplitude at the main length, homogeneous and at
every sigma and seed, undamped), the length scan (every other length at the scan amplitude), the damping scan
(each damping case alone at the scan amplitude and main length, homogeneous and at ``damping_sigma`` over the
seeds). /summary gives, per case, the mean, standard deviation, minimum and maximum over the seeds.
"""
from __future__ import annotations

import math
import time as _time
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.protocol import Analysis, Batches
from cradle.data.variables import Var
from cradle.specs.declare import declared, param, plain
from cradle.specs.values import RTOL_FLOOR

if TYPE_CHECKING:
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors

#: Hertz's exponent of (vhertz) for spheres
ALPHA = 1.5
INCIDENTS = ("striker", "breather")
ZONES = ("launch", "target", "lead")
SCANS = ("amplitude", "length", "damping")
#: beads of the ring on which the breather's profile (the bond homoclinic of (dpsstn)) is solved
PROFILE = 40

_V = {"description": "A striker velocity a (units of (nc)).", "type": "number", "exclusiveMinimum": 0, "maximum": 10}
_A = {"description": "A breather amplitude a = max |x_n(0)| (units of (nc)).", "type": "number",
      "exclusiveMinimum": 0, "maximum": 3}
_LEN = {"description": "A target length (beads).", "type": "integer", "minimum": 4, "maximum": 400}
_SIGMA = {"description": "A disorder strength sigma (std of omega_n - 1).", "type": "number", "exclusiveMinimum": 0,
          "maximum": 0.25}
_GAMMA = {"description": "An on-site damping gamma of (ncdamped).", "type": "number", "exclusiveMinimum": 0,
          "maximum": 1}
_ETA = {"description": "A Kuwabara-Kono eta of (ncdamped).", "type": "number", "exclusiveMinimum": 0, "maximum": 100}
_TAU = {"description": "A slow time tau = a^(alpha-1) t.", "type": "number", "exclusiveMinimum": 0, "maximum": 20000}
_THETA = {"description": "A threshold theta: fraction of H(0).", "type": "number", "exclusiveMinimum": 0,
          "maximum": 0.5}
_INC = {"description": "An incident wave.", "type": "string", "enum": list(INCIDENTS)}


# ----------------------------------------------------------------- the spec (config `beyond: trapping:`)


@declared(doc="The fraction of an incident wave's energy (a striker bead, a kicked travelling breather) that a "
              "chain at rest keeps in static breathers, homogeneous and with detuned strings (sigma, seeds), with "
              "and without damping, against amplitude and target length, under every listed detector setting "
              "(thresholds, windows, measurement times) -> results/trapping/trapping.nc and "
              "results/figures/trapping.{pdf,png}.")
class Trapping:
    incidents: list[str] = param(list(INCIDENTS), "Incident waves: striker (bead 0 given velocity a), breather "
                                 "(the bond-centred breather of largest |x| = a, kicked along its translation mode).",
                                 minItems=1, maxItems=2, items=_INC)
    striker: list[float] = param([0.1, 0.3, 1.0, 3.0], "Striker velocities a (energy a^2 / 2).", minItems=1,
                                 maxItems=8, items=_V,
                                 reduced=[0.3, 1.0])
    breather: list[float] = param([0.1, 0.3, 1.0], "Breather amplitudes a = max |x_n(0)|.", minItems=1, maxItems=8,
                                  items=_A,
                                  reduced=[0.3])
    scan_striker: float = param(1.0, "Striker velocity of the length and damping scans (one of `striker`).",
                                exclusiveMinimum=0, maximum=10)
    scan_breather: float = param(0.3, "Breather amplitude of the length and damping scans (one of `breather`).",
                                 exclusiveMinimum=0, maximum=3)
    kick: float = param(0.8, "Breather kick: v(0) = kick a e along the normalised translation mode e (0.8: a clean "
                        "travelling breather at ~0.17 beads per unit tau).", exclusiveMinimum=0, maximum=10)
    launch: int = param(10, "Beads of the striker's launch zone (homogeneous; the striker is bead 0) before the "
                        "target.", minimum=1, maximum=400)
    back: int = param(80, f"Beads behind the breather: its launch zone is `back` + {PROFILE} beads, its profile "
                      f"solved on the last {PROFILE} (centred {PROFILE // 2} beads before the target); the `back` "
                      "beads are an absorbing back end made of length (`reach_back` checks it).", minimum=1,
                      maximum=2000,
                      reduced=40)
    length: int = param(50, "Beads of the target: the main length (amplitude and damping scans).", minimum=4,
                        maximum=400,
                        reduced=20)
    lengths: list[int] = param([25, 100], "Other target lengths (the length scan, at the scan amplitudes).",
                               minItems=0, maxItems=4, items=_LEN,
                               reduced=[])
    lead: int = param(200, "Beads of the homogeneous lead after the target: long enough that nothing reaches its "
                      "end by tau_end (each run records `reach`).", minimum=10, maximum=2000,
                      reduced=100)
    edge: int = param(20, "Last beads of the lead whose energy is the `reach` check.", minimum=1, maximum=200)
    sigmas: list[float] = param([0.03, 0.1, 0.2], "Disorder strengths sigma: std of omega_n - 1 in the target "
                                "(normal law; sigma = 0 is always run).", minItems=0, maxItems=8, items=_SIGMA,
                                reduced=[0.1])
    seeds: int = param(6, "Seeds per disordered case: seed, seed + 1, ...", minimum=1, maximum=64,
                       reduced=2)
    seed: int = param(0, "First seed of the draws (numpy default_rng).", minimum=0, maximum=2**31 - 1)
    onsite: list[float] = param([1e-3], "On-site damping values gamma (each alone: eta = 0), (nc) units (the "
                                "steel cradle of the dissipation analysis: ~1e-5).",
                                minItems=0, maxItems=6, items=_GAMMA)
    contact: list[float] = param([0.01], "Kuwabara-Kono values eta (each alone: gamma = 0); the steel cradle of "
                                 "the dissipation analysis: ~1e-5.", minItems=0, maxItems=6,
                                 items=_ETA)
    damping_sigma: float = param(0.1, "sigma of the disordered damped runs (0: homogeneous only).", minimum=0,
                                 maximum=0.25)
    tau_end: float = param(600.0, "Length of every run in slow time tau = a^(alpha-1) t.", minimum=10, maximum=20000,
                           reduced=400.0)
    times: list[float] = param([400.0, 600.0], "Measurement times tau_m (<= tau_end).", minItems=1, maxItems=6,
                               items=_TAU,
                               reduced=[300.0, 400.0])
    windows: list[float] = param([30.0, 100.0], "Windows W (tau) of the detector: a breather moving at more than "
                                 "max_shift / W beads per unit tau is not static.", minItems=1, maxItems=6,
                                 items=_TAU)
    thresholds: list[float] = param([0.01, 0.001], "Thresholds theta: a core bead has window-mean energy above theta "
                                    "H(0).", minItems=1, maxItems=6, items=_THETA)
    radius: int = param(4, "Half-width r (beads) of a breather's region [p - r, p + r] around its peak p.",
                        minimum=1, maximum=50)
    contrast: float = param(0.25, "A peak is localised when the window-mean energy at both ends of its region is "
                            "below contrast times its own.", exclusiveMinimum=0, maximum=1)
    max_shift: float = param(2.0, "Largest motion (beads) of a static breather's energy centre over the window.",
                             exclusiveMinimum=0, maximum=20)
    sample_every: float = param(0.5, "Spacing of the samples the detector reads, in t (the period is 2 pi).",
                                exclusiveMinimum=0, maximum=2)
    rtol: float = param(1e-9, "Relative tolerance of the runs (dop853_numba; atol = rtol times the largest initial "
                        "|x| or |v|).", minimum=RTOL_FLOOR, maximum=1e-6)

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Each form: measurement times within the run and after their windows, scan amplitudes listed, the
        launch zone long enough for the kicked breather, no repeated value."""
        for i, tm in enumerate(self.times):
            if tm > self.tau_end:
                out.add(where + ["times", i], f"must be <= tau_end = {self.tau_end:g}", tm)
            if tm < max(self.windows):
                out.add(where + ["times", i], f"must be >= every window (largest: {max(self.windows):g})", tm)
        if "striker" in self.incidents and self.scan_striker not in self.striker:
            out.add(where + ["scan_striker"], f"must be one of striker = {self.striker}", self.scan_striker)
        if "breather" in self.incidents \
                and self.scan_breather not in self.breather:
            out.add(where + ["scan_breather"], f"must be one of breather = {self.breather}", self.scan_breather)
        if self.length in self.lengths:
            out.add(where + ["lengths"], f"lists the main length {self.length}", self.lengths)
        if self.edge > self.lead:
            out.add(where + ["edge"], f"must be <= lead = {self.lead}", self.edge)
        if "breather" in self.incidents and self.edge > self.back:
            out.add(where + ["edge"], f"must be <= back = {self.back} (the beads behind the breather)", self.edge)
        for key in ("incidents", "striker", "breather", "lengths", "sigmas", "onsite", "contact", "times", "windows",
                    "thresholds"):
            values = getattr(self, key)
            if len(set(values)) != len(values):
                out.add(where + [key], "lists a value twice", values)


# ----------------------------------------------------------------- one run


def bounds(spec: Trapping, kind: str, length: int) -> tuple[int, int, int, int]:
    """The zones' bead bounds for the incident ``kind``: launch [b0, b1), target [b1, b2), lead [b2, b3)."""
    b1 = spec.launch if kind == "striker" else spec.back + PROFILE
    return 0, b1, b1 + length, b1 + length + spec.lead


def omegas(spec: Trapping, kind: str, length: int, sigma: float, seed: int) -> np.ndarray:
    """omega_n of every bead: 1 in the launch zone and the lead, the seeded draw of
    :func:`cradle.models.inhomogeneity.sites` (sigma, seed) in the target. The draws of one seed are nested: a
    shorter target holds the first beads of a longer one."""
    from cradle.models.inhomogeneity import Inhomogeneity, sites

    b = bounds(spec, kind, length)
    w = np.ones(b[3])
    if sigma > 0.0:
        w[b[1]:b[2]] = sites(Inhomogeneity(sigma=sigma, seed=seed), length).omega
    return w


def incident(spec: Trapping, kind: str, a: float, n_beads: int) -> tuple[np.ndarray, np.ndarray]:
    """(x(0), v(0)) of the incident wave ``kind`` of amplitude ``a`` on a chain of ``n_beads`` (module docstring)."""
    x0, v0 = np.zeros(n_beads), np.zeros(n_beads)
    if kind == "striker":
        v0[0] = a
        return x0, v0
    from cradle.models import homoclinic_continuation, initial

    sol = homoclinic_continuation.solve_kind(PROFILE, "bond", ALPHA, "periodic")
    if not sol.converged:
        raise ValueError(f"trapping: bond homoclinic on {PROFILE} beads did not converge (residual {sol.residual:.3e})")
    profile = np.zeros(n_beads)
    profile[spec.back:spec.back + PROFILE] = np.asarray(sol.a)
    x0 = initial.breather(profile, ALPHA, amplitude=a, bc="free").x0
    stagger = (-1.0) ** np.arange(n_beads)
    e = stagger * np.gradient(stagger * x0)
    return x0, spec.kick * a * e / np.linalg.norm(e)


def time_scale(a: float) -> float:
    """t per unit slow time tau: a^(1-alpha)."""
    return a ** (1.0 - ALPHA)


def run_one(spec: Trapping, kind: str, a: float, length: int, sigma: float, seed: int, damping) -> dict:
    """One run and its measurements (module docstring): ``damping`` a Damping or None."""
    from cradle.integrators import integrate_lattice
    from cradle.measurements import trapping as m
    from cradle.models.inhomogeneity import Inhomogeneity
    from cradle.models.lattice_terms import Terms

    b = bounds(spec, kind, length)
    w = omegas(spec, kind, length, sigma, seed)
    terms = Terms(inhomogeneity=Inhomogeneity(omega=tuple(w.tolist()))) if sigma > 0.0 else None
    x0, v0 = incident(spec, kind, a, b[3])
    ts = time_scale(a)
    t_end = spec.tau_end * ts
    t = np.linspace(0.0, t_end, int(math.ceil(t_end / spec.sample_every)) + 1)
    sol = integrate_lattice(x0, v0, t, alpha=ALPHA, bc="free", method="dop853_numba", rtol=spec.rtol,
                            damping=damping, terms=terms)
    e = m.site_energies(sol.x, sol.v, ALPHA, omega=w)
    E0 = float(e[0].sum())
    T, W, H = len(spec.times), len(spec.windows), len(spec.thresholds)
    frac, frac_t, count = np.zeros((H, W, T)), np.zeros((H, W, T)), np.zeros((H, W, T), dtype=np.int64)
    zones = np.zeros((T, len(ZONES)))
    dissipated = np.zeros(T)
    for k, tm in enumerate(spec.times):
        i = int(np.searchsorted(t, tm * ts * (1 + 1e-12), side="right")) - 1
        zones[k] = m.zone_energies(e[i], b) / E0
        dissipated[k] = float(sol.dissipated[i]) / E0 if sol.dissipated is not None else 0.0
        for j, wd in enumerate(spec.windows):
            for h, th in enumerate(spec.thresholds):
                d = m.static_breathers(t, e, t[i], wd * ts, th * E0, radius=spec.radius, contrast=spec.contrast,
                                       max_shift=spec.max_shift)
                inside = (d.centre >= b[1]) & (d.centre < b[2])
                frac[h, j, k] = d.total / E0
                frac_t[h, j, k] = float(np.sum(d.energy[inside])) / E0
                count[h, j, k] = d.energy.size
    return {"fraction": frac, "fraction_target": frac_t, "count": count, "zone_energy": zones,
            "dissipated": dissipated, "reach": m.reach(e, spec.edge, E0), "energy0": E0,
            "reach_back": m.reach(e[:, ::-1], spec.edge, E0) if kind == "breather" else math.nan,
            "balance_drift": float(sol.energy_drift), "t": t, "e": e}


# ----------------------------------------------------------------- the runs of each batch


def _amplitudes(spec: Trapping, kind: str) -> list[float]:
    return [float(a) for a in (spec.striker if kind == "striker" else spec.breather)]


def _scan_amplitude(spec: Trapping, kind: str) -> float:
    return float(spec.scan_striker if kind == "striker" else spec.scan_breather)


def _disorder(spec: Trapping, sigmas) -> list[tuple[float, int]]:
    """(sigma, seed) pairs: the homogeneous chain once (seed -1), then every sigma at every seed."""
    return [(0.0, -1)] + [(float(s), spec.seed + k) for s in sigmas for k in range(spec.seeds)]


def dampings(spec: Trapping) -> list[tuple[float, float]]:
    """(gamma, eta) of every damping case: each on-site value alone, then each contact value alone."""
    return [(float(g), 0.0) for g in spec.onsite] + [(0.0, float(e)) for e in spec.contact]


def runs_of(spec: Trapping, kind: str, scan: str) -> list[tuple[float, int, float, int, float, float]]:
    """(a, length, sigma, seed, gamma, eta) of every run of one incident and scan (module docstring)."""
    if scan == "amplitude":
        return [(a, spec.length, s, sd, 0.0, 0.0) for a in _amplitudes(spec, kind)
                for s, sd in _disorder(spec, spec.sigmas)]
    a = _scan_amplitude(spec, kind)
    if scan == "length":
        return [(a, n, s, sd, 0.0, 0.0) for n in spec.lengths for s, sd in _disorder(spec, spec.sigmas)]
    sig = [spec.damping_sigma] if spec.damping_sigma > 0 else []
    return [(a, spec.length, s, sd, g, eta) for g, eta in dampings(spec) for s, sd in _disorder(spec, sig)]


def batch_keys(spec: Trapping) -> list[str]:
    """The batches of one form: ``<incident>-<scan>`` for every incident and every scan that has runs."""
    return [f"{kind}-{scan}" for kind in spec.incidents for scan in SCANS if runs_of(spec, kind, scan)]


#: samples in time of the stored space-time examples
EXAMPLE_SAMPLES = 200

_RUN = ("run",)
_HWT = ("run", "threshold", "window", "tau_m")
RUN_VARIABLES: dict[str, Var] = {
    "run": Var(_RUN, "index of a run"),
    "threshold": Var(("threshold",), "threshold theta of the detector (fraction of H(0))"),
    "window": Var(("window",), "window W of the detector, in slow time tau = a^(alpha-1) t"),
    "tau_m": Var(("tau_m",), "measurement time tau_m, in slow time tau = a^(alpha-1) t"),
    "zone": Var(("zone",), "zone of the chain: 0 launch, 1 target, 2 lead"),
    "incident": Var(_RUN, "incident wave: 0 striker, 1 breather"),
    "amplitude": Var(_RUN, "amplitude a: striker velocity, or the breather's largest |x_n(0)|"),
    "length": Var(_RUN, "beads of the target"),
    "sigma": Var(_RUN, "disorder strength: std of omega_n - 1 in the target"),
    "seed": Var(_RUN, "seed of the draw (-1: homogeneous)"),
    "gamma": Var(_RUN, "on-site damping gamma of (ncdamped)"),
    "eta": Var(_RUN, "Kuwabara-Kono eta of (ncdamped)"),
    "scan": Var(_RUN, "scan the run belongs to: 0 amplitude, 1 length, 2 damping"),
    "energy0": Var(_RUN, "energy H(0) of (ham) (generalised: omega_n) put in by the incident wave"),
    "fraction": Var(_HWT, "energy of the static breathers at tau_m over H(0), whole chain"),
    "fraction_target": Var(_HWT, "energy at tau_m of the static breathers centred in the target, over H(0)"),
    "count": Var(_HWT, "number of static breathers found at tau_m"),
    "zone_energy": Var(("run", "tau_m", "zone"), "energy of each zone at tau_m over H(0)"),
    "dissipated": Var(("run", "tau_m"), "energy D dissipated by tau_m over H(0) (damped runs)"),
    "reach": Var(_RUN, "largest energy of the last `edge` beads over the run, over H(0): 0 when nothing reached "
                 "the far end (so nothing came back)"),
    "reach_back": Var(_RUN, "breather runs: largest energy of the first `edge` beads (behind the launch) over the "
                      "run, over H(0): what reached the back end (NaN for the striker, which is bead 0)"),
    "balance_drift": Var(_RUN, "integrator's max |H + D - H(0)| / H(0)"),
    "wall_time": Var(_RUN, "wall time of the run", "s"),
}
EXAMPLE_VARIABLES: dict[str, Var] = {
    "example": Var(("example",), "index of a space-time example (the first run of each incident's amplitude scan "
                   "at the scan amplitude: homogeneous, then the largest sigma, first seed)"),
    "tau": Var(("tau",), "slow time tau = a^(alpha-1) t of the sample"),
    "bead": Var(("bead",), "bead index n"),
    "end": Var(("end",), "0: first bead of the target, 1: one past its last"),
    "example_incident": Var(("example",), "incident wave of the example: 0 striker, 1 breather"),
    "example_sigma": Var(("example",), "sigma of the example"),
    "example_amplitude": Var(("example",), "amplitude a of the example"),
    "example_target": Var(("example", "end"), "first and one past the last bead of the example's target"),
    "site_energy": Var(("example", "tau", "bead"), "energy e_n of each bead over H(0) (NaN beyond the chain)"),
}


def run_batch(spec: Trapping, key: str, inputs=None, log=None):
    """The batch ``key`` of :func:`batch_keys` (reads no file): a Dataset of its runs (:data:`RUN_VARIABLES`)
    and, for the amplitude scans, the space-time examples."""
    from cradle.data.io import make_dataset
    from cradle.models.damping import Damping

    if key not in batch_keys(spec):
        raise ValueError(f"trapping: no batch {key!r} in this form (batches: {', '.join(batch_keys(spec))})")
    say = log or (lambda *a: None)
    kind, scan = key.rsplit("-", 1)
    rows = runs_of(spec, kind, scan)
    out: dict[str, list] = {k: [] for k in ("fraction", "fraction_target", "count", "zone_energy", "dissipated",
                                           "reach", "reach_back", "energy0", "balance_drift", "wall_time")}
    examples: list[np.ndarray] = []
    ex_sigma: list[float] = []
    a_scan, s_max = _scan_amplitude(spec, kind), max(spec.sigmas, default=0.0)
    for a, n, s, sd, g, eta in rows:
        t0 = _time.perf_counter()
        damping = Damping(onsite=g, contact=eta) if (g > 0 or eta > 0) else None
        r = run_one(spec, kind, a, n, s, sd, damping)
        r["wall_time"] = _time.perf_counter() - t0
        for k in out:
            out[k].append(r[k])
        say(f"trapping: {kind} a = {a:g}, length {n}, sigma {s:g} seed {sd}, gamma {g:g}, eta {eta:g}: fraction "
            f"{r['fraction'][0, 0, -1]:.4f}, target {r['zone_energy'][-1, 1]:.3f}, lead {r['zone_energy'][-1, 2]:.3f}, "
            f"reach {r['reach']:.1e}, drift {r['balance_drift']:.1e} ({r['wall_time']:.1f} s)")
        if scan == "amplitude" and a == a_scan and n == spec.length and (sd == -1 or (s == s_max and
                                                                                      sd == spec.seed)):
            idx = np.linspace(0, len(r["t"]) - 1, EXAMPLE_SAMPLES).round().astype(int)
            examples.append(r["e"][idx] / r["energy0"])
            ex_sigma.append(s)
    cols = np.array(rows, dtype=float).reshape(-1, 6)
    data = {k: np.asarray(v) for k, v in out.items()}
    data.update({"incident": np.full(len(rows), INCIDENTS.index(kind)), "amplitude": cols[:, 0],
                 "length": cols[:, 1].astype(int), "sigma": cols[:, 2], "seed": cols[:, 3].astype(int),
                 "gamma": cols[:, 4], "eta": cols[:, 5], "scan": np.full(len(rows), SCANS.index(scan))})
    coords = {"run": np.arange(len(rows)), "threshold": np.asarray(spec.thresholds, float),
              "window": np.asarray(spec.windows, float), "tau_m": np.asarray(spec.times, float),
              "zone": np.arange(len(ZONES))}
    variables = dict(RUN_VARIABLES)
    if examples:
        width = max(x.shape[1] for x in examples)
        pad = np.full((len(examples), EXAMPLE_SAMPLES, width), np.nan)
        for i, x in enumerate(examples):
            pad[i, :, :x.shape[1]] = x
        b = bounds(spec, kind, spec.length)
        data.update({"site_energy": pad, "example_incident": np.full(len(examples), INCIDENTS.index(kind)),
                     "example_target": np.tile([b[1], b[2]], (len(examples), 1)),
                     "example_sigma": np.asarray(ex_sigma), "example_amplitude": np.full(len(examples), a_scan)})
        coords.update({"example": np.arange(len(examples)), "tau": np.linspace(0.0, spec.tau_end, EXAMPLE_SAMPLES),
                       "bead": np.arange(width), "end": np.arange(2)})
        variables.update(EXAMPLE_VARIABLES)
    return make_dataset(data, coords=coords, params=plain(spec), variables=variables,
                        attrs={"batch": key, "zones": ", ".join(ZONES)})


# ----------------------------------------------------------------- the stored file

_CASE = ("case",)
_CHWT = ("case", "threshold", "window", "tau_m")
SUMMARY_VARIABLES: dict[str, Var] = {
    "case": Var(_CASE, "index of a case: one incident, amplitude, length, sigma and damping, over its seeds"),
    "case_incident": Var(_CASE, "incident wave: 0 striker, 1 breather"),
    "case_amplitude": Var(_CASE, "amplitude a"),
    "case_length": Var(_CASE, "beads of the target"),
    "case_sigma": Var(_CASE, "disorder strength sigma"),
    "case_gamma": Var(_CASE, "on-site damping gamma"),
    "case_eta": Var(_CASE, "Kuwabara-Kono eta"),
    "n_seeds": Var(_CASE, "runs of the case (seeds; 1 when homogeneous)"),
    "fraction_mean": Var(_CHWT, "mean over the seeds of the static-breather fraction (whole chain)"),
    "fraction_std": Var(_CHWT, "standard deviation over the seeds (ddof 1; 0 for one run)"),
    "fraction_min": Var(_CHWT, "smallest over the seeds"),
    "fraction_max": Var(_CHWT, "largest over the seeds"),
    "target_mean": Var(_CHWT, "mean over the seeds of the fraction held by static breathers centred in the target"),
    "target_std": Var(_CHWT, "its standard deviation over the seeds (ddof 1; 0 for one run)"),
    "target_min": Var(_CHWT, "its smallest value over the seeds"),
    "target_max": Var(_CHWT, "its largest value over the seeds"),
    "target_trapping": Var(_CHWT, "fraction of the seeds whose static breathers in the target hold more than half "
                           "of H(0)"),
    "lead_mean": Var(("case", "tau_m"), "mean over the seeds of the lead's energy at tau_m over H(0) (transmitted)"),
}

_AXES = ("threshold", "window", "tau_m")
#: the stored variables: the detector's axes at the root, "/runs" every run, "/summary" per case over the seeds,
#: "/examples" the space-time examples
VARIABLES = {"/": {k: RUN_VARIABLES[k] for k in _AXES},
             "/runs": {k: v for k, v in RUN_VARIABLES.items() if k not in _AXES},
             "/summary": SUMMARY_VARIABLES, "/examples": EXAMPLE_VARIABLES}


def summary(runs: dict) -> dict:
    """The /summary group's data from the /runs arrays: one case per distinct (incident, amplitude, length,
    sigma, gamma, eta), in order of first appearance."""
    keys = np.stack([runs[k] for k in ("incident", "amplitude", "length", "sigma", "gamma", "eta")], axis=1)
    cases: list[list[int]] = []
    first: dict[tuple, int] = {}
    for i, row in enumerate(map(tuple, keys.tolist())):
        if row not in first:
            first[row] = len(cases)
            cases.append([])
        cases[first[row]].append(i)
    out: dict[str, list] = {k: [] for k in SUMMARY_VARIABLES if k != "case"}
    for rows in cases:
        f, ft = runs["fraction"][rows], runs["fraction_target"][rows]
        n = len(rows)
        for name, key in zip(("incident", "amplitude", "length", "sigma", "gamma", "eta"),
                             ("incident", "amplitude", "length", "sigma", "gamma", "eta"), strict=True):
            out[f"case_{name}"].append(runs[key][rows[0]])
        out["n_seeds"].append(n)
        out["fraction_mean"].append(f.mean(axis=0))
        out["fraction_std"].append(f.std(axis=0, ddof=1) if n > 1 else np.zeros(f.shape[1:]))
        out["fraction_min"].append(f.min(axis=0))
        out["fraction_max"].append(f.max(axis=0))
        out["target_mean"].append(ft.mean(axis=0))
        out["target_std"].append(ft.std(axis=0, ddof=1) if n > 1 else np.zeros(ft.shape[1:]))
        out["target_min"].append(ft.min(axis=0))
        out["target_max"].append(ft.max(axis=0))
        out["target_trapping"].append(np.mean(ft > 0.5, axis=0))
        out["lead_mean"].append(runs["zone_energy"][rows][:, :, 2].mean(axis=0))
    return {k: np.asarray(v) for k, v in out.items()}


def compute(spec: Trapping, inputs: dict, log=None):
    """The `trapping` file of one form from its batches (``inputs["batch/<key>"]``): /runs, /summary, /examples."""
    from cradle.data.io import make_tree

    parts = [inputs[f"batch/{key}"] for key in batch_keys(spec)]
    runs = {k: np.concatenate([np.asarray(p[k].values) for p in parts]) for k in RUN_VARIABLES
            if k not in ("run", "threshold", "window", "tau_m", "zone")}
    n_runs = len(runs["incident"])
    ex = [p for p in parts if "site_energy" in p]
    width = max((p.sizes["bead"] for p in ex), default=1)
    energy = np.full((sum(p.sizes["example"] for p in ex), EXAMPLE_SAMPLES, width), np.nan)
    row = 0
    for p in ex:
        k = p.sizes["example"]
        energy[row:row + k, :, :p.sizes["bead"]] = np.asarray(p["site_energy"].values)
        row += k
    examples = {"site_energy": energy,
                **{k: np.concatenate([np.asarray(p[k].values) for p in ex]) if ex else np.zeros(0)
                   for k in ("example_incident", "example_sigma", "example_amplitude")},
                "example_target": (np.concatenate([np.asarray(p["example_target"].values) for p in ex]) if ex
                                   else np.zeros((0, 2), dtype=int))}
    axes = {"threshold": np.asarray(spec.thresholds, float), "window": np.asarray(spec.windows, float),
            "tau_m": np.asarray(spec.times, float)}
    s = summary(runs)
    groups = {"/": ({}, axes),
              "/runs": (runs, {"run": np.arange(n_runs), "zone": np.arange(len(ZONES))}),
              "/summary": (s, {"case": np.arange(len(s["n_seeds"]))}),
              "/examples": (examples, {"example": np.arange(energy.shape[0]),
                                       "tau": np.linspace(0.0, spec.tau_end, EXAMPLE_SAMPLES),
                                       "bead": np.arange(width), "end": np.arange(2)})}
    attrs = {"incidents": ", ".join(INCIDENTS), "zones": ", ".join(ZONES), "scans": ", ".join(SCANS),
             "alpha": ALPHA, "n_runs": n_runs, "max_reach": float(np.max(runs["reach"])),
             "max_reach_back": float(np.nanmax(runs["reach_back"])) if np.isfinite(runs["reach_back"]).any()
             else math.nan,
             "max_balance_drift": float(np.max(runs["balance_drift"])),
             "run_wall_time_s_total": float(np.sum(runs["wall_time"])),
             "integrator": f"dop853_numba, rtol = {spec.rtol:g}, free ends",
             "time_unit": "slow time tau = a^(alpha-1) t, a the incident amplitude",
             "scan_striker": spec.scan_striker, "scan_breather": spec.scan_breather, "main_length": spec.length,
             "damping_sigma": spec.damping_sigma,
             "detector": f"peaks above theta H(0) in the window mean, regions of radius {spec.radius}, contrast "
                         f"{spec.contrast:g}, centre moving <= {spec.max_shift:g} beads over the window"}
    return make_tree(groups, VARIABLES, attrs=attrs, params=plain(spec),
                     title="Trapping of an incident wave's energy into static breathers (shock absorbers)")


ANALYSIS = Analysis(
    name="trapping", spec=Trapping, compute=compute, variables=VARIABLES,
    batches=Batches(keys=batch_keys, run=run_batch),
    title="Energy of an incident wave trapped into static breathers by a chain at rest, homogeneous and disordered, "
          "with and without damping")
