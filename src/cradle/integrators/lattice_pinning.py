"""The pinning mode of the exact site-centred breather of the lattice (nc) against DpS's unstable mode (issue 37,
item 4: why the lattice does not follow DpS's hops at amplitude 0.1).

DpS's site breather phi_n (max |phi| = 1/2, :func:`cradle.models.dps_mobility.unstable_site`) has one real pair
+-lambda (per unit tau) on its symmetry-breaking (translation) modes. Through the ansatz x_n ~ 2 eps Re(A_n e^{it}),
tau = eps^(alpha-1) t, it is the breather of (nc) of amplitude eps and frequency omega_b = 1 + nu eps^(alpha-1) /
(2^alpha tau0) (nu the mu of (dpsst) of the unit-amplitude profile). :func:`exact_site` solves the exact breather of
(nc) at that frequency (:func:`cradle.integrators.lattice_breathers.newton`, site class, started from the DpS
profile) and takes the odd Floquet multiplier nearest +1, the pinning pair m = e^{+-s T}; in DpS's units,
z = ln m / (T eps^(alpha-1)), and

    sigma = Re z^2:  lambda^2 > 0 of a real pair (the breather unstable along its translation),
                     -Omega^2 < 0 of a pair on the unit circle (an oscillating, pinned, internal mode).

DpS is the limit eps -> 0 (:mod:`cradle.models.dps`), so sigma -> lambda^2; the lattice's corrections to it are of
relative order eps^(alpha-1), and since lambda^2 itself is small (the Peierls-Nabarro barrier of DpS is), they
change its sign unless eps^(alpha-1) is small: sigma / lambda^2 is the measure stored.
"""
from __future__ import annotations

import cmath
import functools
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray


@dataclass(frozen=True)
class PinningMode:
    """The exact site breather of (nc) of amplitude ~eps at ``alpha`` and its pinning pair (module docstring):
    ``sigma_ratio`` sigma / lambda^2, ``rate`` the largest growth rate over all its non-trivial multipliers divided
    by eps^(alpha-1) (per unit tau), ``lam`` DpS's lambda, ``amplitude`` max |x_n(0)|, ``residual`` the breather's
    half-period residual, ``trivial`` the distance of its trivial pair to +1, ``converged`` Newton's verdict."""

    alpha: float
    eps: float
    sigma_ratio: float
    rate: float
    lam: float
    amplitude: float
    residual: float
    trivial: float
    converged: bool


@functools.lru_cache(maxsize=32)
def _dps_site(alpha: float, N: int) -> tuple[float, NDArray[np.float64], float]:
    """DpS's growth rate lambda, the unit-amplitude site profile b_n and its nu (one solve per alpha and N)."""
    from cradle.models.dps_mobility import unstable_site
    from cradle.models.homoclinic_continuation import continued

    s = continued("site", alpha, N)
    return unstable_site(alpha, N).lam, s.profile, float(s.nu)


def exact_site(alpha: float, N: int, eps: float) -> PinningMode:
    """The pinning mode of the exact site breather of (nc) at amplitude eps on a ring of N sites."""
    from cradle.integrators import lattice_breathers as lb
    from cradle.models import dps

    lam, profile, nu = _dps_site(alpha, N)
    a_mu1 = profile * nu ** (-1.0 / (alpha - 1.0))    # the mu = 1 profile of (dpsstn)
    pin = int(np.argmax(np.abs(profile)))
    scale = eps ** (alpha - 1.0)
    omega = 1.0 + nu * scale / (2.0**alpha * dps.tau0(alpha))
    b = lb.newton(lb.dps_start(a_mu1, omega, alpha), omega, alpha, kind="site", centre=pin)
    f = lb.floquet(b, "site", centre=pin)
    m = complex(f.mu_odd[int(np.argmin(np.abs(f.mu_odd - 1.0)))])
    z = cmath.log(m) / (b.T * scale)
    return PinningMode(alpha=alpha, eps=eps, sigma_ratio=float((z * z).real / lam**2), rate=float(f.rate / scale),
                       lam=lam, amplitude=b.amplitude, residual=float(b.half_residual), trivial=float(f.trivial),
                       converged=bool(b.converged))
