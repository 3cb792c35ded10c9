"""Checks of the arrays the lattice and DpS drivers take (initial states, output times; clear ValueErrors).

Their scalar arguments are checked against the shared declarations (``cradle.specs.checked``)."""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, DTypeLike


def check_times(t: ArrayLike, name: str, most: float | None = None) -> np.ndarray:
    """Output times: 1-D, non-empty, finite, >= 0, strictly increasing and, with ``most``, at most that (the
    lattice's: :data:`cradle.specs.values.MAX_T_END`)."""
    t = _as_array(t, name, float)
    if t.ndim == 0:
        t = t.reshape(1)
    if t.ndim != 1 or t.size == 0:
        raise ValueError(f"{name} must be a non-empty 1-D array of times, got shape {t.shape}")
    if not np.all(np.isfinite(t)):
        bad = float(t[~np.isfinite(t)][0])
        raise ValueError(f"{name} must be finite, got {name} containing {bad!r}")
    if t[0] < 0.0:
        raise ValueError(f"{name} must be >= 0 (integration starts at 0), got {name}[0]={float(t[0])!r}")
    if most is not None and t[-1] > most:
        from cradle.specs.values import T_END_WHY

        raise ValueError(f"{name} must end by {most:.7g} ({T_END_WHY}), got {name}[-1]={float(t[-1])!r}")
    if t.size > 1:
        dif = np.diff(t)
        if np.any(dif <= 0.0):
            i = int(np.argmax(dif <= 0.0))
            raise ValueError(
                f"{name} must be strictly increasing, "
                f"got {name}[{i}]={float(t[i])!r} >= {name}[{i + 1}]={float(t[i + 1])!r}"
            )
    return t


def check_state(arr: ArrayLike, name: str, dtype: DTypeLike = float) -> np.ndarray:
    """A finite 1-D state vector with N >= 2 entries (real, for a real ``dtype``: an imaginary part is not dropped
    silently)."""
    if np.dtype(dtype).kind == "f" and np.iscomplexobj(arr) and np.any(np.imag(arr) != 0):
        raise ValueError(f"{name} must be real (a position or velocity per bead), got complex values")
    arr = _as_array(arr, name, dtype)
    if arr.ndim != 1:
        raise ValueError(f"{name} must be 1-D (one value per bead), got shape {arr.shape}")
    if arr.size < 2:
        raise ValueError(f"N must be >= 2, got {name} with N={arr.size}")
    if not np.all(np.isfinite(arr)):
        i = int(np.argmax(~np.isfinite(arr)))
        raise ValueError(f"{name} must be finite, got {name}[{i}]={arr[i].item()!r}")
    return arr



def _as_array(values: ArrayLike, name: str, dtype: DTypeLike) -> np.ndarray:
    """``values`` as a new array of ``dtype``, or a ValueError naming ``name`` (an int beyond float64, text)."""
    try:
        return np.array(values, dtype=dtype, copy=True)
    except (OverflowError, TypeError, ValueError) as err:
        raise ValueError(f"{name} must be an array of finite numbers ({err})") from None


def check_energy_scale(x0: np.ndarray, v0: np.ndarray, alpha: float) -> None:
    """x0, v0 whose energy (ham) float64 holds: N max(|x_n|, |v_n|, |x_{n+1} - x_n|)^max(2, alpha + 1) finite (a
    larger state makes H(0), the step size and the drift inf or nan, and the run fails far from its cause)."""
    scale = 2.0 * max(float(np.max(np.abs(x0))), float(np.max(np.abs(v0))), 1.0)
    with np.errstate(over="ignore"):
        ok = bool(np.isfinite(x0.size * np.float64(scale) ** max(2.0, alpha + 1.0)))
    if not ok:
        raise ValueError(f"x0, v0 must be smaller: values up to {scale / 2:.3g} give an energy (ham) beyond float64 "
                         f"(N (2 max|x|)^(alpha+1) overflows at alpha = {alpha:g})")


def check_steps(t_start: float, t_out: np.ndarray, dt: float) -> None:
    """A fixed-step run from ``t_start`` through ``t_out`` with step bound ``dt`` whose steps float64 counts: at most
    :data:`cradle.specs.values.MAX_COUNT` = 2^53 (beyond, the step times t_k + j len / n_k round, and a count past
    int64 wrapped to one step per interval: dt = 1e-300 ran as a step as long as the interval)."""
    from cradle.specs.values import MAX_COUNT

    with np.errstate(over="ignore"):
        steps = float(np.sum(np.diff(np.concatenate(([t_start], t_out))) / np.float64(dt)))
    if not steps <= MAX_COUNT:
        raise ValueError(f"dt = {dt!r}: the run to t = {float(t_out[-1]):.6g} would take {steps:.3g} steps, more "
                         f"than 2^53 = {MAX_COUNT:.3g} (float64 counts steps exactly only below; take a larger step)")


#: the most periods of DpS's fastest oscillation a run may span: an explicit integrator takes several steps per
#: period, so beyond this a run of a few sites takes hours (a paper's run spans thousands)
MAX_DPS_PERIODS = 1e9


def check_dps_pace(A0: np.ndarray, tau_out: np.ndarray, alpha: float) -> None:
    """A run of (dfnls) that spans at most :data:`MAX_DPS_PERIODS` periods of its fastest oscillation, of frequency
    about (2 max|A_n|)^(alpha - 1) 2 / tau0 (the p-Laplacian of differences up to 2 max|A_n|): DpS's scaling
    A -> lambda A, tau -> lambda^(1 - alpha) tau makes a large amplitude run fast, and its steps shrink with it."""
    from cradle.models.dps import plane_wave_frequency

    amp = float(np.max(np.abs(A0)))
    with np.errstate(over="ignore"):   # the fastest plane wave of (ds), q = pi, at |A| = max|A_n(0)|
        periods = float(tau_out[-1]) * plane_wave_frequency(np.float64(amp), np.pi, alpha) / (2.0 * np.pi)
    if not periods <= MAX_DPS_PERIODS:
        raise ValueError(f"A0, tau_out: tau_out[-1] = {float(tau_out[-1]):.6g} spans {periods:.3g} periods of the "
                         f"fastest DpS oscillation at max|A_n(0)| = {amp:.3g}, more than {MAX_DPS_PERIODS:.0e} (hours "
                         f"of steps; DpS runs lambda^(alpha-1) times faster at lambda times the amplitude)")
