"""Homoclinic (breather) solutions of the stationary DpS equation (dpsstn) for one alpha.

    -sign(mu) a_n = g(a_{n+1} - a_n) - g(a_n - a_{n-1}),   g(s) = s |s|^(alpha-1)   (dpsstn)

solved on N sites with periodic (a_{n+N} = a_n) or free-end conditions (no
bond beyond the ends, as in figure fini), by MINPACK's modified Powell hybrid
method (scipy ``root(method="hybr")``, the algorithm behind Scilab's fsolve
that the paper used) with the analytic tridiagonal Jacobian, then polished by
Newton steps, from the paper's starts (section 2.2). A solution of (dpsst)
with any mu > 0 is |mu|^(1/(alpha-1)) times the mu = 1 solution (the scaling
that leads to (dpsstn)). Also the checks of a solution: residual, symmetry,
energy balance, localisation.

Far from alpha = 3/2 these starts fail; the unit-amplitude solve and the
continuation in alpha are in :mod:`cradle.models.homoclinic_continuation`,
the tails below machine precision in :mod:`cradle.models.homoclinic_tails`.
"""
from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import root

from cradle.models.dps import differences, p_laplacian
from cradle.specs.checked import checked

RESIDUAL_TOL = 1e-10  # max |residual| / max |a_n| accepted as converged


def _dg(s: NDArray[np.float64], alpha: float) -> NDArray[np.float64]:
    return alpha * np.abs(s) ** (alpha - 1.0)


def residual(a: ArrayLike, alpha: float, bc: str = "periodic", sign: float = 1.0) -> NDArray[np.float64]:
    """r_n = g(a_{n+1}-a_n) - g(a_n-a_{n-1}) + sign a_n: zero on solutions of (dpsstn) for
    sign = sign(mu), of (dpsst) for sign = mu."""
    a = np.asarray(a, dtype=float)
    return p_laplacian(a, alpha, bc) + sign * a


def jacobian(a: ArrayLike, alpha: float, bc: str = "periodic", sign: float = 1.0) -> NDArray[np.float64]:
    """Analytic Jacobian of :func:`residual` (tridiagonal, with corners if periodic)."""
    a = np.asarray(a, dtype=float)
    N = a.size
    k = _dg(differences(a, bc), alpha)  # stiffness of bond n (0 on a missing free-end bond)
    J = np.zeros((N, N))
    idx = np.arange(N)
    right = (idx + 1) % N
    left = (idx - 1) % N
    k_left = np.roll(k, 1)
    if bc == "free":
        k_left[0] = 0.0
    J[idx, idx] = sign - k - k_left
    np.add.at(J, (idx, right), k)
    np.add.at(J, (idx, left), k_left)
    return J


@dataclass
class Homoclinic:
    """A solution a_n of (dpsst) (mu = 1: (dpsstn)), its max-norm residual and how the solver got there."""

    a: np.ndarray          # solution a_n, n = 0..N-1 (mu = 1 scaling unless mu given)
    residual: float        # max_n |r_n| of (dpsst) at the returned a
    converged: bool
    n_iterations: int
    message: str
    method: str = "direct"          # "direct" (the paper's Powell start) or "continued" (homoclinic_continuation)
    log10_amplitude: float | None = None   # log10 max|a_n|


def initial_guess(N: int, kind: str, alpha: float = 1.5, amplitude: float = 0.1,
                  centre: int | None = None, separation: int = 9) -> NDArray[np.float64]:
    """The starting point of the Powell iteration (section 2.2).

    * ``site``: a_{N/2} = -amplitude, 0 elsewhere (the paper's site-centred start);
    * ``bond``: a_{N/2} = amplitude, a_{N/2+1} = -amplitude (the paper's bond-centred start);
    * ``double``: the sum of two copies of the converged site-centred solution,
      ``separation`` sites apart around N/2. The paper does not give its start
      for the double-humped solution; two single-site seeds do not converge
      (hybr stalls at residuals ~1e-7), two converged humps do for
      separations of 9 and more on N = 50.
    """
    c = N // 2 if centre is None else centre
    a = np.zeros(N)
    if kind == "site":
        a[c % N] = -amplitude
    elif kind == "bond":
        a[c % N], a[(c + 1) % N] = amplitude, -amplitude
    elif kind == "double":
        hump = solve(initial_guess(N, "site", alpha, amplitude, centre=c), alpha).a
        a = np.roll(hump, -(separation // 2)) + np.roll(hump, separation - separation // 2)
    else:
        raise ValueError(f"unknown initial guess kind={kind!r} (site, bond, double)")
    return a


def guess_off_chain(N: int, kind: str, bc: str, centre: int | None = None, separation: int = 9) -> str | None:
    """Why :func:`initial_guess` would put a seed off a chain of N sites with free ends (``bc="free"``), or None.

    On a ring every site is a neighbour of another; with free ends the guess's sites must be beads of the chain,
    or the seed wraps to the other end (a bond-centred guess on the last bead is a_{N-1} and a_0): ``bond`` seeds
    the bond (c, c + 1), so c <= N - 2; ``double`` puts its humps on c - floor(s/2) and c + s - floor(s/2)."""
    if bc != "free":
        return None
    c = N // 2 if centre is None else centre
    if kind == "bond" and not c <= N - 2:
        return (f"a bond-centred guess seeds the bond ({c}, {c + 1}), which a chain of N = {N} with free ends does "
                f"not have: the centre must be <= N-2 = {N - 2}")
    if kind == "double":
        left, right = c - separation // 2, c + separation - separation // 2
        if not (0 <= left and right <= N - 1):
            return (f"the double guess's humps at {left} and {right} (centre {c}, separation {separation}) must be "
                    f"beads of a chain of N = {N} with free ends, in [0, {N - 1}]")
    return None


def _start(guess: ArrayLike, mu: float) -> np.ndarray:
    """``guess`` as a float array after checking mu > 0 and N >= 2 (alpha and bc: ``@checked``)."""
    if not mu > 0:
        raise ValueError(f"mu must be > 0 for nontrivial localised solutions (section 2.2), got mu={mu!r}")
    guess = np.asarray(guess, dtype=float)
    if guess.ndim != 1 or guess.size < 2:
        raise ValueError(f"need N >= 2 sites, got N={guess.size}")
    need, have = 8.0 * guess.size**2, _memory()
    if need > have:   # Powell's method and Newton hold the dense N x N Jacobian: refuse before allocating it
        raise ValueError(f"N = {guess.size}: the dense Jacobian alone needs {need / 2**30:.3g} GiB (N^2 doubles), "
                         f"more than this machine's {have / 2**30:.3g} GiB of memory")
    return guess


def _memory() -> float:
    """This machine's physical memory in bytes (inf where the system does not say)."""
    try:
        return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))
    except (AttributeError, ValueError, OSError):
        return float("inf")


@checked
def solve(guess: ArrayLike, alpha: float, bc: str = "periodic", mu: float = 1.0, xtol: float = 1e-14,
          newton_steps: int = 3) -> Homoclinic:
    """Solve (dpsst) -mu a_n = g(a_{n+1}-a_n) - g(a_n-a_{n-1}) from ``guess`` (a mu = 1 guess).

    The normalised problem (dpsstn) is solved by Powell's hybrid method with
    the analytic Jacobian and polished with a few Newton steps; the result is
    scaled by mu^(1/(alpha-1)). ``residual`` is the max-norm residual of the
    scaled equation (dpsst).
    """
    guess = _start(guess, mu)
    sol = root(residual, guess, args=(alpha, bc), jac=jacobian, method="hybr", options={"xtol": xtol})
    a = sol.x
    for _ in range(newton_steps):  # quadratic convergence from hybr's answer
        r = residual(a, alpha, bc)
        try:
            step = np.linalg.solve(jacobian(a, alpha, bc), r)
        except np.linalg.LinAlgError:
            break
        a_new = a - step
        if np.max(np.abs(residual(a_new, alpha, bc))) < np.max(np.abs(r)):
            a = a_new
    scale = mu ** (1.0 / (alpha - 1.0))
    a_mu = scale * a
    res = float(np.max(np.abs(residual(a_mu, alpha, bc, sign=mu))))  # residual of (dpsst)
    # hybr may report "no progress" once it sits at round-off; judge by the residual itself
    converged = res <= RESIDUAL_TOL * max(float(np.max(np.abs(a_mu))), np.finfo(float).tiny)
    return Homoclinic(a=a_mu, residual=res, converged=bool(converged), n_iterations=int(sol.nfev),
                      message=str(sol.message))


def localised(a: ArrayLike, ratio: float = 1e-3) -> bool:
    """True if |a_n| at the site farthest (on the ring) from the largest |a_n| is below ``ratio`` max|a_n|:
    a homoclinic, not a non-localised solution of (dpsstn) (which hybr finds near alpha = 1)."""
    a = np.asarray(a, dtype=float)
    top = float(np.max(np.abs(a)))
    if not (np.isfinite(top) and top > 0):
        return False
    c = int(np.argmax(np.abs(a)))
    return bool(abs(a[(c + a.size // 2) % a.size]) <= ratio * top)


def symmetry_error(a: ArrayLike, kind: str, centre: int | None = None) -> float:
    """Departure from the symmetry the solution should have.

    ``site``: a_{c-n} = a_{c+n}; ``bond``: a_{c-n} = -a_{c+n+1}.
    """
    a = np.asarray(a)
    N = a.size
    c = N // 2 if centre is None else centre
    n = np.arange(N // 2)
    if kind == "bond":
        return float(np.max(np.abs(a[(c - n) % N] + a[(c + n + 1) % N])))
    return float(np.max(np.abs(a[(c - n) % N] - a[(c + n) % N])))


def energy_balance(a: ArrayLike, alpha: float, bc: str = "periodic") -> tuple[float, float]:
    """(sum a_n^2, sum |a_{n+1}-a_n|^(alpha+1)): equal for mu = 1 solutions of (dpsstn)."""
    a = np.asarray(a)
    return float(np.sum(a**2)), float(np.sum(np.abs(differences(a, bc)) ** (alpha + 1.0)))

