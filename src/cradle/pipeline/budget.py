"""What a job will cost, estimated from its parameters before it starts, and the budgets it must fit.

Every config entry that makes a job (``scenes``, ``homoclinic``, ``map``) gets an
:class:`Estimate` of its peak memory, the bytes it writes and its wall time, computed from the
validated config alone (no initial data, no stored-time array: a 10-million-time store or
``N: 1e9`` is judged in microseconds, before anything is allocated). :func:`check` compares
each estimate with the :class:`Budget` (config key ``budget:``) and raises one
:class:`~cradle.pipeline.config.ConfigError` line naming the entry's key, its value, the
estimate and the budget. It is called at the end of :func:`cradle.pipeline.config.validate`, so
the Snakefile and every ``cradle`` command refuse an over-budget config before any job starts.

How the numbers are obtained:

* **stored bytes**: a scene's simulate job writes, per stored time, ``x, v, force`` (exact),
  ``A_re, A_im, x, force`` (DpS) and the two spectra (metrics): :data:`STORED_ARRAYS` float64
  arrays of N values, plus a few scalars per time (energy, drifts, E, t, tau), plus
  :data:`FILE_BYTES` per file (headers and attributes; a homoclinic or map entry's job writes one, a scene's four);
* **peak memory**: the four Datasets of the job are held until all are written (all-or-nothing,
  :func:`cradle.pipeline.runner.run_chain`), plus the transient arrays of the metrics stage
  (complex FFT of x and its selection): :data:`PEAK_ARRAYS` arrays of N x T float64, plus
  :data:`STATE_ARRAYS` arrays of N for the states and work arrays. Checked against peak RSS by
  ``benchmarks/streamed_store.py`` (large stores, docs/extremes.md) and ``benchmarks/estimates.py``
  (every job of config.yaml, docs/performance.md);
* **time**: steps x N x :data:`COST_PER_BEAD_STEP_S` of the exact run's method, with steps =
  t_end x :data:`STEPS_PER_TIME_UNIT` (the method's default step, or tolerance, on a typical
  travelling wave; a stronger compression takes smaller steps, up to omega_max(c) / omega_max of
  that wave more) and at least one step per stored time, plus a cost per stored value
  (:data:`COST_PER_STORED_VALUE_S`: DpS run, ansatz, metrics, writing) and the job's start-up
  (:data:`BASE_SECONDS`, which every job pays, a homoclinic or map entry's too), plus the DpS run's
  own steps (:data:`DPS_STEPS_PER_PERIOD` per period of its fastest oscillation, :func:`dps_periods`:
  a few thousand for the paper's scenes, hours at a desk toy's displacement in (nc)'s units). The
  per-step constants were measured on this machine by ``benchmarks/bead_step_cost.py`` (fft106
  initial data, N = 200, t = 100, best of three after a warm-up), the others from single jobs as
  each constant says; rerun them on another machine and update them here.

A large store is streamed, not refused: when a scene's in-memory peak would exceed
:data:`STREAM_ABOVE_BYTES` (and its methods can be continued block by block: a fixed-step
splitting for (nc), DOP853 in numba for DpS), :func:`streams` says so and the job runs block by
block (:mod:`cradle.scenes.streamed`), holding :data:`STREAMED_BLOCK_BYTES` of block plus
:data:`STREAMED_BYTES_PER_TIME` per stored time, whatever N x T. Such a scene is then judged on
disk and time; a store that cannot stream (an adaptive method for (nc)) is judged on its
in-memory peak as before.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, fields
from typing import TYPE_CHECKING, Any, Protocol

from cradle.models.lattice import DEFAULT_DT_FACTOR, default_dt, omega_max
from cradle.scenes.spec import SPLITTINGS, ExactIntegrator, HomoclinicEntry, MapEntry, Scene, Store
from cradle.specs.declare import declared, param

if TYPE_CHECKING:
    from cradle.models.damping import Damping



class Config(Protocol):
    """What the estimates read of a typed config (:class:`cradle.pipeline.config.sections.Config`, whose module
    imports this one): its entries, the sections of ``beyond:`` (by module name) and its budget."""

    @property
    def scenes(self) -> Mapping[str, Scene]: ...
    @property
    def homoclinic(self) -> Mapping[str, HomoclinicEntry]: ...
    @property
    def map(self) -> Mapping[str, MapEntry]: ...
    @property
    def beyond(self) -> Any: ...   # a class made at import, one attribute per analysis
    @property
    def budget(self) -> Budget: ...


#: float64 arrays of N values written per stored time by a scene's job (exact x, v, force; DpS
#: A_re, A_im, x, force; metrics spectrum_exact, spectrum_dps)
STORED_ARRAYS = 9
#: scalars written per stored time (t, tau, energy, l2_drift, dps_energy_drift, P_drift, E)
STORED_SCALARS = 7
#: N x T float64 arrays held at the peak of a scene's job: the stored ones plus the metrics
#: stage's complex FFT of x and its selection
PEAK_ARRAYS = 13
#: arrays of N float64 held whatever the store (initial data, states, integrator work arrays)
STATE_ARRAYS = 32
#: bytes of a process before any array (interpreter, numpy, xarray, numba, netCDF4): the max RSS
#: of tw-weak's simulate job (results/benchmarks/sim/tw-weak.tsv), whose arrays are a few MB
BASE_BYTES = 250e6
#: wall seconds of a job before its first step (interpreter, imports, compiled-kernel cache loads):
#: tw-weak's simulate job, 5.8 s wall for 0.1 s of integration
BASE_SECONDS = 5.0
#: wall seconds per stored value (stored time x bead) beyond the exact run's steps: the DpS run
#: stepping to every stored time, the ansatz, forces, metrics and writing the four files with their
#: checksums. Measured with `cradle run fft106` stored every 0.01 (54373 times x 200 beads): 27.6 s
#: for the job, of which 0.35 s were exact steps
COST_PER_STORED_VALUE_S = 2.5e-6
#: wall seconds per (step x bead) and steps per unit of simulated time at the default step or
#: tolerance (rtol = 1e-10), measured by benchmarks/bead_step_cost.py on this machine (2 cores):
#: fft106's initial data, N = 200, best of three after a warm-up. lsoda and radau were not
#: measured and take scipy dop853's values.
COST_PER_BEAD_STEP_S = {"srkn6c": 3.2e-8, "srkn4c": 1.4e-8, "srkn6": 1.8e-8, "srkn4": 1.1e-8, "strang": 4.5e-9,
                        "dop853_numba": 1.4e-7, "dop853": 1.7e-6, "rk45": 6.2e-7, "lsoda": 1.7e-6, "radau": 1.7e-6}
STEPS_PER_TIME_UNIT = {"srkn6c": 23.3, "srkn4c": 58.2, "srkn6": 466.0, "srkn4": 931.0, "strang": 7760.0,
                       "dop853_numba": 14.7, "dop853": 14.6, "rk45": 31.6, "lsoda": 14.6, "radau": 14.6}
#: a scene's job streams (:mod:`cradle.scenes.streamed`) when its in-memory peak estimate exceeds this
STREAM_ABOVE_BYTES = 2e9
#: peak memory of a streamed job beyond BASE_BYTES: its blocks (cradle.data.appending
#: DEFAULT_CHUNK_BYTES of stored values, times the copies a block goes through: both runs' Datasets,
#: the metrics' FFTs, the HDF5 chunk caches) -- measured by benchmarks/streamed_store.py
STREAMED_BLOCK_BYTES = 0.5e9
#: bytes held per stored time by a streamed job (the stored and slow times, the E(t) maxima, the
#: breather's site signal of both models)
STREAMED_BYTES_PER_TIME = 48
#: bytes of a netCDF file beyond its values (HDF5 headers and chunk indexes, the attributes: parameters,
#: provenance, checksums): 22 to 51 kB, 34 kB on average, over the files of `cradle run tw-weak` (initial, exact,
#: dps, metrics) and `cradle run site` (homoclinic) in this build
FILE_BYTES = 35e3
#: netCDF files a scene's job writes (initial data, exact and DpS runs, metrics)
SCENE_FILES = 4
#: runs estimated to take longer than this print their estimate and an ETA while they run
LONG_RUN_S = 60.0

GB = 1e9



@declared(doc="Limits every job must fit, checked on estimates before any work starts (cradle.pipeline.budget); "
              "raise them on a bigger machine.")
class Budget:
    """Limits every job must fit (config key ``budget:``); the defaults fit a 2-core, 24 GB machine
    running two jobs side by side."""

    # each at most what no machine this runs on exceeds: a larger budget would turn its check off
    memory_gb: float = param(8.0, "Peak memory one job may use (GB), at most 1e4; two jobs run side by side on two "
                             "cores.", exclusiveMinimum=0, maximum=1e4)
    disk_gb: float = param(20.0, "Bytes one job may write, and all scenes together (GB), at most 1e5.",
                           exclusiveMinimum=0, maximum=1e5)
    hours: float = param(12.0, "Wall time one job may take (hours), at most 1e4 (a year), estimated from its steps "
                         "and beads.", exclusiveMinimum=0, maximum=1e4)

    @classmethod
    def from_config(cls, cfg: Any) -> Budget:  # a typed Config, its plain mapping, or None: told apart by duck typing
        """The budget of a validated config (typed, or its plain values): its ``budget:`` values over the
        defaults."""
        if isinstance(getattr(cfg, "budget", None), Budget):
            return cfg.budget
        given = (cfg or {}).get("budget") or {}
        return cls(**{f.name: float(given[f.name]) for f in fields(cls) if given.get(f.name) is not None})


@dataclass(frozen=True)
class Estimate:
    """What one job will cost: peak memory and output bytes, wall seconds, and what drives them."""

    key: str          # the config entry, e.g. scenes.fft106
    cause: str        # its values that drive the cost, e.g. "N = 200, t_end = 543.7, store.every = 0.001"
    memory_bytes: float
    disk_bytes: float
    seconds: float
    steps: float = 0.0
    streamed: bool = False  # a scene's job that runs block by block (cradle.scenes.streamed)

    def describe(self) -> str:
        """One line: memory, disk, time."""
        return (f"{self.key}: estimated peak memory {fmt_bytes(self.memory_bytes)}, "
                f"writes {fmt_bytes(self.disk_bytes)}, about {fmt_duration(self.seconds)} ({self.cause})")


def fmt_bytes(b: float) -> str:
    for unit, size in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if b >= size:
            return f"{b / size:.3g} {unit}"
    return f"{b:.0f} B"


def fmt_duration(s: float) -> str:
    for unit, size in (("years", 365.25 * 86400), ("days", 86400), ("h", 3600), ("min", 60)):
        if s >= size:
            return f"{s / size:.3g} {unit}"
    return f"{s:.2g} s"


def _g(x: float) -> str:
    return f"{float(x):g}"


def _count(n: float) -> str:
    """A count as a message writes it: exact up to a million, else three digits (1e+300, not 301 of them)."""
    return str(int(n)) if n < 1e6 else f"{float(n):.3g}"


def stored_count(store: Store, t_end: float) -> int:
    """Upper bound on the number of stored times (0, t_end, the snapshots and the grid), without
    building the time array."""
    n = len(store.snapshots or ()) + 2
    if store.every:
        k = t_end / store.every * (1.0 + 1e-12) + 1e-9
        n += int(math.floor(min(k, 1e18))) + 1   # t_end / every may overflow to inf
    return n


#: how far DOP853's region of absolute stability reaches along the negative real axis (|h lambda| <= ~6): an
#: explicit step resolves a decay rate lambda only with h <= this / lambda
DOP853_STABLE = 6.0


def damping_rate(damping: Damping | None, amplitude: float, alpha: float = 1.5) -> float:
    """The fastest decay rate (nc)'s damping imposes on a run of displacement ``amplitude``: gamma of the on-site
    term, and 2 eta c^(alpha - 1) of a bond's relative velocity under the Kuwabara-Kono term at a compression c
    of the amplitude (reduced mass 1/2); 0 without damping."""
    if damping is None or not damping.active:
        return 0.0
    try:
        return min(damping.onsite + 2.0 * damping.contact * min(abs(amplitude), 1e300) ** (alpha - 1.0), 1e300)
    except OverflowError:   # c^(alpha-1) beyond float64 (a large alpha): the fastest rate the estimate says
        return 1e300


#: the linearised frequency omega_max (cradle.models.lattice) above which a splitting's default step, not the
#: measured STEPS_PER_TIME_UNIT (a wave of omega_max ~ 1.5), sets an estimate's steps
STIFF_OMEGA = 10.0


def _exact_seconds(N: int, t_end: float, exact: ExactIntegrator, stored: int,
                   rate: float = 0.0, amplitude: float = 0.0, alpha: float = 1.5) -> tuple[float, float]:
    """(wall seconds, steps) of the exact run at the measured steps per unit time of its method,
    scaled by the ratio of step factors when a splitting's ``dt_factor`` is given; every interval
    between stored times takes at least one step (the steps end on the stored times), a damping
    ``rate`` (:func:`damping_rate`) takes at least t_end rate / :data:`DOP853_STABLE` steps, and a splitting
    at least t_end / dt steps of its default step dt = dt_factor 2 pi / omega_max(c) at a compression c = 2
    ``amplitude`` (:func:`cradle.models.lattice.default_dt`; a large amplitude takes small steps)."""
    method = exact.method
    steps = t_end * STEPS_PER_TIME_UNIT.get(method, max(STEPS_PER_TIME_UNIT.values()))
    c = min(2.0 * abs(amplitude), 1e300)
    stiff = method in SPLITTINGS and omega_max(c, alpha) > STIFF_OMEGA
    if exact.dt_factor:
        steps *= DEFAULT_DT_FACTOR.get(method, exact.dt_factor) / exact.dt_factor
    if stiff:
        dt = default_dt(c, alpha, method, exact.dt_factor)
        steps = max(steps, t_end / dt if dt > 0.0 else math.inf)
    steps = max(steps, float(stored - 1), min(t_end * rate / DOP853_STABLE, 1e300))
    return steps * N * COST_PER_BEAD_STEP_S.get(method, max(COST_PER_BEAD_STEP_S.values())), steps


#: steps of DOP853 (rtol 1e-10) per period of the fastest DpS oscillation (:func:`dps_periods`): 5-15 measured on
#: a packet, a plane wave and random data of 32 sites at alpha 1.5 and 2.5; the largest is taken
DPS_STEPS_PER_PERIOD = 15.0


def dps_periods(spec: Scene) -> float:
    """Periods of the fastest oscillation of a scene's DpS run over [0, t_end] (lattice time): its frequency is
    about (2 / tau0) (2 a)^(alpha - 1) at the displacement a of the initial data (the p-Laplacian of differences
    up to 2 a; (freq) for a wave given by its frequency, whose a follows from it), so DpS runs a^(alpha - 1)
    times faster at a larger a, and a run at a desk toy's displacement in (nc)'s units takes hours."""
    from cradle.models import dps

    ini, alpha = spec.initial, spec.alpha
    a = abs(_amplitude(ini)) or abs(getattr(ini, "velocity", 0.0) or 0.0)   # a kick: a displacement of its size
    try:   # the fastest plane wave of (ds), q = pi, at |A| = a
        rate = dps.plane_wave_frequency(a, math.pi, alpha) if a else 0.0
    except OverflowError:
        rate = math.inf
    omega = getattr(ini, "omega_tw", None) or getattr(ini, "omega_sw", None)
    if omega is not None:   # a wave or breather given by its frequency: its shift omega - 1 is the DpS one
        rate = max(rate, 2.0 ** (alpha + 1.0) * (omega - 1.0))
    return min(spec.t_end * rate / (2.0 * math.pi), 1e300)


def scene_estimate(cfg: Config, name: str) -> Estimate:
    """The cost of scene ``name``'s simulate job (initial data, exact and DpS runs, metrics) in a typed
    config (:func:`cradle.pipeline.config.typed`)."""
    return spec_estimate(cfg.scenes[name], name)


def spec_estimate(spec: Scene, name: str = "?") -> Estimate:
    """The cost of the job of scene ``name`` from its resolved spec (:func:`cradle.pipeline.config.scene`):
    N, t_end, store and the exact integrator."""
    N, t_end, store = spec.N, spec.t_end, spec.store
    T = stored_count(store, t_end)
    rate = damping_rate(spec.damping, _amplitude(spec.initial), spec.alpha)
    seconds, steps = _exact_seconds(N, t_end, spec.exact, T, rate, _amplitude(spec.initial), spec.alpha)
    seconds += BASE_SECONDS + COST_PER_STORED_VALUE_S * N * T
    dps_steps = DPS_STEPS_PER_PERIOD * dps_periods(spec)
    seconds += dps_steps * N * COST_PER_BEAD_STEP_S.get(spec.dps.method, max(COST_PER_BEAD_STEP_S.values()))
    per_time = 8.0 * (STORED_ARRAYS * N + STORED_SCALARS)
    cause = f"N = {N}, t_end = {_g(t_end)}" + (f", store.every = {_g(store.every)}" if store.every else "")
    cause += f": {_count(T)} stored times"
    if steps:
        cause += f", ~{steps:.3g} steps of {spec.exact.method}"
    if dps_steps > max(steps, float(T)):   # said where the DpS run, not the lattice's, sets the time
        cause += f", ~{dps_steps:.3g} steps of DpS ({spec.dps.method}; its pace grows as amplitude^(alpha-1))"
    if rate * t_end > DOP853_STABLE * T:
        cause += f" (a damping rate {_g(rate)} to resolve)"
    memory = BASE_BYTES + 8.0 * (PEAK_ARRAYS * N * T + STATE_ARRAYS * N)
    streamed = memory > STREAM_ABOVE_BYTES and streamable(spec)
    if streamed:
        memory = BASE_BYTES + STREAMED_BLOCK_BYTES + STREAMED_BYTES_PER_TIME * T + 8.0 * STATE_ARRAYS * N
        cause += ", streamed block by block"
    return Estimate(f"scenes.{name}", cause, memory_bytes=memory,
                    disk_bytes=per_time * T + 8.0 * 6 * N + SCENE_FILES * FILE_BYTES, seconds=seconds, steps=steps,
                    streamed=streamed)


def _amplitude(initial: object) -> float:  # a scene's initial data, of any kind
    """The displacement a scene's initial data reach, as far as its parameters say (0 when they do not say it
    directly: a breather or wave given by its frequency, a kick)."""
    for key in ("a", "amplitude"):
        value = getattr(initial, key, None)
        if isinstance(value, (int, float)):
            return float(value)
    return 0.0


def desk_toy_estimate(cfg: Config, form: str) -> Estimate:
    """The job of one form of ``beyond.desk-toy``: a (nc) run of every chain length and lifted count over
    ``swings`` periods 2 pi at the desk toy's amplitude (its damping resolved: :func:`damping_rate`), stored
    ``samples`` times per period."""
    from cradle.analyses.desk_toy import DEFAULT_CRADLE
    from cradle.analyses.protocol import REDUCED, form_spec
    from cradle.models.physical import release_amplitude

    spec = form_spec(cfg.beyond.desk_toy, form)
    N, t_end = max(spec.chains), 2.0 * math.pi * spec.swings
    rate = damping_rate(spec.damping, release_amplitude(spec.cradle or DEFAULT_CRADLE, spec.angle_deg))
    T = spec.swings * spec.samples + 1
    runs = len(spec.chains) * len(spec.lifted)
    one, steps = _exact_seconds(N, t_end, ExactIntegrator(method="dop853_numba"), T, rate)
    return Estimate("beyond.desk-toy" + (".reduced" if form == REDUCED else ""),
                    f"{runs} runs of N <= {N} over {spec.swings} swings" + (f", damping rate {_g(rate)}: ~{steps:.3g} "
                                                                            f"steps each" if rate else ""),
                    memory_bytes=BASE_BYTES + 8.0 * (4 * N * T + STATE_ARRAYS * N), disk_bytes=8.0 * 4 * N * T * runs,
                    seconds=BASE_SECONDS + runs * one, steps=runs * steps)


def streamable(spec: Scene) -> bool:
    """Whether a scene's runs can be computed block by block (:mod:`cradle.scenes.streamed`): a
    fixed-step splitting for (nc) and DOP853 in numba for DpS (both continue bitwise)."""
    return spec.exact.method in SPLITTINGS and spec.dps.method == "dop853_numba"


def streams(spec: Scene) -> bool:
    """Whether scene ``spec``'s job runs block by block: streamable, and its in-memory peak estimate
    above :data:`STREAM_ABOVE_BYTES`."""
    return spec_estimate(spec).streamed


def long_run(spec: Scene, name: str = "?") -> Estimate | None:
    """The estimate of scene ``name``'s job if it is long enough (:data:`LONG_RUN_S`) to announce, else None."""
    e = spec_estimate(spec, name)
    return e if e.seconds >= LONG_RUN_S else None


def homoclinic_estimate(cfg: Config, name: str) -> Estimate:
    """Powell's hybrid method holds a dense N x N Jacobian (and its QR factors): a few N^2 floats; one file."""
    N = cfg.homoclinic[name].N
    return Estimate(f"homoclinic.{name}", f"N = {N}: dense N x N Jacobian",
                    memory_bytes=BASE_BYTES + 8.0 * 4 * N * N, disk_bytes=8.0 * 4 * N + FILE_BYTES,
                    seconds=BASE_SECONDS + 1e-9 * N**3 * 50)


def map_estimate(cfg: Config, name: str) -> Estimate:
    """Orbits x iterations points of the map G, two floats each; one file."""
    m = cfg.map[name]
    orbits = len(m.starts or ()) + (m.line.count if m.line is not None else 0)
    points = float(orbits) * (m.iterations + 1)
    return Estimate(f"map.{name}", f"{orbits} orbits x iterations = {_count(m.iterations)}",
                    memory_bytes=BASE_BYTES + 8.0 * 4 * points, disk_bytes=8.0 * 2 * points + FILE_BYTES,
                    seconds=BASE_SECONDS + points * 1e-6)


def mi_statistics_estimate(cfg: Config, form: str) -> Estimate:
    """The largest batch job of one form of ``beyond.mi-statistics`` (the full one at the top of the section,
    ``reduced``): ceil(q values / chunks) x seeds runs of the largest N to t_end, at the scenes' measured
    cost per bead-step of the exact method (a DpS batch costs less: 5.4 s against 7.9 s for the reduced
    form's batches), the spectra sampled every ``sample_every`` held per run."""
    from cradle.analyses.protocol import REDUCED, form_spec

    spec = form_spec(cfg.beyond.mi_statistics, form)
    N, t_end = max(spec.N), spec.t_end
    runs = math.ceil(spec.q_over_pi.count / spec.chunks) * spec.n_seeds
    exact = ExactIntegrator(method=spec.exact.method, dt_factor=spec.exact.dt_factor)
    one, steps = _exact_seconds(N, t_end, exact, 2)
    samples = t_end / spec.sample_every + 1
    return Estimate("beyond.mi-statistics" + (".reduced" if form == REDUCED else ""),
                    f"{runs} runs per batch (q values / chunks x n_seeds), N = {N}, t_end = {_g(t_end)}",
                    memory_bytes=BASE_BYTES + 8.0 * (STATE_ARRAYS * N + 2 * N * samples),
                    disk_bytes=8.0 * 8 * runs * samples, seconds=BASE_SECONDS + runs * one, steps=runs * steps)


def work_precision_estimate(cfg: Config, form: str) -> Estimate:
    """The largest batch job of one form of ``beyond.work-precision``: for one scene (its N from ``scenes:``),
    the two reference runs and every setting of every method's ladder to the scene's t_end, each at the
    measured cost per bead-step of its method (a step factor scales its steps; a tolerance is costed at the
    default one), the states on the comparison grid held for the two references and the run measured."""
    from cradle.analyses.protocol import REDUCED, form_spec
    from cradle.analyses.work_precision import ladder

    spec = form_spec(cfg.beyond.work_precision, form)
    scenes = cfg.scenes
    ref = spec.reference
    runs = [(ref.method, ref.dt_factor), (ref.method, 2.0 * ref.dt_factor)]
    for method in spec.methods:
        key, values = ladder(spec, method)
        runs += [(method, v if key == "dt_factor" else None) for v in values]
    worst = None
    for name, measured in spec.scenes.items():
        if name not in scenes:
            continue   # an unknown scene: the checks name it
        N, t_end = scenes[name].N, measured.t_end
        T = stored_count(Store(every=spec.compare_every), t_end)
        seconds = steps = 0.0
        for method, dt_factor in runs:
            exact = ExactIntegrator(method=method, dt_factor=dt_factor)
            one, n = _exact_seconds(N, t_end, exact, T)
            seconds, steps = seconds + one, steps + n
        e = Estimate("beyond.work-precision" + (".reduced" if form == REDUCED else ""),
                     f"scene {name}: N = {N}, t_end = {_g(t_end)}, {len(runs)} runs, {_count(T)} comparison times",
                     memory_bytes=BASE_BYTES + 8.0 * (3 * 2 * N * T + STATE_ARRAYS * N),
                     disk_bytes=8.0 * (T + 12 * len(runs)), seconds=BASE_SECONDS + seconds, steps=steps)
        if worst is None or e.seconds > worst.seconds:
            worst = e
    if worst is None:
        raise NothingToEstimate("no scene to measure")   # every scene unknown: the checks name them
    return worst


def sampled_estimate(key: str, N: int, t_end: float, every: float, runs: int, arrays: int) -> Estimate:
    """The cost of an analysis's job of ``runs`` dop853_numba runs on N beads to ``t_end``, each sampled every
    ``every`` (``arrays`` float64 arrays of N values held per sample while a run is measured): the samples go
    through the same count as a scene's stored times (:func:`stored_count`)."""
    T = stored_count(Store(every=every), t_end)
    one, steps = _exact_seconds(N, t_end, ExactIntegrator(method="dop853_numba"), T)
    return Estimate(key, f"{runs} runs of N = {N}, t_end = {_g(t_end)}, sample_every = {_g(every)}: {_count(T)} "
                         f"samples each",
                    memory_bytes=BASE_BYTES + 8.0 * (arrays * N * T + STATE_ARRAYS * N),
                    disk_bytes=8.0 * 8 * runs * min(T, 1e4),   # the measures written, not the samples
                    seconds=BASE_SECONDS + runs * (one + COST_PER_STORED_VALUE_S * N * T), steps=runs * steps)


def dissipation_estimate(cfg: Config, form: str) -> Estimate:
    """The job of one form of ``beyond.dissipation``: each family (a breather, each wave) under each damping
    value, lattice and DpS runs sampled every ``sample_every`` (x, v, A and the site energies held)."""
    from cradle.analyses.protocol import REDUCED, form_spec

    spec = form_spec(cfg.beyond.dissipation, form)
    runs = 2 * (1 + len(spec.waves)) * (len(spec.onsite) + len(spec.contact))
    return sampled_estimate("beyond.dissipation" + (".reduced" if form == REDUCED else ""), spec.N, spec.t_end,
                            spec.sample_every, runs, arrays=6)


def trapping_estimate(cfg: Config, form: str) -> Estimate:
    """The largest batch job of one form of ``beyond.trapping``: the longest chain (launch zone, longest target,
    lead) run to tau_end in t at the slowest incident's time scale, sampled every ``sample_every`` (x, v and the
    site energies held), as many runs as seeds per disordered case."""
    from cradle.analyses.protocol import REDUCED, form_spec
    from cradle.analyses.trapping import PROFILE, time_scale

    spec = form_spec(cfg.beyond.trapping, form)
    N = max(spec.launch, spec.back + PROFILE) + max([spec.length, *spec.lengths]) + spec.lead
    t_end = spec.tau_end * max(time_scale(a) for a in [*spec.striker, *spec.breather])
    return sampled_estimate("beyond.trapping" + (".reduced" if form == REDUCED else ""), N, t_end,
                            spec.sample_every, spec.seeds, arrays=3)


def extend_estimate(key: str, N: int, method: str, dt: float, t_from: float, t_end: float, added: int,
                    kept: int) -> Estimate:
    """The cost of ``cradle extend`` (:func:`cradle.pipeline.extend.extend`): ``added`` stored times from
    ``t_from`` to ``t_end`` at the file's step ``dt`` of splitting ``method`` on N beads, streamed block
    by block, and the ``kept`` stored times of the file copied first (``key``: the file)."""
    steps = max((t_end - t_from) / dt, float(added))
    per_time = 8.0 * (3 * N + 2)   # x, v, force, energy and t
    per_bead_step = COST_PER_BEAD_STEP_S.get(method, max(COST_PER_BEAD_STEP_S.values()))
    return Estimate(key, f"N = {N}, t = {_g(t_from)} -> {_g(t_end)}: {_count(added)} stored times added, "
                         f"~{steps:.3g} steps of {method} (dt = {_g(dt)})",
                    memory_bytes=BASE_BYTES + STREAMED_BLOCK_BYTES + STREAMED_BYTES_PER_TIME * (added + kept)
                    + 8.0 * STATE_ARRAYS * N,
                    disk_bytes=per_time * (added + kept) + FILE_BYTES,
                    seconds=BASE_SECONDS + steps * N * per_bead_step + COST_PER_STORED_VALUE_S * N * added,
                    steps=steps, streamed=True)


#: each limit of a :class:`Budget`: (what it bounds, its key, the estimate's amount, the limit in that unit)
_LIMITS: tuple[tuple[str, str, Callable[[Estimate], float], Callable[[Budget], float]], ...] = (
    ("peak memory", "memory_gb", lambda e: e.memory_bytes, lambda b: b.memory_gb * GB),
    ("output", "disk_gb", lambda e: e.disk_bytes, lambda b: b.disk_gb * GB),
    ("run time", "hours", lambda e: e.seconds, lambda b: b.hours * 3600.0))


def _shown(key: str, amount: float) -> str:
    return fmt_duration(amount) if key == "hours" else fmt_bytes(amount)


def exceeds(e: Estimate, budget: Budget, skip: frozenset[str] = frozenset()) -> str | None:
    """The line saying how estimate ``e`` exceeds ``budget`` (memory, then output, then time; a limit named in
    ``skip`` left out), or None."""
    for what, key, amount, limit in _LIMITS:
        if key not in skip and amount(e) > limit(budget):
            return (f"{e.key}: {e.cause}: estimated {what} {_shown(key, amount(e))} exceeds budget.{key} = "
                    f"{_g(getattr(budget, key))}")
    return None


def below_every_job(jobs: list[Estimate], budget: Budget) -> dict[str, str]:
    """Budget key -> its line, for each limit of ``budget`` that every one of ``jobs`` exceeds: the budget is the
    value to change (a config's jobs include every analysis at its defaults, so one oversized entry never makes
    this so)."""
    out = {}
    for what, key, amount, limit in _LIMITS:
        if jobs and all(amount(e) > limit(budget) for e in jobs):
            least = min(jobs, key=amount)
            out[key] = (f"budget.{key} = {_g(getattr(budget, key))}: below the estimated {what} of every job (the "
                        f"least, {least.key}: {_shown(key, amount(least))}); raise it to what this machine allows")
    return out


class NothingToEstimate(LookupError):
    """A job with nothing to estimate (an analysis whose every scene is unknown, which the checks name)."""


#: what a job whose estimate fails is told: it is refused, not run unbudgeted
UNESTIMATED_HINT = "refused rather than run without a budget; change the entry's values"


def estimates(cfg: Config) -> list[Estimate]:
    """An :class:`Estimate` for every job of a typed config that can be estimated (:func:`estimated`)."""
    return estimated(cfg)[0]


def _failed(key: str, err: BaseException) -> str:
    """The line of a job whose estimate raised ``err``: its key, the error and why it is refused."""
    why = " ".join(str(err).split()) or "no message"
    return f"{key}: its cost cannot be estimated ({type(err).__name__}: {why}): {UNESTIMATED_HINT}"


def estimated(cfg: Config) -> tuple[list[Estimate], dict[str, str]]:
    """An :class:`Estimate` for every scene, homoclinic and map entry of a typed config
    (:func:`cradle.pipeline.config.typed`), and for the largest batch job of each form of
    ``beyond.mi-statistics``, ``beyond.work-precision``, ``beyond.dissipation``, ``beyond.trapping`` and
    ``beyond.desk-toy``; and, key -> line (:func:`_failed`), each job whose estimate failed: such a job is refused
    (:func:`cradle.pipeline.config.typed` says the line when nothing else is wrong), never run unbudgeted."""
    out, failed = [], {}
    per_entry = (("scenes", scene_estimate), ("homoclinic", homoclinic_estimate), ("map", map_estimate))
    # (the key a failure is said at, the name the estimate takes, the estimate)
    jobs: list[tuple[str, str, Callable[[Any, str], Estimate]]] = [
        (f"{section}.{name}", name, fn) for section, fn in per_entry for name in getattr(cfg, section)]
    def beyond(analysis: str, form: str, fn: Callable[[Any, str], Estimate]) -> tuple:
        return f"beyond.{analysis}" + (".reduced" if form == "reduced" else ""), form, fn

    jobs += [beyond("mi-statistics", form, mi_statistics_estimate) for form in ("reduced", "full")]
    jobs += [beyond(analysis, form, fn) for form in ("reduced", "full")
             for analysis, fn in (("dissipation", dissipation_estimate), ("trapping", trapping_estimate),
                                  ("desk-toy", desk_toy_estimate))]
    if cfg.beyond.work_precision.scenes:
        jobs += [beyond("work-precision", form, work_precision_estimate) for form in ("reduced", "full")]
    for key, name, fn in jobs:
        try:
            out.append(fn(cfg, name))
        except NothingToEstimate:
            continue
        except (TypeError, ValueError, KeyError, AttributeError, ArithmeticError) as err:
            failed[key] = _failed(key, err)
    return out, failed


#: what a line over the budget suggests
OVER_HINT = "raise it under budget: in the config if this machine allows, or change the entry"


def over_budget(cfg: Config, jobs: list[Estimate] | None = None) -> list[str]:
    """One line per job (and for all scenes' output together) that exceeds the budget, or one line at a limit that
    every job exceeds (:func:`below_every_job`); empty if all fit. ``jobs``: the :func:`estimates` of ``cfg``, if
    known."""
    budget = Budget.from_config(cfg)
    jobs = estimates(cfg) if jobs is None else jobs
    below = below_every_job(jobs, budget)
    lines = list(below.values())
    hint = OVER_HINT
    total = 0.0
    for e in jobs:
        if e.key.startswith("scenes."):
            total += e.disk_bytes
        line = exceeds(e, budget, frozenset(below))
        if line is not None:
            lines.append(f"{line} ({hint})")
    if total > budget.disk_gb * GB and not lines:
        lines.append(f"scenes: all scenes together write an estimated {fmt_bytes(total)}, over budget.disk_gb = "
                     f"{_g(budget.disk_gb)} ({hint})")
    return lines


def check_scenes(scenes: dict[str, Scene], budget: Any) -> dict[str, str]:
    """:func:`check` for the scenes alone (name -> resolved :class:`Scene`) against ``budget`` (when it is not a
    :class:`Budget`, one with every limit at its largest: the bad budget is reported, and only what no budget
    runs is refused here): a config with problems elsewhere still has its scenes' stores judged before the
    physical checks build their times. Returns, key -> line, the scenes whose estimate failed (as :func:`check`)."""
    if not isinstance(budget, Budget):
        budget = Budget(**{f.name: f.metadata["keywords"]["maximum"] for f in fields(Budget)})
    lines, failed = [], {}
    for name, spec in scenes.items():
        try:
            line = exceeds(spec_estimate(spec, name), budget)
        except (TypeError, ValueError, AttributeError, ArithmeticError) as err:
            failed[f"scenes.{name}"] = _failed(f"scenes.{name}", err)
            continue
        if line is not None:
            lines.append(f"config error: {line} ({OVER_HINT})")
    if lines:
        from cradle.specs.values import ConfigError

        raise ConfigError(lines)
    return failed


def check(cfg: Config) -> dict[str, str]:
    """Raise :class:`~cradle.pipeline.config.ConfigError` (one line per job over budget) if any job of
    ``cfg`` (schema-valid, defaults filled) exceeds its budget; called by ``validate`` before its
    physical checks (which build the stored-time arrays), so an oversized store is refused first. Returns,
    key -> line, the jobs whose estimate failed (:func:`estimated`): ``validate`` refuses each after the physical
    checks, which may name the value at fault more precisely."""
    jobs, failed = estimated(cfg)
    lines = over_budget(cfg, jobs)
    if lines:
        from cradle.specs.values import ConfigError

        raise ConfigError([f"config error: {line}" for line in lines])
    return failed
