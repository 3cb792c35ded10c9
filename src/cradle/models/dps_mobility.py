"""The unstable stationary DpS breather and its perturbations: the starts of the mobility runs (issue 37, item 4).

At unit amplitude (:func:`cradle.models.homoclinic_continuation.continued`, max |b| = 1, mu = nu) the DpS breather
of (ansatzapproxst2) is A_n = phi_n e^{i Omega tau}, phi_n = b_n / 2 (the frequency omega with mu(omega) = nu:
:func:`cradle.models.dps.omega_sw_from_mu`). Its linearisation (:func:`cradle.models.dps_breathers.operators`),
u' = A w, w' = -B u, has lambda^2 the eigenvalues of -A B. For 1.25 <= alpha <= 3 the site-centred breather is
unstable (one real lambda > 0, about 1.6e-3 at alpha = 3/2 and 0.37 at alpha = 3) and the bond-centred one stable;
below alpha ~ 1.25 the site breather's lambda falls below the rounding of the eigenvalues (~1e-8): its instability
vanishes faster than any power as alpha -> 1+ (the Peierls-Nabarro barrier does), and no run of bounded length
sees it grow. :func:`unstable_site` gives phi, the growing mode (u, w) with w = -B u / lambda (so that u + i w
grows as e^{lambda tau}), and lambda; :func:`start` the perturbed initial data.

DpS is invariant under A -> s A, tau -> s^(1 - alpha) tau, so one amplitude covers all: the verdicts hold for every
amplitude, the times scale.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from cradle.models import dps, dps_breathers


@dataclass(frozen=True)
class UnstableBreather:
    """The site-centred DpS breather phi_n (max |phi| = 1/2) at ``alpha`` on a ring of N sites, its growing mode
    (u + i w, max |u| = 1) and growth rate ``lam`` (per unit tau), and the largest real part over all its
    eigenvalues ``lam_max`` (equal to ``lam`` when the growing mode is real)."""

    alpha: float
    phi: NDArray[np.float64]
    u: NDArray[np.float64]
    w: NDArray[np.float64]
    lam: float
    lam_max: float
    residual: float


def unstable_site(alpha: float, N: int) -> UnstableBreather:
    """The unstable site-centred breather of (dfnls) at ``alpha`` on a ring of N sites (module docstring)."""
    from cradle.models.homoclinic_continuation import continued

    s = continued("site", alpha, N)
    b, nu = s.profile, s.nu
    a_mu1 = b * nu ** (-1.0 / (alpha - 1.0))       # the mu = 1 profile whose frequency has mu(omega) = nu
    omega = dps.omega_sw_from_mu(nu, alpha)
    A, B = dps_breathers.operators(a_mu1, omega, alpha)
    ev, vec = np.linalg.eig(-A @ B)
    j = int(np.argmax(ev.real))
    lam = float(np.sqrt(max(float(ev[j].real), 0.0)))
    u = vec[:, j].real
    u = u / np.max(np.abs(u))
    w = -(B @ u) / lam if lam > 0 else np.zeros_like(u)
    lam_max = float(np.max(np.sqrt(ev.astype(complex)).real))
    return UnstableBreather(alpha=alpha, phi=0.5 * b, u=u, w=w, lam=lam, lam_max=lam_max, residual=s.residual)


def start(br: UnstableBreather, delta: float, noise: float = 0.0, seed: int | None = None) -> NDArray[np.complex128]:
    """A_n(0) = phi_n + delta max|phi| (u_n + i w_n) + noise max|phi| (xi_n + i eta_n), xi, eta standard normal from
    numpy's default generator seeded with ``seed`` (no noise without a seed)."""
    top = float(np.max(np.abs(br.phi)))
    A0 = br.phi + delta * top * (br.u + 1j * br.w)
    if seed is not None and noise > 0:
        rng = np.random.default_rng(seed)
        A0 = A0 + noise * top * (rng.standard_normal(br.phi.size) + 1j * rng.standard_normal(br.phi.size))
    return np.asarray(A0, dtype=np.complex128)
