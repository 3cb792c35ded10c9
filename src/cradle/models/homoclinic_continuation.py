"""Homoclinic solutions of (dpsst) for any alpha > 1: unit-amplitude profiles continued in alpha.

The paper's starts (:func:`cradle.models.homoclinic.initial_guess`) converge
at alpha = 3/2 but not far from it, and the mu = 1 amplitude of (dpsstn)
underflows as alpha -> 1+. Here (dpsst) is solved for a unit-amplitude
profile and the mu it solves (:func:`solve_scaled`), the profile is carried
from alpha = 3/2 to any alpha by continuation in ln(alpha - 1)
(:func:`continued`), the ring is sized from the decay of the tails
(:func:`solve_sized`), and :func:`solve_kind` gives the homoclinic of figure
bcsc for any alpha: the paper's procedure where it works, continuation
where it does not.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import root

from cradle.models.dps import p_laplacian
from cradle.models.homoclinic import (
    RESIDUAL_TOL,
    Homoclinic,
    _start,
    initial_guess,
    jacobian,
    localised,
    residual,
    solve,
)
from cradle.models.homoclinic_tails import decay_sites, log10_abs_scaled
from cradle.specs.checked import checked


@dataclass
class ScaledHomoclinic:
    """A homoclinic solution of (dpsst) held as a unit-amplitude profile and a scale.

    The solution of (dpsst) with the requested mu is ``a = 10**log10_scale * profile``;
    ``profile`` (max |profile_n| = 1) solves (dpsst) with mu = ``nu``. ``a`` itself is
    10**log10_scale * profile in double precision and may underflow (to 0, flagged by
    ``underflow``) when alpha -> 1+; ``log10_scale`` never does.
    """
    profile: np.ndarray     # unit-amplitude solution b_n of -nu b_n = g(b_{n+1}-b_n) - g(b_n-b_{n-1})
    nu: float               # the mu of (dpsst) that ``profile`` solves
    log10_scale: float      # log10 of the factor (mu/nu)^(1/(alpha-1)) to the requested mu
    mu: float
    alpha: float
    bc: str
    residual: float         # max_n |residual| of the profile's equation (max |profile| = 1: relative)
    converged: bool
    n_iterations: int
    message: str
    pin: int                # site held fixed (the largest |guess_n|)

    @property
    def a(self) -> np.ndarray:
        """The solution of (dpsst) at the requested mu in double precision (0 where it underflows)."""
        return self.profile * 10.0**self.log10_scale if self.log10_scale > -300 else \
            np.exp(np.log(np.abs(self.profile), where=self.profile != 0, out=np.full(self.profile.size, -np.inf))
                   + self.log10_scale * np.log(10.0)) * np.sign(self.profile)

    @property
    def underflow(self) -> bool:
        """True when max |a_n| is not representable as a normal double (log10 < -307)."""
        return self.log10_scale < -307.0

    @property
    def log10_amplitude(self) -> float:
        """log10 max_n |a_n| (= log10_scale, the profile having unit amplitude)."""
        return self.log10_scale


def _sparse_solve(J: NDArray[np.float64], r: NDArray[np.float64]) -> NDArray[np.float64] | None:
    """J^{-1} r by SuperLU (J is tridiagonal with corners plus one column): single-threaded, unlike a
    dense LAPACK solve, which under a multithreaded BLAS on a loaded machine costs ~30 ms at N = 128
    instead of ~0.2 ms. None if J is singular."""
    import warnings

    from scipy.sparse import csc_matrix
    from scipy.sparse.linalg import MatrixRankWarning, spsolve

    with warnings.catch_warnings():
        warnings.simplefilter("error", MatrixRankWarning)
        try:
            x = spsolve(csc_matrix(J), r)
        except (MatrixRankWarning, RuntimeError):
            return None
    return x if np.all(np.isfinite(x)) else None


@checked
def solve_scaled(guess: ArrayLike, alpha: float, bc: str = "periodic", mu: float = 1.0, xtol: float = 1e-14,
                 newton_steps: int = 4) -> ScaledHomoclinic:
    """Solve (dpsst) through a unit-amplitude profile: robust for any alpha > 1.

    (dpsst) is homogeneous: if b solves it with mu = nu, then
    a = (mu/nu)^(1/(alpha-1)) b solves it with mu. So the largest site of the
    guess, c, is pinned to b_c = sign(guess_c) (unit amplitude) and the
    unknowns are b_n (n != c) and ln nu: N equations, N unknowns, all O(1)
    for every alpha. The mu = 1 amplitude (mu/nu)^(1/(alpha-1)) itself is
    only formed at the end, as a log10: it is ~1e-61 at alpha = 1.01 and
    underflows below alpha ~ 1.002, where the direct solve of
    :func:`~cradle.models.homoclinic.solve` (unknowns of that size, starting from 0.1) either stalls
    or converges to a = 0. Powell's hybrid method with the analytic
    Jacobian, then Newton steps. The start for nu is the balance at the
    pinned site, nu0 = -(p-Laplacian of b)_c / b_c (2 for a single-site guess).
    """
    guess = _start(guess, mu)
    top = float(np.max(np.abs(guess)))
    if not (np.isfinite(top) and top > 0):
        raise ValueError(f"the guess must be finite and not identically 0, got max|guess| = {top!r}")
    N = guess.size
    c = int(np.argmax(np.abs(guess)))
    b0 = guess / top
    lap_c = float(p_laplacian(b0, alpha, bc)[c])
    nu0 = -lap_c / b0[c]
    nu0 = nu0 if np.isfinite(nu0) and nu0 > 0 else 2.0
    free = np.array([n for n in range(N) if n != c])

    def unpack(z: NDArray[np.float64]) -> tuple[NDArray[np.float64], float]:
        b = b0.copy()
        b[free] = z[:-1]
        return b, z[-1]

    def F(z: NDArray[np.float64]) -> NDArray[np.float64]:
        b, m = unpack(z)
        return residual(b, alpha, bc, sign=np.exp(m))

    def JF(z: NDArray[np.float64]) -> NDArray[np.float64]:
        b, m = unpack(z)
        nu = np.exp(m)
        J = jacobian(b, alpha, bc, sign=nu)
        return np.column_stack((J[:, free], nu * b))

    z = np.concatenate((b0[free], [np.log(nu0)]))
    sol = root(F, z, jac=JF, method="hybr", options={"xtol": xtol})
    z = sol.x
    for _ in range(newton_steps):
        r = F(z)
        step = _sparse_solve(JF(z), r)
        if step is None:
            break
        z_new = z - step
        if np.max(np.abs(F(z_new))) < np.max(np.abs(r)):
            z = z_new
    b, m = unpack(z)
    nu = float(np.exp(m))
    amp = float(np.max(np.abs(b)))        # the pin need not stay the largest site: renormalise
    res = float(np.max(np.abs(F(z)))) / amp
    b = b / amp
    nu = nu * amp ** (alpha - 1.0)        # b/amp solves (dpsst) with nu amp^(alpha-1)
    log10_scale = (np.log10(mu) - np.log10(nu)) / (alpha - 1.0)
    converged = bool(np.isfinite(res) and res <= RESIDUAL_TOL and np.all(np.isfinite(b)))
    return ScaledHomoclinic(profile=b, nu=nu, log10_scale=float(log10_scale), mu=float(mu), alpha=alpha, bc=bc,
                            residual=res, converged=converged, n_iterations=int(sol.nfev), message=str(sol.message),
                            pin=c)


@checked
def continued(kind: str, alpha: float, N: int, bc: str = "periodic", mu: float = 1.0, centre: int | None = None,
              separation: int = 9, alpha_start: float = 1.5, step: float = 0.25) -> ScaledHomoclinic:
    """A homoclinic of (dpsst) at any alpha > 1 by continuation in alpha from the paper's case.

    The paper's starts (:func:`~cradle.models.homoclinic.initial_guess`) converge at alpha = 3/2; far
    from it they do not (at alpha = 2 and 3 the site start falls to a = 0, at
    alpha = 1.1 the bond start stalls, at alpha = 1.01 a non-localised
    solution is found). So the profile is solved by :func:`solve_scaled` at
    ``alpha_start`` and carried to ``alpha`` in steps of ``step`` in
    ln(alpha - 1), each solve starting from the previous unit-amplitude
    profile. ``double``: two continued site humps ``separation`` sites apart,
    solved once more at ``alpha``. Raises ValueError naming alpha if a step
    does not converge.
    """
    if kind == "double":
        hump = continued("site", alpha, N, bc, 1.0, centre, alpha_start=alpha_start, step=step).profile
        guess = np.roll(hump, -(separation // 2)) + np.roll(hump, separation - separation // 2)
        sol = solve_scaled(guess, alpha, bc, mu)
    else:
        sol = solve_scaled(initial_guess(N, kind, alpha_start, 0.1, centre=centre), alpha_start, bc, mu)
        l0, l1 = np.log(alpha_start - 1.0), np.log(alpha - 1.0)
        n = max(1, int(np.ceil(abs(l1 - l0) / step)))
        for lal in np.linspace(l0, l1, n + 1)[1:]:
            if not sol.converged:
                break
            sol = solve_scaled(sol.profile, 1.0 + float(np.exp(lal)), bc, mu)
        if sol.converged and sol.alpha != alpha:   # the last node of the path is alpha up to rounding
            sol = solve_scaled(sol.profile, alpha, bc, mu)
    if not sol.converged:
        raise ValueError(f"{kind} homoclinic: continuation in alpha from {alpha_start} to alpha={alpha!r} failed "
                         f"on N={N} (residual {sol.residual:.3e} at alpha={sol.alpha!r}: "
                         f"{' '.join(sol.message.split())})")
    return sol


@checked
def solve_sized(kind: str, alpha: float, mu: float = 1.0, decades: float = 16.0, margin: int = 2,
                N_min: int = 16, N_max: int = 1 << 14) -> tuple[ScaledHomoclinic, int]:
    """A periodic homoclinic of (dpsst) on a ring just wide enough for its core: N chosen from its decay.

    The half-width k is the number of sites from the centre at which |a_n|
    has dropped ``decades`` decades below max |a_n| (:func:`decay_sites` on
    :func:`log10_abs_scaled`). N doubles from ``N_min`` until
    k + margin < N/2 (so the antipode is ``decades`` decades down and
    the ring solution is the lattice one to that accuracy), then shrinks to
    the even N = 2 (k + margin) + 2 and is solved once more there. The
    width grows as alpha -> 1+ (about 4.3 (alpha-1)^(-1/2) sites at 8
    decades, sqrt(8 ln 10) of the log-NLS Gaussian of :mod:`cradle.models.continuum`: 14 at alpha = 1.1, 44 at
    1.01), so N = 50 no longer holds the
    breather of figure bcsc below alpha ~ 1.05. Returns (solution, N).
    """
    if kind not in ("site", "bond"):
        raise ValueError(f"solve_sized: kind must be 'site' or 'bond' (a double hump has a set separation), "
                         f"got kind={kind!r}")
    N = max(int(N_min), 8)
    N += N % 2
    while True:
        sol = continued(kind, alpha, N, mu=mu)
        k = decay_sites(log10_abs_scaled(sol), decades)
        if k + margin < N // 2:
            break
        if 2 * N > N_max:
            raise ValueError(f"solve_sized: the {kind} homoclinic at alpha={alpha!r} needs more than "
                             f"N_max={N_max} sites to decay by {decades} decades")
        N *= 2
    N_fit = 2 * (k + margin) + 2
    if N_fit < N:
        c = int(np.argmax(np.abs(sol.profile)))
        guess = sol.profile[[(c - N_fit // 2 + i) % N for i in range(N_fit)]]
        fit = solve_scaled(guess, alpha, "periodic", mu)
        if fit.converged and decay_sites(log10_abs_scaled(fit), decades) + margin < N_fit // 2:
            return fit, N_fit
    return sol, N


@checked
def solve_kind(N: int, kind: str, alpha: float, bc: str = "periodic", mu: float = 1.0, amplitude: float = 0.1,
               centre: int | None = None, separation: int = 9) -> Homoclinic:
    """The homoclinic of figure bcsc for any alpha > 1: the paper's start first, continuation if it fails.

    :func:`~cradle.models.homoclinic.solve` from
    :func:`~cradle.models.homoclinic.initial_guess` (the paper's procedure; at
    alpha = 3/2 nothing changes) is kept when it converges to a nontrivial,
    localised solution (:func:`~cradle.models.homoclinic.localised`). Otherwise (alpha = 2 and 3: site
    start falls to 0; alpha = 1.1: bond start stalls; alpha = 1.01: a
    non-localised solution) the profile is continued in alpha from 3/2 in
    rescaled variables (:func:`continued`). ``log10_amplitude`` is always
    set. Below alpha ~ 1.002 (mu = 1) ``a`` would underflow: ValueError
    naming alpha, mu and the amplitude (the rescaled profile of
    :func:`continued` / :func:`solve_scaled` remains available).
    """
    sol = solve(initial_guess(N, kind, alpha, amplitude, centre=centre, separation=separation), alpha, bc, mu=mu) \
        if kind != "double" or alpha == 1.5 else None
    if sol is not None and sol.converged and localised(sol.a) and np.max(np.abs(sol.a)) > 0:
        sol.log10_amplitude = float(np.log10(np.max(np.abs(sol.a))))
        return sol
    sc = continued(kind, alpha, N, bc, mu, centre, separation)
    if sc.underflow:
        raise ValueError(f"{kind} homoclinic at alpha={alpha!r}, mu={mu!r}: max|a_n| = 10^{sc.log10_scale:.1f} "
                         f"underflows double precision; take mu >= {10.0 ** (np.log10(sc.nu) - 300 * (alpha - 1)):.3g} "
                         f"or use the unit-amplitude profile of homoclinic_continuation.solve_scaled / continued")
    a = sc.a
    res = float(np.max(np.abs(residual(a, alpha, bc, sign=mu))))
    return Homoclinic(a=a, residual=res, converged=bool(sc.converged), n_iterations=sc.n_iterations,
                      message=sc.message, method="continued", log10_amplitude=sc.log10_scale)


#: sites of the chain on which :func:`zero_at` solves a long chain's profile (its tails leave double precision
#: within ~15 sites of its centre at alpha = 3/2): a solve of this size takes milliseconds
WINDOW = 64


@functools.lru_cache(maxsize=256)   # a config is validated again and again (Snakemake, the fuzz): solve once
def zero_at(site: int, N: int, kind: str, alpha: float, bc: str = "periodic", mu: float = 1.0,
            amplitude: float = 0.1, centre: int | None = None, separation: int = 9) -> bool | None:
    """Whether the profile :func:`solve_kind` gives for these arguments is 0 (in double precision) at ``site``:
    beyond its core |a_n| falls super-exponentially and underflows to 0 within a few sites. A chain of at most
    :data:`WINDOW` sites (plus the separation of a double guess) is solved as the homoclinic job solves it; a longer
    one on a window of that many sites around its core (a ring, or the free end it is near), whose profile is the
    chain's wherever the window's own ends are 0. None when this cannot say: the window's profile reaches its ends
    (alpha near 1: wide tails) or the solve fails (the homoclinic job reports that)."""
    c = N // 2 if centre is None else centre
    size = WINDOW + (separation if kind == "double" else 0)
    try:
        if N <= size:
            return bool(solve_kind(N, kind, alpha, bc, mu, amplitude, centre, separation).a[site] == 0)
        start, wbc = c - size // 2, "periodic"     # the window's first site on the chain
        if bc == "free" and not size // 2 <= c <= N - 1 - size // 2:
            start, wbc = (0 if c < size // 2 else N - size), "free"
        a = solve_kind(size, kind, alpha, wbc, mu, amplitude, c - start, separation).a
    except (ValueError, ArithmeticError, np.linalg.LinAlgError):
        return None
    if wbc == "periodic" and (a[0] != 0 or a[-1] != 0) or wbc == "free" and a[-1 if start == 0 else 0] != 0:
        return None
    k = (site - start) % N if bc == "periodic" else site - start
    return not 0 <= k < size or bool(a[k] == 0)


@functools.lru_cache(maxsize=256)   # a config is validated again and again (Snakemake, the fuzz): solve once
def solve_fails(N: int, kind: str, alpha: float, bc: str = "periodic", mu: float = 1.0, amplitude: float = 0.1,
                centre: int | None = None, separation: int = 9) -> str | None:
    """Why :func:`solve_kind` fails for these arguments (it raises, or its answer did not converge or is not
    finite: what the homoclinic job refuses), for a chain of at most :data:`WINDOW` sites, where the solve takes
    milliseconds; None when it succeeds, or for a longer chain (not tried)."""
    if N > WINDOW:
        return None
    try:
        sol = solve_kind(N, kind, alpha, bc, mu, amplitude, centre, separation)
    except (ValueError, ArithmeticError, np.linalg.LinAlgError) as err:
        return " ".join(str(err).split())
    if not sol.converged or not np.all(np.isfinite(sol.a)):
        return f"Powell hybrid did not converge (residual {sol.residual:.3e})"
    return None
