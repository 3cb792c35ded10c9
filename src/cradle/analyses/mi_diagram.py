"""Linear stability of the DpS plane waves (ansatz3): the modulational-instability diagram.

In the rotating frame A_n = e^{i(Omega tau - q n)} (R + b_n), (dfnls) becomes

    2 i tau0 (b_n' + i Omega (R + b_n)) = g(D_n) - g(E_n),   g(z) = z |z|^(alpha-1),
    D_n = (R + b_{n+1}) e^{-iq} - (R + b_n),  E_n = (R + b_n) - (R + b_{n-1}) e^{iq},

whose fixed point b = 0 is the plane wave iff Omega obeys (ds). Linearising
g about z: dg = P dz + Q conj(dz), P = (alpha+1)/2 |z|^(alpha-1),
Q = (alpha-1)/2 |z|^(alpha-1) z/conj(z). A perturbation
b_n = beta e^{ipn} + conj(gamma) e^{-ipn} couples the sidebands p and -p:
(beta, gamma)' = L(q, p) (beta, gamma), a 2x2 complex matrix; the growth
rate is lambda(q, p) = max Re eig L. Every entry of L scales as
R^(alpha-1)/tau0 (scale invariance A -> R A, tau -> R^(1-alpha) tau), so
lambda tau0 R^(1-alpha) depends on (q, p) only: that is what we tabulate.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.protocol import Analysis
from cradle.data.variables import Var
from cradle.models import dps
from cradle.specs.declare import declared, param, plain

if TYPE_CHECKING:
    import xarray as xr
    from numpy.typing import ArrayLike, NDArray

    from cradle.analyses.protocol import Log
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors


@declared(doc="Linear stability of the DpS plane waves (ansatz3): growth-rate map over (q, p) -> "
              "results/mi-diagram/mi-diagram.nc and results/figures/mi-diagram.{pdf,png}.")
class MIDiagram:
    alpha: list[float] = param([1.5, 2.0, 3.0], "Exponents alpha of (dfnls) (each > 1).", minItems=1, maxItems=6,
                               items={"$ref": "#/$defs/alpha", "maximum": 10})
    n_q: int = param(181, "Number of plane-wave wavenumbers q in [0, pi].", minimum=3, maximum=2001)
    n_p: int = param(361, "Number of perturbation wavenumbers p in [-pi, pi].", minimum=3, maximum=4001)
    check_N: int = param(200, "Ring size N of the direct DpS runs that check the growth rates.", minimum=8,
                         maximum=2000)
    check_pairs: list[list[int]] = param([[70, 10], [100, 27], [80, 20]], "Direct checks [k_q, m_p]: q = 2 pi k_q / N, "
                                         "p = 2 pi m_p / N, 0 < k_q, m_p < N, an unstable pair for every alpha.",
                                         maxItems=10, items={"description": "One pair [k_q, m_p] of integers.",
                                                             "type": "array", "minItems": 2, "maxItems": 2,
                                                             "items": {"description": "k_q or m_p.", "type": "integer",
                                                                       "minimum": 1, "maximum": 1999}})

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Each check pair on the ring (0 < k_q, m_p < check_N) and unstable, lambda > 0 (ansatz3), for
        every alpha (a direct run measures a growth rate)."""
        N = self.check_N
        for i, pair in enumerate(self.check_pairs):
            k, m = pair
            if not (0 < k < N and 0 < m < N):
                out.add(where + ["check_pairs", i], f"need 0 < k_q, m_p < check_N = {N}", pair)
                continue
            for al in self.alpha:
                if not growth_rate(2 * math.pi * k / N, 2 * math.pi * m / N, al) > 0:
                    out.add(where + ["check_pairs", i], f"stable for alpha = {al}; a check needs an unstable "
                                                        f"(q, p)", pair)
                    break


def _g(z: np.ndarray, alpha: float) -> np.ndarray:
    return z * np.abs(z) ** (alpha - 1.0)


def rotating_rhs(b: np.ndarray, q: float, R: float, alpha: float) -> NDArray[np.complex128]:
    """b' in the rotating frame (periodic lattice, N = b.size, q N / 2 pi an integer)."""
    t0 = dps.tau0(alpha)
    Om = dps.plane_wave_frequency(R, q, alpha)
    B = R + np.asarray(b, dtype=complex)
    D = np.roll(B, -1) * np.exp(-1j * q) - B
    E = B - np.roll(B, 1) * np.exp(1j * q)
    return (_g(D, alpha) - _g(E, alpha)) / (2j * t0) - 1j * Om * B


def stability_matrix(q: ArrayLike, p: ArrayLike, alpha: float, R: float = 1.0) -> NDArray[np.complex128]:
    """L(q, p): d/dtau (beta, gamma) = L (beta, gamma); q, p broadcast; shape (..., 2, 2)."""
    q, p = np.broadcast_arrays(np.asarray(q, dtype=float), np.asarray(p, dtype=float))
    t0 = dps.tau0(alpha)
    Om = 2.0**alpha * R ** (alpha - 1.0) * np.abs(np.sin(q / 2.0)) ** (alpha + 1.0) / t0   # (ds)
    D = R * (np.exp(-1j * q) - 1.0)
    E = R * (1.0 - np.exp(1j * q))
    rho = np.abs(D)
    P = (alpha + 1.0) / 2.0 * rho ** (alpha - 1.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        QD = np.where(rho > 0, (alpha - 1.0) / 2.0 * rho ** (alpha - 1.0) * D / np.conj(D), 0.0)
        QE = np.where(rho > 0, (alpha - 1.0) / 2.0 * rho ** (alpha - 1.0) * E / np.conj(E), 0.0)

    def d(k: np.ndarray) -> np.ndarray:
        return np.exp(1j * (k - q)) - 1.0

    def e(k: np.ndarray) -> np.ndarray:
        return 1.0 - np.exp(-1j * (k - q))

    c = 1.0 / (2j * t0)
    L = np.empty(q.shape + (2, 2), dtype=complex)
    L[..., 0, 0] = c * P * (d(p) - e(p)) - 1j * Om
    L[..., 0, 1] = c * (QD * np.conj(d(-p)) - QE * np.conj(e(-p)))
    L[..., 1, 1] = np.conj(c * P * (d(-p) - e(-p)) - 1j * Om)
    L[..., 1, 0] = np.conj(c * (QD * np.conj(d(p)) - QE * np.conj(e(p))))
    return L


def growth_rate_matrix(q: ArrayLike, p: ArrayLike, alpha: float, R: float = 1.0) -> NDArray[np.float64]:
    """max Re eig L(q, p) from the 2x2 matrix (cross-check of :func:`growth_rate`).

    mu = tr/2 +- sqrt(((L00 - L11)/2)^2 + L01 L10); the discriminant carries a round-off
    ~ 1e-16 |L|^2, so rates ~ 1e-8 |L| here are noise (p -> 0 or stable bands).
    """
    L = stability_matrix(q, p, alpha, R)
    half_tr = 0.5 * (L[..., 0, 0] + L[..., 1, 1])
    disc = (0.5 * (L[..., 0, 0] - L[..., 1, 1])) ** 2 + L[..., 0, 1] * L[..., 1, 0]
    return half_tr.real + np.abs(np.sqrt(disc).real)


def growth_rate(q: ArrayLike, p: ArrayLike, alpha: float, R: float = 1.0) -> NDArray[np.float64]:
    """lambda(q, p) = max Re eig L(q, p) in units of 1/tau, in closed form.

    With c = cos q, s = |sin(q/2)|, w = 1 - cos p = 2 sin^2(p/2), K = (2 R s)^(alpha-1) / tau0, the
    entries of L are L00 = i K X, L11 = -i K Y, L01 L10 = K^2 (alpha-1)^2 (c - cos p)^2 / 4 with
    X + Y = (alpha-1)(1-c) + (alpha+1) c w, so that

        lambda = (K/2) sqrt(max(0, f)),
        f = w [(alpha-1) + (alpha+1) c] [w ((alpha-1) - (alpha+1) c) - 4 (alpha-1) s^2],

    written without cancellation (the Goldstone mode p = 0 is exactly neutral). For c >= 0 the last
    bracket is <= -4c <= 0 (w <= 2): every plane wave with |q| <= pi/2 is linearly stable; for c < 0
    the staggered perturbation p = pi (w = 2) grows as soon as c > -(alpha-1)/(alpha+1). So the
    threshold is q_c = pi/2 exactly, for every alpha, and p = pi goes unstable first.
    """
    q, p = np.broadcast_arrays(np.asarray(q, dtype=float), np.asarray(p, dtype=float))
    s = np.abs(np.sin(q / 2.0))
    c = np.cos(q)
    w = 2.0 * np.sin(p / 2.0) ** 2
    K = (2.0 * R * s) ** (alpha - 1.0) / dps.tau0(alpha)
    f = w * ((alpha - 1.0) + (alpha + 1.0) * c) * (w * ((alpha - 1.0) - (alpha + 1.0) * c) - 4.0 * (alpha - 1.0) * s**2)
    return 0.5 * K * np.sqrt(np.maximum(f, 0.0))


def max_growth_rate(q: float, alpha: float, R: float = 1.0) -> tuple[float, float, float, float]:
    """(max_p lambda, its p, the unstable band's edges p_lo, p_hi in [0, pi]) of the plane wave R e^{i q n} of
    (dfnls), in closed form from :func:`growth_rate`'s f(w) = w a (w b - d), a = (alpha-1) + (alpha+1) c,
    b = (alpha-1) - (alpha+1) c, d = 4 (alpha-1) s^2, w = 2 sin^2(p/2) in [0, 2]:

    * c = cos q >= 0: f <= 0 for every p (no band: NaN edges), rate 0;
    * -(alpha-1)/(alpha+1) < c < 0 (a > 0): f > 0 for w > d/b, largest at w = 2 (p = pi), where
      2 a (2 b - d) = -8 a c: lambda = K sqrt(-2 a c);
    * c <= -(alpha-1)/(alpha+1) (a <= 0): f > 0 for 0 < w < d/b, largest at w = d / (2 b), where
      f = -a d^2 / (4 b): lambda = (K d / 4) sqrt(-a / b),

    K = (2 R s)^(alpha-1) / tau0. Every R > 0 has the same band and sign; the rate scales as R^(alpha-1)."""
    c, s = math.cos(q), abs(math.sin(q / 2.0))
    a, b = (alpha - 1.0) + (alpha + 1.0) * c, (alpha - 1.0) - (alpha + 1.0) * c
    d = 4.0 * (alpha - 1.0) * s**2
    K = (2.0 * R * s) ** (alpha - 1.0) / dps.tau0(alpha)

    def p_of(w: float) -> float:
        return 2.0 * math.asin(math.sqrt(min(w, 2.0) / 2.0))

    if c >= 0.0:
        return 0.0, float("nan"), float("nan"), float("nan")
    if a > 0.0:
        return K * math.sqrt(-2.0 * a * c), math.pi, p_of(d / b), math.pi
    return 0.25 * K * d * math.sqrt(-a / b), p_of(d / (2.0 * b)), 0.0, p_of(d / b)


def scaled_growth_rate(q: ArrayLike, p: ArrayLike, alpha: float) -> NDArray[np.float64]:
    """lambda tau0 R^(1-alpha): a function of (q, p) only."""
    return growth_rate(q, p, alpha, 1.0) * dps.tau0(alpha)


def growth_map(alpha: float, n_q: int,
               n_p: int) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """q in [0, pi] (n_q points), p in [-pi, pi] (n_p points), scaled growth rate (n_q, n_p)."""
    q = np.linspace(0.0, np.pi, n_q)
    p = np.linspace(-np.pi, np.pi, n_p)
    return q, p, scaled_growth_rate(q[:, None], p[None, :], alpha)


def max_over_p(q: float, alpha: float, n_p: int = 4001) -> tuple[float, float]:
    """(max_p lambda tau0 R^(1-alpha), argmax |p|): grid search on [0, pi], then a bounded refinement."""
    from scipy.optimize import minimize_scalar

    p = np.linspace(0.0, np.pi, n_p)   # lambda(q, -p) = lambda(q, p)
    lam = scaled_growth_rate(q, p, alpha)
    i = int(np.argmax(lam))
    if lam[i] <= 0.0:
        return 0.0, float(p[i])
    lo, hi = p[max(i - 1, 0)], p[min(i + 1, n_p - 1)]
    res = minimize_scalar(lambda x: -float(scaled_growth_rate(q, x, alpha)), bounds=(lo, hi), method="bounded",
                          options={"xatol": 1e-12})
    if -res.fun > lam[i]:
        return float(-res.fun), float(res.x)
    return float(lam[i]), float(p[i])


def threshold(alpha: float, tol: float = 0.0, n_p: int = 4001) -> tuple[float, float]:
    """Smallest q in (0, pi] with max_p lambda > tol (bisection), and the p maximising lambda just above it.

    The closed form of :func:`growth_rate` is exactly 0 on stable bands, so tol = 0 works; the answer
    is pi/2 for every alpha (see :func:`growth_rate`), which this search confirms numerically.
    """
    qs = np.linspace(1e-3, np.pi, 400)
    unstable = np.array([max_over_p(q, alpha, n_p)[0] > tol for q in qs])
    if not unstable.any():
        return float("nan"), float("nan")
    i = int(np.argmax(unstable))
    if i == 0:
        return float(qs[0]), max_over_p(qs[0], alpha, n_p)[1]
    lo, hi = qs[i - 1], qs[i]
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        if max_over_p(mid, alpha, n_p)[0] > tol:
            hi = mid
        else:
            lo = mid
    # the most unstable p just above threshold (the first unstable band)
    q_above = hi + 1e-6
    return float(hi), max_over_p(q_above, alpha, n_p)[1]


def simulated_growth(alpha: float, N: int = 200, k_q: int = 70, m_p: int = 10, R: float = 1.0,
                     delta: float = 1e-7, growth_factor: float = 1e3, rtol: float = 1e-12) -> tuple[float, float]:
    """Growth rate of a small perturbation of the plane wave, from a direct DpS run (integrate_dps).

    q = 2 pi k_q / N, p = 2 pi m_p / N; A_n(0) = plane wave + delta R e^{i p n} (rotating-frame b_n);
    integrate to tau with e^{lambda tau} = growth_factor (lambda from the linear theory), fit the
    log of the sideband amplitude |b_hat(p)|^2 + |b_hat(-p)|^2 over the second half.
    Returns (lambda_simulated, lambda_theory) in units 1/tau.
    """
    from cradle.integrators import integrate_dps

    q, p = 2 * np.pi * k_q / N, 2 * np.pi * m_p / N
    lam = float(growth_rate(q, p, alpha, R))
    if lam <= 0:
        raise ValueError(f"(q, p) = ({q}, {p}) is stable (lambda = {lam}); nothing to fit")
    n = np.arange(N)
    tau_end = np.log(growth_factor) / lam
    tau = np.linspace(0.0, tau_end, 201)
    A0 = np.exp(-1j * q * n) * (R + delta * R * np.exp(1j * p * n))
    # scipy's DOP853, as when this check was first published: its numbers stay the same (the
    # compiled default, dop853_numba, has the same tableau but need not round identically)
    sol = integrate_dps(A0, tau, alpha=alpha, bc="periodic", method="dop853", rtol=rtol, atol=rtol * delta * R)
    A = np.asarray(sol.A)
    Om = dps.plane_wave_frequency(R, q, alpha)
    b = A * np.exp(-1j * (Om * tau[:, None] - q * n[None, :])) - R
    bh = np.fft.fft(b, axis=-1) / N
    amp = np.abs(bh[:, m_p]) ** 2 + np.abs(bh[:, -m_p]) ** 2
    sel = tau >= 0.5 * tau_end
    slope = np.polyfit(tau[sel], 0.5 * np.log(amp[sel]), 1)[0]
    return float(slope), lam


# ----------------------------------------------------------------- the pipeline stage

_AC = ("alpha", "check")

#: the stored variables of the `mi-diagram` file, per netCDF group: "/" the thresholds per alpha,
#: "/map" the growth-rate map over (q, p), "/checks" the direct DpS runs against the theory
VARIABLES = {
    "/": {
        "alpha": Var(("alpha",), "exponent alpha of the DpS equation (dfnls)"),
        "q_threshold": Var(("alpha",), "smallest q with an unstable perturbation", "rad"),
        "p_first": Var(("alpha",), "|p| of the first unstable perturbation at the threshold", "rad"),
        "growth_pi": Var(("alpha",), "max over p of the scaled growth rate at q = pi"),
        "p_max_pi": Var(("alpha",), "|p| of the fastest-growing perturbation at q = pi", "rad"),
        "fixed_point_residual": Var(("alpha",), "max |rotating-frame right-hand side| at the plane wave, N = check_N"),
    },
    "/map": {
        "q": Var(("q",), "wavenumber q of the plane wave (ansatz3)", "rad"),
        "p": Var(("p",), "wavenumber p of the perturbation sidebands", "rad"),
        "growth": Var(("alpha", "q", "p"), "scaled growth rate lambda tau0 R^(1-alpha) of the sidebands +-p"),
        "max_growth": Var(("alpha", "q"), "max over p of the scaled growth rate"),
        "argmax_p": Var(("alpha", "q"), "|p| of the fastest-growing perturbation (NaN where stable)", "rad"),
    },
    "/checks": {
        "check": Var(("check",), "index of a direct-simulation check"),
        "q": Var(_AC, "q = 2 pi k_q / N of a direct DpS check", "rad"),
        "p": Var(_AC, "p = 2 pi m_p / N of a direct DpS check", "rad"),
        "growth_theory": Var(_AC, "scaled growth rate from the linear stability matrix"),
        "growth_simulated": Var(_AC, "scaled growth rate fitted on a direct DpS run"),
        "rel_error": Var(_AC, "simulated / theoretical growth rate - 1"),
    },
}


def compute(spec: MIDiagram, inputs: dict, log: Log | None = None) -> xr.DataTree:
    """The `mi-diagram` analysis as a tree of groups (:data:`VARIABLES`); it reads no file.

    The map on n_q x n_p points of [0, pi] x [-pi, pi]; each check pair [k_q, m_p] (q = 2 pi k_q / N,
    p = 2 pi m_p / N, N = check_N) simulated for every alpha.
    """
    import time

    from cradle.data.io import make_tree

    t_start = time.perf_counter()
    say = log or (lambda *a: None)
    alphas = list(spec.alpha)
    n_q, n_p, N = spec.n_q, spec.n_p, spec.check_N
    pairs = [tuple(pq) for pq in spec.check_pairs]
    q = np.linspace(0.0, np.pi, n_q)
    p = np.linspace(-np.pi, np.pi, n_p)
    G = np.empty((len(alphas), n_q, n_p))
    gmax, pmax = np.empty((len(alphas), n_q)), np.empty((len(alphas), n_q))
    qc, pc, gpi, ppi, fp = (np.empty(len(alphas)) for _ in range(5))
    chk = {k: np.full((len(alphas), len(pairs)), np.nan) for k in ("q", "p", "th", "sim")}
    for ia, al in enumerate(alphas):
        G[ia] = scaled_growth_rate(q[:, None], p[None, :], al)
        i = np.argmax(G[ia], axis=1)
        gmax[ia], pmax[ia] = G[ia, np.arange(n_q), i], np.where(G[ia, np.arange(n_q), i] > 0, np.abs(p[i]), np.nan)
        qc[ia], pc[ia] = threshold(al)
        gpi[ia], ppi[ia] = max_over_p(np.pi, al)
        fp[ia] = max(float(np.max(np.abs(rotating_rhs(np.zeros(N), 2 * np.pi * k / N, 1.0, al)))) for k in range(N))
        for ic, (k, m) in enumerate(pairs):
            chk["q"][ia, ic], chk["p"][ia, ic] = 2 * np.pi * k / N, 2 * np.pi * m / N
            sim, th = simulated_growth(al, N=N, k_q=k, m_p=m)
            chk["th"][ia, ic], chk["sim"][ia, ic] = th * dps.tau0(al), sim * dps.tau0(al)
        say(f"mi-diagram: alpha={al}: q_c={qc[ia]:.12g} (first p={pc[ia]:.6g}), growth at q=pi {gpi[ia]:.6g} "
            f"(p={ppi[ia]:.6g}), checks {np.round(chk['sim'][ia] / chk['th'][ia] - 1.0, 6)}")
    rel = chk["sim"] / chk["th"] - 1.0
    groups = {"/": ({"q_threshold": qc, "p_first": pc, "growth_pi": gpi, "p_max_pi": ppi,
                     "fixed_point_residual": fp}, {"alpha": alphas}),
              "/map": ({"growth": G, "max_growth": gmax, "argmax_p": pmax}, {"q": q, "p": p}),
              "/checks": ({"q": chk["q"], "p": chk["p"], "growth_theory": chk["th"], "growth_simulated": chk["sim"],
                           "rel_error": rel}, {"check": np.arange(len(pairs))})}
    attrs = {"check_N": N, "check_pairs": str(pairs),
             "growth_units": "lambda tau0 R^(1-alpha) (scale-free; lambda in units of 1/tau of (dfnls))",
             "max_check_rel_error": float(np.nanmax(np.abs(rel))),
             "wall_time_s": time.perf_counter() - t_start}
    return make_tree(groups, VARIABLES, attrs=attrs, params=plain(spec),
                     title="Modulational instability of the DpS plane waves (ansatz3): growth-rate map")


ANALYSIS = Analysis(
    name="mi-diagram", spec=MIDiagram, compute=compute, variables=VARIABLES,
    title="Modulational instability of the DpS plane waves: growth-rate map and direct checks")
