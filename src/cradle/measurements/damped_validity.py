"""How well the damped DpS (dpsdamped) describes the damped lattice (ncdamped): the sup error of dps-validity.

For a lattice run of (ncdamped) from well-prepared data (:func:`cradle.models.dps_damped.lattice_state`:
x_n(0) = eps (A_n(0) + c.c.) and the velocities of the ansatz with the damped dA/dtau) and the run of
(dpsdamped) from the same A_n(0) with gamma~ = gamma eps^(1-alpha) and the same eta
(:func:`cradle.models.dps_damped.slow_damping`), x_app is rebuilt by (ansatz) and, as in dps-validity
(:mod:`cradle.analyses.dps_validity`),

    E_abs(eps, T) = sup_{0 <= t <= T eps^(1-alpha)} max_n |x_n(t) - x_n^app(t)|,   E_rel = E_abs / (2 eps),

taken on the samples given (the caller chooses their spacing: the error oscillates at the frequencies 1, 3,
..., and a spacing of a fraction of the period gives the sup within a few per cent). With damping the wave
decays, so the error is also given against the amplitude left: E_env = sup_t max_n |x_n - x_n^app| /
(2 eps max_n |A_n(tau)|). The consistency order of (ansatz) is unchanged by the damping terms (they enter
(calculapp) at order eps^alpha with gamma = O(eps^(alpha-1)) and eta = O(1); docs/damped-dps.md), so the
reference law is E_abs = O(eps^alpha) as for dps-validity.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.measurements.compare import approximate_displacement


def sup_error(t: ArrayLike, x: ArrayLike, A: ArrayLike, eps: float, alpha: float, T_marks: ArrayLike,
              v: ArrayLike | None = None) -> dict[str, NDArray[np.float64]]:
    """The running sup errors of a damped (or undamped) lattice run against its DpS run, read at t = T eps^(1-alpha).

    Parameters
    ----------
    t : array_like, shape (K,)
        Lattice sample times, increasing, from 0; they must reach the largest mark.
    x : array_like, shape (K, N)
        Lattice displacements x_n(t) of (ncdamped).
    A : array_like, shape (K, N), complex
        DpS amplitudes A_n(tau) at tau = eps^(alpha-1) t, run from the A_n(0) of the lattice's initial data.
    eps, alpha : float
        Small parameter of (ansatz) and Hertz exponent.
    T_marks : array_like
        Slow times T > 0.
    v : array_like, shape (K, N), optional
        Lattice velocities: their error against the leading order of (ansatz), 2 eps Re(i A_n e^{it}), is
        returned too (that leading order omits eps^alpha dA/dtau: this error is O(eps^alpha) by itself).

    Returns
    -------
    dict
        ``T`` (the marks, sorted), ``t_mark`` (T eps^(1-alpha)), ``abs_error`` (E_abs), ``rel_error``
        (E_rel), ``envelope_error`` (E_env) and, with ``v``, ``velocity_abs_error``: arrays over the marks.
    """
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    A = np.asarray(A, dtype=complex)
    if t.ndim != 1 or x.shape != A.shape or x.shape[:1] != t.shape:
        raise ValueError(f"t, x, A must have shapes (K,), (K, N), (K, N); got t {t.shape}, x {x.shape}, A {A.shape}")
    if not (eps > 0.0 and np.isfinite(eps)):
        raise ValueError(f"eps must be a finite number > 0, got eps={eps!r}")
    marks = np.sort(np.asarray(T_marks, dtype=float).ravel())
    if marks.size == 0 or not marks[0] > 0.0:
        raise ValueError(f"T_marks must be slow times > 0, got T_marks={T_marks!r}")
    t_marks = marks * eps ** (1.0 - alpha)
    if t_marks[-1] > t[-1] * (1.0 + 1e-12):
        raise ValueError(f"T_marks: the lattice run ends at t = {t[-1]!r} < T eps^(1-alpha) = {t_marks[-1]!r}")
    # the last sample at or before each mark (a mark sampled exactly counts)
    at_mark = np.searchsorted(t, t_marks * (1.0 + 1e-12), side="right") - 1
    x_app = approximate_displacement(A, t, eps)
    err = np.max(np.abs(x - x_app), axis=1)
    running = np.maximum.accumulate(err)
    amp = 2.0 * eps * np.max(np.abs(A), axis=1)
    envelope = np.maximum.accumulate(err / np.where(amp > 0.0, amp, np.inf))
    out = {"T": marks, "t_mark": t_marks, "abs_error": running[at_mark], "rel_error": running[at_mark] / (2.0 * eps),
           "envelope_error": envelope[at_mark]}
    if v is not None:
        v = np.asarray(v, dtype=float)
        if v.shape != x.shape:
            raise ValueError(f"v must have the shape of x {x.shape}, got {v.shape}")
        v_app = 2.0 * eps * np.real(1j * A * np.exp(1j * t)[:, None])
        out["velocity_abs_error"] = np.maximum.accumulate(np.max(np.abs(v - v_app), axis=1))[at_mark]
    return out
