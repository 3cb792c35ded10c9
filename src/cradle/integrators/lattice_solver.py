"""Time integration of Newton's cradle (nc) with the Hertz potential (vhertz),
or of the smooth lattice (meca) with kappa = 1, or of the damped cradle (ncdamped).

    d^2 x_n/dt^2 + x_n = V'(x_{n+1} - x_n) - V'(x_n - x_{n-1})        (nc)/(meca)

Conventions are those of :mod:`cradle.models.lattice`: beads n = 0..N-1, bond n joins
beads n and n+1 and carries f_n = V'(x_{n+1} - x_n); periodic ends close the
ring with bond N-1, free ends drop it.

Three families of methods:

* symplectic splittings ("strang", "srkn4", "srkn6") of the energy (ham),
  H = sum (v_n^2 + x_n^2)/2 [exact rotation] + sum V(x_{n+1}-x_n) [kicks],
  fixed step, the splitting loop :func:`cradle.integrators._splitting.split_run`;
  and the same splittings with the contact-onset correction ("srkn6c",
  "srkn4c", the correction of :mod:`cradle.integrators._onset`): on every step where a bond
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
O(h^2.5) to O(h^5) and the observed global order well above 2.5
(benchmarks/onset_correction.py): at equal error srkn6c is the fastest
(benchmarks/bench_vs_scipy.py, `snakemake work_precision`).

With damping (``damping=Damping(onsite=gamma, contact=eta)``, the damped lattice (ncdamped) of
:mod:`cradle.models.damping`): the force depends on the velocities (-gamma v_n, and the contact term
eta c^(alpha-1) c'), so (ncdamped) is no longer Hamiltonian and the splittings above, built on the
split (ham) = rotation + kicks of position-only forces, do not apply as such. Damped runs use
"dop853_numba" only (the system :class:`cradle.integrators.systems.lattice.DampedLattice` of
:mod:`cradle.integrators._dop853`, Hertz contacts only), on the state
y = [x, v, s D]: the dissipated energy D(t) = int_0^t P is integrated as its own component
(dD/dt = P, never H(0) - H(t)), and the drift of H + D from H(0), monitored after every step, is
the integrator's error. The force and the dissipated power are smooth except where a bond changes
state (onset, release, clip of the contact damping, opening of a clipped bond): at an onset the
contact damping force rises like (t - t_on)^(1/2), and a DOP853 step across it errs by O(h^(3/2)).
The steps therefore end at these events (:mod:`cradle.integrators._dop853_events`: located by a
Hermite guess and Newton re-steps, the step after an onset taken in (t - t_on)^(1/2)); a step
without one is DOP853's step, bitwise. Measured by benchmarks/damped_orders.py (docs/damped-orders.md,
docs/dissipation.md): on figure loc1's packet the observed order in rtol is ~1 instead of 0.6-0.9,
and H + D holds to 1e-8 at rtol 1e-10 instead of 1e-14.

This module checks the arguments (the scalar ones against the shared declarations,
``@checked``; the arrays and the combinations here) and dispatches: the default step is chosen in
:mod:`cradle.integrators.lattice_step`, the splittings are run by
:mod:`cradle.integrators.lattice_splitting`, the adaptive methods by
:mod:`cradle.integrators.lattice_adaptive`.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from cradle.integrators import _kernels as K, lattice_adaptive as LA
from cradle.integrators._validate import check_energy_scale, check_state, check_times
from cradle.integrators.lattice_adaptive import ADAPTIVE_METHODS, run_dop853_damped, run_dop853_numba, run_scipy
from cradle.integrators.lattice_splitting import SPLITTING_METHODS, run_splitting
from cradle.integrators.lattice_step import compression_bounds
from cradle.models.damping import Damping
from cradle.models.lattice import DEFAULT_DT_FACTOR, default_dt
from cradle.models.lattice_terms import Terms, check as check_terms
from cradle.specs.checked import checked
from cradle.specs.values import MAX_T_END

if TYPE_CHECKING:
    from collections.abc import Callable

    from numpy.typing import ArrayLike

    from cradle.models.inhomogeneity import Sites

METHODS = SPLITTING_METHODS + ADAPTIVE_METHODS
POTENTIALS = ("hertz", "smooth")

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
    dissipated : ndarray, shape (T,)
        Energy D(t) = int_0^t P dissipated by the damping terms of (ncdamped) up to ``t``, integrated
        as a component of the state (:mod:`cradle.models.damping`); zeros without damping.
    damping : Damping or None
        The damping integrated (as given; None when none was given).

    With damping, ``energy_drift`` is max over every step of |H(t) + D(t) - H(0)| / |H(0)|: the stored
    plus dissipated energy is conserved by (ncdamped), so its drift is the integrator's error.

    With active ``terms`` (the imperfect cradle (ncimperfect) of :mod:`cradle.models.lattice_terms`), ``energy``
    is its generalised (ham) and ``energy_drift`` the drift of H + D; ``max_compression`` the largest bond
    overlap delta_n - (u_{n+1} - u_n); for the pendulum on-site potential ``x`` and ``v`` are the arc variable
    (the angle of bead n is s_n x_n, its horizontal position sin(s_n x_n)/s_n) and its rate.
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
    dissipated: np.ndarray = field(default_factory=lambda: np.zeros(0))
    damping: Damping | None = None
    terms: Terms | None = None

    def __post_init__(self) -> None:
        if self.dissipated.size == 0:   # no damping: nothing dissipated at any output time
            self.dissipated = np.zeros(len(self.t))


@checked(method="latticeMethod")
def integrate_lattice(x0: ArrayLike, v0: ArrayLike, t_out: ArrayLike, *, alpha: float, bc: str = "periodic",
                      method: str = "srkn6c", dt: float | None = None, dt_factor: float | None = None,
                      rtol: float | None = None, atol: float | None = None, potential: str = "hertz",
                      progress: Callable[[float, float], None] | None = None, t0: float = 0.0,
                      energy0: float | None = None, damping: Damping | None = None,
                      terms: Terms | None = None) -> LatticeSolution:
    """Integrate the lattice (nc) (Hertz V0 of (vhertz)) or (meca) (kappa = 1), or the damped (ncdamped).

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
    damping : Damping, optional
        The damping terms of (ncdamped) (:class:`cradle.models.damping.Damping`). None or an
        inactive one (gamma = eta = 0): the conservative (nc), integrated exactly as without the
        argument. Active: Hertz contacts only, method "dop853_numba" only (see the module
        docstring), no continuation (t0 = 0, no energy0); the result's ``dissipated`` holds the
        dissipated energy D and ``energy_drift`` the drift of H + D.
    terms : Terms, optional
        The terms of the imperfect cradle (ncimperfect) (:class:`cradle.models.lattice_terms.Terms`: site
        masses, on-site frequencies and contact stiffnesses, precompression, on-site potential). None or an
        inactive one: (nc), integrated exactly as without the argument. Active: Hertz contacts only, method
        "dop853_numba" only (:mod:`cradle.integrators.systems.imperfect`, damping allowed on top, no
        contact-event location), no continuation; validated with its sites drawn before any work (one
        ConfigError line naming key and value). For the pendulum x is the arc variable.

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
    x0 = check_state(x0, "x0")
    v0 = check_state(v0, "v0")
    if v0.shape != x0.shape:
        raise ValueError(f"x0 and v0 must have the same shape, got x0 {x0.shape} and v0 {v0.shape}")
    check_energy_scale(x0, v0, alpha)
    t_out = check_times(t_out, "t_out", most=MAX_T_END)
    t0 = float(t0)
    if not (np.isfinite(t0) and 0.0 <= t0 <= t_out[0]):
        raise ValueError(f"t0 must be finite, >= 0 and <= t_out[0] = {float(t_out[0])!r}, got t0={t0!r}")
    if damping is not None and not isinstance(damping, Damping):
        raise ValueError(f"damping must be a cradle.models.damping.Damping or None, got damping={damping!r}")
    damped = damping is not None and damping.active
    sites = None
    if terms is not None:
        sites = _check_terms(terms, x0.size, bc, method, potential, t0, energy0)
    if damped and sites is None:
        _check_damped(method, potential, t0, energy0, damping)
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
            out = run_splitting(x0, v0, t_out, dt, method, alpha, mode, periodic, progress, t0=t0, energy0=energy0)
        else:
            fac = DEFAULT_DT_FACTOR[method] if dt_factor is None else dt_factor
            c_assumed, c_energy = compression_bounds(x0, v0, alpha, bc, potential)
            while True:
                dt = default_dt(c_assumed, alpha, method, fac)
                out = run_splitting(x0, v0, t_out, dt, method, alpha, mode, periodic, progress, t0=t0,
                                    energy0=energy0)
                cmax = out[6]
                if cmax <= c_assumed * (1.0 + 1e-12) or c_assumed >= c_energy or n_reruns >= MAX_RERUNS:
                    break
                c_assumed = min(1.5 * cmax, c_energy)
                n_reruns += 1
        X, V, E, drift, n_steps, nfev, cmax, n_corr = out
        return LatticeSolution(t_out, X, V, E, drift, method, float(dt), None, None, n_steps, nfev, cmax,
                               time.perf_counter() - wall0, c_assumed, n_reruns, n_corr, damping=damping)

    if dt is not None or dt_factor is not None:
        raise ValueError(f"dt/dt_factor apply to splitting methods only, got dt={dt!r}, dt_factor={dt_factor!r} "
                         f"with method={method!r} (use rtol/atol)")
    rtol = DEFAULT_RTOL if rtol is None else rtol
    if atol is None:
        amp = max(float(np.max(np.abs(x0))), float(np.max(np.abs(v0))))
        atol = rtol * amp if amp > 0.0 else rtol
    if sites is not None:
        run = LA.run_dop853_terms(x0, v0, t_out, rtol, atol, alpha, mode, periodic, terms, sites,  # type: ignore[arg-type]  # sites: terms given
                                  damping if damped else None, progress)
        X, V, E, D, drift, n_steps, nfev, cmax = run
        return LatticeSolution(t_out, X, V, E, drift, method, None, rtol, atol, n_steps, nfev, cmax,
                               time.perf_counter() - wall0, dissipated=D, damping=damping, terms=terms)
    if damped:
        X, V, E, D, drift, n_steps, nfev, cmax = run_dop853_damped(x0, v0, t_out, rtol, atol, alpha, mode, periodic,
                                                                   damping, progress)  # type: ignore[arg-type]  # damped
        return LatticeSolution(t_out, X, V, E, drift, method, None, rtol, atol, n_steps, nfev, cmax,
                               time.perf_counter() - wall0, dissipated=D, damping=damping)
    if method == "dop853_numba":
        X, V, E, drift, n_steps, nfev, cmax = run_dop853_numba(x0, v0, t_out, rtol, atol, alpha, mode, periodic,
                                                                progress)
    else:
        X, V, E, drift, n_steps, nfev, cmax = run_scipy(x0, v0, t_out, method, rtol, atol, alpha, mode, periodic,
                                                         progress)
    return LatticeSolution(t_out, X, V, E, drift, method, None, rtol, atol, n_steps, nfev, cmax,
                           time.perf_counter() - wall0, damping=damping)


def _check_dop853_only(method: str, law: str, t0: float, energy0: float | None, what: str) -> None:
    """Refuse, in one line, what a run with ``what`` (damping, active terms) is not integrated with: a method other
    than DOP853 in numba, a potential other than Hertz's (``law``), a continued run."""
    if method != "dop853_numba":
        raise ValueError(f"method={method!r} with {what}: this lattice is integrated by method='dop853_numba' only "
                         f"(no symplectic splitting of its forces)")
    if law != "hertz":
        raise ValueError(f"potential={law!r} with {what}: declared for Hertz contacts (potential='hertz') only")
    if t0 != 0.0 or energy0 is not None:
        raise ValueError(f"t0={t0!r}/energy0={energy0!r} with {what}: such a run cannot be continued (it starts at "
                         f"t = 0)")


def _check_damped(method: str, law: str, t0: float, energy0: float | None, damping: Damping | None) -> None:
    """Refuse, in one line, what the damped (ncdamped) is not integrated with (``law``: the potential)."""
    _check_dop853_only(method, law, t0, energy0, f"damping={damping!r}")


def _check_terms(terms: Terms, N: int, bc: str, method: str, law: str, t0: float,
                 energy0: float | None) -> Sites | None:
    """The sites of active ``terms`` (None for inactive ones, which leave (nc) as it is), refusing in one line
    what the imperfect cradle (ncimperfect) is not integrated with (``law``: the potential)."""
    sites = check_terms(terms, N, bc)
    if not terms.active:
        return None
    _check_dop853_only(method, law, t0, energy0, "active terms (ncimperfect)")
    return sites
