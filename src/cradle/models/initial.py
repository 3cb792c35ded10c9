"""Initial conditions for (nc) and (dfnls), built from a DpS amplitude A_n(0).

The paper's procedure (section 4): choose A_n(0), set
x_n(0) = eps (A_n(0) + c.c.) from (ansatz), and take the velocities from the
same ansatz, d/dt x_n^app at t = 0, where dA_n/dtau(0) comes from the DpS
right-hand side (dfnls) at tau = 0:

    v_n(0) = 2 eps ( -Im A_n(0) + eps^(alpha-1) Re dA_n/dtau(0) ).

Families:
  * travelling waves (ansatzapprox): A_n(0) = R e^{-i(q n + phi)}, R = 1,
    eps = a/2 with a from (freq), optionally perturbed as in (perturb);
  * breathers (ansatzapproxst2)/(breatherdps): A_n(0) = mu^(1/(alpha-1)) a_n / 2
    with eps = 1, from a solution a_n of (dpsstn).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.models import dps
from cradle.specs.checked import checked

NOISE_KINDS = ("none", "uniform", "gaussian")


@dataclass
class InitialData:
    """Initial data of both models: the DpS amplitude A_n(0) and eps of (ansatz), the lattice state it gives
    (x_n(0), v_n(0)), the noise of (perturb) if any, and the derived parameters in ``info``."""

    A0: np.ndarray          # complex DpS amplitude A_n(0)
    eps: float              # small parameter of (ansatz); tau = eps^(alpha-1) t
    x0: np.ndarray          # x_n(0)
    v0: np.ndarray          # dx_n/dt(0)
    rho1: np.ndarray | None = None   # noise of (perturb), if any
    rho2: np.ndarray | None = None
    info: dict = field(default_factory=dict)  # derived parameters (a, omega_tw, ...)


@checked
def lattice_state(A0: ArrayLike, eps: float, alpha: float,
                  bc: str = "periodic") -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(x_n(0), v_n(0)) of the ansatz (ansatz) for DpS data A0 and small parameter eps."""
    A0 = np.asarray(A0, dtype=complex)
    dA = dps.rhs(A0, alpha, bc)
    x0 = 2.0 * eps * A0.real
    v0 = 2.0 * eps * (-A0.imag + eps ** (alpha - 1.0) * dA.real)
    return x0, v0


def noise(N: int, kind: str, amplitude: float, seed: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(rho1, rho2) of (perturb): uniform on [-amplitude, amplitude] or Gaussian with sd amplitude.

    Drawn from ``numpy.random.default_rng(seed)`` (PCG64): the same seed
    gives the same numbers on every machine.
    """
    rng = np.random.default_rng(seed)
    if kind == "uniform":
        return rng.uniform(-amplitude, amplitude, N), rng.uniform(-amplitude, amplitude, N)
    if kind == "gaussian":
        return rng.normal(0.0, amplitude, N), rng.normal(0.0, amplitude, N)
    raise ValueError(f"noise kind must be 'uniform' or 'gaussian', got {kind!r}")


@checked(a="amplitude")
def travelling_wave(N: int, q: float, alpha: float, *, a: float | None = None, omega_tw: float | None = None,
                    phi: float = 0.0, bc: str = "periodic", noise_kind: str = "none",
                    noise_amplitude: float = 0.0, seed: int | None = None) -> InitialData:
    """Travelling-wave data (ansatzapprox) with R = 1, a = 2 eps, perturbed as in (perturb).

    Exactly one of ``a`` and ``omega_tw`` is given; the other follows from
    (freq). Unperturbed: x_n(0) = a cos(q n + phi). With noise,
    A_n(0) = (1 + rho1_n) cos(q n + phi) - i (1 + rho2_n) sin(q n + phi)
    (perturb; the paper has phi = 0).
    """
    if (a is None) == (omega_tw is None):
        raise ValueError(f"give exactly one of a and omega_tw (got a={a!r}, omega_tw={omega_tw!r})")
    if a is None:
        a = dps.amplitude_from_omega(omega_tw, q, alpha)
    elif not a > 0:
        raise ValueError(f"amplitude a must be > 0, got a={a!r}")
    omega = dps.omega_tw(a, q, alpha)
    n = np.arange(N)
    rho1 = rho2 = None
    if noise_kind == "none":
        A0 = np.exp(-1j * (q * n + phi))
    else:
        if seed is None:
            raise ValueError("noisy initial data need a recorded seed")
        rho1, rho2 = noise(N, noise_kind, noise_amplitude, seed)
        A0 = (1.0 + rho1) * np.cos(q * n + phi) - 1j * (1.0 + rho2) * np.sin(q * n + phi)
    eps = a / 2.0
    x0, v0 = lattice_state(A0, eps, alpha, bc)
    info = {"a": a, "omega_tw": omega, "eps": eps, "R": 1.0,
            "Omega": dps.plane_wave_frequency(1.0, q, alpha)}
    return InitialData(A0=A0, eps=eps, x0=x0, v0=v0, rho1=rho1, rho2=rho2, info=info)


@checked
def breather(a_n: ArrayLike, alpha: float, *, omega_sw: float | None = None, amplitude: float | None = None,
             site: int | None = None, bc: str = "periodic") -> InitialData:
    """Breather data (ansatzapproxst2)/(breatherdps) from a mu = 1 solution ``a_n`` of (dpsstn).

    A_n(0) = mu^(1/(alpha-1)) a_n / 2, eps = 1, so x_n(0) = mu^(1/(alpha-1)) a_n
    and v_n(0) = 0. Give either ``omega_sw`` (then mu = (omega_sw - 1) 2^alpha tau0)
    or the initial ``amplitude`` |x_site(0)| at bead ``site`` (default: the
    largest |a_n|), from which mu and omega_sw are derived.
    """
    a_n = np.asarray(a_n, dtype=float)
    if (omega_sw is None) == (amplitude is None):
        raise ValueError(f"give exactly one of omega_sw and amplitude (got {omega_sw!r}, {amplitude!r})")
    if omega_sw is not None:
        if not omega_sw > 1.0:
            raise ValueError(f"omega_sw must be > 1 (mu > 0), got omega_sw={omega_sw!r}")
        mu = dps.mu_from_omega_sw(omega_sw, alpha)
    else:
        assert amplitude is not None   # exactly one of the two is given
        k = int(np.argmax(np.abs(a_n))) if site is None else site
        if not (amplitude > 0 and a_n[k] != 0):
            raise ValueError(f"need amplitude > 0 at a site where a_n != 0 (amplitude={amplitude!r}, site={k})")
        mu = (amplitude / abs(a_n[k])) ** (alpha - 1.0)
        omega_sw = dps.omega_sw_from_mu(mu, alpha)
    A0 = 0.5 * mu ** (1.0 / (alpha - 1.0)) * a_n.astype(complex)
    x0, v0 = lattice_state(A0, 1.0, alpha, bc)
    info = {"mu": mu, "omega_sw": omega_sw, "eps": 1.0}
    return InitialData(A0=A0, eps=1.0, x0=x0, v0=v0, info=info)


# ----------------------------------------------------------------------------- localised envelopes (loc1)

ENVELOPES = ("gaussian", "cos2")
PAIR_PROFILES = ("site", "bond")


@checked
def from_displacements(x0: ArrayLike, alpha: float, bc: str = "periodic", info: dict | None = None) -> InitialData:
    """Data with zero velocities whose DpS start is tau = 0 in (breatherdps): A_n(0) = x_n(0)/2, eps = 1.

    For a real A_n(0) the DpS right-hand side is purely imaginary, so the
    ansatz velocities v_n(0) = 2 (-Im A_n(0) + Re dA_n/dtau(0)) vanish:
    the lattice starts at rest from x_n(0), as in figure loc1.
    """
    x0 = np.asarray(x0, dtype=float)
    A0 = 0.5 * x0.astype(complex)
    x0_ansatz, v0 = lattice_state(A0, 1.0, alpha, bc)
    return InitialData(A0=A0, eps=1.0, x0=x0_ansatz, v0=v0, info={**(info or {}), "eps": 1.0})


@checked
def envelope(s: ArrayLike, kind: str, width: float) -> NDArray[np.float64]:
    """A packet envelope of peak 1 at s = 0, (almost) supported on ``width`` sites.

    * ``gaussian``: exp(-s^2 / (2 sigma^2)) with sigma = width / 6, so the
      envelope is below 0.5 % of its peak one site beyond ``width`` sites
      (6 sigma = width): "almost compactly supported";
    * ``cos2``: cos^2(pi s / width) for |s| < width / 2, 0 elsewhere
      (compactly supported; ``width`` sites are nonzero when the centre is
      a half-integer and ``width`` even).
    """
    s = np.asarray(s, dtype=float)
    if kind == "gaussian":
        sigma = width / 6.0
        return np.exp(-0.5 * (s / sigma) ** 2)
    if kind == "cos2":
        return np.where(np.abs(s) < width / 2.0, np.cos(np.pi * s / width) ** 2, 0.0)
    raise ValueError(f"unknown envelope {kind!r} (known: {', '.join(ENVELOPES)})")


def envelope_peak(N: int, kind: str, width: float, centre: float | None = None) -> float:
    """The largest value :func:`envelope` takes at a bead of a packet (:func:`packet`) of N beads centred on
    ``centre`` (default (N - 1)/2): at the beads either side of the centre, which a narrow envelope may miss
    entirely (a Gaussian of width 1e-300 centred on a bond is 0 at every bead, and so is the packet)."""
    c = (N - 1) / 2.0 if centre is None else float(centre)
    near = np.array([c - np.floor(c), np.ceil(c) - c])
    return float(np.max(envelope(near, kind, width)))


@checked
def packet(N: int, alpha: float, *, amplitude: float, width: float, envelope_kind: str = "gaussian",
           centre: float | None = None, bc: str = "periodic") -> InitialData:
    """A modulated binary oscillation at rest (figure loc1, left):

        x_n(0) = amplitude (-1)^n env(n - centre),   v_n(0) = 0,   A_n(0) = x_n(0)/2, eps = 1,

    with ``env`` from :func:`envelope` (peak 1, ``width`` sites). On a ring the
    distance n - centre is taken modulo N (nearest image). Default centre:
    (N - 1)/2, the bond in the middle of the chain, so an even number of
    sites sits symmetrically under the envelope.
    """
    c = (N - 1) / 2.0 if centre is None else float(centre)
    n = np.arange(N)
    s = n - c
    if bc == "periodic":
        s = (s + N / 2.0) % N - N / 2.0
    x0 = amplitude * (-1.0) ** n * envelope(s, envelope_kind, width)
    info = {"envelope": envelope_kind, "width": float(width), "amplitude": float(amplitude), "centre": c,
            "max_abs_x0": float(np.max(np.abs(x0)))}
    return from_displacements(x0, alpha, bc, info)


@checked
def kick(N: int, alpha: float, *, velocity: float, site: int = 0, bc: str = "periodic") -> InitialData:
    """One bead kicked from rest (James, Kevrekidis & Cuevas, Physica D 251 (2013) 39: "small perturbations at
    the first site of the chain"):

        x_n(0) = 0,   v_n(0) = velocity delta_{n, site},   A_n(0) = -i velocity/2 delta_{n, site}, eps = 1.

    A_n(0) is the leading order of (ansatz) (v_n = 2 eps (-Im A_n) at t = 0); the eps^(alpha-1) Re dA/dtau term
    of :func:`lattice_state` is left out, so that the lattice starts exactly from the kick.
    """
    if not 0 <= site < N:
        raise ValueError(f"site must be a bead index in [0, N-1] = [0, {N - 1}], got site={site!r}")
    x0 = np.zeros(N)
    v0 = np.zeros(N)
    v0[site] = velocity
    A0 = np.zeros(N, dtype=complex)
    A0[site] = -0.5j * velocity
    info = {"velocity": float(velocity), "kick_site": int(site), "eps": 1.0, "max_abs_v0": float(abs(velocity))}
    return InitialData(A0=A0, eps=1.0, x0=x0, v0=v0, info=info)


@checked
def pair(N: int, alpha: float, *, amplitude: float, separation: int, profile: str = "bond", sign: int = 1,
         centre: int | None = None, bc: str = "periodic", a_n: ArrayLike | None = None) -> InitialData:
    """Two static breathers at rest (figure loc1, right): the sum of two copies of one
    homoclinic profile a_n of (dpsstn), ``separation`` sites apart,

        x_n(0) = mu^(1/(alpha-1)) (a_{n+l} + sign a_{n-r}),  l = separation // 2, r = separation - l,
        v_n(0) = 0,   A_n(0) = x_n(0)/2, eps = 1   (tau = 0 in (breatherdps)),

    where mu is such that one copy alone has |x_n(0)| = ``amplitude`` at its
    largest site, and omega_sw = 1 + mu / (2^alpha tau0) is the frequency of
    that single breather. ``profile`` (site | bond) is solved here by
    :mod:`cradle.models.homoclinic` from the paper's start (amplitude 0.1) on the
    scene's N and bc, centred at ``centre`` (default N // 2), unless ``a_n``
    is given. A bond profile centred on bond (c, c+1) with separation 3 and
    sign +1 gives two breathers with a node at one site between them.
    """
    from cradle.models import homoclinic

    if profile not in PAIR_PROFILES:
        raise ValueError(f"unknown pair profile {profile!r} (known: {', '.join(PAIR_PROFILES)})")
    if sign not in (1, -1):
        raise ValueError(f"sign must be 1 or -1, got sign={sign!r}")
    if not 1 <= separation < N:
        raise ValueError(f"separation must be in [1, N-1] = [1, {N - 1}], got separation={separation!r}")
    residual = float("nan")
    if a_n is None:
        sol = homoclinic.solve(homoclinic.initial_guess(N, profile, alpha, 0.1, centre=centre), alpha, bc)
        if not sol.converged:
            raise ValueError(f"the {profile} profile did not converge (residual {sol.residual:.3e})")
        a_n, residual = sol.a, sol.residual
    a_n = np.asarray(a_n, dtype=float)
    if a_n.shape != (N,):
        raise ValueError(f"a_n must have N = {N} sites, got shape {a_n.shape}")
    left, right = separation // 2, separation - separation // 2
    env = np.roll(a_n, -left) + sign * np.roll(a_n, right)
    mu = (amplitude / float(np.max(np.abs(a_n)))) ** (alpha - 1.0)
    x0 = mu ** (1.0 / (alpha - 1.0)) * env
    info = {"profile": profile, "separation": int(separation), "sign": int(sign), "amplitude": float(amplitude),
            "mu": mu, "omega_sw": dps.omega_sw_from_mu(mu, alpha), "profile_residual": residual,
            "max_abs_x0": float(np.max(np.abs(x0)))}
    return from_displacements(x0, alpha, bc, info)
