"""Time integration of Newton's cradle (nc) with the Hertz potential (vhertz),
or of the smooth lattice (meca) with kappa = 1.

    d^2 x_n/dt^2 + x_n = V'(x_{n+1} - x_n) - V'(x_n - x_{n-1})        (nc)/(meca)

Conventions are those of :mod:`cradle.models.lattice`: beads n = 0..N-1, bond n joins
beads n and n+1 and carries f_n = V'(x_{n+1} - x_n); periodic ends close the
ring with bond N-1, free ends drop it.

Three families of methods:

* symplectic splittings ("strang", "srkn4", "srkn6") of the energy (ham),
  H = sum (v_n^2 + x_n^2)/2 [exact rotation] + sum V(x_{n+1}-x_n) [kicks],
  fixed step, numba kernel :func:`cradle.integrators._kernels.split_run`;
  and the same splittings with the contact-onset correction ("srkn6c",
  "srkn4c", :mod:`cradle.integrators._onset`): on every step where a bond
  is near or crosses contact onset, its quadrature is replaced by the
  exact integral of its force along a cubic model of its elongation;
* scipy's adaptive solvers ("dop853", "rk45", "lsoda", "radau") stepped
  manually, right-hand side compiled with numba
  (:func:`cradle.integrators._kernels.lattice_rhs`), dense output at t_out;
* "dop853_numba": DOP853 with scipy's controller, fully in numba
  (:mod:`cradle.integrators._dop853`), for tight references.

In all cases the energy (ham) is evaluated after every (accepted) step.

Accuracy note: the Hertz force -max(-d, 0)^alpha is only C^{1, alpha-1} at
contact onset (d = 0), so every uncorrected method's observed order on (nc)
is capped near alpha + 1 (2.5 for alpha = 3/2; tests/test_integrators.py),
and the energy error of the splittings decreases like dt^~3 instead of
dt^6. The nominal orders 2/4/6 are recovered on the smooth potential of
(meca). The onset correction lifts the local error of a crossing step from
O(h^2.5) to O(h^5) and the observed global order from 2.5 to 5 on a 16-bead
travelling wave, to 3.2-3.8 on the paper's scenes at t = 100
(benchmarks/onset_correction.py): at equal error srkn6c is 5-30 times
faster than srkn6 (benchmarks/bench_vs_scipy.py, `snakemake work_precision`).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from cradle.models.lattice import check_alpha, check_bc
from cradle.integrators import _dop853
from cradle.integrators import _kernels as K
from cradle.integrators import _onset
from cradle.integrators._coefficients import SPLITTINGS
from cradle.integrators._validate import check_choice, check_positive, check_state, check_times

#: Splittings with the contact-onset correction (:mod:`._onset`) -> the splitting they correct.
CORRECTED_METHODS = {"srkn6c": "srkn6", "srkn4c": "srkn4"}
SPLITTING_METHODS = tuple(SPLITTINGS) + tuple(CORRECTED_METHODS)
#: scipy.integrate.solve_ivp classes, the baselines (looked up when used: scipy.integrate costs 0.5 s to import)
SCIPY_METHODS = {"dop853": "DOP853", "rk45": "RK45", "lsoda": "LSODA", "radau": "Radau"}
ADAPTIVE_METHODS = tuple(SCIPY_METHODS) + ("dop853_numba",)
METHODS = SPLITTING_METHODS + ADAPTIVE_METHODS
POTENTIALS = ("hertz", "smooth")

#: Default step, as a fraction of the shortest linearised period 2 pi / omega_max(c)
#: (see :func:`default_dt`). Chosen (benchmarks/tune_dt_factor.py) so that the
#: relative energy drift stays <= 1e-8, with a margin of >= 2, on every scene
#: of config.yaml run to its t_end (tw-*, mi-4pi5, binary-pi, fft106,
#: fftseuil-*, fft344, breather-*, loc1-*, fini). Worst drifts measured:
#: srkn6c 1.6e-9 (loc1-packet; 1.0 s for all 16 scenes), srkn4c 3.1e-9
#: (1.6 s), srkn6 2.8e-9 (15 s), srkn4 1.9e-9 (18 s), strang 2.1e-9 (71 s). The
#: breather and loc1 scenes (long runs, slow contact onsets) are the
#: hardest: srkn6 at its former 0.001 reached 1.8e-8 on loc1-pair. The
#: uncorrected steps are small (srkn6: ~2000 per linear period) because of
#: the Hertz non-smoothness at contact onset; the onset correction allows 20
#: times larger steps at a smaller drift.
DEFAULT_DT_FACTOR = {"strang": 0.00003, "srkn4": 0.00025, "srkn6": 0.0005, "srkn4c": 0.004, "srkn6c": 0.01}

#: Reruns allowed when the run reaches a compression above the assumed bound.
MAX_RERUNS = 3

DEFAULT_RTOL = 1e-10


@dataclass
class LatticeSolution:
    """Result of :func:`integrate_lattice`.

    Attributes
    ----------
    t : ndarray, shape (T,)
        Output times (= ``t_out``).
    x, v : ndarray, shape (T, N)
        Displacements and velocities at ``t``.
    energy : ndarray, shape (T,)
        Hamiltonian (ham) at ``t``.
    energy_drift : float
        max over every step of |H(t) - H(0)| / |H(0)| (absolute if H(0) = 0).
    method : str
    dt : float or None
        Nominal fixed step (splittings); steps actually taken are <= dt so that
        every output time is hit exactly. None for adaptive methods.
    rtol, atol : float or None
        Tolerances (adaptive methods), None for splittings.
    n_steps, n_force_evals : int
    max_compression : float
        Largest bond compression met (splittings: at the end of every step;
        adaptive methods: at every accepted step): max_n
        max(-(x_{n+1} - x_n), 0) for Hertz, max_n |x_{n+1} - x_n| for the
        smooth potential (the stiffness alpha |d|^(alpha-1) is even).
    wall_time_s : float
        Wall time of the whole call (including reruns).
    c_assumed : float or None
        Compression c used to set the default step (splittings, dt=None).
    n_reruns : int
        Runs repeated because max_compression exceeded c_assumed.
    n_onset_corrections : int
        Corrected methods ("srkn6c", "srkn4c"): bond crossings (contact
        onsets and releases) whose step contribution was replaced by the
        exact integral (:mod:`cradle.integrators._onset`); 0 otherwise.
    """

    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    energy: np.ndarray
    energy_drift: float
    method: str
    dt: float | None
    rtol: float | None
    atol: float | None
    n_steps: int
    n_force_evals: int
    max_compression: float
    wall_time_s: float
    c_assumed: float | None = None
    n_reruns: int = 0
    n_onset_corrections: int = 0


def omega_max(c: float, alpha: float) -> float:
    """Highest linearised frequency sqrt(1 + 4 alpha c^(alpha-1)) at bond compression c.

    Linearising (nc) about a state where every bond is compressed by c gives
    the bond stiffness k = V0''(-c) = alpha c^(alpha-1) and the dispersion
    omega(q)^2 = 1 + 4 k sin^2(q/2), maximal at q = pi.
    """
    return math.sqrt(1.0 + 4.0 * alpha * max(c, 0.0) ** (alpha - 1.0))


def compression_bounds(x0, v0, alpha: float, bc: str = "periodic", potential: str = "hertz"):
    """Compression c assumed for the default step, and the energy bound on it.

    Returns ``(c_assumed, c_energy)``:

    * ``c_energy = ((alpha + 1) H)^(1/(alpha+1))``: every term of (ham) is
      >= 0, so a single bond holding all the energy H satisfies
      c^(alpha+1)/(alpha+1) <= H. Rigorous (H is conserved) but pessimistic
      for long chains, where H grows like N;
    * the working guess ``2 c0 + A0`` with c0 the largest initial compression
      and A0 = max_n sqrt(x_n^2 + v_n^2) the largest initial oscillator
      amplitude (a bond is compressed by at most |x_n| + |x_{n+1}|; the factor 2
      on c0 leaves room for moderate energy focusing, e.g. breather formation).

    ``c_assumed = min(2 c0 + A0, c_energy)``. After the run, if a larger
    compression was met, :func:`integrate_lattice` reruns with
    ``min(1.5 max_compression, c_energy)``.
    """
    alpha = float(alpha)
    x0 = np.ascontiguousarray(x0, dtype=float)
    v0 = np.ascontiguousarray(v0, dtype=float)
    mode = K.mode_flag(potential, alpha)
    H0, c0 = K.lattice_energy(x0, v0, alpha, mode, bc == "periodic")
    A0 = float(np.sqrt(np.max(x0**2 + v0**2)))
    c_energy = ((alpha + 1.0) * max(H0, 0.0)) ** (1.0 / (alpha + 1.0))
    return min(2.0 * c0 + A0, c_energy), c_energy


def default_dt(c: float, alpha: float, method: str = "srkn6c", dt_factor: float | None = None) -> float:
    """dt = dt_factor * 2 pi / omega_max(c) (default dt_factor from DEFAULT_DT_FACTOR)."""
    fac = DEFAULT_DT_FACTOR[method] if dt_factor is None else dt_factor
    return fac * 2.0 * math.pi / omega_max(c, alpha)


#: (variant, n_iter, near) of the onset correction (:mod:`._onset`): variant 2 replaces the
#: quadrature actually taken, 0 refinements of the model's end values, and a bond is treated when
#: |d| < near * h * (|d'(0)| + |d'(h)|) at a step end or d changes sign (benchmarks/onset_correction.py).
ONSET_OPTIONS = (2, 0, _onset.NEAR_DEFAULT)


def _run_splitting(x0, v0, t_out, dt, method, alpha, mode, periodic, progress, onset=None, t0=0.0, energy0=None):
    corrected = method in CORRECTED_METHODS
    a, b, _order = SPLITTINGS[CORRECTED_METHODS.get(method, method)]
    N = x0.size
    T = t_out.size
    if t_out[0] == t0:
        tgrid, shift = t_out, 0
    else:
        tgrid, shift = np.concatenate(([t0], t_out)), 1
    X = np.empty((T, N))
    V = np.empty((T, N))
    E = np.empty(T)
    x = x0.copy()
    v = v0.copy()
    f = np.empty(N)
    F = np.empty(N)
    if corrected:
        variant, n_iter, near = ONSET_OPTIONS if onset is None else onset
        fs = np.zeros((a.size + 1, N))
        f = fs[-1]
        cnode = np.concatenate(([0.0], np.cumsum(a)))
        cnode[-1] = 1.0
        d0 = np.roll(x, -1) - x
        w0 = np.roll(v, -1) - v
        d1, w1 = np.empty(N), np.empty(N)
        flag = np.zeros(N, dtype=np.uint8)
        idx = np.empty(N, dtype=np.int64)
    pot, c0 = K.forces(x, f, F, alpha, mode, periodic)
    H0 = 0.5 * float(np.dot(x, x) + np.dot(v, v)) + pot
    if shift == 0:
        X[0], V[0], E[0] = x, v, H0
    # drift measured from energy0 (the energy at the start of the run being continued) if given
    stats = np.array([H0 if energy0 is None else float(energy0), 0.0, c0, H0])
    counts = np.array([0, 1, 0, 0, 0], dtype=np.int64)
    nint = tgrid.size - 1
    k, j = 0, 0
    t_final = float(tgrid[-1])
    if progress is None:
        budget = np.iinfo(np.int64).max
    else:  # first chunk ~0.2 s at ~4 ns per bond evaluation
        budget = max(1, int(5e7 / (N * a.size)))
    while k < nint:
        t0 = time.perf_counter()
        n_before = counts[0]
        if corrected:
            k, j = _onset.split_run_onset(x, v, F, fs, d0, w0, d1, w1, flag, idx, tgrid, float(dt), k, j, budget, a, b,
                                          cnode, alpha, mode, periodic, int(variant), int(n_iter), float(near), X, V, E,
                                          shift, stats, counts)
        else:
            k, j = K.split_run(x, v, f, F, tgrid, float(dt), k, j, budget, a, b, alpha, mode, periodic,
                               X, V, E, shift, stats, counts)
        if progress is not None:
            elapsed = time.perf_counter() - t0
            taken = int(counts[0] - n_before)
            if elapsed > 0 and taken > 0:
                budget = max(1, int(taken / elapsed))  # ~1 s per chunk
            if k < nint:
                length = tgrid[k + 1] - tgrid[k]
                nk = max(1, math.ceil(length / dt * (1.0 - 1e-12)))
                t_reached = float(tgrid[k] + j * length / nk)
            else:
                t_reached = t_final
            progress(t_reached, t_final)
    return X, V, E, float(stats[1]), int(counts[0]), int(counts[1]), float(stats[2]), int(counts[2])


def _run_scipy(x0, v0, t_out, method, rtol, atol, alpha, mode, periodic, progress):
    N = x0.size
    T = t_out.size
    y0 = np.concatenate((x0, v0))
    f = np.empty(N)
    F = np.empty(N)

    def fun(t, y):
        dy = np.empty_like(y)
        K.lattice_rhs(y, dy, f, F, alpha, mode, periodic)
        return dy

    extra = {}
    if method in ("radau", "lsoda"):
        def jac(t, y):
            J = np.empty((2 * N, 2 * N))
            K.lattice_jac(y, J, alpha, mode, periodic)
            return J
        extra["jac"] = jac

    X = np.empty((T, N))
    V = np.empty((T, N))
    E = np.empty(T)
    H0, cmax = K.lattice_energy(x0, v0, alpha, mode, periodic)
    scale = abs(H0) if H0 != 0.0 else 1.0
    drift = 0.0
    idx = 0
    if t_out[0] == 0.0:
        X[0], V[0], E[0] = x0, v0, H0
        idx = 1
    t_final = float(t_out[-1])
    n_steps = 0
    if idx < T:
        from scipy import integrate

        solver = getattr(integrate, SCIPY_METHODS[method])(fun, 0.0, y0, t_final, rtol=rtol, atol=atol, **extra)
        t_last = time.perf_counter()
        while solver.status == "running":
            msg = solver.step()
            if solver.status == "failed":
                raise RuntimeError(f"{method} failed at t={solver.t!r}: {msg}")
            n_steps += 1
            y = solver.y
            H, cm = K.lattice_energy(y[:N], y[N:], alpha, mode, periodic)
            drift = max(drift, abs(H - H0) / scale)
            cmax = max(cmax, cm)
            dense = None
            while idx < T and t_out[idx] <= solver.t:
                if t_out[idx] == solver.t:
                    yk = y
                else:
                    if dense is None:
                        dense = solver.dense_output()
                    yk = dense(t_out[idx])
                X[idx], V[idx] = yk[:N], yk[N:]
                E[idx] = K.lattice_energy(X[idx], V[idx], alpha, mode, periodic)[0]
                idx += 1
            if progress is not None and time.perf_counter() - t_last >= 1.0:
                t_last = time.perf_counter()
                progress(float(solver.t), t_final)
        nfev = solver.nfev
    else:
        nfev = 0
    if progress is not None:
        progress(t_final, t_final)
    return X, V, E, drift, n_steps, int(nfev), float(cmax)


def _run_dop853_numba(x0, v0, t_out, rtol, atol, alpha, mode, periodic, progress):
    N = x0.size
    H0, c0 = K.lattice_energy(x0, v0, alpha, mode, periodic)
    stats = np.array([H0, 0.0, c0, H0])
    Y, n_steps, nfev = _dop853.run_dop853(_dop853.LATTICE, np.concatenate((x0, v0)), t_out, rtol, atol, alpha,
                                          mode, 0.0, periodic, stats, progress)
    X = np.ascontiguousarray(Y[:, :N])
    V = np.ascontiguousarray(Y[:, N:])
    E = np.array([K.lattice_energy(X[i], V[i], alpha, mode, periodic)[0] for i in range(len(t_out))])
    return X, V, E, float(stats[1]), n_steps, nfev, float(stats[2])


def integrate_lattice(x0, v0, t_out, *, alpha, bc="periodic", method="srkn6c", dt=None, dt_factor=None,
                      rtol=None, atol=None, potential="hertz", progress=None, t0=0.0,
                      energy0=None) -> LatticeSolution:
    """Integrate the lattice (nc) (Hertz V0 of (vhertz)) or (meca) (kappa = 1).

    Parameters
    ----------
    x0, v0 : array_like, shape (N,)
        Initial displacements and velocities, N >= 2, finite.
    t_out : array_like, shape (T,)
        Strictly increasing output times, t_out[0] >= 0. Integration starts at
        t = 0; the state is stored exactly at every t_out (row 0 is the initial
        state when t_out[0] == 0).
    alpha : float
        Contact exponent, > 1 (alpha = 1.5 uses a c sqrt(c) fast path).
    bc : {"periodic", "free"}
        Ring (bond N-1 joins beads N-1 and 0) or free ends (bond N-1 absent).
    method : {"srkn6c", "srkn4c", "srkn6", "srkn4", "strang", "dop853", "rk45", "lsoda", "radau", "dop853_numba"}
        Default "srkn6c", as ``defaults.exact.method`` of the config.
        Symplectic splitting of (ham) (orders 6, 4, 2; rotation for the
        harmonic part, kicks for the contact part, Blanes & Moan 2002
        SRKN_11^b and SRKN_6^b), the same with the contact-onset correction
        ("srkn6c", "srkn4c": :mod:`cradle.integrators._onset`; the fastest at
        equal accuracy on (nc)), a scipy adaptive solver stepped manually
        (numba right-hand side; "radau"/"lsoda" get the analytic Jacobian),
        or "dop853_numba": the same DOP853 8(5,3) pair and step control as
        scipy, entirely in numba, steps ending exactly on t_out (references).
    dt : float, optional
        Splittings: step bound. Between consecutive output times
        n = ceil((t_{k+1} - t_k)/dt) equal steps are taken. Default:
        ``dt_factor * 2 pi / omega_max(c)`` (:func:`default_dt`) with c from
        :func:`compression_bounds`; if the run meets a compression above c,
        it is rerun with a larger c (at most ``MAX_RERUNS`` times).
    dt_factor : float, optional
        Fraction of the shortest linearised period used when dt is None
        (default ``DEFAULT_DT_FACTOR[method]``).
    rtol, atol : float, optional
        Adaptive methods only. Defaults rtol = 1e-10,
        atol = rtol * max(max|x0|, max|v0|).
    potential : {"hertz", "smooth"}
        "hertz": V0(d) = max(-d, 0)^(alpha+1)/(alpha+1) (vhertz);
        "smooth": U(d) = |d|^(alpha+1)/(alpha+1) of (meca) with kappa = 1.
    progress : callable, optional
        ``progress(t_reached, t_final)``, called about once per second of wall
        time (and at the end).
    t0 : float, optional
        Time of the state (x0, v0) (default 0), t_out[0] >= t0. Splittings
        only: continuing a run from its stored state at t0 with the same dt
        and the same later output times takes exactly the same steps, so the
        result is bitwise that of one run (:mod:`cradle.pipeline.extend`).
    energy0 : float, optional
        Splittings only: reference energy for ``energy_drift`` (default
        H(x0, v0)); the energy at t = 0 of the run being continued.

    Returns
    -------
    LatticeSolution

    Raises
    ------
    ValueError
        On invalid input (the message names the offending value), or when
        dt/dt_factor are given to an adaptive method or rtol/atol to a
        splitting.
    """
    wall0 = time.perf_counter()
    alpha = check_alpha(alpha)
    bc = check_bc(bc)
    method = check_choice(method, METHODS, "method")
    potential = check_choice(potential, POTENTIALS, "potential")
    x0 = check_state(x0, "x0")
    v0 = check_state(v0, "v0")
    if v0.shape != x0.shape:
        raise ValueError(f"x0 and v0 must have the same shape, got x0 {x0.shape} and v0 {v0.shape}")
    t_out = check_times(t_out, "t_out")
    t0 = float(t0)
    if not (np.isfinite(t0) and 0.0 <= t0 <= t_out[0]):
        raise ValueError(f"t0 must be finite, >= 0 and <= t_out[0] = {float(t_out[0])!r}, got t0={t0!r}")
    if (t0 != 0.0 or energy0 is not None) and method not in SPLITTING_METHODS:
        raise ValueError(f"t0/energy0 (continuing a run) need a fixed-step splitting method, got method={method!r} "
                         f"(t0={t0!r}, energy0={energy0!r})")
    if progress is not None and not callable(progress):
        raise ValueError(f"progress must be callable or None, got progress={progress!r}")
    periodic = bc == "periodic"
    mode = K.mode_flag(potential, alpha)

    if method in SPLITTING_METHODS:
        if rtol is not None or atol is not None:
            raise ValueError(f"rtol/atol apply to adaptive methods only, got rtol={rtol!r}, atol={atol!r} "
                             f"with method={method!r} (use dt or dt_factor)")
        if dt is not None and dt_factor is not None:
            raise ValueError(f"give dt or dt_factor, not both (got dt={dt!r}, dt_factor={dt_factor!r})")
        c_assumed = None
        n_reruns = 0
        if dt is not None:
            dt = check_positive(dt, "dt")
            out = _run_splitting(x0, v0, t_out, dt, method, alpha, mode, periodic, progress, t0=t0, energy0=energy0)
        else:
            fac = DEFAULT_DT_FACTOR[method] if dt_factor is None else check_positive(dt_factor, "dt_factor")
            c_assumed, c_energy = compression_bounds(x0, v0, alpha, bc, potential)
            while True:
                dt = default_dt(c_assumed, alpha, method, fac)
                out = _run_splitting(x0, v0, t_out, dt, method, alpha, mode, periodic, progress, t0=t0,
                                     energy0=energy0)
                cmax = out[6]
                if cmax <= c_assumed * (1.0 + 1e-12) or c_assumed >= c_energy or n_reruns >= MAX_RERUNS:
                    break
                c_assumed = min(1.5 * cmax, c_energy)
                n_reruns += 1
        X, V, E, drift, n_steps, nfev, cmax, n_corr = out
        return LatticeSolution(t_out, X, V, E, drift, method, float(dt), None, None, n_steps, nfev, cmax,
                               time.perf_counter() - wall0, c_assumed, n_reruns, n_corr)

    if dt is not None or dt_factor is not None:
        raise ValueError(f"dt/dt_factor apply to splitting methods only, got dt={dt!r}, dt_factor={dt_factor!r} "
                         f"with method={method!r} (use rtol/atol)")
    rtol = DEFAULT_RTOL if rtol is None else check_positive(rtol, "rtol")
    if atol is None:
        amp = max(float(np.max(np.abs(x0))), float(np.max(np.abs(v0))))
        atol = rtol * amp if amp > 0.0 else rtol
    else:
        atol = check_positive(atol, "atol")
    if method == "dop853_numba":
        X, V, E, drift, n_steps, nfev, cmax = _run_dop853_numba(x0, v0, t_out, rtol, atol, alpha, mode, periodic,
                                                                 progress)
    else:
        X, V, E, drift, n_steps, nfev, cmax = _run_scipy(x0, v0, t_out, method, rtol, atol, alpha, mode, periodic,
                                                          progress)
    return LatticeSolution(t_out, X, V, E, drift, method, None, rtol, atol, n_steps, nfev, cmax,
                           time.perf_counter() - wall0)
