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

from cradle.models.dps import differences, p_laplacian
from cradle.models.lattice import check_alpha, check_bc


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
    method: str = "direct"          # "direct" (the paper's Powell start) or "continued" (:func:`continued`)
    log10_amplitude: float | None = None   # log10 max|a_n|


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


def _checked(guess, alpha: float, bc: str, mu: float):
    """(alpha, guess as a float array) after checking alpha > 1, bc, mu > 0 and N >= 2."""
    alpha = check_alpha(alpha)
    check_bc(bc)
    if not mu > 0:
        raise ValueError(f"mu must be > 0 for nontrivial localised solutions (section 2.2), got mu={mu!r}")
    guess = np.asarray(guess, dtype=float)
    if guess.ndim != 1 or guess.size < 2:
        raise ValueError(f"need N >= 2 sites, got N={guess.size}")
    return alpha, guess


def solve(guess, alpha: float, bc: str = "periodic", mu: float = 1.0, xtol: float = 1e-14,
          newton_steps: int = 3) -> Homoclinic:
    """Solve (dpsst) -mu a_n = g(a_{n+1}-a_n) - g(a_n-a_{n-1}) from ``guess`` (a mu = 1 guess).

    The normalised problem (dpsstn) is solved by Powell's hybrid method with
    the analytic Jacobian and polished with a few Newton steps; the result is
    scaled by mu^(1/(alpha-1)). ``residual`` is the max-norm residual of the
    scaled equation (dpsst).
    """
    alpha, guess = _checked(guess, alpha, bc, mu)
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


def localised(a, ratio: float = 1e-3) -> bool:
    """True if |a_n| at the site farthest (on the ring) from the largest |a_n| is below ``ratio`` max|a_n|:
    a homoclinic, not a non-localised solution of (dpsstn) (which hybr finds near alpha = 1)."""
    a = np.asarray(a, dtype=float)
    top = float(np.max(np.abs(a)))
    if not (np.isfinite(top) and top > 0):
        return False
    c = int(np.argmax(np.abs(a)))
    return bool(abs(a[(c + a.size // 2) % a.size]) <= ratio * top)


def solve_kind(N: int, kind: str, alpha: float, bc: str = "periodic", mu: float = 1.0, amplitude: float = 0.1,
               centre: int | None = None, separation: int = 9) -> Homoclinic:
    """The homoclinic of figure bcsc for any alpha > 1: the paper's start first, continuation if it fails.

    :func:`solve` from :func:`initial_guess` (the paper's procedure; at
    alpha = 3/2 nothing changes) is kept when it converges to a nontrivial,
    localised solution (:func:`localised`). Otherwise (alpha = 2 and 3: site
    start falls to 0; alpha = 1.1: bond start stalls; alpha = 1.01: a
    non-localised solution) the profile is continued in alpha from 3/2 in
    rescaled variables (:func:`continued`). ``log10_amplitude`` is always
    set. Below alpha ~ 1.002 (mu = 1) ``a`` would underflow: ValueError
    naming alpha, mu and the amplitude (the rescaled profile of
    :func:`continued` / :func:`solve_scaled` remains available).
    """
    alpha = check_alpha(alpha)
    sol = solve(initial_guess(N, kind, alpha, amplitude, centre=centre, separation=separation), alpha, bc, mu=mu) \
        if kind != "double" or alpha == 1.5 else None
    if sol is not None and sol.converged and localised(sol.a) and np.max(np.abs(sol.a)) > 0:
        sol.log10_amplitude = float(np.log10(np.max(np.abs(sol.a))))
        return sol
    sc = continued(kind, alpha, N, bc, mu, centre, separation)
    if sc.underflow:
        raise ValueError(f"{kind} homoclinic at alpha={alpha!r}, mu={mu!r}: max|a_n| = 10^{sc.log10_scale:.1f} "
                         f"underflows double precision; take mu >= {10.0 ** (np.log10(sc.nu) - 300 * (alpha - 1)):.3g} "
                         f"or use the unit-amplitude profile of homoclinic.solve_scaled / continued")
    a = sc.a
    res = float(np.max(np.abs(residual(a, alpha, bc, sign=mu))))
    return Homoclinic(a=a, residual=res, converged=bool(sc.converged), n_iterations=sc.n_iterations,
                      message=sc.message, method="continued", log10_amplitude=sc.log10_scale)


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
    return log_tail_log(float(np.sign(a_junction)), float(np.log(abs(a_junction))), alpha, length, extra)


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


# ---------------------------------------------------------------- rescaled solve (alpha -> 1+, alpha >= 2)

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


def _sparse_solve(J, r):
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


def solve_scaled(guess, alpha: float, bc: str = "periodic", mu: float = 1.0, xtol: float = 1e-14,
                 newton_steps: int = 4) -> ScaledHomoclinic:
    """Solve (dpsst) through a unit-amplitude profile: robust for any alpha > 1.

    (dpsst) is homogeneous: if b solves it with mu = nu, then
    a = (mu/nu)^(1/(alpha-1)) b solves it with mu. So the largest site of the
    guess, c, is pinned to b_c = sign(guess_c) (unit amplitude) and the
    unknowns are b_n (n != c) and ln nu: N equations, N unknowns, all O(1)
    for every alpha. The mu = 1 amplitude (mu/nu)^(1/(alpha-1)) itself is
    only formed at the end, as a log10: it is ~1e-61 at alpha = 1.01 and
    underflows below alpha ~ 1.002, where the direct solve of
    :func:`solve` (unknowns of that size, starting from 0.1) either stalls
    or converges to a = 0. Powell's hybrid method with the analytic
    Jacobian, then Newton steps. The start for nu is the balance at the
    pinned site, nu0 = -(p-Laplacian of b)_c / b_c (2 for a single-site guess).
    """
    alpha, guess = _checked(guess, alpha, bc, mu)
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

    def unpack(z):
        b = b0.copy()
        b[free] = z[:-1]
        return b, z[-1]

    def F(z):
        b, m = unpack(z)
        return residual(b, alpha, bc, sign=np.exp(m))

    def JF(z):
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


def log10_abs_scaled(sol: ScaledHomoclinic, floor: float = 1e-9, centre: int | None = None):
    """log10 |a_n| of a :class:`ScaledHomoclinic` on every site (periodic ends), never underflowing.

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


def log_tail_log(sign_j: float, L_j: float, alpha: float, length: int, extra: int = 8):
    """:func:`log_tail` with the junction value given as (sign, ln|a_j|), so that it may be far below
    the smallest double (mu = 1 solutions near alpha = 1). The bracket on ln|a_M| is widened until it
    holds the root."""
    alpha = check_alpha(alpha)
    depth = length + extra
    s_far = sign_j * (-1.0) ** depth

    def end(L_far):
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


def decay_sites(log10a, decades: float = 16.0, centre: int | None = None) -> int:
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


def continued(kind: str, alpha: float, N: int, bc: str = "periodic", mu: float = 1.0, centre: int | None = None,
              separation: int = 9, alpha_start: float = 1.5, step: float = 0.25) -> ScaledHomoclinic:
    """A homoclinic of (dpsst) at any alpha > 1 by continuation in alpha from the paper's case.

    The paper's starts (:func:`initial_guess`) converge at alpha = 3/2; far
    from it they do not (at alpha = 2 and 3 the site start falls to a = 0, at
    alpha = 1.1 the bond start stalls, at alpha = 1.01 a non-localised
    solution is found). So the profile is solved by :func:`solve_scaled` at
    ``alpha_start`` and carried to ``alpha`` in steps of ``step`` in
    ln(alpha - 1), each solve starting from the previous unit-amplitude
    profile. ``double``: two continued site humps ``separation`` sites apart,
    solved once more at ``alpha``. Raises ValueError naming alpha if a step
    does not converge.
    """
    alpha = check_alpha(alpha)
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


def solve_sized(kind: str, alpha: float, mu: float = 1.0, decades: float = 16.0, margin: int = 2,
                N_min: int = 16, N_max: int = 1 << 14) -> tuple[ScaledHomoclinic, int]:
    """A periodic homoclinic of (dpsst) on a ring just wide enough for its core: N chosen from its decay.

    The half-width k is the number of sites from the centre at which |a_n|
    has dropped ``decades`` decades below max |a_n| (:func:`decay_sites` on
    :func:`log10_abs_scaled`). N doubles from ``N_min`` until
    k + margin < N/2 (so the antipode is ``decades`` decades down and
    the ring solution is the lattice one to that accuracy), then shrinks to
    the even N = 2 (k + margin) + 2 and is solved once more there. The
    width grows as alpha -> 1+ (about 0.4 (alpha-1)^(-1/2) sites at 8
    decades: 14 at alpha = 1.1, 44 at 1.01), so N = 50 no longer holds the
    breather of figure bcsc below alpha ~ 1.05. Returns (solution, N).
    """
    alpha = check_alpha(alpha)
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
