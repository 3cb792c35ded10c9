"""Two breathers of the DpS family on one chain (figure loc1, right; the `breather-interactions`
analysis): initial data of (nc) and of (dfnls) from two copies of homoclinic profiles of (dpsstn).

Each copy k is a site- or bond-centred solution a_n of (dpsstn) (mu = 1,
solved from the paper's start), written as a carrier times an envelope,
a_n = (-1)^n e_n with e_n >= 0 (the solutions of section 2.2 are staggered),
centred at c_k (a site for `site`, a bond midpoint c + 1/2 for `bond`) and
scaled to peak |x| = amplitude_k. With theta the phase of the second copy
relative to the first *on the carrier*,

    A_n(0) = 1/2 (-1)^n [ s_1 e_{n - c_1} + e^{i theta} s_2 e_{n - c_2} ],   eps = 1,
    s_k = mu_k^(1/(alpha-1)),  mu_k = (amplitude_k / max e)^(alpha-1)   (ansatzapproxst2),

so theta = 0 puts the two copies in phase (same sign of x_n(0) at equal
distance from either core), theta = pi in antiphase (a node between them when
the copies are alike). (x_n(0), v_n(0)) follow from the ansatz (ansatz) at
tau = 0 (:func:`cradle.models.initial.lattice_state`); for theta in {0, pi}
A_n(0) is real and v_n(0) = 0: two static breathers at rest, as in loc1.
"""
from __future__ import annotations

from collections.abc import Sequence
from functools import lru_cache
from typing import Any

import numpy as np
from numpy.typing import NDArray

from cradle.models import dps
from cradle.models.initial import InitialData, lattice_state
from cradle.specs.checked import checked

PROFILES = ("site", "bond")


@lru_cache(maxsize=16)
def _solved(N: int, profile: str, alpha: float, bc: str) -> tuple[NDArray[np.float64], float]:
    from cradle.models import homoclinic

    sol = homoclinic.solve(homoclinic.initial_guess(N, profile, alpha, 0.1, centre=N // 2), alpha, bc)
    if not sol.converged:
        raise ValueError(f"the {profile} profile did not converge on N = {N} (residual {sol.residual:.3e})")
    return sol.a.copy(), float(sol.residual)


def envelope_profile(N: int, profile: str, alpha: float = 1.5,
                     bc: str = "periodic") -> tuple[NDArray[np.float64], float, float]:
    """(e_n, centre, residual): the envelope e_n = (-1)^n a_n >= 0 of the solved ``profile`` (site or
    bond) of (dpsstn) on N sites, its centre (a site, or a bond midpoint) and the solver's residual."""
    if profile not in PROFILES:
        raise ValueError(f"unknown profile {profile!r} (known: {', '.join(PROFILES)})")
    a, res = _solved(int(N), profile, float(alpha), bc)
    e = (-1.0) ** np.arange(N) * a
    e = e * np.sign(e[np.argmax(np.abs(e))])
    centre = N // 2 + (0.5 if profile == "bond" else 0.0)
    return e, centre, res


def _placed(e: NDArray[np.float64], centre: float, target: float) -> NDArray[np.float64]:
    """e shifted from ``centre`` to ``target``; the two must differ by an integer."""
    k = target - centre
    if abs(k - round(k)) > 1e-9:
        raise ValueError(f"a copy centred at {centre} cannot be moved to {target} (not an integer shift)")
    return np.roll(e, round(k))


@checked
def two_breathers(N: int, alpha: float, *, profiles: Sequence[str] = ("site", "site"),
                  centres: Sequence[float | None] = (None, None),
                  amplitudes: Sequence[float] = (0.01, 0.01), theta: float = 0.0, bc: str = "periodic") -> InitialData:
    """Initial data of two breathers (module docstring). ``centres``: where copy k sits (a site for
    a site profile, a half-integer for a bond profile); ``amplitudes``: peak |x| of each copy alone.
    info: the spacing c_2 - c_1, both mu_k and omega_sw_k = 1 + mu_k / (2^alpha tau0)."""
    A0 = np.zeros(N, dtype=complex)
    info: dict[str, Any] = {"profile_1": profiles[0], "profile_2": profiles[1], "theta": float(theta)}
    for k, (prof, c, amp) in enumerate(zip(profiles, centres, amplitudes, strict=True), start=1):
        if not amp > 0:
            raise ValueError(f"amplitude {k} must be > 0, got {amp!r}")
        e, c0, res = envelope_profile(N, prof, alpha, bc)
        target = c0 if c is None else float(c)
        if not 0 <= target <= N - 0.5:
            raise ValueError(f"centre {k} must be in [0, N - 1/2] = [0, {N - 0.5}], got {target!r}")
        mu = (amp / float(e.max())) ** (alpha - 1.0)
        scale = mu ** (1.0 / (alpha - 1.0))
        phase = 1.0 if k == 1 else np.exp(1j * theta)
        A0 += 0.5 * scale * phase * (-1.0) ** np.arange(N) * _placed(e, c0, target)
        info.update({f"centre_{k}": target, f"amplitude_{k}": float(amp), f"mu_{k}": mu,
                     f"omega_sw_{k}": dps.omega_sw_from_mu(mu, alpha), f"profile_residual_{k}": res})
    d = info["centre_2"] - info["centre_1"]
    info["spacing"] = float(min(abs(d), N - abs(d))) if bc == "periodic" else float(abs(d))
    info["omega_sw"] = info["omega_sw_1"]
    info["mu"] = info["mu_1"]
    x0, v0 = lattice_state(A0, 1.0, alpha, bc)
    info["max_abs_x0"] = float(np.max(np.abs(x0)))
    info["eps"] = 1.0
    return InitialData(A0=A0, eps=1.0, x0=x0, v0=v0, info=info)


def symmetric_centres(N: int, profiles: Sequence[str], spacing: float) -> tuple[float, float]:
    """Centres (c_1, c_2) = (m - spacing/2, m + spacing/2) around the chain's middle m, chosen so each
    copy lands where its profile can sit (sites for site, half-integers for bond)."""
    want = [0.0 if p == "site" else 0.5 for p in profiles]
    m = N / 2.0
    c1 = m - spacing / 2.0
    c1 = np.floor(c1 - want[0]) + want[0]
    c2 = c1 + spacing
    if abs((c2 - want[1]) - round(c2 - want[1])) > 1e-9:
        raise ValueError(f"spacing {spacing} does not fit profiles {profiles} (site-site and bond-bond: "
                         "integers; site-bond: half-integers)")
    return float(c1), float(c2)
