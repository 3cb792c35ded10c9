"""Where a Floquet mode of a travelling breather lives: its weight per site, its participation ratio and the share of
its weight on the breather's core.

On a finite ring the linearisation about a TB has two kinds of modes: extended ones (the Bogoliubov modes of the
tail's plane wave, spread over the ring) and localised ones (internal modes of the core). An instability from the
collision of two extended modes of opposite Krein signature couples them through the core only, by an overlap of
order 1/N, and fades as the ring grows; one in which a localised mode takes part keeps an O(1) share of its weight
on the core (Marin and Aubry, Physica D 119 (1998) 163, on static breathers). The measures here tell the two apart
from one monodromy: for the mode of the multiplier of largest modulus among the non-trivial ones,

* its weight per site w_n = (|x_n|^2 + |y_n|^2) / sum, (x, y) the eigenvector of the real 2N x 2N monodromy in the
  coordinates (Re A, Im A) (its entries complex: a real matrix's eigenvector);
* its participation ratio 1 / sum w_n^2 (1 for a mode on one site, N for one spread evenly over the ring);
* its core fraction sum_{n in core} w_n, the core from A by one of two definitions (:func:`core_mask`): the sites
  whose |A_n| exceeds a fraction of the peak, or the sites within the smallest ring distance of the centre that holds
  a fraction of the norm.

All three are unchanged by the shift of the ring (A and the mode rolled together), by the phase of the eigenvector
(any complex multiple) and by the phase rotation of the TB (A -> e^{i phi} A turns each site's (x_n, y_n) by phi).

Arrays and numbers in, arrays and numbers out: no integration here.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.measurements import floquet_bubbles as FB

#: a monodromy's (eigenvalues, eigenvectors as columns), as numpy.linalg.eig returns them
Eig = tuple[NDArray[np.complex128], NDArray[np.complex128]]
#: the core definitions the measurements report under: (kind, level) of :func:`core_mask`
CORE_DEFINITIONS: tuple[tuple[str, float], ...] = (("amplitude", 1e-2), ("amplitude", 1e-3), ("norm", 1.0 - 1e-6))


def site_weights(v: ArrayLike) -> NDArray[np.float64]:
    """w_n = (|x_n|^2 + |y_n|^2) / sum of a vector v = (x, y) of length 2N in the coordinates (Re A, Im A) (complex
    entries allowed: an eigenvector of the real monodromy): non-negative, sum 1."""
    v = np.asarray(v)
    if v.ndim != 1 or v.size % 2:
        raise ValueError(f"site_weights: a vector of length 2N expected, got shape {v.shape}")
    N = v.size // 2
    w = np.abs(v[:N]) ** 2 + np.abs(v[N:]) ** 2
    total = float(np.sum(w))
    if not total > 0.0:
        raise ValueError("site_weights: a zero vector has no weights")
    return np.asarray(w / total, dtype=np.float64)


def participation(w: ArrayLike) -> float:
    """The participation ratio 1 / sum w_n^2 of weights summing to 1: the number of sites the mode occupies."""
    w = np.asarray(w, float)
    return float(1.0 / np.sum(w * w))


def ring_distance(N: int, centre: float) -> NDArray[np.float64]:
    """|n - centre| on the ring of N sites, for every site n."""
    return np.abs((np.arange(N) - centre + N / 2) % N - N / 2)


def core_mask(A: ArrayLike, kind: str = "amplitude", level: float = 1e-2) -> NDArray[np.bool_]:
    """The TB's core on its ring: ``kind`` "amplitude", the sites with |A_n| > level max |A_n|; "norm", the sites
    within the smallest ring distance r of the centre (:func:`cradle.models.dps_travelling.centre`) that holds at
    least ``level`` of sum |A_n|^2 (r taken over the distances of the sites themselves)."""
    from cradle.models import dps_travelling as M

    a = np.abs(np.asarray(A))
    if kind == "amplitude":
        return np.asarray(a > level * float(np.max(a)), dtype=np.bool_)
    if kind != "norm":
        raise ValueError(f"core_mask: kind = {kind!r}: must be 'amplitude' or 'norm'")
    d = ring_distance(a.size, M.centre(A))
    p = a**2 / float(np.sum(a**2))
    for r in np.unique(d):
        inside = d <= r
        if float(np.sum(p[inside])) >= level:
            return np.asarray(inside, dtype=np.bool_)
    return np.ones(a.size, dtype=np.bool_)


def core_fraction(w: ArrayLike, core: ArrayLike) -> float:
    """The share sum_{n in core} w_n of weights w (summing to 1) on the sites of the mask ``core``."""
    return float(np.sum(np.asarray(w, float)[np.asarray(core, bool)]))


def top_mode(monodromy: ArrayLike, trivial: int,
             eig: Eig | None = None) -> tuple[complex, NDArray[np.complex128]]:
    """(mu, v): the multiplier of largest modulus among all but the ``trivial`` ones nearest 1 of the real 2N x 2N
    monodromy, and its eigenvector (length 2N, coordinates (Re A, Im A)); ``eig`` the monodromy's (eigenvalues,
    eigenvectors) when the caller has them (:func:`cradle.measurements.floquet_bubbles.krein_modes`)."""
    from cradle.models.multipliers import split_trivial

    mu, V = eig if eig is not None else np.linalg.eig(np.asarray(monodromy, float))
    _, k = split_trivial(mu, trivial)
    j = int(k[int(np.argmax(np.abs(mu[k])))])
    return complex(mu[j]), np.asarray(V[:, j], dtype=np.complex128)


def mode_measures(monodromy: ArrayLike, A: ArrayLike, T: float, trivial: int,
                  cores: tuple[tuple[str, float], ...] = CORE_DEFINITIONS,
                  eig: Eig | None = None) -> dict[str, float]:
    """The unstable (largest) non-trivial mode of a TB of state A and period T: growth rate ln|mu| / T, |arg mu| (a
    quartet's mu and conj(mu) are equally large: the eigensolver picks either),
    participation ratio and its share of the ring's N sites, and per core definition of ``cores`` the core's size in
    sites and the mode's core fraction (keys ``core_sites_i``, ``core_fraction_i`` in the order of ``cores``);
    ``eig`` as :func:`top_mode` takes it."""
    mu, v = top_mode(monodromy, trivial, eig)
    w = site_weights(v)
    N = w.size
    pr = participation(w)
    out = {"growth": float(np.log(abs(mu)) / T), "arg": abs(float(np.angle(mu))), "participation": pr,
           "participation_share": pr / N}
    for i, (kind, level) in enumerate(cores):
        core = core_mask(A, kind, level)
        out[f"core_sites_{i}"] = float(np.sum(core))
        out[f"core_fraction_{i}"] = core_fraction(w, core)
    return out


def internal_modes(monodromy: ArrayLike, A: ArrayLike, trivial: int, core: ArrayLike,
                   share: float = 0.5) -> list[tuple[float, float, float]]:
    """The non-trivial multipliers on the unit circle whose mode holds more than ``share`` of its weight on the sites
    of ``core``: the core's internal modes, as (arg mu, Krein signature, core fraction), one per conjugate pair (arg
    >= 0; its conjugate carries the opposite signature)."""
    from cradle.models.multipliers import split_trivial

    mu, sigma, V = FB.krein_modes(monodromy)
    out = []
    for j in split_trivial(mu, trivial)[1]:
        if abs(abs(mu[j]) - 1.0) > FB.ON_CIRCLE or np.angle(mu[j]) < 0.0:
            continue
        f = core_fraction(site_weights(V[:, j]), core)
        if f > share:
            out.append((float(np.angle(mu[j])), float(sigma[j]), f))
    return sorted(out)


def power_slope(N: ArrayLike, y: ArrayLike) -> tuple[float, float]:
    """(s, error): the least-squares slope of ln y against ln N (y ~ N^s) over the finite positive y, and its standard
    error (NaN with fewer than three points, where no error can be estimated)."""
    n, v = np.asarray(N, float), np.asarray(y, float)
    ok = np.isfinite(v) & (v > 0)
    n, v = n[ok], v[ok]
    if n.size < 3:
        return np.nan, np.nan
    p, cov = np.polyfit(np.log(n), np.log(v), 1, cov=True)
    return float(p[0]), float(np.sqrt(cov[0, 0]))


# ----------------------------------------------------------------- the limit read from the mechanism
#: verdict codes of a limit rule (the travelling-breathers analysis's LIMIT_STABLE, ... are these)
STABLE, UNSTABLE, UNDECIDED = 0, 1, -1
#: a mode with more than this share of its weight on the core is a mode of the core (localised)
CORE_SHARE = 0.5
#: the thresholds delta of MODE_RULE under which its verdicts are reported (the first is the analysis's)
MODE_RULE_THRESHOLDS = (0.3, 0.2, 0.5)
#: fewest unstable rings whose slopes MODE_RULE reads (a slope and its standard error need three)
MODE_RULE_MIN = 3
MODE_RULE = ("for a member whose tail is MI-stable: stable when it is stable on every ring reached, at least 4 of "
             "them; else, over the rings where it is unstable (at least MODE_RULE_MIN), the unstable mode's core "
             "fraction f_N (its weight on the sites where |A_n| > 1e-2 max |A|) and growth rate g_N fitted as "
             "powers of N (least squares in log-log, standard errors e). Reading 1, two extended modes of the tail "
             "meeting through the core (coupling ~ 1/N): f_N < CORE_SHARE on every such ring, its slope within "
             "delta of -1 and below 0 by 2 e (reading 2's O(1) share excluded), and g_N no slower to fall than "
             "1/N within 2 e (slope - 2 e <= -1; 'resolved': the fall itself resolved, slope + 2 e < 0): stable "
             "in the limit, a finite-size instability. Reading 2, a mode of the core meeting the tail's modes (an "
             "O(1) share on the core, a Fermi-golden-rule rate in the limit): f_N >= CORE_SHARE on the largest "
             "unstable ring, or f_N's slope above -delta and above -1 by 2 e (reading 1 excluded): unstable in the "
             "limit. Undecided otherwise. delta = "
             "MODE_RULE_THRESHOLDS[0] and the growth read as consistent with 1/N; the other thresholds and the "
             "resolved reading reported beside")


def mode_verdict(N: ArrayLike, growth: ArrayLike, core: ArrayLike, threshold: float,
                 delta: float = MODE_RULE_THRESHOLDS[0], resolved: bool = False) -> tuple[int, dict[str, float]]:
    """(verdict, slopes) of :data:`MODE_RULE` for one member whose tail is MI-stable: ``growth`` its growth rate and
    ``core`` its unstable mode's core fraction on each ring of ``N`` (NaN: not reached), ``threshold`` the stability
    threshold of the growth rate, ``delta`` the tolerance on the core fraction's slope, ``resolved`` the stricter
    reading of the growth (its fall resolved at two standard errors, not only consistent with 1/N). ``slopes``: the
    growth's and the core fraction's power of N over the unstable rings with their standard errors, and how many
    such rings."""
    n, g, f = (np.asarray(x, float) for x in (N, growth, core))
    ok = np.isfinite(g)
    n, g, f = n[ok], g[ok], f[ok]
    u = g > threshold
    sg, eg = power_slope(n[u], g[u])
    sf, ef = power_slope(n[u], f[u])
    info = {"growth_slope": sg, "growth_slope_error": eg, "core_slope": sf, "core_slope_error": ef,
            "unstable_rings": float(np.sum(u)), "rings": float(n.size)}
    if not np.any(u):
        return (STABLE if n.size >= FB.LIMIT_FIT_MIN else UNDECIDED), info
    if np.sum(u) < MODE_RULE_MIN or not (np.isfinite(sf) and np.isfinite(sg)):
        return UNDECIDED, info
    largest = f[u][int(np.argmax(n[u]))]
    if largest >= CORE_SHARE or (sf > -delta and sf - 2.0 * ef > -1.0):
        return UNSTABLE, info
    falls = sg + 2.0 * eg < 0.0 if resolved else sg - 2.0 * eg <= -1.0
    if np.all(f[u] < CORE_SHARE) and abs(sf + 1.0) <= delta and sf + 2.0 * ef < 0.0 and falls:
        return STABLE, info
    return UNDECIDED, info
