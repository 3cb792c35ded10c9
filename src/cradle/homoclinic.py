"""Homoclinic (breather) solutions of the stationary DpS equation (dpsstn).

    -sign(mu) a_n = g(a_{n+1} - a_n) - g(a_n - a_{n-1}),   g(s) = s |s|^(alpha-1)   (dpsstn)

solved on N sites with periodic (a_{n+N} = a_n) or free-end conditions (no
bond beyond the ends, as in figure fini), by MINPACK's modified Powell hybrid
method (scipy ``root(method="hybr")``, the algorithm behind Scilab's fsolve
that the paper used) with the analytic tridiagonal Jacobian, then polished by
Newton steps. A solution of (dpsst) with any mu > 0 is |mu|^(1/(alpha-1))
times the mu = 1 solution (the scaling that leads to (dpsstn)).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import root

from .dps import differences, p_laplacian
from .lattice import check_alpha, check_bc


RESIDUAL_TOL = 1e-10  # max |residual| / max |a_n| accepted as converged


def _dg(s, alpha):
    return alpha * np.abs(s) ** (alpha - 1.0)


def residual(a, alpha: float, bc: str = "periodic", sign: float = 1.0):
    """r_n = g(a_{n+1}-a_n) - g(a_n-a_{n-1}) + sign a_n: zero on solutions of (dpsstn) for
    sign = sign(mu), of (dpsst) for sign = mu."""
    a = np.asarray(a, dtype=float)
    return p_laplacian(a, alpha, bc) + sign * a


def jacobian(a, alpha: float, bc: str = "periodic", sign: float = 1.0):
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
    a: np.ndarray          # solution a_n, n = 0..N-1 (mu = 1 scaling unless mu given)
    residual: float        # max_n |r_n| of (dpsst) at the returned a
    converged: bool
    n_iterations: int
    message: str


def initial_guess(N: int, kind: str, alpha: float = 1.5, amplitude: float = 0.1,
                  centre: int | None = None, separation: int = 9):
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


def solve(guess, alpha: float, bc: str = "periodic", mu: float = 1.0, xtol: float = 1e-14,
          newton_steps: int = 3) -> Homoclinic:
    """Solve (dpsst) -mu a_n = g(a_{n+1}-a_n) - g(a_n-a_{n-1}) from ``guess`` (a mu = 1 guess).

    The normalised problem (dpsstn) is solved by Powell's hybrid method with
    the analytic Jacobian and polished with a few Newton steps; the result is
    scaled by mu^(1/(alpha-1)). ``residual`` is the max-norm residual of the
    scaled equation (dpsst).
    """
    alpha = check_alpha(alpha)
    check_bc(bc)
    if not mu > 0:
        raise ValueError(f"mu must be > 0 for nontrivial localised solutions (section 2.2), got mu={mu!r}")
    guess = np.asarray(guess, dtype=float)
    if guess.ndim != 1 or guess.size < 2:
        raise ValueError(f"need N >= 2 sites, got N={guess.size}")
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


def symmetry_error(a, kind: str, centre: int | None = None) -> float:
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


def energy_balance(a, alpha: float, bc: str = "periodic"):
    """(sum a_n^2, sum |a_{n+1}-a_n|^(alpha+1)): equal for mu = 1 solutions of (dpsstn)."""
    a = np.asarray(a)
    return float(np.sum(a**2)), float(np.sum(np.abs(differences(a, bc)) ** (alpha + 1.0)))


# ---------------------------------------------------------------- tails below machine precision

def _backward_step(s1, L1, s0, L0, alpha):
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


def _tail_from(s_far, L_far, s_next, L_next, steps, alpha):
    """Iterate :func:`_backward_step` ``steps`` times from (a_{M+1}, a_M); returns signs and logs
    of a_{M+1}, a_M, ..., a_{M-steps} (outermost first)."""
    signs, logs = [s_next, s_far], [L_next, L_far]
    for _ in range(steps):
        s, L = _backward_step(signs[-2], logs[-2], signs[-1], logs[-1], alpha)
        signs.append(s)
        logs.append(L)
    return np.array(signs), np.array(logs)


def log_tail(a_junction: float, alpha: float, length: int, extra: int = 8):
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
    alpha = check_alpha(alpha)
    depth = length + extra
    s_j, L_j = float(np.sign(a_junction)), float(np.log(abs(a_junction)))
    s_far = s_j * (-1.0) ** depth               # signs alternate in a tail

    def run(L_far):
        return _tail_from(s_far, L_far, -s_far, alpha * L_far, depth, alpha)

    # log|a_j| grows with log|a_M| (one decaying branch): bisect on log|a_M| ~ L_j alpha^depth
    lo, hi = L_j * alpha ** (depth + 2), L_j * alpha ** (depth - 2)
    for _ in range(400):
        mid = 0.5 * (lo + hi)
        if run(mid)[1][-1] < L_j:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 4e-16 * abs(mid):
            break
    sg, L = run(0.5 * (lo + hi))
    return sg[::-1][:length], L[::-1][:length]   # site j, j+1, ..., j+length-1


def log10_abs(a, alpha: float, floor: float = 1e-9, centre: int | None = None):
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
