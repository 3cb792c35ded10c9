"""Floquet multipliers of a Hamiltonian periodic orbit (modulo shift) on a finite ring: Krein signatures, the
symmetries of the spectrum, the collisions that open instability bubbles, and the limit of a verdict as the ring
grows.

The monodromy M of a Hamiltonian flow (here DpS's (dfnls) composed with the phase turn and the shift of (tb)) is
symplectic, M^T J M = J with J = [[0, I], [-I, 0]] in the coordinates (Re A, Im A) (the form Im sum conj(u) v,
which the phase rotation and the shift preserve). Its multipliers therefore come in quadruples mu, conj(mu),
1/mu, 1/conj(mu) (pairs on the unit circle). A simple multiplier on the circle with eigenvector w has the Krein
signature sign(-Im w^H J w) (+1 for the eigenvalue lambda of a complex-linear map z -> L z, whose real eigenvector
is (z, -i z)); two multipliers of the same signature pass through each other on the circle, two of opposite
signature that meet may leave it as a quartet (a Krein collision), and a pair that meets at -1 leaves it along
the negative real axis. Near such a collision the two-mode model
mu = e^{i phi} exp(+-sqrt(g^2 - (Delta/2)^2)), Delta the detuning of the two uncoupled multipliers' angles and g
their coupling, gives ln |mu| = sqrt(g^2 - (Delta/2)^2) inside |Delta| < 2 g: a bubble whose width in Delta is 4 g
and whose largest ln |mu| is g.

Arrays and numbers in, arrays and numbers out: no integration here.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.models.multipliers import split_trivial

#: a multiplier counts as on the unit circle when ||mu| - 1| is below this (the trivial ones' defect is ~1e-6)
ON_CIRCLE = 1e-6


def symplectic_form(n: int) -> NDArray[np.float64]:
    """J = [[0, I_n], [-I_n, 0]]: the form Im sum conj(u) v in the coordinates (Re, Im) of C^n."""
    Z, E = np.zeros((n, n)), np.eye(n)
    return np.block([[Z, E], [-E, Z]])


def symplectic_defect(M: ArrayLike) -> float:
    """max |M^T J M - J| / max(1, max |M|^2): how far the real 2n x 2n matrix M is from symplectic."""
    M = np.asarray(M, float)
    J = symplectic_form(M.shape[0] // 2)
    return float(np.max(np.abs(M.T @ J @ M - J)) / max(1.0, float(np.max(np.abs(M))) ** 2))


def krein_signatures(M: ArrayLike) -> tuple[NDArray[np.complex128], NDArray[np.float64]]:
    """(mu, sigma): the eigenvalues of the symplectic matrix M and the Krein signature of each, sign(-Im w^H J w) of
    its eigenvector w for a multiplier on the unit circle (:data:`ON_CIRCLE`), 0 off it (a quartet's members carry
    none). A multiple multiplier's eigenvectors are mixed by the eigensolver: its signatures are not meaningful."""
    mu, sigma, _ = krein_modes(M)
    return mu, sigma


def krein_modes(M: ArrayLike) -> tuple[NDArray[np.complex128], NDArray[np.float64], NDArray[np.complex128]]:
    """(mu, sigma, W): :func:`krein_signatures` with the eigenvectors (the columns of W, in the order of mu), for
    readers that also need the modes (:mod:`cradle.measurements.floquet_modes`) from the one eigendecomposition."""
    M = np.asarray(M, float)
    J = symplectic_form(M.shape[0] // 2)
    mu, W = np.linalg.eig(M)
    q = -np.imag(np.einsum("ik,ij,jk->k", W.conj(), J, W))
    sigma = np.where(np.abs(np.abs(mu) - 1.0) <= ON_CIRCLE, np.sign(q), 0.0)
    return mu.astype(complex), sigma, W.astype(complex)


def quartet_defect(mu: ArrayLike) -> float:
    """max over the multipliers of the distance from 1/conj(mu) and from conj(mu) to the nearest multiplier: zero
    for the spectrum of a real symplectic matrix (quadruples mu, conj(mu), 1/mu, 1/conj(mu))."""
    mu = np.asarray(mu, complex)
    d1 = np.min(np.abs(1.0 / np.conj(mu)[:, None] - mu[None, :]), axis=1)
    d2 = np.min(np.abs(np.conj(mu)[:, None] - mu[None, :]), axis=1)
    return float(max(np.max(d1), np.max(d2)))


def krein_gap(mu: ArrayLike, sigma: ArrayLike, trivial: int) -> float:
    """The smallest angle between two non-trivial multipliers of opposite Krein signature on the unit circle (pi if
    no such pair): it closes where a pair collides and a bubble can open."""
    mu, sigma = np.asarray(mu, complex), np.asarray(sigma, float)
    _, k = split_trivial(mu, trivial)
    a, s = np.angle(mu[k]), sigma[k]
    plus, minus = a[s > 0], a[s < 0]
    if plus.size == 0 or minus.size == 0:
        return float(np.pi)
    d = np.abs(np.angle(np.exp(1j * (plus[:, None] - minus[None, :]))))
    return float(np.min(d))


def windows(c: ArrayLike, unstable: ArrayLike) -> list[tuple[float, float]]:
    """The runs of consecutive unstable grid points (first c, last c) along the grid c (NaN-free, increasing)."""
    c = np.asarray(c, float)
    u = np.asarray(unstable, bool)
    out: list[tuple[float, float]] = []
    i = 0
    while i < u.size:
        if u[i]:
            j = i
            while j + 1 < u.size and u[j + 1]:
                j += 1
            out.append((float(c[i]), float(c[j])))
            i = j + 1
        else:
            i += 1
    return out


def collision_peak(width: float, detuning_rate: float) -> float:
    """The largest ln |mu| of a bubble of the two-mode Krein collision model (module docstring) whose width along
    the parameter is ``width`` when the uncoupled multipliers' angles separate at ``detuning_rate`` (radians per
    unit of the parameter): g = detuning_rate * width / 4."""
    return 0.25 * abs(detuning_rate) * width


def collision_log_modulus(delta: ArrayLike, g: float) -> NDArray[np.float64]:
    """ln |mu| = sqrt(max(0, g^2 - (delta/2)^2)) of the two-mode model at detuning ``delta``."""
    d = np.asarray(delta, float)
    return np.sqrt(np.maximum(0.0, g * g - 0.25 * d * d))


def pair_splitting(mu: ArrayLike, sigma: ArrayLike, angle: float, width: float) -> float:
    """|arg mu_+ - arg mu_-| of the one multiplier of each Krein signature on the unit circle within ``width`` of
    the angle ``angle`` (NaN unless there is exactly one of each there): the splitting of a pair about to collide
    or just separated."""
    mu, sigma = np.asarray(mu, complex), np.asarray(sigma, float)
    a = np.angle(mu)
    near = np.abs(np.angle(np.exp(1j * (a - angle)))) < width
    plus, minus = np.where(near & (sigma > 0))[0], np.where(near & (sigma < 0))[0]
    if plus.size != 1 or minus.size != 1:
        return np.nan
    return float(abs(np.angle(np.exp(1j * (a[plus[0]] - a[minus[0]])))))


def collision_fit(c: ArrayLike, splitting: ArrayLike, centre: float) -> tuple[float, float]:
    """(s, g) of the two-mode model from the splitting of the pair outside its bubble: there the coupled angles are
    2 sqrt((Delta/2)^2 - g^2) apart with Delta = s (c - centre), so splitting^2 = s^2 (c - centre)^2 - 4 g^2 is
    linear in (c - centre)^2 (least squares). The model then predicts the bubble's height g (largest ln |mu|) and
    width 4 g / s from the multipliers outside it alone."""
    x = (np.asarray(c, float) - centre) ** 2
    y = np.asarray(splitting, float) ** 2
    slope, intercept = np.polyfit(x, y, 1)
    return float(np.sqrt(max(slope, 0.0))), float(0.5 * np.sqrt(max(-intercept, 0.0)))


def bubble(scan: dict[str, NDArray[np.float64]], threshold: float, angle: float, span: float) -> dict[str, float]:
    """The widest run of a resolved scan (arrays c, log_modulus, top_arg, splitting, period along an even grid of
    c) where the most unstable multiplier grows faster than ``threshold`` per unit time and lies within 0.05 of
    ``angle``, and the two-mode model (:func:`collision_fit`) fitted to the pair's splitting over ``span`` on
    either side of it: measured and modelled width and height (largest ln |mu|), the detuning rate s, the largest
    growth rate ln |mu| / T inside."""
    c, lm, T = scan["c"], scan["log_modulus"], scan["period"]
    inside = (np.isfinite(lm) & (lm > threshold * T)
              & (np.abs(np.angle(np.exp(1j * (scan["top_arg"] - angle)))) < 0.05))
    a, b = max(windows(c, inside), key=lambda w: w[1] - w[0])
    step = float(c[1] - c[0])
    out = (((c >= a - span) & (c < a)) | ((c > b) & (c <= b + span))) & np.isfinite(scan["splitting"])
    s, g = collision_fit(c[out], scan["splitting"][out], 0.5 * (a + b))
    inner = (c >= a) & (c <= b)
    return {"bubble_from": a, "bubble_to": b, "step": step, "width_measured": b - a + step, "width_model": 4 * g / s,
            "height_measured": float(np.nanmax(lm[inner])), "height_model": g, "detuning_rate": s,
            "growth_rate_measured": float(np.nanmax(lm[inner] / T[inner])), "points_outside": float(out.sum())}


#: fewest rings for :func:`fit_limit`: three parameters and at least one degree of freedom for their errors
LIMIT_FIT_MIN = 4
#: the range of the exponent k in :func:`fit_limit` (a fit that ends on either bound is degenerate)
LIMIT_FIT_K = (0.0, 8.0)


def fit_limit(N: ArrayLike, g: ArrayLike) -> dict[str, float]:
    """:func:`fit_once` over every ring, its error widened to the change of g_inf when the smallest or the largest
    ring is left out (when at least :data:`LIMIT_FIT_MIN` remain; as :func:`cradle.measurements.continuum.fit_power`
    does): a g_inf that one ring moves is no better known than that. ``g_inf_stderr`` keeps the standard error."""
    n, y = np.asarray(N, float), np.asarray(g, float)
    ok = np.isfinite(y)
    n, y = n[ok], y[ok]
    fit = fit_once(n, y)
    fit["g_inf_stderr"] = fit["g_inf_error"]
    if n.size > LIMIT_FIT_MIN and np.isfinite(fit["g_inf"]):
        order = np.argsort(n)
        for keep in (order[1:], order[:-1]):
            sub = fit_once(n[keep], y[keep])["g_inf"]
            fit["g_inf_error"] = max(fit["g_inf_error"], abs(sub - fit["g_inf"])) if np.isfinite(sub) else np.nan
    return fit


def fit_once(N: ArrayLike, g: ArrayLike) -> dict[str, float]:
    """g(N) = g_inf + b N^(-k) fitted to growth rates g on rings of N sites (least squares, k in
    :data:`LIMIT_FIT_K`): the growth rate in the limit N -> infinity g_inf, its standard error (from the residuals;
    NaN with fewer than :data:`LIMIT_FIT_MIN` finite points, as every output then), b, k and ``degenerate`` (1 when
    k ends on a bound of its range: the standard error is then no error of g_inf). A series that settles at g_inf
    returns it; a finite-size effect returns g_inf consistent with 0."""
    from scipy.optimize import curve_fit

    n, y = np.asarray(N, float), np.asarray(g, float)
    ok = np.isfinite(y)
    n, y = n[ok], y[ok]
    nan = {"g_inf": np.nan, "g_inf_error": np.nan, "b": np.nan, "k": np.nan, "points": float(n.size),
           "degenerate": np.nan}
    if n.size < LIMIT_FIT_MIN:
        return nan
    scale = max(float(np.max(np.abs(y))), np.finfo(float).tiny)
    # in units of the largest rate and of the smallest ring: every parameter of order 1 for the solver
    x, z = n / np.min(n), y / scale

    def model(x: NDArray[np.float64], g0: float, b: float, k: float) -> NDArray[np.float64]:
        return g0 + b * x ** (-k)

    best = None
    for k0 in (0.5, 1.0, 2.0):
        try:
            p, cov = curve_fit(model, x, z, p0=(z[-1], z[0] - z[-1], k0),
                               bounds=([-np.inf, -np.inf, LIMIT_FIT_K[0]], [np.inf, np.inf, LIMIT_FIT_K[1]]))
        except RuntimeError:
            continue
        cost = float(np.sum((model(x, *p) - z) ** 2))
        if best is None or cost < best[0]:
            best = (cost, p, cov)
    if best is None:
        return nan
    _, p, cov = best
    err = float(np.sqrt(cov[0, 0])) if np.isfinite(cov[0, 0]) else np.nan
    # on a bound (to the solver's tolerance) the exponent is not fitted but imposed
    degenerate = min(p[2] - LIMIT_FIT_K[0], LIMIT_FIT_K[1] - p[2]) < 1e-6
    return {"g_inf": float(p[0] * scale), "g_inf_error": err * scale,
            "b": float(p[1] * scale * np.min(n) ** p[2]), "k": float(p[2]), "points": float(n.size),
            "degenerate": float(degenerate)}
