"""Tails of the homoclinic solutions of (dpsstn) far below machine precision.

Beyond the core, |a_n| decays super-exponentially (|a_{n+1}| ~ |a_n|^alpha)
and leaves double precision within a few sites. The exact recursion of
(dpsstn) is run backward in (sign, log|a_n|) variables, where nothing
underflows or cancels, and matched to the double-precision core: log10|a_n|
on every site of a solution (:func:`log10_abs`), of a unit-amplitude profile
of :mod:`cradle.models.homoclinic_continuation` (:func:`log10_abs_scaled`),
and the half-width of the core at a given depth (:func:`decay_sites`).
"""
from __future__ import annotations

from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.specs.checked import checked


class ScaledProfile(Protocol):
    """What :func:`log10_abs_scaled` reads of a solution (a
    :class:`~cradle.models.homoclinic_continuation.ScaledHomoclinic`)."""

    profile: np.ndarray
    nu: float
    alpha: float
    log10_scale: float


def _backward_step(s1: float, L1: float, s0: float, L0: float, alpha: float) -> tuple[float, float]:
    """One step of (dpsstn) solved for a_{n-1}, all in (sign, log|.|) variables.

    (dpsstn) at site n, mu = 1:  g(a_n - a_{n-1}) = g(a_{n+1} - a_n) + a_n, hence

        a_{n-1} = a_n - g^{-1}(a_n + g(a_{n+1} - a_n)),   g^{-1}(b) = sign(b) |b|^(1/alpha).

    In a tail |a_{n+1}| << |a_n| << |a_{n-1}|: every sum above is a large
    term times (1 + a small ratio), so it is computed as a sign, a log and a
    log1p of a ratio formed as exp(difference of logs). Nothing underflows
    and nothing cancels. (s1, L1) is a_{n+1}, (s0, L0) is a_n; returns a_{n-1}.
    """
    r = s1 * s0 * np.exp(L1 - L0)                # a_{n+1} / a_n
    sd, Ld = -s0 * np.sign(1.0 - r), L0 + np.log(abs(1.0 - r))   # d = a_{n+1} - a_n = a_n (r - 1)
    rho1 = sd * s0 * np.exp(alpha * Ld - L0)     # g(d) / a_n
    ss, Ls = s0 * np.sign(1.0 + rho1), L0 + np.log1p(rho1) if rho1 > -1 else L0 + np.log(abs(1.0 + rho1))
    Lh = Ls / alpha                              # h = g^{-1}(s)
    rho2 = s0 * ss * np.exp(L0 - Lh)             # a_n / h
    return -ss * np.sign(1.0 - rho2), Lh + np.log(abs(1.0 - rho2))


def _tail_from(s_far: float, L_far: float, s_next: float, L_next: float, steps: int,
               alpha: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Iterate :func:`_backward_step` ``steps`` times from (a_{M+1}, a_M); returns signs and logs
    of a_{M+1}, a_M, ..., a_{M-steps} (outermost first)."""
    signs, logs = [s_next, s_far], [L_next, L_far]
    for _ in range(steps):
        s, L = _backward_step(signs[-2], logs[-2], signs[-1], logs[-1], alpha)
        signs.append(s)
        logs.append(L)
    return np.array(signs), np.array(logs)


def log_tail(a_junction: float, alpha: float, length: int,
             extra: int = 8) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The tail of a homoclinic solution of (dpsstn) from one site outwards, far below
    machine precision, as (sign, ln|a_n|) for ``length`` sites starting at the given one.

    The exact recursion of (dpsstn) is run backward in logarithmic variables
    (:func:`_backward_step`) from a far site M = length + extra: there any
    start near the decay law a_{M+1} = -sign(a_M) |a_M|^alpha is drawn onto the
    solution's stable manifold as the recursion runs inward (deviations
    shrink at every step), and log|a_M| is fixed by bisection so that the
    backward tail reproduces ``a_junction`` at the first site. The last
    ``extra`` sites, nearest the arbitrary start, are dropped.
    """
    return log_tail_log(float(np.sign(a_junction)), float(np.log(abs(a_junction))), alpha, length, extra)


def log10_abs(a: ArrayLike, alpha: float, floor: float = 1e-9, centre: int | None = None) -> NDArray[np.float64]:
    """log10|a_n| of a homoclinic solution on every site, exact far below machine precision.

    Sites where |a_n| > floor * max|a| keep their double-precision value;
    beyond, on each side of the core, the tail comes from :func:`log_tail`
    (the equation is invariant under n -> -n, so the left tail is a right
    tail of the reflected sequence). On a ring each tail runs to the
    antipode of ``centre`` (default: the site of max |a_n|).
    """
    a = np.asarray(a, dtype=float)
    N = a.size
    c = int(np.argmax(np.abs(a))) if centre is None else centre
    out = np.log10(np.abs(a), where=a != 0, out=np.full(N, -np.inf))
    top = float(np.max(np.abs(a)))
    for direction in (1, -1):
        order = [(c + direction * k) % N for k in range(N // 2 + 1)]
        vals = a[order]
        big = np.flatnonzero(np.abs(vals) > floor * top)
        j = int(big[-1])                           # last trusted site on this side
        length = len(order) - j
        _, L = log_tail(vals[j], alpha, length)
        for k in range(length):
            out[order[j + k]] = L[k] / np.log(10.0)
    return out


def log10_abs_scaled(sol: ScaledProfile, floor: float = 1e-9,
                     centre: int | None = None) -> NDArray[np.float64]:
    """log10 |a_n| of a :class:`~cradle.models.homoclinic_continuation.ScaledHomoclinic` on every site
    (periodic ends), never underflowing.

    The profile b solves (dpsst) with mu = nu, so nu^(1/(alpha-1)) b solves
    (dpsstn) with an amplitude that may underflow; the tails are continued in
    log variables from the profile, shifted by log10 nu/(alpha-1), exactly as
    :func:`log10_abs` does (:func:`log_tail_log`), then scaled to the requested mu.
    """
    b, alpha = sol.profile, sol.alpha
    N = b.size
    c = int(np.argmax(np.abs(b))) if centre is None else centre
    shift = -np.log(sol.nu) / (alpha - 1.0)            # ln of the factor from b to the mu = 1 solution
    out = np.log10(np.abs(b), where=b != 0, out=np.full(N, -np.inf))
    for direction in (1, -1):
        order = [(c + direction * k) % N for k in range(N // 2 + 1)]
        vals = b[order]
        big = np.flatnonzero(np.abs(vals) > floor)
        j = int(big[-1])
        length = len(order) - j
        _, L = log_tail_log(float(np.sign(vals[j])), float(np.log(abs(vals[j]))) + shift, alpha, length)
        for k in range(length):
            out[order[j + k]] = (L[k] - shift) / np.log(10.0)
    return out + sol.log10_scale


@checked
def log_tail_log(sign_j: float, L_j: float, alpha: float, length: int,
                 extra: int = 8) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """:func:`log_tail` with the junction value given as (sign, ln|a_j|), so that it may be far below
    the smallest double (mu = 1 solutions near alpha = 1). The bracket on ln|a_M| is widened until it
    holds the root."""
    depth = length + extra
    s_far = sign_j * (-1.0) ** depth

    def end(L_far: float) -> float:
        with np.errstate(all="ignore"):
            v = _tail_from(s_far, L_far, -s_far, alpha * L_far, depth, alpha)[1][-1]
        return v if np.isfinite(v) else np.inf   # a start too close to the core blows up: "too big"

    lo, hi = L_j * alpha ** (depth + 2), L_j * alpha ** (depth - 2)
    for _ in range(200):                      # widen: end() grows with L_far
        if end(lo) < L_j:
            break
        lo *= 2.0
    for _ in range(200):
        if end(hi) >= L_j or hi > -1e-300:
            break
        hi *= 0.5
    for _ in range(400):
        mid = 0.5 * (lo + hi)
        if end(mid) < L_j:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 4e-16 * abs(mid):
            break
    sg, L = _tail_from(s_far, 0.5 * (lo + hi), -s_far, alpha * 0.5 * (lo + hi), depth, alpha)
    return sg[::-1][:length], L[::-1][:length]


def decay_sites(log10a: ArrayLike, decades: float = 16.0, centre: int | None = None) -> int:
    """Sites from the centre (largest |a_n|) until log10|a_n| is ``decades`` below its maximum, on the
    slower side; the half-width of the core at that level. ``len(log10a)//2 + 1`` if never reached."""
    L = np.asarray(log10a, dtype=float)
    N = L.size
    c = int(np.argmax(L)) if centre is None else centre
    top = L[c]
    worst = 0
    for direction in (1, -1):
        k_hit = N // 2 + 1
        for k in range(1, N // 2 + 1):
            if L[(c + direction * k) % N] <= top - decades:
                k_hit = k
                break
        worst = max(worst, k_hit)
    return worst
