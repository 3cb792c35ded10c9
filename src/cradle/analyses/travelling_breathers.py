"""Travelling breathers of the DpS equation (dfnls) (issue 37, item 1): their family in the velocity at fixed norm,
tails, invariants and Floquet multipliers modulo shift, against the dH/dc criterion.

A TB on a ring of N sites solves A_n(tau + T) = e^{i theta} A_{n-1}(tau) (tb), c = 1/T
(:mod:`cradle.models.dps_travelling`). DpS's scaling A -> lambda A, tau -> lambda^(1-alpha) tau keeps theta and maps
(T, P) to (lambda^(1-alpha) T, lambda^2 P) (P = sum |A_n|^2): the family that remains is the one in c at fixed P,
computed here at P = ``norm`` (any other norm is its image; the invariant velocity is c P^((1-alpha)/2)). This
analysis

* builds the static DpS breathers (ansatzapproxst2) of both parities (the mu = 1 solutions a_n of (dpsstn) of
  :mod:`cradle.models.homoclinic`, as the breathers analysis, scaled to the norm), pushes the site one by the
  phase gradient ``kick`` and takes one site of its motion as the first guess;
* solves (tb) by Gauss-Newton on the shooting map modulo shift (:mod:`cradle.integrators.dps_travelling`) and
  continues the family over ``speeds`` (down to the slowest and up to the fastest, tangent predictor);
* stores each member's profile, theta, H, its tail (max |A_n| on the far quarter ring, relative), its shift-map
  residual, its multipliers modulo shift (the four trivial ones at 1 filtered, their defect stored: the precision
  of the stability verdict) and the growth rate ln max|mu| / T of the others; dH/dc along the family and where it
  changes sign (Xu, Cuevas-Maraver, Kevrekidis and Vainchtein, arXiv 1701.04882: a sufficient condition for a
  change of stability) against where the verdict changes;
* at small c, the distance of |A_n(tau)| over one period to the static breathers' profiles (the c -> 0 end);
* robustness of the verdicts (issue 37: verdicts that do not change with the discretisation): every member re-solved
  at each of ``check_rtol`` and the family recomputed on each ring of ``check_N``; a verdict is settled where all of
  them agree; what explains the others (the unstable mode's extent over the ring, the tail as a plane wave of
  (dfnls) with its wavenumber q = theta and its modulational growth rate);
* the verdicts in the limit N -> infinity: each member's neighbourhood scanned in steps of ``limit_step`` on every ring
  of ``limit_N`` (growth rates, Krein signatures, the tail's MI rate per TB), the typical (median) growth rate of the
  neighbourhood per ring, and one rule (:data:`LIMIT_RULE`) that reads the limit verdict from the two largest rings;
  a window resolved as a Krein collision (:func:`bubble_scan`, :mod:`cradle.measurements.floquet_bubbles`);
* checks: a direct run of the member
  at ``direct_speed`` over ``direct_periods`` periods (norm and H drifts, the residual of (tb) after k periods);
  the scaling symmetry (the TB re-solved at lambda^(1-alpha) T and lambda^2 P from another member's profile,
  against lambda A);
* the cited papers' statements as claims rows (group /claims, the columns of the claims table).
"""
from __future__ import annotations

import itertools
import math
import time as _time
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.claims_table import GROUP_VARIABLES, Row, group
from cradle.analyses.protocol import Analysis
from cradle.data.variables import Var
from cradle.specs.declare import declared, param, plain
from cradle.specs.values import RTOL_FLOOR

if TYPE_CHECKING:
    import xarray as xr
    from numpy.typing import NDArray

    from cradle.analyses.protocol import Log
    from cradle.integrators.dps_travelling import TravellingBreather
    from cradle.integrators.lattice_tail import SignedTail
    from cradle.integrators.lattice_travelling import LatticeTB
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors

_SPEED = {"type": "number", "exclusiveMinimum": 0, "maximum": 2,
          "description": "One velocity c = 1/T of the family (sites per unit tau at the norm of the spec)."}

_RING = {"type": "integer", "minimum": 8, "maximum": 200, "description": "Sites of a check ring."}
_RTOL = {"type": "number", "minimum": RTOL_FLOOR, "maximum": 1e-8, "description": "A DOP853 relative tolerance."}

#: multipliers modulo shift equal to 1 on every TB: phase and time shift, each in a Jordan block with its
#: conserved quantity (norm, H)
TRIVIAL = 4
#: the scaling check starts Newton this fraction of the way from the member towards its neighbour
SCALING_NUDGE = 1e-3
#: a multiplier is real when |Im mu| <= REAL |mu| (a real pair's imaginary parts are rounding)
REAL = 1e-8
#: a tail dips at a grid point when it is below this fraction of both neighbours' tails
DIP = 0.3
#: where the docs page explains the claims rows
EXPLAINED = "analyses/travelling-breathers.md#claims"


@declared(doc="Travelling breathers of the DpS equation (dfnls) on a ring (issue 37): Newton on the shooting map "
              "modulo shift, continued in the velocity at fixed norm from a pushed static breather; tails, H, "
              "Floquet multipliers modulo shift against the dH/dc criterion, the c -> 0 end against the static "
              "breathers, checks of N, tolerance, scaling and a direct run -> results/travelling-breathers/"
              "travelling-breathers.nc and results/figures/travelling-breathers.{pdf,png}.")
class TravellingBreathers:
    alpha: float = param(1.5, "Exponent alpha of (dfnls) (p = alpha + 1; Hertz: 3/2).", ref="alpha", maximum=10)
    N: int = param(24, "Sites of the ring.", minimum=8, maximum=200, reduced=16)
    norm: float = param(1.0, "Squared l2 norm P = sum |A_n|^2 of the family (the scaling maps every other onto it).",
                        exclusiveMinimum=0, maximum=1e6)
    kick: float = param(0.15, "Phase gradient kappa of the pushed static breather A_n = phi_n e^{i kappa (n - n_0)} "
                        "whose motion gives the first guess.", exclusiveMinimum=0, maximum=1.5)
    speeds: list[float] = param([0.05, 0.06, 0.08, 0.1, 0.12, 0.14, 0.16, 0.18, 0.2, 0.22, 0.24],
                                "Velocities c of the stored members (increasing); the family is continued from the "
                                "first guess's c down to the slowest and up to the fastest.", minItems=3,
                                maxItems=60, items=_SPEED, reduced=[0.06, 0.08, 0.1, 0.12])
    newton_tol: float = param(1e-11, "Newton stops when the shift-map residual max|R| <= newton_tol max|A|.",
                              exclusiveMinimum=0, maximum=1e-6)
    rtol: float = param(1e-13, "DOP853 relative tolerance of the shooting and of the monodromy.",
                        minimum=RTOL_FLOOR, maximum=1e-8)
    check_rtol: list[float] = param([1e-12, 3e-14], "The tolerances of the verdict check (every member re-solved on "
                                    "the ring of N at each; the first is also stored in /family).", minItems=1,
                                    maxItems=6, items=_RTOL, reduced=[1e-12])
    check_N: list[int] = param([30, 40, 48], "Sites of the rings of the verdict check (the family recomputed on each; "
                               "the first is also stored in /family).", minItems=1, maxItems=8, items=_RING,
                               reduced=[20])
    stability_threshold: float = param(1e-5, "Growth rate ln max|mu| / T (per unit tau) above which a TB is called "
                                       "unstable.", exclusiveMinimum=0, maximum=1)
    direct_speed: float = param(0.1, "c of the member run directly (one of speeds).", exclusiveMinimum=0, maximum=2)
    direct_periods: int = param(20, "Periods T of the direct run.", minimum=1, maximum=10000, reduced=4)
    scale: float = param(2.0, "lambda of the scaling check.", exclusiveMinimum=0, minimum=0.01, maximum=100)
    static_samples: int = param(64, "Samples per period of |A_n(tau)| against the static profiles.", minimum=8,
                                maximum=4096, reduced=32)
    # TBs in motion (issue 37, item 3): the member at motion_speed launched in (nc) through (ansatz)
    motion_speed: float = param(0.1, "c of the member launched in the lattice (nc) through (ansatz) (one of speeds).",
                                exclusiveMinimum=0, maximum=2)
    motion_eps: list[float] = param([0.03, 0.01, 0.003, 0.001, 3e-4, 1e-4, 3e-5],
                                    "Small parameters eps of (ansatz) at which the member is launched in (nc) "
                                    "(decreasing; the lattice time of a run grows as eps^(1-alpha)).", minItems=4,
                                    maxItems=20, items={"type": "number", "minimum": 1e-6, "maximum": 0.5},
                                    reduced=[0.01, 0.003, 0.001, 3e-4])
    motion_sites: int = param(60, "Length of the runs: the sites the DpS TB travels (motion_sites T in tau).",
                              minimum=2, maximum=2000, reduced=20)
    motion_ring: int = param(96, "Sites of the ring the member is launched on (its N sites, then zeros): at least N + "
                             "motion_sites + motion_window, so that it never meets what it left behind.", minimum=8,
                             maximum=8192, reduced=42)
    motion_window: int = param(6, "Half-width (sites) of the window around the breather outside which its weight "
                               "(lattice energy, DpS norm) counts as radiation.", minimum=1, maximum=100)
    motion_samples: int = param(16, "Samples per DpS period T of both runs (the positions, radiation and distances "
                                "stored).", minimum=4, maximum=1000, reduced=8)

    # the verdicts in the limit N -> infinity (issue 37, "verdicts robust to the discretisation"): section
    # "robustness in the limit" below
    limit_N: list[int] = param([24, 32, 48, 64], "Rings on which the neighbourhood of every member is scanned in "
                               "fine steps of c (increasing; the limit verdict is read from the two largest).",
                               minItems=2, maxItems=8, items=_RING, reduced=[16, 20])
    limit_step: float = param(0.001, "Step in c of the fine scan around each member.", exclusiveMinimum=0,
                              maximum=0.05, reduced=0.004)
    limit_halfwidth: float = param(0.005, "Half-width in c of each member's neighbourhood in the fine scan (the "
                                   "neighbourhoods of neighbouring members may overlap).", exclusiveMinimum=0,
                                   maximum=0.1, reduced=0.004)
    # the tail rule (section "the tail rule in the limit" below): larger rings around the members whose tail is
    # modulationally stable, the only ones whose limit verdict needs the growth rates' extrapolation in N
    limit_large_N: list[int] = param([80, 96, 112, 128, 160], "Larger rings (each above the largest of limit_N) "
                                     "scanned only over the neighbourhoods of the members whose tail's plane wave is "
                                     "modulationally stable; with limit_N they give the fit g_inf + b N^-k of the tail "
                                     "rule (from 128 sites the first TB needs the core-first Newton).",
                                     minItems=0, maxItems=6, items=_RING, reduced=[])
    limit_large_step: float = param(0.002, "Step in c of the scan on limit_large_N (a multiple of limit_step: the "
                                    "fit compares every ring on the points common to all).", exclusiveMinimum=0,
                                    maximum=0.05)
    limit_large_newton_tol: float = param(5e-11, "newton_tol on limit_large_N (on 96 sites the first TB stops at "
                                          "2.4e-11 against 1e-11).", exclusiveMinimum=0, maximum=1e-6)
    # the windows as folds (section "the windows are folds" below): the family near the first member followed
    # through its fold in c by pseudo-arclength, the check of Xu et al.'s dH/dc criterion on a ring
    limit_fold_N: list[int] = param([48, 80], "Rings on which the family is continued upwards in c from the first "
                                    "member until it turns (a fold), then followed through the fold by "
                                    "pseudo-arclength (group /limit_fold).", minItems=0, maxItems=4, items=_RING,
                                    reduced=[])
    limit_fold_points: int = param(60, "Members of the pseudo-arclength continuation on each ring of limit_fold_N.",
                                   minimum=2, maximum=1000)

    # exact TBs of the lattice (nc) (issue 37, items 2 and 3): section "the lattice's travelling breathers" below
    lattice: bool = param(True, "Also solve exact TBs of the lattice (nc) from a DpS member's ansatz (groups "
                          "/lattice, /lattice_eps, /lattice_states): minutes of CPU, so in the full form only.",
                          reduced=False)
    lattice_N: int = param(16, "Sites of the ring of the lattice's TBs (the DpS member at lattice_source solved on "
                           "it; lattice_rings carries them to larger rings).", minimum=8, maximum=200)
    lattice_source: float = param(0.1, "c of the DpS member (one of speeds) whose ansatz starts the lattice's TBs; the "
                                  "same member launched in (nc) beside the exact TBs (item 3's comparison).",
                                  exclusiveMinimum=0, maximum=2)
    lattice_eps: list[float] = param([0.005, 0.003, 0.002, 0.001],
                                     "eps of the ansatz x_n = 2 eps Re(A_n(eps^(alpha-1) t) e^{it}) from which an "
                                     "exact TB is solved at each (decreasing; the time per site is T_d "
                                     "eps^(1-alpha)); the distance to the DpS TB is fitted against them.",
                                     minItems=3, maxItems=12,
                                     items={"type": "number", "exclusiveMinimum": 0, "maximum": 0.5})
    lattice_steps: list[float] = param([-0.02, -0.01, 0.0, 0.01, 0.02],
                                       "Relative changes s of the lattice's velocity: members at c = c0 (1 + s), c0 "
                                       "the velocity of the TB at the first lattice_eps (increasing, one of them 0).",
                                       minItems=1, maxItems=40,
                                       items={"type": "number", "minimum": -0.5, "maximum": 0.5,
                                              "description": "One relative change of the lattice TB's velocity."},
                                       reduced=[0.0, 0.01])
    lattice_periods: int = param(4, "Periods T of the direct run of the first lattice TB.", minimum=1, maximum=1000,
                                 reduced=2)
    # the lattice's TBs on other rings and at larger amplitude: section "the lattice's TBs on other rings" below
    lattice_rings: list[int] = param([24, 32, 48], "Rings beyond lattice_N on which the lattice's TBs at every "
                                     "lattice_eps are solved again, each carried from the ring before by adding sites "
                                     "at rest on the far side (increasing; group /lattice_rings).", minItems=0,
                                     maxItems=8, items=_RING)
    lattice_family_rings: list[int] = param([24, 32, 48], "Rings of lattice_rings on which the continuation in c "
                                            "(lattice_steps) is done too (its cost grows as N^2).", minItems=0,
                                            maxItems=8, items=_RING)
    lattice_large_eps: list[float] = param([0.01, 0.03], "eps of the ansatz above lattice_eps at which an exact TB "
                                           "is solved on the ring of lattice_N, the core first (group "
                                           "/lattice_large; increasing).", minItems=0, maxItems=8,
                                           items={"type": "number", "exclusiveMinimum": 0, "maximum": 0.5})
    # the zeros of the lattice TBs' signed tail: section "where the lattice's tail vanishes" below
    lattice_zero_rings: list[int] = param([24, 32, 48], "Rings of lattice_family_rings on which the signed tail is "
                                          "followed through its two minima and its zeros located (group "
                                          "/lattice_zeros).", minItems=0, maxItems=8, items=_RING)
    lattice_zero_eps: float = param(0.003, "The member of lattice_eps whose branch is followed through the first "
                                    "minimum of the tail.", exclusiveMinimum=0, maximum=0.5)
    lattice_zero_step: float = param(0.01, "The member of lattice_steps (on each ring's continuation) whose branch is "
                                     "followed through the second minimum.", minimum=-0.5, maximum=0.5)
    lattice_zero_grid: list[float] = param([-0.0004, -0.0002, 0.0, 0.0002, 0.0004],
                                           "Relative changes s of the velocity around each minimum's member, c = c1 "
                                           "(1 + s) (increasing, one of them 0): the fine grid whose sign change "
                                           "brackets the zero.", minItems=2, maxItems=40,
                                           items={"type": "number", "minimum": -0.05, "maximum": 0.05,
                                                  "description": "One relative change of the velocity."})

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Each form: speeds increasing, direct_speed among them, a check ring other than the ring."""
        if any(y <= x for x, y in itertools.pairwise(self.speeds)):
            out.add(where + ["speeds"], "must be strictly increasing", self.speeds)
        if float(self.direct_speed) not in [float(x) for x in self.speeds]:
            out.add(where + ["direct_speed"], f"must be one of speeds = {self.speeds}", self.direct_speed)
        if float(self.lattice_source) not in [float(x) for x in self.speeds]:
            out.add(where + ["lattice_source"], f"must be one of speeds = {self.speeds}", self.lattice_source)
        if any(y <= x for x, y in itertools.pairwise(self.lattice_steps)) or 0.0 not in self.lattice_steps:
            out.add(where + ["lattice_steps"], "must be strictly increasing and hold 0 (the first solve)",
                    self.lattice_steps)
        if any(y >= x for x, y in itertools.pairwise(self.lattice_eps)):
            out.add(where + ["lattice_eps"], "must be strictly decreasing", self.lattice_eps)
        self.check_rings(where, out)
        if self.N in self.check_N or len(set(self.check_N)) < len(self.check_N):
            out.add(where + ["check_N"], f"must be distinct rings other than N = {self.N} (they check the verdicts "
                    "against N)", self.check_N)
        self.check_motion(where, out)
        if any(y <= x for x, y in itertools.pairwise(self.limit_N)):
            out.add(where + ["limit_N"], "must be strictly increasing", self.limit_N)
        if self.limit_step > self.limit_halfwidth:
            out.add(where + ["limit_step"], f"must be <= limit_halfwidth = {self.limit_halfwidth} (a neighbourhood "
                    "of one point says nothing of its bubbles)", self.limit_step)
        self.check_limit_large(where, out)

    def check_limit_large(self, where: Where, out: Errors) -> None:
        """The larger rings of the tail rule: increasing, above limit_N, on a grid that is a multiple of
        limit_step."""
        if any(y <= x for x, y in itertools.pairwise(self.limit_large_N)):
            out.add(where + ["limit_large_N"], "must be strictly increasing", self.limit_large_N)
        elif self.limit_large_N and self.limit_large_N[0] <= max(self.limit_N):
            out.add(where + ["limit_large_N"], f"must be above the largest of limit_N = {self.limit_N}",
                    self.limit_large_N)
        if any(y <= x for x, y in itertools.pairwise(self.limit_fold_N)):
            out.add(where + ["limit_fold_N"], "must be strictly increasing", self.limit_fold_N)
        ratio = self.limit_large_step / self.limit_step
        if self.limit_large_N and (abs(ratio - round(ratio)) > 1e-9 or round(ratio) < 1):
            out.add(where + ["limit_large_step"], f"must be a whole multiple of limit_step = {self.limit_step} (the "
                    "fit compares the rings on common points)", self.limit_large_step)

    def check_rings(self, where: Where, out: Errors) -> None:
        """The keys of the lattice's TBs on other rings and at larger amplitude."""
        rings = [self.lattice_N, *self.lattice_rings]
        if any(y <= x for x, y in itertools.pairwise(rings)):
            out.add(where + ["lattice_rings"], f"must be strictly increasing and above lattice_N = {self.lattice_N} "
                    "(each ring is carried from the one before)", self.lattice_rings)
        if any(n not in self.lattice_rings for n in self.lattice_family_rings):
            out.add(where + ["lattice_family_rings"], f"must be among lattice_rings = {self.lattice_rings}",
                    self.lattice_family_rings)
        if any(y <= x for x, y in itertools.pairwise([max(self.lattice_eps), *self.lattice_large_eps])):
            out.add(where + ["lattice_large_eps"], f"must be strictly increasing and above max(lattice_eps) = "
                    f"{max(self.lattice_eps)}", self.lattice_large_eps)
        self.check_zeros(where, out)

    def check_zeros(self, where: Where, out: Errors) -> None:
        """The keys of the tail's zeros: rings with a continuation, members that are computed, a grid about 0."""
        if any(n not in self.lattice_family_rings for n in self.lattice_zero_rings):
            out.add(where + ["lattice_zero_rings"], f"must be among lattice_family_rings = "
                    f"{self.lattice_family_rings} (the second minimum's member is on the continuation)",
                    self.lattice_zero_rings)
        if float(self.lattice_zero_eps) not in [float(x) for x in self.lattice_eps]:
            out.add(where + ["lattice_zero_eps"], f"must be one of lattice_eps = {self.lattice_eps}",
                    self.lattice_zero_eps)
        if float(self.lattice_zero_step) not in [float(x) for x in self.lattice_steps]:
            out.add(where + ["lattice_zero_step"], f"must be one of lattice_steps = {self.lattice_steps}",
                    self.lattice_zero_step)
        if any(y <= x for x, y in itertools.pairwise(self.lattice_zero_grid)) or 0.0 not in self.lattice_zero_grid:
            out.add(where + ["lattice_zero_grid"], "must be strictly increasing and hold 0 (the minimum's member)",
                    self.lattice_zero_grid)

    def check_motion(self, where: Where, out: Errors) -> None:
        """The keys of the TBs in motion: motion_speed among speeds, motion_eps decreasing, a ring long enough."""
        if float(self.motion_speed) not in [float(x) for x in self.speeds]:
            out.add(where + ["motion_speed"], f"must be one of speeds = {self.speeds}", self.motion_speed)
        if any(y >= x for x, y in itertools.pairwise(self.motion_eps)):
            out.add(where + ["motion_eps"], "must be strictly decreasing", self.motion_eps)
        least = self.N + self.motion_sites + self.motion_window
        if self.motion_ring < least:
            out.add(where + ["motion_ring"], f"must be >= N + motion_sites + motion_window = {least} (the breather "
                    "would meet what it left behind)", self.motion_ring)


# ----------------------------------------------------------------- the family


def static_profiles(N: int, alpha: float, norm: float) -> dict[str, tuple[NDArray[np.float64], float]]:
    """The static breathers A_n = phi_n e^{i Omega tau} of both parities at the norm: phi = s a (a of (dpsstn),
    mu = 1, as the breathers analysis builds it), Omega = s^(alpha-1) / (2 tau0) (the scaling of (dpsstn))."""
    from cradle.models import dps, homoclinic

    out = {}
    for kind in ("site", "bond"):
        a = homoclinic.solve(homoclinic.initial_guess(N, kind, alpha, 0.1), alpha).a
        s = math.sqrt(norm / float(np.sum(a**2)))
        out[kind] = (s * a, s ** (alpha - 1.0) / (2.0 * dps.tau0(alpha)))
    return out


#: the first TB of each ring (solved from the pushed static breather), by (N, alpha, norm, kick, newton_tol, rtol):
#: the family and the limit scan of the same ring start from it
_FIRST: dict[tuple[int, float, float, float, float, float], TravellingBreather] = {}


def first_member(spec: TravellingBreathers, N: int, rtol: float) -> TravellingBreather:
    """The TB that Newton reaches from the static site breather pushed by ``kick`` on the ring of N (computed once
    per process and parameters: the same numbers each call); where the plain Newton stops short (rings of 128 and
    more), the one :func:`cradle.integrators.dps_travelling.newton_core_first` reaches from the same start."""
    from cradle.integrators import dps_travelling as DT

    key = (N, float(spec.alpha), float(spec.norm), float(spec.kick), float(spec.newton_tol), float(rtol))
    if key not in _FIRST:
        phi, _ = static_profiles(N, spec.alpha, spec.norm)["site"]
        A, T, theta = DT.start(phi, spec.kick, spec.alpha)
        b = DT.newton(A, T, theta, spec.alpha, spec.norm, tol=spec.newton_tol, rtol=rtol)
        if not b.converged:
            b = DT.newton_core_first(A, T, theta, spec.alpha, spec.norm, tol=spec.newton_tol, rtol=rtol)[0]
        _FIRST[key] = b
    return _FIRST[key]


def family(spec: TravellingBreathers, N: int, rtol: float,
           log: Log | None = None) -> tuple[list[TravellingBreather], float]:
    """The members at the spec's speeds (those reached; a missing one is absent) on the ring of N sites, and
    the c of the first guess."""
    from cradle.integrators import dps_travelling as DT

    first = first_member(spec, N, rtol)
    if not first.converged:
        raise RuntimeError(f"travelling breathers: no TB from the pushed breather (kick {spec.kick}, "
                           f"c = {first.c:.4g})")
    cs = np.asarray(spec.speeds, float)
    down, _ = DT.continue_family(first, cs[cs < first.c][::-1], spec.newton_tol, rtol, log=log)
    up, _ = DT.continue_family(first, cs[cs >= first.c], spec.newton_tol, rtol, log=log)
    return down[::-1] + up, first.c


def verdict(b: TravellingBreather | LatticeTB, threshold: float,
            trivial: int = TRIVIAL) -> tuple[float, float, bool, bool]:
    """(trivial defect, growth rate, unstable, real): the ``trivial`` multipliers nearest 1 are the trivial ones (four
    for DpS, :data:`LATTICE_TRIVIAL` for the lattice); their
    largest |mu - 1| is the defect, ln max|mu| / T over the others the growth rate; ``real`` when the unstable
    multiplier is real and > 1 (a pair left +1 along the real axis, the kind the dH/dc criterion is about)
    rather than an oscillatory quartet."""
    mu = b.multipliers
    order = np.argsort(np.abs(mu - 1.0))
    defect = float(np.abs(mu[order[trivial - 1]] - 1.0))
    rest = mu[order[trivial:]]
    top = rest[int(np.argmax(np.abs(rest)))]
    rate = float(np.log(np.abs(top)) / b.T)
    unstable = rate > threshold
    return defect, rate, bool(unstable), bool(unstable and top.real > 0 and abs(top.imag) <= REAL * abs(top))


def static_distance(b: TravellingBreather, profiles: dict, samples: int, rtol: float) -> dict[str, float]:
    """min over tau in one period and over shifts k of max_n ||A_n(tau)| - |phi_{n-k}|| / max phi, for each
    parity: how close the moving breather comes to the static one."""
    from cradle.integrators import integrate_dps

    tau = np.linspace(0.0, b.T, samples + 1)
    run = integrate_dps(b.A, tau, alpha=b.alpha, rtol=rtol)
    mod = np.abs(run.A)
    out = {}
    for kind, (phi, _) in profiles.items():
        P = np.stack([np.roll(np.abs(phi), k) for k in range(phi.size)])      # (shift, n)
        d = np.max(np.abs(mod[:, None, :] - P[None, :, :]), axis=2)
        out[kind] = float(np.min(d) / np.max(np.abs(phi)))
    return out


def direct_run(b: TravellingBreather, periods: int, rtol: float) -> dict:
    """The member run by (dfnls) over ``periods`` periods (integrate_dps, dop853_numba): norm and H drifts and
    the residual max_n |A_n(kT) - e^{i k theta} A_{n-k}(0)| / max|A| at each k."""
    from cradle.integrators import integrate_dps
    from cradle.models import dps_travelling as M

    k = np.arange(periods + 1)
    run = integrate_dps(b.A, k * b.T, alpha=b.alpha, rtol=rtol)
    res = np.array([np.max(np.abs(run.A[j] - np.exp(1j * j * b.theta) * M.shift(b.A, int(j)))) for j in k])
    return {"k": k, "residual": res / np.max(np.abs(b.A)), "norm_drift": float(run.max_l2_drift),
            "energy_drift": float(run.max_energy_drift)}


def scaling_check(b: TravellingBreather, other: TravellingBreather, lam: float, spec: TravellingBreathers) -> dict:
    """The TB at (lambda^(1-alpha) T, lambda^2 P) solved by Newton from lambda times a guess moved by
    ``SCALING_NUDGE`` of the way towards ``other`` (another member: a guess that is no TB), with lambda A as the
    phase reference: its distance to lambda A and the change of theta."""
    from cradle.integrators import dps_travelling as DT
    from cradle.models import dps_travelling as M

    A_l, T_l = M.scaled(b.A, b.T, lam, spec.alpha)
    guess = lam * (b.A + SCALING_NUDGE * (other.A - b.A))
    theta = b.theta + SCALING_NUDGE * math.remainder(other.theta - b.theta, 2 * math.pi)
    s = DT.newton(guess, T_l, theta, spec.alpha, lam**2 * spec.norm, A_l, spec.newton_tol, rtol=spec.rtol)
    return {"profile_error": float(np.max(np.abs(s.A - A_l)) / np.max(np.abs(A_l))),
            "theta_error": float(abs(math.remainder(s.theta - b.theta, 2 * math.pi))), "converged": s.converged,
            "residual": s.residual}


def sign_changes(c: NDArray[np.float64], y: NDArray[np.float64]) -> list[float]:
    """The c where y changes sign between grid points (linear interpolation)."""
    out = []
    for i in range(len(c) - 1):
        if np.isfinite(y[i]) and np.isfinite(y[i + 1]) and y[i] * y[i + 1] < 0:
            out.append(float(c[i] - y[i] * (c[i + 1] - c[i]) / (y[i + 1] - y[i])))
    return out


def verdict_changes(c: NDArray[np.float64], unstable: NDArray[np.bool_]) -> list[float]:
    """The midpoints of the grid intervals where the verdict changes."""
    return [float(0.5 * (c[i] + c[i + 1])) for i in range(len(c) - 1) if unstable[i] != unstable[i + 1]]


# ----------------------------------------------------------------- the lattice's travelling breathers
# Issue 37, item 2: exact TBs of (nc), x_n(t + T) = x_{n-1}(t), started from a DpS member through the ansatz
# (cradle.integrators.lattice_travelling); kept apart from the DpS family above.

#: multipliers modulo shift of a lattice TB at 1: the time shift in a Jordan block with the energy, and the carrier's
#: phase (DpS's phase symmetry, broken weakly in (nc)) in one with the near-conserved wave action
LATTICE_TRIVIAL = 4


def lattice_source(spec: TravellingBreathers, fam: list[TravellingBreather]) -> TravellingBreather:
    """The DpS member at ``lattice_source`` on the ring of ``lattice_N``: from the family when that is its ring, else
    solved on it as :func:`family` starts (the pushed static breather) and continued to that c."""
    from cradle.integrators import dps_travelling as DT

    if spec.lattice_N == spec.N:
        return fam[int(np.argmin([abs(b.c - spec.lattice_source) for b in fam]))]
    phi, _ = static_profiles(spec.lattice_N, spec.alpha, spec.norm)["site"]
    A, T, theta = DT.start(phi, spec.kick, spec.alpha)
    first = DT.newton(A, T, theta, spec.alpha, spec.norm, tol=spec.newton_tol, rtol=spec.rtol)
    members, _ = DT.continue_family(first, [spec.lattice_source], spec.newton_tol, spec.rtol)
    if not first.converged or not members:
        raise RuntimeError(f"lattice travelling breathers: no DpS TB at c = {spec.lattice_source} on the ring of "
                           f"{spec.lattice_N}")
    return members[0]


def lattice_tb(spec: TravellingBreathers, source: TravellingBreather, eps: float,
               log: Log | None = None) -> tuple[LatticeTB, dict]:
    """The exact TB of (nc) from the ansatz of the DpS member ``source`` at ``eps``: the ansatz run by (nc) for its time
    per site T_d eps^(1-alpha); the period T of the solve is the time when the run comes closest to the shifted start
    (:func:`LT.launch_period`: the lattice breather is slower than DpS's, issue 37 item 3)."""
    from cradle.integrators import lattice_travelling as LT

    z, T_hop = LT.ansatz_start(source.A, source.T, spec.alpha, eps)
    T, start_res = LT.launch_period(z, T_hop, spec.alpha)
    b = LT.newton(z, T, spec.alpha, tol=spec.newton_tol, max_iter=20, log=log)
    if not b.converged:
        raise RuntimeError(f"lattice travelling breathers: no TB from the ansatz of c = {source.c:.4g} at eps = {eps} "
                           f"(residual {b.residual:.3g} after {b.iterations} iterations)")
    return b, {"T_hop": T_hop, "start_residual": start_res}


def matched_dps(spec: TravellingBreathers, source: TravellingBreather, b: LatticeTB) -> TravellingBreather:
    """The DpS TB at the lattice TB's own parameters through the ansatz: norm ``spec.norm``, period
    T_d = T eps_b^(alpha-1), eps_b = :attr:`LatticeTB.eps` / sqrt(norm) (continued from ``source``)."""
    from cradle.integrators import dps_travelling as DT

    eps_b = b.eps / math.sqrt(spec.norm)
    c_d = 1.0 / (b.T * eps_b ** (spec.alpha - 1.0))
    members, _ = DT.continue_family(source, [c_d], spec.newton_tol, spec.rtol)
    if not members:
        raise RuntimeError(f"lattice travelling breathers: no DpS TB at c = {c_d:.6g} (the lattice TB's through the "
                           "ansatz)")
    return members[0]


def launched_pair(spec: TravellingBreathers, source: TravellingBreather, b: LatticeTB, eps: float) -> dict:
    """Item 3's comparison at ``eps``: the DpS member ``source`` launched in (nc) through (ansatz) and the exact TB
    ``b`` launched the same way (its N beads on the ring of ``motion_ring``, centred at N/2, zeros elsewhere), both run
    by (nc) (srkn6c) over the lattice time of ``motion_sites`` DpS periods and measured as in :func:`motion`: speeds in
    units of the DpS TB's c eps^(alpha-1), the radiation at the end."""
    from cradle.integrators import integrate_lattice
    from cradle.measurements import breather_motion as BM
    from cradle.models import tb_launch

    al, S, per = spec.alpha, spec.motion_sites, spec.motion_samples
    s = np.linspace(0.0, float(S), S * per + 1)
    t = s * source.T / eps ** (al - 1.0)
    ini = tb_launch.launch(source.A, eps, al, spec.motion_ring)
    xi = tb_launch.embedded(b.envelope, spec.motion_ring)
    out: dict = {}
    for key, (x0, v0) in {"dps": (ini.x0, ini.v0), "exact": (2.0 * xi.real, -2.0 * xi.imag)}.items():
        sol = integrate_lattice(x0, v0, t, alpha=al)
        e = BM.energy_density(sol.x, sol.v, al)
        p = BM.track(e, MOTION_CORE)
        rad = BM.radiation(e, p, spec.motion_window)
        out |= {f"{key}_speed": BM.velocity(s, p), f"{key}_radiation": float(rad[-1]),
                f"{key}_radiation_max": float(np.max(rad)), f"{key}_energy_drift": float(sol.energy_drift),
                f"{key}_distance": p - p[0]}
    out["s"] = s
    return out


def lattice_groups(spec: TravellingBreathers, fam: list[TravellingBreather],
                   log: Log | None = None) -> tuple[dict, dict]:
    """The groups /lattice (the continuation in c at the first of ``lattice_eps``), /lattice_eps (one exact TB at
    eps: residual, tail, multipliers, distance to the DpS TB through the ansatz, and item 3's launched pair),
    /lattice_states and /lattice_motion, and their attributes (prefixed ``lattice_``)."""
    from cradle.integrators import lattice_breathers as LB, lattice_travelling as LT
    from cradle.models import dps_travelling as M

    t0 = _time.process_time()
    say = log or (lambda *a: None)
    source = lattice_source(spec, fam)
    tbs, starts, dist, dps_m, pairs = [], [], [], [], []
    for eps in spec.lattice_eps:
        b, info = lattice_tb(spec, source, eps, log)
        d = matched_dps(spec, source, b)
        tbs.append(b)
        starts.append(info)
        dps_m.append(d)
        dist.append(LT.ansatz_distance(b, d.A, d.T))
        pairs.append(launched_pair(spec, source, b, eps))
        say(f"travelling-breathers: lattice TB from eps = {eps:g}: T = {b.T:.10g} (ansatz {info['T_hop']:.6g}), "
            f"eps_b = {b.eps:.6g}, residual {b.residual:.2g}, {b.iterations} iterations, distance to DpS "
            f"{dist[-1]['distance']:.3g}")
    ver = [verdict(b, spec.stability_threshold, LATTICE_TRIVIAL) for b in tbs]
    eps_b = np.array([b.eps for b in tbs]) / math.sqrt(spec.norm)
    distance = np.array([x["distance"] for x in dist])
    fit, cov = np.polyfit(np.log(eps_b), np.log(distance), 1, cov=True)
    # the continuation in c from the first TB
    first = tbs[0]
    steps = np.asarray(spec.lattice_steps, float)
    cs = first.c * (1.0 + steps)
    # steps halved down to a tenth of the grid's (the amplitude moves some 30 times faster than c along the family)
    least = 0.1 * float(np.min(np.diff(steps))) if steps.size > 1 else 0.001
    down, _ = LT.continue_family(first, cs[steps < 0][::-1], spec.newton_tol, min_step=least, log=log)
    up, _ = LT.continue_family(first, cs[steps > 0], spec.newton_tol, min_step=least, log=log)
    family = down[::-1] + [first] + up
    fver = [verdict(b, spec.stability_threshold, LATTICE_TRIVIAL) for b in family]
    run = LT.direct_run(first, spec.lattice_periods)
    N = first.z.size // 2
    c_f = np.array([b.c for b in family])
    groups = {
        "/lattice": ({"period": 1.0 / c_f, "eps": [b.eps / math.sqrt(spec.norm) for b in family],
                      "energy": [b.energy for b in family], "residual": [b.residual for b in family],
                      "tail": [M.tail_amplitude(b.envelope) for b in family],
                      "trivial_defect": [v[0] for v in fver], "growth_rate": [v[1] for v in fver],
                      "unstable": [int(v[2]) for v in fver],
                      "reciprocal_defect": [LB.multiplier_checks(b.multipliers)["reciprocal"] for b in family],
                      "smallest_singular": [b.smallest_singular for b in family]},
                     {"c_lattice": c_f}),
        "/lattice_eps": ({"period": [b.T for b in tbs], "c_tb": [b.c for b in tbs], "eps_tb": eps_b,
                          "ansatz_period": [x["T_hop"] for x in starts],
                          "start_residual": [x["start_residual"] for x in starts],
                          "residual": [b.residual for b in tbs], "iterations": [b.iterations for b in tbs],
                          "energy": [b.energy for b in tbs], "tail": [M.tail_amplitude(b.envelope) for b in tbs],
                          "trivial_defect": [v[0] for v in ver], "growth_rate": [v[1] for v in ver],
                          "unstable": [int(v[2]) for v in ver],
                          "reciprocal_defect": [LB.multiplier_checks(b.multipliers)["reciprocal"] for b in tbs],
                          "smallest_singular": [b.smallest_singular for b in tbs],
                          "dps_c": [d.c for d in dps_m],
                          "resonance": [math.remainder(d.theta + b.T, 2.0 * math.pi) for b, d in zip(tbs, dps_m,
                                                                                                   strict=True)],
                          "ansatz_distance": distance,
                          **{k: [p[k] for p in pairs] for k in ("dps_speed", "exact_speed", "dps_radiation",
                                                                "exact_radiation", "exact_radiation_max",
                                                                "dps_energy_drift", "exact_energy_drift")}},
                         {"eps_lattice": list(spec.lattice_eps)}),
        "/lattice_states": ({"x": np.array([b.z[:N] for b in tbs]), "v": np.array([b.z[N:] for b in tbs]),
                             "mu_re": np.array([b.multipliers.real for b in tbs]),
                             "mu_im": np.array([b.multipliers.imag for b in tbs]),
                             "dps_A_re": np.array([d.A.real for d in dps_m]),
                             "dps_A_im": np.array([d.A.imag for d in dps_m]),
                             "source_A_re": source.A.real, "source_A_im": source.A.imag},
                            {"eps_lattice": list(spec.lattice_eps), "site": np.arange(N), "mode": np.arange(2 * N)}),
    }
    groups["/lattice_motion"] = ({"dps_distance": np.array([p["dps_distance"] for p in pairs]),
                                  "exact_distance": np.array([p["exact_distance"] for p in pairs])},
                                 {"eps_lattice": list(spec.lattice_eps), "s_lattice": pairs[0]["s"]})
    attrs = {"lattice_source_c": source.c,
             "lattice_max_residual": float(max(b.residual for b in tbs + family)),
             "lattice_max_trivial_defect": float(max(v[0] for v in ver + fver)),
             "lattice_max_reciprocal_defect": float(max(LB.multiplier_checks(b.multipliers)["reciprocal"]
                                                        for b in tbs + family)),
             "lattice_n_unstable": int(sum(v[2] for v in ver + fver)),
             "lattice_distance_power": float(fit[0]), "lattice_distance_power_error": float(math.sqrt(cov[0, 0])),
             "lattice_distance_power_expected": spec.alpha - 1.0,
             "lattice_c_reached": f"{c_f[0]:.8g} to {c_f[-1]:.8g} ({len(family)} of {len(cs)} members)",
             "lattice_direct_periods": spec.lattice_periods,
             "lattice_direct_energy_drift": float(np.max(run["energy_drift"])),
             "lattice_direct_max_residual": float(np.max(run["residual"])),
             "lattice_method": "Gauss-Newton on R = S^{-1} Phi_T(z) - z at fixed T with the time-shift phase "
                               "condition; Phi_T by DOP853 with contact events (rtol "
                               f"{LT.RTOL:g}), the Jacobian by the variational equations (rtol {LT.JAC_RTOL:g}); the "
                               "near-symmetry's direction left out of the step (truncated least squares) until the "
                               "residual is what it alone can remove",
             "lattice_cpu_s": _time.process_time() - t0}
    more, more_attrs = lattice_rings_groups(spec, source, tbs, by_step(cs, family), log)
    return groups | more, attrs | more_attrs


# ----------------------------------------------------------------- the lattice's TBs on other rings
# Issue 37, item 2: the TBs of (nc) on rings beyond lattice_N (each carried from the ring before, sites at rest added
# on the far side), the continuation in c on some of them, and TBs at larger eps solved the core first
# (cradle.integrators.lattice_travelling.newton_core_first); kept apart from the ring of lattice_N above.

#: the per-member variables of /lattice_rings, (ring, eps_lattice) and, with the suffix _family, (ring, c_step)
RING_MEMBER = ("period", "eps_tb", "dps_c", "residual", "iterations", "tail", "energy", "trivial_defect",
               "growth_rate", "unstable", "reciprocal_defect", "smallest_singular")


def by_step(cs: NDArray[np.float64], members: list[LatticeTB]) -> list[LatticeTB | None]:
    """The members of a continuation at the grid's c (None where it was not reached)."""
    return [next((b for b in members if math.isclose(b.c, c, rel_tol=1e-12)), None) for c in cs]


def ring_member(b: LatticeTB | None, spec: TravellingBreathers) -> dict[str, float]:
    """The stored numbers of one lattice TB (:data:`RING_MEMBER`; NaN for a member not reached); dps_c the velocity
    of the DpS TB through the ansatz, 1 / (T eps_b^(alpha-1)), eps_b = eps / sqrt(norm)."""
    from cradle.integrators import lattice_breathers as LB
    from cradle.models import dps_travelling as M

    out = dict.fromkeys(RING_MEMBER, math.nan)
    if b is None:
        return out
    eps_b = b.eps / math.sqrt(spec.norm)
    out |= {"period": b.T, "eps_tb": eps_b, "dps_c": 1.0 / (b.T * eps_b ** (spec.alpha - 1.0)),
            "residual": b.residual, "iterations": b.iterations, "tail": M.tail_amplitude(b.envelope),
            "energy": b.energy, "smallest_singular": b.smallest_singular}
    if b.multipliers.size:    # a converged member's
        triv, growth, unstable, _ = verdict(b, spec.stability_threshold, LATTICE_TRIVIAL)
        out |= {"trivial_defect": triv, "growth_rate": growth, "unstable": int(unstable),
                "reciprocal_defect": LB.multiplier_checks(b.multipliers)["reciprocal"]}
    return out


def _padded(members: list[LatticeTB | None], width: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(x, v) of the members as rows of ``width`` sites, NaN beyond each ring and for a member not reached."""
    x, v = np.full((len(members), width), np.nan), np.full((len(members), width), np.nan)
    for i, b in enumerate(members):
        if b is not None:
            N = b.z.size // 2
            x[i, :N], v[i, :N] = b.z[:N], b.z[N:]
    return x, v


def carried(spec: TravellingBreathers, b: LatticeTB, N: int, log: Log | None) -> LatticeTB | None:
    """The TB ``b`` of a smaller ring solved again on the ring of N (:func:`LT.embed`; the phase condition about the
    carried state), or None when Newton does not converge."""
    from cradle.integrators import lattice_travelling as LT

    out = LT.newton(LT.embed(b.z, N), b.T, spec.alpha, tol=spec.newton_tol, log=log)
    return out if out.converged else None


def lattice_rings_groups(spec: TravellingBreathers, source: TravellingBreather, tbs: list[LatticeTB],
                         family: list[LatticeTB | None], log: Log | None = None) -> tuple[dict, dict]:
    """The groups /lattice_rings (the TBs at every lattice_eps on the ring of lattice_N and on every ring of
    ``lattice_rings``; the continuation in c on ``lattice_family_rings``) and /lattice_large (TBs at
    ``lattice_large_eps`` on the ring of lattice_N by :func:`LT.newton_core_first`), with their attributes
    (prefixed ``lattice_rings_``, ``lattice_large_``). ``source``: the DpS member whose ansatz started ``tbs`` (the
    TBs at lattice_eps); ``family``: the members of /lattice at the lattice_steps (None where not reached)."""
    from cradle.integrators import lattice_travelling as LT

    t0 = _time.process_time()
    say = log or (lambda *a: None)
    rings = [spec.lattice_N, *spec.lattice_rings]
    steps = np.asarray(spec.lattice_steps, float)
    i0 = int(np.argmin(np.abs(steps)))
    eps_rows: list[list[LatticeTB | None]] = [list(tbs)]
    fam_rows: list[list[LatticeTB | None]] = [list(family)]
    for N in spec.lattice_rings:
        # each member from the same member of the ring before (the first ring: the ring of lattice_N)
        row = [None if p is None else carried(spec, p, N, log) for p in eps_rows[-1]]
        eps_rows.append(row)
        fam: list[LatticeTB | None] = [None] * steps.size
        first = row[0]
        if N in spec.lattice_family_rings and first is not None:
            cs = first.c * (1.0 + steps)
            least = 0.1 * float(np.min(np.diff(steps))) if steps.size > 1 else 0.001
            # the corrector on the core first: the predictor's error would otherwise put a tail on the far sites
            down, _ = LT.continue_family(first, cs[:i0][::-1], spec.newton_tol, min_step=least, log=log,
                                         core_first=True)
            up, _ = LT.continue_family(first, cs[i0 + 1:], spec.newton_tol, min_step=least, log=log, core_first=True)
            fam = by_step(cs, down[::-1] + [first] + up)
        fam_rows.append(fam)
        say(f"travelling-breathers: lattice TBs on the ring of {N}: " + ", ".join(
            "-" if b is None else f"eps {b.eps:.4g} residual {b.residual:.2g}" for b in row)
            + (f"; {sum(b is not None for b in fam)} of {steps.size} members in c" if N in spec.lattice_family_rings
               else ""))
    width = max(rings)
    eps_vals = [[ring_member(b, spec) for b in row] for row in eps_rows]
    fam_vals = [[ring_member(b, spec) for b in row] for row in fam_rows]
    xe, ve = zip(*[_padded(row, width) for row in eps_rows], strict=True)
    xf, vf = zip(*[_padded(row, width) for row in fam_rows], strict=True)
    data = {k: np.array([[m[k] for m in row] for row in eps_vals]) for k in RING_MEMBER}
    data |= {f"{k}_family": np.array([[m[k] for m in row] for row in fam_vals]) for k in RING_MEMBER}
    data |= {"x": np.array(xe), "v": np.array(ve), "x_family": np.array(xf), "v_family": np.array(vf),
             "c_family": np.array([[math.nan if b is None else b.c for b in row] for row in fam_rows])}
    stored = [b for row in eps_rows + fam_rows for b in row if b is not None]
    cpu_rings = _time.process_time() - t0
    large, large_attrs = lattice_large(spec, source, log)
    zeros, zeros_attrs = lattice_zeros(spec, rings, eps_rows, fam_rows, log)
    groups = {"/lattice_rings": (data, {"ring": rings, "eps_lattice": list(spec.lattice_eps),
                                        "c_step": list(steps), "ring_site": np.arange(width)}),
              **large, **zeros}
    attrs = {"lattice_rings_max_residual": float(max(b.residual for b in stored)),
             "lattice_rings_reached": f"{sum(b is not None for row in eps_rows for b in row)} of "
                                      f"{len(rings) * len(tbs)} members at lattice_eps, "
                                      f"{sum(b is not None for row in fam_rows[1:] for b in row)} of "
                                      f"{len(spec.lattice_family_rings) * steps.size} in c beyond the first ring",
             "lattice_rings_method": "each ring's TB from the same member of the ring before, sites at rest added on "
                                     "the far side (the breather centred), Newton at the same T; the continuation in "
                                     "c as on the ring of lattice_N, its corrector on the core's unknowns first",
             "lattice_rings_cpu_s": cpu_rings, **large_attrs, **zeros_attrs}
    return groups, attrs


def lattice_large(spec: TravellingBreathers, source: TravellingBreather, log: Log | None = None) -> tuple[dict, dict]:
    """The group /lattice_large: the exact TBs from the ansatz of the DpS member ``source`` at each
    ``lattice_large_eps`` on the ring of lattice_N, by :func:`LT.newton_core_first` at the period of the closest
    return (:func:`LT.launch_period`); its attributes prefixed ``lattice_large_``. Empty without such eps."""
    from cradle.integrators import lattice_travelling as LT

    if not spec.lattice_large_eps:
        return {}, {}
    t0 = _time.process_time()
    say = log or (lambda *a: None)
    members, extra = [], []
    for eps in spec.lattice_large_eps:
        z, T_hop = LT.ansatz_start(source.A, source.T, spec.alpha, eps)
        T, start_res = LT.launch_period(z, T_hop, spec.alpha)
        b, core_res = LT.newton_core_first(z, T, spec.alpha, tol=spec.newton_tol, max_iter=20, log=log)
        say(f"travelling-breathers: lattice TB at eps = {eps:g} (core first): residual {b.residual:.2g}, "
            f"converged {b.converged}")
        members.append(b)
        extra.append({"ansatz_period": T_hop, "start_residual": start_res, "core_residual": core_res,
                      "converged": int(b.converged)})
    vals = [ring_member(b, spec) for b in members]
    data: dict[str, object] = {k: [m[k] for m in vals] for k in RING_MEMBER}
    data |= {k: [e[k] for e in extra] for k in extra[0]}
    data |= {"x": np.array([b.z[:b.z.size // 2] for b in members]),
             "v": np.array([b.z[b.z.size // 2:] for b in members])}
    attrs = {"lattice_large_max_residual": float(max(b.residual for b in members)),
             "lattice_large_method": "Newton in two stages at the period of the closest return: the core's unknowns "
                                     f"alone (|xi_n| above {LT.CORE:g} of the largest) to a residual of "
                                     f"{LT.CORE_TOL:g}, the far sites at the ansatz's values, then all unknowns",
             "lattice_large_cpu_s": _time.process_time() - t0}
    return {"/lattice_large": (data, {"eps_large": list(spec.lattice_large_eps),
                                      "site": np.arange(spec.lattice_N)})}, attrs


# ----------------------------------------------------------------- where the lattice's tail vanishes
# Issue 37, item 2: "the parameters where it nearly vanishes". The signed tail of a lattice TB
# (cradle.integrators.lattice_tail) followed along the branch of each of the two members where the far field is
# least (the TB at lattice_zero_eps, the continuation's member at lattice_zero_step) on a fine grid of c, and its
# zero located by regula falsi; kept apart from the rings above.

#: the regula falsi's iterates at most (from the measured slopes, one to three reach the floor)
ZERO_ITERATIONS = 4
#: the numbers of each grid point and of each located zero in /lattice_zeros
ZERO_POINT = ("c_tb", "period", "eps_tb", "dps_c", "residual", "sigma", "tail", "phase_defect")
#: the located zero's further numbers: its Floquet verdict, the symmetric time's defect, the bracket, the iterates
ZERO_MORE = ("c_error", "symmetry_defect", "trivial_defect", "growth_rate", "unstable", "reciprocal_defect",
             "bracket_low", "bracket_high", "iterations")


def zero_point(b: LatticeTB | None, s: SignedTail | None, spec: TravellingBreathers) -> dict[str, float]:
    """The numbers :data:`ZERO_POINT` of one member and its signed tail (NaN for a member not reached)."""
    m = ring_member(b, spec)
    if b is None or s is None:
        return dict.fromkeys(ZERO_POINT, math.nan)
    return {k: m[k] for k in ZERO_POINT if k in m} | {"c_tb": b.c, "sigma": s.sigma, "phase_defect": s.phase_defect}


def zero_grid(spec: TravellingBreathers, start: LatticeTB,
              log: Log | None) -> list[tuple[LatticeTB, SignedTail] | None]:
    """(member, signed tail) at each c = c1 (1 + s), s of ``lattice_zero_grid``, c1 the velocity of ``start`` (None
    where the continuation stopped): :func:`LT.continue_family` from ``start`` down and up with the plain corrector
    (the grid's steps leave a predictor error far below the far field)."""
    from cradle.integrators import lattice_tail as LTail, lattice_travelling as LT

    grid = np.asarray(spec.lattice_zero_grid, float)
    cs = start.c * (1.0 + grid)
    least = 0.125 * float(np.min(np.diff(grid))) if grid.size > 1 else 1e-4
    down, _ = LT.continue_family(start, cs[grid < 0][::-1], spec.newton_tol, min_step=least, log=log)
    up, _ = LT.continue_family(start, cs[grid > 0], spec.newton_tol, min_step=least, log=log)
    members = by_step(cs, [*down[::-1], start, *up])
    return [None if b is None else (b, LTail.signed_tail(b.z, b.T, b.alpha)) for b in members]


def zero_bracket(points: list[tuple[LatticeTB, SignedTail] | None]) -> int | None:
    """i such that the grid points i and i + 1 bracket a zero of the signed tail: their signs differ, and beyond them
    the tail grows away (|sigma| larger with the same sign at i - 1 or at i + 2) and shrinks on neither side (a ring
    resonance's bracket, where |sigma| grows towards the sign change, is not a zero's; a point beyond with the other
    sign is a resonance or another zero beyond and says nothing); of several, the one with the smallest larger
    |sigma| of the two. None without one."""
    s = [math.nan if p is None else p[1].sigma for p in points]

    def beyond(i: int, j: int) -> int:
        """+1 if point j has point i's sign and a larger |sigma|, -1 if that sign and a smaller one, else 0."""
        if not 0 <= j < len(s) or not math.isfinite(s[j]) or s[i] * s[j] <= 0:
            return 0
        return 1 if abs(s[j]) > abs(s[i]) else -1

    pairs = []
    for i in range(len(s) - 1):
        if not s[i] * s[i + 1] < 0:
            continue
        outer = (beyond(i, i - 1), beyond(i + 1, i + 2))
        if 1 in outer and -1 not in outer:
            pairs.append((max(abs(s[i]), abs(s[i + 1])), i))
    return min(pairs)[1] if pairs else None


def tail_zero(spec: TravellingBreathers, start: LatticeTB, log: Log | None = None) -> dict:
    """The zero of the signed tail on the branch of ``start``: the grid of :func:`zero_grid`, then
    :func:`LTail.locate_zero` in its bracket (:func:`zero_bracket`); located when the iterates reach the floor,
    |sigma| at most newton_tol (the residuals' bound; below it they scatter). Returns the grid's points (``grid``: a
    dict of :data:`ZERO_POINT` lists), the zero's numbers (``zero``: :data:`ZERO_POINT` and :data:`ZERO_MORE`, NaN
    without a zero located), its state ``z`` (None without) and the iterates' (c, sigma) (``trace``)."""
    from cradle.integrators import lattice_breathers as LB, lattice_tail as LTail

    pts = zero_grid(spec, start, log)
    rows = [zero_point(None, None, spec) if p is None else zero_point(p[0], p[1], spec) for p in pts]
    grid = {k: [r[k] for r in rows] for k in ZERO_POINT}
    zero = dict.fromkeys(ZERO_POINT + ZERO_MORE, math.nan)
    i = zero_bracket(pts)
    if i is None:
        return {"grid": grid, "zero": zero, "z": None, "trace": []}
    (a, sa), (b, sb) = pts[i], pts[i + 1]  # type: ignore[misc]
    m, s, trace = LTail.locate_zero(a, b, sa.sigma, sb.sigma, spec.newton_tol, ZERO_ITERATIONS, log)
    if abs(s.sigma) > spec.newton_tol:
        # the iterates did not reach the floor: a flip within the tail's scatter, not a zero that can be seen
        return {"grid": grid, "zero": zero, "z": None, "trace": trace}
    triv, growth, unstable, _ = verdict(m, spec.stability_threshold, LATTICE_TRIVIAL)
    # the place is known to the c over which the bracket's slope moves sigma by what is not resolved
    slope = abs(sb.sigma - sa.sigma) / abs(b.c - a.c)
    zero = zero_point(m, s, spec) | {"c_error": max(abs(s.sigma), m.residual) / slope,
                                      "symmetry_defect": s.symmetry_defect, "trivial_defect": triv,
                                      "growth_rate": growth, "unstable": int(unstable),
                                      "reciprocal_defect": LB.multiplier_checks(m.multipliers)["reciprocal"],
                                      "bracket_low": a.c, "bracket_high": b.c, "iterations": len(trace)}
    return {"grid": grid, "zero": zero, "z": m.z, "trace": trace}


def lattice_zeros(spec: TravellingBreathers, rings: list[int], eps_rows: list[list[LatticeTB | None]],
                  fam_rows: list[list[LatticeTB | None]], log: Log | None = None) -> tuple[dict, dict]:
    """The group /lattice_zeros: on each ring of ``lattice_zero_rings`` (``rings``, ``eps_rows`` and ``fam_rows``
    as :func:`lattice_rings_groups` builds them) the zero of the signed tail on the branch of the TB at
    lattice_zero_eps and on that of the continuation's member at lattice_zero_step (:func:`tail_zero`); its
    attributes prefixed ``lattice_zeros_``. Empty without such rings."""
    if not spec.lattice_zero_rings:
        return {}, {}
    t0 = _time.process_time()
    say = log or (lambda *a: None)
    j_eps = [float(e) for e in spec.lattice_eps].index(float(spec.lattice_zero_eps))
    j_step = [float(s) for s in spec.lattice_steps].index(float(spec.lattice_zero_step))
    found: list[list[dict | None]] = []
    for N in spec.lattice_zero_rings:
        k = rings.index(N)
        row: list[dict | None] = []
        for start in (eps_rows[k][j_eps], fam_rows[k][j_step]):
            f = None if start is None else tail_zero(spec, start, log)
            row.append(f)
            if f is not None:
                zr = f["zero"]
                say(f"travelling-breathers: tail zero on the ring of {N}: c = {zr['c_tb']:.10g}, sigma "
                    f"{zr['sigma']:.2g}, residual {zr['residual']:.2g}")
        found.append(row)
    width = max(spec.lattice_zero_rings)
    n_grid, n_it = len(spec.lattice_zero_grid), ZERO_ITERATIONS
    blank_grid = {k: [math.nan] * n_grid for k in ZERO_POINT}
    blank = dict.fromkeys(ZERO_POINT + ZERO_MORE, math.nan)
    data: dict[str, object] = {
        f"{k}_grid": np.array([[(blank_grid if f is None else f["grid"])[k] for f in row] for row in found])
        for k in ZERO_POINT}
    data |= {k: np.array([[(blank if f is None else f["zero"])[k] for f in row] for row in found])
             for k in ZERO_POINT + ZERO_MORE}
    trace = np.full((len(found), 2, n_it, 2), np.nan)
    xs, vs = np.full((len(found), 2, width), np.nan), np.full((len(found), 2, width), np.nan)
    for i, row in enumerate(found):
        for j, f in enumerate(row):
            if f is None:
                continue
            for q, cs in enumerate(f["trace"]):
                trace[i, j, q] = cs
            if f["z"] is not None:
                n = f["z"].size // 2
                xs[i, j, :n], vs[i, j, :n] = f["z"][:n], f["z"][n:]
    data |= {"c_iterate": trace[..., 0], "sigma_iterate": trace[..., 1], "x": xs, "v": vs}
    located = [f["zero"] for row in found for f in row if f is not None and np.isfinite(f["zero"]["c_tb"])]
    attrs = {"lattice_zeros_located": f"{len(located)} of {2 * len(found)}",
             "lattice_zeros_max_residual": float(max((z["residual"] for z in located), default=math.nan)),
             "lattice_zeros_max_abs_sigma": float(max((abs(z["sigma"]) for z in located), default=math.nan)),
             "lattice_zeros_method": "signed tail sigma = Re(B / xi_n0) |xi_n0| / max|xi| at the TB's symmetric time "
                                     "(cradle.integrators.lattice_tail); the grid by the continuation in c from each "
                                     "minimum's member, the zero by regula falsi (Illinois) in a sign change of the "
                                     "grid away from which |sigma| grows (zero_bracket), at most "
                                     f"{ZERO_ITERATIONS} iterates, stopped and accepted where |sigma| is at most "
                                     "newton_tol (the residual's bound)",
             "lattice_zeros_cpu_s": _time.process_time() - t0}
    coords = {"zero_ring": list(spec.lattice_zero_rings), "minimum": [0, 1],
              "zero_step": list(spec.lattice_zero_grid), "iterate": np.arange(n_it), "zero_site": np.arange(width)}
    return {"/lattice_zeros": (data, coords)}, attrs


# ----------------------------------------------------------------- TBs in motion (issue 37, item 3)

#: half-width (sites) of the centroid that gives a breather's position: the DpS core decays doubly exponentially,
#: so its weight beyond it is below rounding of the weight's sum and radiation near the core barely moves it
MOTION_CORE = 4
#: DOP853's relative tolerance in the rerun that checks the lattice's speed against the integrator
MOTION_CHECK_RTOL = 1e-11


def motion(spec: TravellingBreathers, b: TravellingBreather, log: Log) -> tuple[dict, dict]:
    """The member ``b`` launched on a ring of ``motion_ring`` sites (:mod:`cradle.models.tb_launch`): in (dfnls)
    (integrate_dps at the family's rtol), and in (nc) through (ansatz) at each eps of ``motion_eps`` (integrate_lattice,
    srkn6c, the pipeline's exact method), both over ``motion_sites`` periods T of tau; positions, distances,
    velocities and radiation by :mod:`cradle.measurements.breather_motion` (lattice: energy density; DpS: norm
    density). Returns the ``/motion`` group and its attributes (prefixed ``motion_``)."""
    from cradle.integrators import integrate_dps, integrate_lattice
    from cradle.measurements import breather_motion as BM
    from cradle.measurements.continuum import fit_power
    from cradle.models import dps_travelling as M, tb_launch

    t0 = _time.process_time()
    al, S, per = spec.alpha, spec.motion_sites, spec.motion_samples
    s = np.linspace(0.0, float(S), S * per + 1)
    half = s.size // 2
    # DpS: the same start on the same ring; after k periods it should be the start shifted by k sites
    A0 = tb_launch.embedded(b.A, spec.motion_ring)
    run = integrate_dps(A0, s * b.T, alpha=al, rtol=spec.rtol)
    w = np.abs(run.A) ** 2
    p_dps = BM.track(w, MOTION_CORE)
    k = np.arange(S + 1)
    at_k = run.A[k * per]
    shift_res = max(float(np.max(np.abs(at_k[j] - np.exp(1j * j * b.theta) * M.shift(A0, int(j))))) for j in k)
    dps_rad = BM.radiation(w, p_dps, spec.motion_window)
    attrs: dict = {
        "motion_c": b.c, "motion_ring": spec.motion_ring, "motion_core": MOTION_CORE,
        "motion_window": spec.motion_window,
        "motion_dps_speed_error": abs(BM.velocity(s, p_dps) - 1.0),
        "motion_dps_position_error": float(np.max(np.abs(p_dps[k * per] - p_dps[0] - k))),
        "motion_dps_shift_residual": shift_res / float(np.max(np.abs(A0))),
        "motion_dps_norm_drift": float(run.max_l2_drift),
        "motion_dps_radiation_max": float(np.max(dps_rad)),
    }
    rows: dict[str, list] = {key: [] for key in ("speed_ratio", "speed_early", "speed_late", "radiation_end",
                                                 "energy_drift", "distance", "radiation")}
    for eps in spec.motion_eps:
        ini = tb_launch.launch(b.A, eps, al, spec.motion_ring)
        sol = integrate_lattice(ini.x0, ini.v0, s * b.T / eps ** (al - 1.0), alpha=al)
        e = BM.energy_density(sol.x, sol.v, al)
        p = BM.track(e, MOTION_CORE)
        rad = BM.radiation(e, p, spec.motion_window)
        # velocities against s = tau / T: in units of the DpS TB's c eps^(alpha-1)
        rows["speed_ratio"].append(BM.velocity(s, p))
        rows["speed_early"].append(BM.velocity(s[:half + 1], p[:half + 1]))
        rows["speed_late"].append(BM.velocity(s[half:], p[half:]))
        rows["radiation_end"].append(float(rad[-1]))
        rows["energy_drift"].append(float(sol.energy_drift))
        rows["distance"].append(p - p[0])
        rows["radiation"].append(rad)
        log(f"travelling-breathers: c = {b.c:.4g} in (nc) at eps = {eps:g}: {p[-1] - p[0]:.4f} sites while DpS "
            f"travels {S}, speed ratio {rows['speed_ratio'][-1]:.6f} (halves {rows['speed_early'][-1]:.6f}, "
            f"{rows['speed_late'][-1]:.6f}), radiation {rad[-1]:.3g}, energy drift {sol.energy_drift:.2g}")
    ratio = np.asarray(rows["speed_ratio"])
    # the integrator's share: the largest eps rerun by the adaptive DOP853 (another method, its own error control)
    eps0 = spec.motion_eps[0]
    ini = tb_launch.launch(b.A, eps0, al, spec.motion_ring)
    ref = integrate_lattice(ini.x0, ini.v0, s * b.T / eps0 ** (al - 1.0), alpha=al, method="dop853_numba",
                            rtol=MOTION_CHECK_RTOL)
    ref_ratio = BM.velocity(s, BM.track(BM.energy_density(ref.x, ref.v, al), MOTION_CORE))
    attrs.update({"motion_check_method": f"dop853_numba, rtol {MOTION_CHECK_RTOL:g}, at eps = {eps0:g}",
                  "motion_check_speed_ratio": ref_ratio,
                  "motion_check_speed_difference": abs(ref_ratio - float(ratio[0]))})
    deficit = 1.0 - ratio
    if np.all(deficit > 0):
        # (ansatz) leaves out terms of relative order eps^(alpha-1): the deficit's first correction is of that power
        f = fit_power(spec.motion_eps, deficit, correction=al - 1.0)
        attrs.update({"motion_order": f.power, "motion_order_uncertainty": f.uncertainty,
                      "motion_order_constant": f.K, "motion_order_correction": f.k})
    else:
        attrs.update({"motion_order": np.nan, "motion_order_uncertainty": np.nan,
                      "motion_order_constant": np.nan, "motion_order_correction": np.nan})
    loss = 1.0 - np.asarray(rows["speed_late"]) / np.asarray(rows["speed_early"])
    attrs.update({
        "motion_order_expected": al - 1.0,
        "motion_order_fit": "ln(1 - speed_ratio) = p ln eps + ln K + k eps^(alpha-1) over every eps (least squares); "
                            "uncertainty the larger of the standard error and the change when the smallest or the "
                            "largest eps is left out",
        "motion_max_energy_drift": float(max(rows["energy_drift"])),
        "motion_speed_loss_max": float(np.max(np.abs(loss))),
        "motion_exact_tb": "the exact TBs of (nc) launched the same way beside the DpS member (its own ring and eps): "
                           "/lattice_eps (dps_speed, exact_speed, *_radiation), with the key lattice (the full form)",
        "motion_cpu_s": _time.process_time() - t0,
    })
    data = {"speed_ratio": ratio, "speed_early": rows["speed_early"], "speed_late": rows["speed_late"],
            "deficit": deficit, "radiation_end": rows["radiation_end"], "energy_drift": rows["energy_drift"],
            "distance": np.array(rows["distance"]), "radiation": np.array(rows["radiation"]),
            "dps_distance": p_dps - p_dps[0], "dps_radiation": dps_rad}
    return {"/motion": (data, {"eps": list(spec.motion_eps), "s": s})}, attrs


# ----------------------------------------------------------------- robustness of the verdicts (rings, tolerances)

#: a member's verdict is settled when the ring of N, every check ring and every check tolerance give it
SETTLED_STABLE, SETTLED_UNSTABLE, RING_DEPENDENT = 0, 1, -1
#: sideband wavenumbers p in (0, pi] over which the tail's plane-wave MI rate is maximised
MI_SIDEBANDS = 512


def far_sites(A: NDArray[np.complex128]) -> NDArray[np.bool_]:
    """The quarter ring farthest from the centre (ring distance >= 3N/8), where the tail is measured."""
    from cradle.models import dps_travelling as M

    N = A.size
    return np.abs((np.arange(N) - M.centre(A) + N / 2) % N - N / 2) >= 3 * N / 8


def tail_wave(A: NDArray[np.complex128]) -> tuple[float, float]:
    """(q, R): the tail as a plane wave R e^{i q n} on the far quarter ring, q = arg sum A_{n+1} conj(A_n) and R the
    rms |A_n| there. A tail that is a plane wave of (dfnls) of small amplitude has frequency ~ R^(alpha-1), so
    (tb) gives q = theta mod 2 pi to that order."""
    far = np.where(far_sites(A))[0]
    q = float(np.angle(np.sum(A[(far + 1) % A.size] * np.conj(A[far]))))
    return q, float(np.sqrt(np.mean(np.abs(A[far]) ** 2)))


def tail_mi_rate(q: float, R: float, alpha: float) -> float:
    """The largest growth rate over the sidebands p of the plane wave R e^{i q n} of (dfnls) on the infinite
    lattice (:func:`cradle.analyses.mi_diagram.growth_rate`): 0 for |q| <= pi/2."""
    from cradle.analyses import mi_diagram

    p = np.linspace(0.0, np.pi, MI_SIDEBANDS + 1)[1:]
    return float(np.max(mi_diagram.growth_rate(q, p, alpha, R)))


def member_checks(b: TravellingBreather, threshold: float) -> dict[str, float]:
    """One member's verdict and what explains it: growth rate, verdict, tail and its plane wave (q, MI rate), and
    the extent of the most unstable mode (participation ratio 1 / sum w_n^2 of its |v_n|^2 = w_n, over N: 1 for
    a mode spread evenly over the ring, ~ (core width) / N for a mode of the core; NaN when stable)."""
    from cradle.models import dps_travelling as M

    _, rate, unstable, _ = verdict(b, threshold)
    q, R = tail_wave(b.A)
    extent = np.nan
    if unstable:
        _, w = b.unstable_mode(TRIVIAL)
        extent = float(1.0 / np.sum(w**2) / b.A.size)
    return {"growth": rate, "unstable": float(unstable), "tail": M.tail_amplitude(b.A), "theta": b.theta,
            "tail_q": q, "tail_mi": tail_mi_rate(q, R, b.alpha), "extent": extent}


ROBUST_RING = ("growth", "unstable", "tail", "theta", "tail_q", "tail_mi", "extent")


def robustness(spec: TravellingBreathers, fam: list[TravellingBreather], log: Log | None = None) -> dict:
    """The verdicts of the members ``fam`` (on the ring of N, at rtol) on every check ring (the family recomputed
    there: :func:`family`) and at every check tolerance (each member re-solved on the ring of N): arrays (ring, c)
    of :func:`member_checks` (NaN, verdict -1, where a ring's family does not reach the c), (rtol, c) of growth rate
    and verdict, and per c the settled verdict (:data:`SETTLED_STABLE`, :data:`SETTLED_UNSTABLE`,
    :data:`RING_DEPENDENT`)."""
    from cradle.integrators import dps_travelling as DT

    c = np.array([b.c for b in fam])
    rings = [spec.N, *spec.check_N]
    per_ring = {k: np.full((len(rings), c.size), np.nan) for k in ROBUST_RING}
    for i, N in enumerate(rings):
        members = fam if N == spec.N else family(spec, N, spec.rtol, log)[0]
        byc = {round(b.c, 12): b for b in members}
        for j, x in enumerate(c):
            b = byc.get(round(float(x), 12))
            if b is not None:
                for k, v in member_checks(b, spec.stability_threshold).items():
                    per_ring[k][i, j] = v
    rtols = [spec.rtol, *spec.check_rtol]
    growth_tol = np.full((len(rtols), c.size), np.nan)
    growth_tol[0] = per_ring["growth"][0]
    theta_tol = np.full((len(rtols), c.size), np.nan)
    theta_tol[0] = per_ring["theta"][0]
    for i, rt in enumerate(rtols[1:], 1):
        for j, b in enumerate(fam):
            r = DT.newton(b.A, b.T, b.theta, spec.alpha, spec.norm, b.A, spec.newton_tol, rtol=rt)
            if r.converged:
                growth_tol[i, j] = verdict(r, spec.stability_threshold)[1]
                theta_tol[i, j] = r.theta
    unstable_tol = np.where(np.isnan(growth_tol), -1, growth_tol > spec.stability_threshold).astype(int)
    unstable_ring = np.where(np.isnan(per_ring["unstable"]), -1, per_ring["unstable"]).astype(int)
    everything = np.concatenate([unstable_ring, unstable_tol])
    settled = np.where(np.all(everything == 1, axis=0), SETTLED_UNSTABLE,
                       np.where(np.all(everything == 0, axis=0), SETTLED_STABLE, RING_DEPENDENT))
    return {"ring": np.array(rings), "rtol": np.array(rtols), **{f"{k}_ring": v for k, v in per_ring.items()},
            "unstable_ring": unstable_ring, "growth_tol": growth_tol, "unstable_tol": unstable_tol,
            "theta_tol": theta_tol, "settled": settled}


def robustness_attrs(c: NDArray[np.float64], rob: dict) -> dict:
    """The summary of :func:`robustness` stored as attributes: the rings and tolerances, the c of each settled
    verdict, how far the tail's q is from theta (on the ring of N), the smallest extent of an unstable mode."""
    settled = rob["settled"]
    dq = np.abs(np.angle(np.exp(1j * (rob["tail_q_ring"][0] - rob["theta_ring"][0]))))
    extent = rob["extent_ring"]
    return {"rings": ", ".join(str(int(n)) for n in rob["ring"]),
            "rtols": ", ".join(f"{x:g}" for x in rob["rtol"]),
            "verdicts_settled": f"{int(np.sum(settled != RING_DEPENDENT))} of {settled.size}",
            **{f"{name}_c": ", ".join(f"{x:g}" for x in c[settled == v]) or "none"
               for name, v in (("settled_stable", SETTLED_STABLE), ("settled_unstable", SETTLED_UNSTABLE),
                               ("ring_dependent", RING_DEPENDENT))},
            "tail_q_minus_theta_max": float(np.max(dq)),
            "unstable_mode_extent_min": float(np.nanmin(extent)) if np.any(np.isfinite(extent)) else np.nan}


# ----------------------------------------------------------------- robustness in the limit N -> infinity
# Issue 37, "verdicts robust to the discretisation": on a ring the family's verdict at a given c flips with N
# because the instabilities come in narrow windows of c whose places move with N. Each member's neighbourhood is
# scanned in fine steps of c on rings of growing N; the limit verdict is read from how the neighbourhood's growth
# rates change with N (LIMIT_RULE).

#: limit verdicts per member (/robustness_limit/verdict)
LIMIT_STABLE, LIMIT_UNSTABLE, LIMIT_UNDECIDED = 0, 1, -1
#: consecutive grid points the fine scan may fail to reach before it stops in that direction
LIMIT_MISSES = 4
#: a failed continuation step is halved down to this fraction of c
LIMIT_MIN_STEP = 1e-4
#: a Newton iterate whose max |A| exceeds this many times sqrt(norm) has left the family (a TB's max |A| is below
#: sqrt(norm)): the scan stops that attempt rather than integrate ever stiffer states
LIMIT_RUNAWAY = 3.0
LIMIT_RULE = ("for each member c and ring N, the fine grid c +- limit_halfwidth gives the median growth rate "
              "g_N(c): the typical TB near c, which windows covering less than half of the neighbourhood cannot "
              "set; the typical TB is unstable on that ring when g_N exceeds the stability threshold. The limit "
              "verdict is the typical TB's verdict when the two largest rings that reach the neighbourhood agree "
              "on it, undecided when they differ. The exponents k of g_N and of the largest rate G_N against N "
              "(least-squares slopes of -ln g against ln N where above the threshold) are reported, not used: "
              "they do not settle on these rings")


def limit_grid(c: NDArray[np.float64], step: float, halfwidth: float) -> NDArray[np.float64]:
    """The fine grid: every step from the slowest member minus ``halfwidth`` to the fastest plus it (rounded to
    1e-9), so that the scan walks in steps of ``step`` only (a longer jump of the predictor sends Newton far
    off) and the windows are counted over the whole range."""
    m = int(math.floor(halfwidth / step + 1e-9))
    n = int(round((float(c[-1]) - float(c[0])) / step)) + 2 * m
    grid = float(c[0]) - m * step + step * np.arange(n + 1)
    return np.round(grid[grid > 0], 9)


def limit_scan(spec: TravellingBreathers, N: int, grid: NDArray[np.float64],
               log: Log | None = None) -> list[TravellingBreather | None]:
    """The TBs on the ring of N at the velocities ``grid`` (None where not reached): from the pushed static breather
    (as :func:`family`), continued up and down the grid point by point, a failed step halved down to
    :data:`LIMIT_MIN_STEP` of c; a point not reached is skipped (the next is tried from the last member reached)
    and the scan stops in that direction after :data:`LIMIT_MISSES` misses in a row (the family ends, turns or
    breaks at a resonance of the ring there)."""
    from cradle.integrators import dps_travelling as DT

    first = first_member(spec, N, spec.rtol)
    out: list[TravellingBreather | None] = [None] * grid.size
    if not first.converged:
        if log:
            log(f"travelling-breathers: limit scan, ring of {N}: no TB from the pushed breather (residual "
                f"{first.residual:.3g}); the ring is left out")
        return out

    from cradle.integrators.continuation import continue_in_c

    cap = LIMIT_RUNAWAY * math.sqrt(spec.norm)

    def correct(cur: TravellingBreather, c2: float) -> TravellingBreather:
        A_g, th_g = cur.predict(1.0 / c2)
        return DT.newton(A_g, 1.0 / c2, th_g, spec.alpha, spec.norm, cur.A, spec.newton_tol, max_iter=8,
                         rtol=spec.rtol, max_amplitude=cap)

    def walk(order: NDArray[np.int64]) -> None:
        cur, misses = first, 0
        for i in order:
            fam, _ = continue_in_c(cur, [grid[i]], correct, LIMIT_MIN_STEP, lambda *a: None, "limit scan",
                                   lambda b: "")
            if not fam:
                misses += 1
                if misses >= LIMIT_MISSES:
                    return
                continue
            cur, misses, out[i] = fam[0], 0, fam[0]

    idx = np.arange(grid.size)
    walk(idx[grid >= first.c])
    walk(idx[grid < first.c][::-1])
    if log:
        log(f"travelling-breathers: limit scan, ring of {N}: {sum(b is not None for b in out)} of {grid.size} "
            f"velocities reached")
    return out


def limit_rule(rings: NDArray[np.float64], typical: NDArray[np.float64], threshold: float) -> tuple[int, float]:
    """(verdict, k) of :data:`LIMIT_RULE` for one member: ``typical`` its median growth rate on each ring (NaN: not
    reached there, left out); k the slope of -ln typical against ln N over the rings where it exceeds the
    threshold (NaN with fewer than two)."""
    ok = np.isfinite(typical)
    n, g = rings[ok], typical[ok]
    above = g > threshold
    k = float(-np.polyfit(np.log(n[above]), np.log(g[above]), 1)[0]) if np.sum(above) >= 2 else np.nan
    if n.size < 2:
        return LIMIT_UNDECIDED, k
    last = above[np.argsort(n)[-2:]]
    if last[0] != last[1]:
        return LIMIT_UNDECIDED, k
    return (LIMIT_UNSTABLE if last[1] else LIMIT_STABLE), k


def limit_member(b: TravellingBreather, threshold: float) -> dict[str, float]:
    """One scanned TB: growth rate, verdict, theta, tail, the tail's MI rate, the multipliers' quartet and Krein
    measures (:mod:`cradle.measurements.floquet_bubbles`) and how the unstable multiplier leaves the circle (its
    argument: pi through -1, 0 through +1, else a quartet)."""
    from cradle.measurements import floquet_bubbles as FB
    from cradle.models import dps_travelling as M

    assert b.monodromy is not None
    _, rate, unstable, _ = verdict(b, threshold)
    mu, sigma = FB.krein_signatures(b.monodromy)
    k = FB.nontrivial(mu, TRIVIAL)
    top = mu[k[int(np.argmax(np.abs(mu[k])))]]
    q, R = tail_wave(b.A)
    return {"growth": rate, "unstable": float(unstable), "theta": math.remainder(b.theta, 2 * math.pi),
            "tail": M.tail_amplitude(b.A), "tail_mi": tail_mi_rate(q, R, b.alpha),
            "krein_gap": FB.krein_gap(mu, sigma, TRIVIAL), "quartet_defect": FB.quartet_defect(mu),
            "top_arg": float(np.angle(top)) if unstable else np.nan}


def bubble_scan(spec: TravellingBreathers, b: TravellingBreather, cs: NDArray[np.float64], angle: float,
                width: float) -> dict[str, NDArray[np.float64]]:
    """One window resolved: the TBs continued from ``b`` over the velocities ``cs`` (in order; steps halved down to
    :data:`LIMIT_MIN_STEP` of c), at each the largest ln |mu| of the non-trivial multipliers, the argument of that
    multiplier and the splitting of the pair of opposite Krein signature within ``width`` of ``angle``
    (:func:`cradle.measurements.floquet_bubbles.pair_splitting`; NaN inside the bubble, where the pair is a
    quartet off the circle). Returns arrays c, log_modulus, top_arg, splitting, period (NaN where not reached)."""
    from cradle.integrators import dps_travelling as DT
    from cradle.measurements import floquet_bubbles as FB

    fam, _ = DT.continue_family(b, cs, spec.newton_tol, spec.rtol, min_step=LIMIT_MIN_STEP)
    out = {k: np.full(cs.size, np.nan) for k in ("log_modulus", "top_arg", "splitting", "period")}
    byc = {round(m.c, 12): m for m in fam}
    for i, x in enumerate(cs):
        m = byc.get(round(float(x), 12))
        if m is None or m.monodromy is None:
            continue
        mu, sigma = FB.krein_signatures(m.monodromy)
        k = FB.nontrivial(mu, TRIVIAL)
        top = mu[k[int(np.argmax(np.abs(mu[k])))]]
        out["log_modulus"][i] = float(np.log(np.abs(top)))
        out["top_arg"][i] = float(np.angle(top))
        out["splitting"][i] = FB.pair_splitting(mu, sigma, angle, width)
        out["period"][i] = m.T
    return {"c": np.asarray(cs, float), **out}


LIMIT_FINE = ("growth", "unstable", "theta", "tail", "tail_mi", "krein_gap", "quartet_defect", "top_arg")


def robustness_limit(spec: TravellingBreathers, c: NDArray[np.float64], log: Log | None = None) -> tuple[dict, dict]:
    """The group /robustness_limit and its attributes: every ring of ``limit_N`` scanned over the fine grid around
    the members ``c`` (:func:`limit_scan`, :func:`limit_member` per point), per member and ring the unstable
    fraction, the median and the largest growth rate of its neighbourhood, and per member the limit verdict with
    its exponent (:func:`limit_rule`)."""
    t0 = _time.process_time()
    grid = limit_grid(c, spec.limit_step, spec.limit_halfwidth)
    rings = np.array(spec.limit_N, float)
    fine = {k: np.full((rings.size, grid.size), np.nan) for k in LIMIT_FINE}
    for i, N in enumerate(spec.limit_N):
        for j, b in enumerate(limit_scan(spec, N, grid, log)):
            if b is not None:
                for k, v in limit_member(b, spec.stability_threshold).items():
                    fine[k][i, j] = v
    near = np.abs(grid[None, :] - c[:, None]) <= spec.limit_halfwidth + 1e-9      # (c, fine)
    frac, typical, largest, reached = (np.full((rings.size, c.size), np.nan) for _ in range(4))
    for i in range(rings.size):
        for j in range(c.size):
            g = fine["growth"][i, near[j]]
            g = g[np.isfinite(g)]
            reached[i, j] = g.size / max(int(np.sum(near[j])), 1)
            if g.size:
                frac[i, j] = float(np.mean(g > spec.stability_threshold))
                typical[i, j] = float(np.median(g))
                largest[i, j] = float(np.max(g))
    rule = [limit_rule(rings, typical[:, j], spec.stability_threshold) for j in range(c.size)]
    env = [limit_rule(rings, largest[:, j], spec.stability_threshold)[1] for j in range(c.size)]
    # the windows' ring-by-ring census over the whole fine grid: how many, how wide, how fast
    from cradle.measurements import floquet_bubbles as FB

    census: dict[str, list[float]] = {"count": [], "mean_width": [], "largest": [], "fraction": []}
    for i in range(rings.size):
        ok = np.isfinite(fine["growth"][i])
        w = FB.windows(grid[ok], fine["unstable"][i][ok] == 1)
        census["count"].append(len(w))
        census["mean_width"].append(float(np.mean([b - a + spec.limit_step for a, b in w])) if w else 0.0)
        census["largest"].append(float(np.nanmax(fine["growth"][i])) if np.any(ok) else np.nan)
        census["fraction"].append(float(np.mean(fine["unstable"][i][ok] == 1)) if np.any(ok) else np.nan)
    verdicts = np.array([v for v, _ in rule], int)
    data = {"growth_rate": fine["growth"], "unstable": np.where(np.isnan(fine["unstable"]), -1,
                                                                fine["unstable"]).astype(int),
            "theta": fine["theta"], "tail": fine["tail"], "tail_mi_rate": fine["tail_mi"],
            "krein_gap": fine["krein_gap"], "quartet_defect": fine["quartet_defect"], "top_arg": fine["top_arg"],
            "unstable_fraction": frac.T, "typical_growth": typical.T, "largest_growth": largest.T,
            "reached": reached.T, "decay": [k for _, k in rule], "envelope_decay": env, "verdict": verdicts,
            "windows": census["count"], "window_width": census["mean_width"],
            "ring_largest_growth": census["largest"], "ring_unstable_fraction": census["fraction"]}
    attrs = {"limit_rule": LIMIT_RULE, "limit_rings": ", ".join(str(n) for n in spec.limit_N),
             "limit_step": spec.limit_step, "limit_halfwidth": spec.limit_halfwidth,
             **{f"limit_{name}_c": ", ".join(f"{x:g}" for x in c[verdicts == v]) or "none"
                for name, v in (("stable", LIMIT_STABLE), ("unstable", LIMIT_UNSTABLE),
                                ("undecided", LIMIT_UNDECIDED))},
             "limit_max_quartet_defect": (float(np.nanmax(fine["quartet_defect"]))
                                          if np.any(np.isfinite(fine["quartet_defect"])) else np.nan),
             "limit_cpu_s": _time.process_time() - t0}
    return {"/robustness_limit": (data, {"limit_ring": rings.astype(int), "c_fine": grid})}, attrs


# ----------------------------------------------------------------- the tail rule in the limit N -> infinity
# Issue 37, "verdicts robust to the discretisation", with an input that does not change with N: the tail. A TB on
# the infinite lattice carries a tail that never vanishes (James 2018), a plane wave of wavenumber q = theta; the
# linearisation about the TB has the tail's own spectrum as its essential spectrum (in the TB's frame shifted by an
# imaginary Doppler term only), so a tail that is modulationally unstable makes the TB unstable at the tail's MI
# rate, whatever its core does. theta is the same on every ring and tolerance (/limit_tail/theta_spread); whether
# the plane wave is modulationally unstable is cos q < 0 for every amplitude (mi_diagram.max_growth_rate). Only
# the members whose tail is stable need the extrapolation of their finite-size instabilities in N.

TAIL_RULE = ("tail MI-unstable (cos theta < 0, closed form: every tail amplitude R > 0 is unstable at a rate "
             "proportional to R^(alpha-1)): unstable in the limit. Tail MI-stable: the largest growth rate over the "
             "member's neighbourhood c +- limit_halfwidth, on the points whose own tail is MI-stable and that every "
             "ring's grid holds, on each ring of limit_N and limit_large_N, fitted as g_inf + b N^-k (its error the "
             "larger of the standard error and g_inf's change when the smallest or the largest ring is left out); "
             "stable when g_inf plus TAIL_RULE_SIGMAS errors is below the stability threshold, unstable when g_inf "
             "less that many errors is above it, undecided otherwise (both are consistent with the fit: a g_inf "
             "merely consistent with 0 is not enough), when the fit is missing (fewer than 4 rings) and when it is "
             "degenerate (k on a bound of its range: its error is then no error of g_inf)")
#: a verdict from the fit needs g_inf this many standard errors on one side of the stability threshold
TAIL_RULE_SIGMAS = 2.0


def tail_mi_unstable(theta: float) -> bool:
    """Whether the tail's plane wave e^{i theta n} is modulationally unstable (cos theta < 0, any amplitude)."""
    return math.cos(theta) < 0.0


def common_points(grids: list[NDArray[np.float64]]) -> NDArray[np.float64]:
    """The velocities every grid holds (rounded to 1e-9, as :func:`limit_grid` rounds)."""
    common = set(np.round(grids[0], 9))
    for g in grids[1:]:
        common &= set(np.round(g, 9))
    return np.array(sorted(common))


def kind_envelope(grid: NDArray[np.float64], growth: NDArray[np.float64], theta: NDArray[np.float64],
                  centre: float, halfwidth: float, unstable_kind: bool, points: NDArray[np.float64]) -> float:
    """The largest growth rate over the grid points within ``halfwidth`` of ``centre`` that are among ``points``
    and whose tail is of the kind ``unstable_kind`` (:func:`tail_mi_unstable`); NaN when none is reached."""
    keep = (np.abs(grid - centre) <= halfwidth + 1e-9) & np.isin(np.round(grid, 9), points) & np.isfinite(growth)
    keep &= np.array([tail_mi_unstable(t) == unstable_kind if np.isfinite(t) else False for t in theta])
    return float(np.max(growth[keep])) if np.any(keep) else np.nan


def tail_rule_verdict(mi_unstable: bool, fit: dict[str, float], threshold: float) -> int:
    """The limit verdict of :data:`TAIL_RULE` from the tail's kind and the fit of the envelope against N
    (:func:`cradle.measurements.floquet_bubbles.fit_limit`)."""
    if mi_unstable:
        return LIMIT_UNSTABLE
    g, err = fit["g_inf"], fit["g_inf_error"]
    if not (np.isfinite(g) and np.isfinite(err)) or fit.get("degenerate", 0.0) == 1.0:
        return LIMIT_UNDECIDED
    if g - TAIL_RULE_SIGMAS * err > threshold:
        return LIMIT_UNSTABLE
    if g + TAIL_RULE_SIGMAS * err < threshold:
        return LIMIT_STABLE
    return LIMIT_UNDECIDED


MEMBER_RULE = ("two questions the envelope of TAIL_RULE mixes: (i) the member itself, its own growth rate at c on "
               "each ring of limit_N and limit_large_N fitted as g_inf + b N^-k and read as TAIL_RULE reads the "
               "envelope, or stable when it is stable on every ring reached, at least 4 of them (member_verdict); "
               "(ii) any TB within c +- limit_halfwidth, the envelope (verdict). A window near c may hold TBs of "
               "another branch of the ring's family (past a fold in c, on a larger tail: /limit_fold), unstable where "
               "the member is not")


def member_verdict(mi_unstable: bool, growth: NDArray[np.float64], fit: dict[str, float], threshold: float) -> int:
    """The limit verdict of the member itself (:data:`MEMBER_RULE`): stable when it is stable on every ring reached
    and at least as many rings as a fit needs are reached (no growth to extrapolate), else the reading of
    :func:`tail_rule_verdict` of its own growth rates' fit."""
    from cradle.measurements import floquet_bubbles as FB

    g = growth[np.isfinite(growth)]
    if not mi_unstable and g.size >= FB.LIMIT_FIT_MIN and np.all(g <= threshold):
        return LIMIT_STABLE
    return tail_rule_verdict(mi_unstable, fit, threshold)


def member_growth(grid: NDArray[np.float64], growth: NDArray[np.float64], c: float) -> float:
    """The growth rate at the grid point c itself (NaN when the grid does not hold c or the scan did not reach it)."""
    hit = np.flatnonzero(np.abs(grid - c) <= 1e-9)
    return float(growth[hit[0]]) if hit.size else np.nan


LARGE_FINE = ("growth", "unstable", "theta", "tail", "tail_mi", "quartet_defect")


def large_scan(spec: TravellingBreathers, c: NDArray[np.float64], theta: NDArray[np.float64],
               log: Log | None = None) -> tuple[NDArray[np.float64], dict[str, NDArray[np.float64]]]:
    """The rings of ``limit_large_N`` scanned (:func:`limit_scan` at ``limit_large_newton_tol``) over the grid of step
    ``limit_large_step`` around the members whose tail is MI-stable: the grid and, per (ring, point), the
    quantities of :func:`limit_member` named in :data:`LARGE_FINE` (NaN where not reached)."""
    import dataclasses

    stable = np.array([not tail_mi_unstable(t) for t in theta])
    if not spec.limit_large_N or not np.any(stable):
        return np.zeros(0), {k: np.zeros((len(spec.limit_large_N), 0)) for k in LARGE_FINE}
    grid = limit_grid(c[stable], spec.limit_large_step, spec.limit_halfwidth)
    out = {k: np.full((len(spec.limit_large_N), grid.size), np.nan) for k in LARGE_FINE}
    relaxed = dataclasses.replace(spec, newton_tol=spec.limit_large_newton_tol)
    for i, N in enumerate(spec.limit_large_N):
        for j, b in enumerate(limit_scan(relaxed, N, grid, log)):
            if b is not None:
                m = limit_member(b, spec.stability_threshold)
                for k in LARGE_FINE:
                    out[k][i, j] = m[k]
    return grid, out


def tail_rule(spec: TravellingBreathers, c: NDArray[np.float64], theta: NDArray[np.float64], rob: dict,
              limit: tuple[dict, dict], log: Log | None = None) -> tuple[dict, dict]:
    """The groups /limit_tail (per member: the tail's plane wave and its MI in closed form, the envelope of the
    growth rates on every ring, its fit in N and the verdict of :data:`TAIL_RULE`) and /limit_large (the scans of
    :func:`large_scan`), with their attributes (prefixed ``tail_rule_``). ``theta`` the members' theta on the ring
    of N, ``rob`` :func:`robustness`'s arrays, ``limit`` the (data, coords) of /robustness_limit."""
    t0 = _time.process_time()
    grid_large, large = large_scan(spec, c, theta, log)
    groups, attrs = tail_rule_of(spec, c, theta, rob, limit, grid_large, large)
    attrs["tail_rule_cpu_s"] = _time.process_time() - t0
    return groups, attrs


def tail_rule_of(spec: TravellingBreathers, c: NDArray[np.float64], theta: NDArray[np.float64], rob: dict,
                 limit: tuple[dict, dict], grid_large: NDArray[np.float64],
                 large: dict[str, NDArray[np.float64]]) -> tuple[dict, dict]:
    """:func:`tail_rule` from the scans of the larger rings (:func:`large_scan`'s grid and arrays), without its CPU
    attribute: the rule's reading alone (``benchmarks/tb_limit.py --rule`` applies it to stored scans)."""
    from cradle.analyses import mi_diagram
    from cradle.measurements import floquet_bubbles as FB

    data, coords = limit
    grid_small = coords["c_fine"]
    rings = [*spec.limit_N, *spec.limit_large_N]
    points = common_points([grid_small, grid_large] if grid_large.size else [grid_small])
    per_ring = ([(grid_small, data["growth_rate"][i], data["theta"][i]) for i in range(len(spec.limit_N))]
                + [(grid_large, large["growth"][i], large["theta"][i]) for i in range(len(spec.limit_large_N))])
    q = np.array([math.remainder(t, 2 * math.pi) for t in theta])
    kind = np.array([tail_mi_unstable(t) for t in q])
    closed = [mi_diagram.max_growth_rate(float(x), spec.alpha, 1.0) for x in q]
    hw = spec.limit_halfwidth
    # a member whose neighbourhood the larger rings' grid covers is compared on the points every ring holds, any
    # other on the fine grid of limit_N (the larger rings hold none of its points)
    h = spec.limit_large_step
    covered = [grid_large.size > 0 and grid_large[0] - h < x - hw + 1e-9 and grid_large[-1] + h > x + hw - 1e-9
               for x in c]
    envelope = np.array([[kind_envelope(g_, gr, th, float(x), hw, bool(k), points if cov else np.round(grid_small, 9))
                          for g_, gr, th in per_ring] for x, k, cov in zip(c, kind, covered, strict=True)])
    fits = [FB.fit_limit(rings, envelope[j]) for j in range(c.size)]
    verdicts = np.array([tail_rule_verdict(bool(kind[j]), fits[j], spec.stability_threshold)
                         for j in range(c.size)], int)
    # the member itself (question (i) of MEMBER_RULE): its own growth rate at c on each ring, fitted the same way
    at_c = np.array([[member_growth(g_, gr, float(x)) for g_, gr, _ in per_ring] for x in c])
    member_fits = [FB.fit_limit(rings, at_c[j]) for j in range(c.size)]
    member_verdicts = np.array([member_verdict(bool(kind[j]), at_c[j], member_fits[j], spec.stability_threshold)
                                for j in range(c.size)], int)
    # theta on every ring of /robustness and at every tolerance, against the ring of N's: the rule's input
    spread = np.nanmax(np.abs(np.angle(np.exp(1j * (np.vstack([rob["theta_ring"], rob["theta_tol"]])
                                                        - rob["theta_ring"][0])))), axis=0)
    mi_ring = rob["tail_mi_ring"]
    group = {"tail_q": q, "tail_mi_unstable": kind.astype(int), "theta_spread": spread,
             "unit_amplitude_mi_rate": [x[0] for x in closed], "fastest_sideband": [x[1] for x in closed],
             "unstable_band_low": [x[2] for x in closed], "unstable_band_high": [x[3] for x in closed],
             "tail_mi_rate_min": np.nanmin(mi_ring, axis=0), "tail_mi_rate_max": np.nanmax(mi_ring, axis=0),
             "envelope": envelope, **{f"fit_{k}": [f[k] for f in fits] for k in ("g_inf", "g_inf_error", "g_inf_stderr",
                                                                                 "b", "k", "points", "degenerate")},
             "verdict": verdicts, "member_growth": at_c,
             **{f"member_fit_{k}": [f[k] for f in member_fits] for k in ("g_inf", "g_inf_error", "k", "degenerate")},
             "member_verdict": member_verdicts}
    groups = {"/limit_tail": (group, {"fit_ring": np.array(rings)})}
    if grid_large.size:
        groups["/limit_large"] = ({"growth_rate": large["growth"], "theta": large["theta"], "tail": large["tail"],
                                   "tail_mi_rate": large["tail_mi"], "quartet_defect": large["quartet_defect"],
                                   "unstable": np.where(np.isnan(large["unstable"]), -1,
                                                        large["unstable"]).astype(int)},
                                  {"large_ring": np.array(spec.limit_large_N), "c_large": grid_large})
    attrs = {"tail_rule": TAIL_RULE, "tail_rule_rings": ", ".join(str(n) for n in rings),
             "tail_rule_points": f"{points.size} common velocities, step {float(np.min(np.diff(points))):.3g}"
             if points.size > 1 else f"{points.size}",
             "tail_rule_mi_unstable_c": ", ".join(f"{x:g}" for x in c[kind]) or "none",
             **{f"tail_rule_{name}_c": ", ".join(f"{x:g}" for x in c[verdicts == v]) or "none"
                for name, v in (("stable", LIMIT_STABLE), ("unstable", LIMIT_UNSTABLE),
                                ("undecided", LIMIT_UNDECIDED))},
             "tail_rule_theta_spread_max": float(np.nanmax(spread)), "member_rule": MEMBER_RULE,
             **{f"member_rule_{name}_c": ", ".join(f"{x:g}" for x in c[member_verdicts == v]) or "none"
                for name, v in (("stable", LIMIT_STABLE), ("unstable", LIMIT_UNSTABLE),
                                ("undecided", LIMIT_UNDECIDED))}}
    return groups, attrs


# ----------------------------------------------------------------- the windows are folds
# A window near c in which a real multiplier leaves +1 (c ~ 0.084 on the rings up to 112) is no instability of the
# member itself: natural continuation in c stops below it (dA/dT grows without bound: a fold), and followed through the
# fold by pseudo-arclength the family comes back in c on a branch with a larger tail, where a real pair leaves +1 and
# returns at the extrema of H(c), as Xu et al.'s criterion says. The scan of fixed c jumps onto that branch.

#: the step in c of the natural continuation that finds the fold, and the pseudo-arclength step in (A, theta, T)
FOLD_STEP, FOLD_DS = 2e-4, 1e-2
FOLD = ("on each ring of limit_fold_N: the family continued from the first member upwards in c in steps of FOLD_STEP "
        "until the step, halved down to LIMIT_MIN_STEP of c, fails (the family turns), then followed by "
        "pseudo-arclength (steps FOLD_DS in (Re A, Im A, theta, T)) for limit_fold_points members while c stays "
        "within limit_halfwidth of the first member; per member c, H, the growth rate, the growth rate of a real "
        "multiplier above +1 and the tail. Xu et al.'s criterion: a real pair leaves +1 where dH/dc changes sign")


def real_growth(b: TravellingBreather) -> float:
    """ln mu / T of the largest real multiplier mu > 1 among the non-trivial ones (0 when there is none): the growth
    through +1 that the dH/dc criterion is about."""
    from cradle.measurements import floquet_bubbles as FB

    mu = b.multipliers
    rest = mu[FB.nontrivial(mu, TRIVIAL)]
    real = rest[(np.abs(rest.imag) <= REAL * np.abs(rest)) & (rest.real > 1.0)]
    return float(np.log(np.max(real.real)) / b.T) if real.size else 0.0


def fold_scan(spec: TravellingBreathers, N: int, log: Log | None = None) -> dict[str, NDArray[np.float64]]:
    """The family on the ring of N through its fold nearest above the first member (:data:`FOLD`): arrays c, H,
    theta, growth, real_growth, tail, residual and the states A (arc, site) along the arclength (first the natural
    continuation's members, then the pseudo-arclength ones), padded to ``limit_fold_points`` plus the natural ones
    with NaN."""
    from cradle.integrators import dps_travelling as DT
    from cradle.models import dps_travelling as M

    first = first_member(spec, N, spec.rtol)
    hw = spec.limit_halfwidth
    grid = np.round(first.c + FOLD_STEP * np.arange(1, int(hw / FOLD_STEP) + 1), 9)
    fam, _ = DT.continue_family(first, grid, spec.limit_large_newton_tol, spec.rtol, min_step=LIMIT_MIN_STEP)
    last = fam[-1] if fam else first
    arc = DT.continue_arclength(last, FOLD_DS, spec.limit_fold_points, (first.c - hw, first.c + hw),
                                spec.limit_large_newton_tol, spec.rtol, log=log)
    members = [first, *fam, *arc[1:]]
    width = spec.limit_fold_points + grid.size + 1
    out = {k: np.full(width, np.nan) for k in ("velocity", "energy", "theta", "growth", "real_growth", "tail",
                                               "residual")}
    out["A_re"], out["A_im"] = np.full((width, N), np.nan), np.full((width, N), np.nan)
    for i, b in enumerate(members):
        out["A_re"][i], out["A_im"][i] = b.A.real, b.A.imag
        out["velocity"][i], out["energy"][i] = b.c, b.energy
        out["theta"][i] = math.remainder(b.theta, 2 * math.pi)
        out["growth"][i] = verdict(b, spec.stability_threshold)[1]
        out["real_growth"][i], out["tail"][i], out["residual"][i] = real_growth(b), M.tail_amplitude(b.A), b.residual
    if log:
        log(f"travelling-breathers: fold scan, ring of {N}: {len(fam)} members by c up to c = {last.c:.6g}, "
            f"{len(arc) - 1} by arclength")
    return out


def fold_turns(c: NDArray[np.float64], H: NDArray[np.float64]) -> tuple[list[float], list[float]]:
    """(folds, extrema): the c where the arclength's c turns (dc changes sign) and where H(c) has an extremum
    along a branch (dH changes sign while c keeps its direction), each the c of the middle member."""
    ok = np.isfinite(c)
    c, H = c[ok], H[ok]
    dc, dH = np.diff(c), np.diff(H)
    folds = [float(c[i + 1]) for i in range(dc.size - 1) if dc[i] * dc[i + 1] < 0]
    extrema = [float(c[i + 1]) for i in range(dc.size - 1) if dc[i] * dc[i + 1] > 0 and dH[i] * dH[i + 1] < 0]
    return folds, extrema


def real_edges(c: NDArray[np.float64], g: NDArray[np.float64], threshold: float) -> list[float]:
    """The c midway between consecutive members along the arclength where the growth through +1 crosses the
    stability threshold (a real pair leaving or returning to +1)."""
    ok = np.isfinite(c)
    c, above = c[ok], g[ok] > threshold
    return [float(0.5 * (c[i] + c[i + 1])) for i in range(c.size - 1) if above[i] != above[i + 1]]


def fold_group(spec: TravellingBreathers, log: Log | None = None) -> tuple[dict, dict]:
    """The group /limit_fold (:func:`fold_scan` on each ring of limit_fold_N) and its attributes: per ring the folds
    in c, the extrema of H(c) and the c where a real pair crosses the threshold through +1."""
    t0 = _time.process_time()
    scans = [fold_scan(spec, N, log) for N in spec.limit_fold_N]
    width, sites = max(s["velocity"].size for s in scans), max(spec.limit_fold_N)
    data = {k: np.array([np.pad(s[k], [(0, width - s[k].shape[0])] + [(0, sites - N)] * (s[k].ndim - 1),
                                constant_values=np.nan) for s, N in zip(scans, spec.limit_fold_N, strict=True)])
            for k in scans[0]}
    attrs: dict = {"fold_rule": FOLD}
    for N, s in zip(spec.limit_fold_N, scans, strict=True):
        folds, extrema = fold_turns(s["velocity"], s["energy"])
        attrs[f"fold_{N}_c_turns"] = ", ".join(f"{x:.7f}" for x in folds) or "none"
        attrs[f"fold_{N}_dH_dc_zero"] = ", ".join(f"{x:.7f}" for x in extrema) or "none"
        attrs[f"fold_{N}_real_edges"] = ", ".join(f"{x:.7f}" for x in real_edges(s["velocity"], s["real_growth"],
                                                                                  spec.stability_threshold)) or "none"
        attrs[f"fold_{N}_largest_real_growth"] = float(np.nanmax(s["real_growth"]))
    attrs["fold_cpu_s"] = _time.process_time() - t0
    return {"/limit_fold": ({k: v for k, v in data.items()},
                            {"fold_ring": np.array(spec.limit_fold_N), "arc": np.arange(width),
                             "fold_site": np.arange(sites)})}, attrs


# ----------------------------------------------------------------- the stored file

_C = ("c",)
VARIABLES = {
    "/": {
        "c": Var(_C, "velocity c = 1/T of the travelling breather (sites per unit tau at the family's norm)"),
    },
    "/family": {
        "period": Var(_C, "period T of (tb): one site per T"),
        "theta": Var(_C, "phase theta of (tb), in (-pi, pi]"),
        "energy": Var(_C, "DpS Hamiltonian H = -sum |A_{n+1} - A_n|^(alpha+1) / ((alpha+1) tau0)"),
        "dH_dc": Var(_C, "dH/dc along the family at fixed norm (centred differences on the grid)"),
        "tail": Var(_C, "max |A_n| on the quarter ring farthest from the centre / max |A_n| (the oscillatory tail)"),
        "residual": Var(_C, "shift-map residual max_n |e^{-i theta} A_{n+1}(T) - A_n(0)| / max |A|"),
        "iterations": Var(_C, "Newton iterations from the tangent predictor"),
        "trivial_defect": Var(_C, "largest |mu - 1| of the four trivial multipliers modulo shift (exactly 0)"),
        "growth_rate": Var(_C, "ln max |mu| / T over the non-trivial multipliers modulo shift (per unit tau)"),
        "unstable": Var(_C, "1 if growth_rate > stability_threshold"),
        "real_mode": Var(_C, "1 if unstable through a real multiplier > 1 (the dH/dc kind), not a complex quartet"),
        "unstable_rtol": Var(_C, "the verdict re-solved at check_rtol"),
        "growth_rate_rtol": Var(_C, "growth_rate re-solved at check_rtol"),
        "unstable_N": Var(_C, "the verdict on the ring of check_N sites (-1: member not reached there)"),
        "growth_rate_N": Var(_C, "growth_rate on the ring of check_N sites (NaN: not reached)"),
        "tail_N": Var(_C, "tail on the ring of check_N sites (NaN: not reached)"),
        "static_distance_site": Var(_C, "min over one period and shifts of max_n ||A_n(tau)| - phi_n^site| / max phi"),
        "static_distance_bond": Var(_C, "the same against the bond-centred static breather"),
    },
    "/profiles": {
        "n": Var(("n",), "site index on the ring"),
        "A_re": Var(("c", "n"), "Re A_n(0) of the travelling breather"),
        "A_im": Var(("c", "n"), "Im A_n(0) of the travelling breather"),
        "static_site": Var(("n",), "phi_n of the site-centred static breather at the family's norm"),
        "static_bond": Var(("n",), "phi_n of the bond-centred static breather at the family's norm"),
    },
    "/multipliers": {
        "m": Var(("m",), "index of a Floquet multiplier modulo shift"),
        "mu_re": Var(("c", "m"), "real part of a multiplier of e^{-i theta} S^{-1} DPhi_T"),
        "mu_im": Var(("c", "m"), "imaginary part of a multiplier of e^{-i theta} S^{-1} DPhi_T"),
    },
    "/direct": {
        "k": Var(("k",), "periods of the direct run"),
        "residual": Var(("k",), "max_n |A_n(kT) - e^{i k theta} A_{n-k}(0)| / max |A|"),
    },
    "/lattice": {
        "c_lattice": Var(("c_lattice",), "velocity c = 1/T of the lattice's TB (sites per unit t), the continuation "
                         "from the TB at the first lattice_eps"),
        "period": Var(("c_lattice",), "period T of (tbnc): x_n(t + T) = x_{n-1}(t)"),
        "eps": Var(("c_lattice",), "eps of the ansatz at the TB's amplitude: sqrt(sum |xi_n|^2 / norm)"),
        "energy": Var(("c_lattice",), "energy (ham) of the lattice's TB"),
        "residual": Var(("c_lattice",), "shift-map residual max |S^{-1} Phi_T(z) - z| / max |z|"),
        "tail": Var(("c_lattice",), "max |xi_n| on the quarter ring farthest from the centre / max |xi_n|, "
                    "xi_n = (x_n - i v_n)/2"),
        "trivial_defect": Var(("c_lattice",), "largest |mu - 1| of the four multipliers modulo shift nearest 1 (time "
                              "shift and energy; the carrier's phase and the wave action)"),
        "growth_rate": Var(("c_lattice",), "ln max |mu| / T over the other multipliers modulo shift (per unit t)"),
        "unstable": Var(("c_lattice",), "1 if growth_rate > stability_threshold"),
        "reciprocal_defect": Var(("c_lattice",), "max over mu of the distance of 1/mu to the nearest multiplier"),
        "smallest_singular": Var(("c_lattice",), "smallest singular value of the bordered Jacobian over its largest "
                                 "(the near-symmetry's direction)"),
    },
    "/lattice_eps": {
        "eps_lattice": Var(("eps_lattice",), "eps of the ansatz that started the solve (lattice_eps)"),
        "period": Var(("eps_lattice",), "period T of (tbnc) of the exact TB"),
        "c_tb": Var(("eps_lattice",), "its velocity 1/T (sites per unit t)"),
        "eps_tb": Var(("eps_lattice",), "eps at the TB's own amplitude: sqrt(sum |xi_n|^2 / norm)"),
        "ansatz_period": Var(("eps_lattice",), "time per site T_d eps^(1-alpha) of the DpS member at eps_lattice"),
        "start_residual": Var(("eps_lattice",), "shift-map residual of the ansatz at T (the closest return)"),
        "residual": Var(("eps_lattice",), "shift-map residual max |S^{-1} Phi_T(z) - z| / max |z| of the TB"),
        "iterations": Var(("eps_lattice",), "Newton iterations from the ansatz"),
        "energy": Var(("eps_lattice",), "energy (ham) of the TB"),
        "tail": Var(("eps_lattice",), "max |xi_n| on the far quarter ring / max |xi_n|"),
        "trivial_defect": Var(("eps_lattice",), "largest |mu - 1| of the four multipliers modulo shift nearest 1"),
        "growth_rate": Var(("eps_lattice",), "ln max |mu| / T over the other multipliers modulo shift (per unit t)"),
        "unstable": Var(("eps_lattice",), "1 if growth_rate > stability_threshold"),
        "reciprocal_defect": Var(("eps_lattice",), "max over mu of the distance of 1/mu to the nearest multiplier"),
        "smallest_singular": Var(("eps_lattice",), "smallest singular value of the bordered Jacobian over its "
                                 "largest"),
        "dps_c": Var(("eps_lattice",), "velocity of the DpS TB through the ansatz: 1 / (T eps_tb^(alpha-1))"),
        "resonance": Var(("eps_lattice",), "theta + T of that DpS TB, modulo 2 pi into (-pi, pi] (0: the ansatz's "
                         "resonance)"),
        "ansatz_distance": Var(("eps_lattice",), "min over the DpS time, site shift and phase of max |z - "
                               "z_ansatz(A, eps_tb)| / max |z|, A that DpS TB"),
        "dps_speed": Var(("eps_lattice",), "the DpS member launched in (nc) through (ansatz): speed over c "
                         "eps^(alpha-1)"),
        "exact_speed": Var(("eps_lattice",), "the exact TB launched the same way: speed over c eps^(alpha-1)"),
        "dps_radiation": Var(("eps_lattice",), "the DpS launch: energy outside the window / total, at the end"),
        "exact_radiation": Var(("eps_lattice",), "the exact TB's launch: energy outside the window / total, at the "
                               "end"),
        "exact_radiation_max": Var(("eps_lattice",), "the exact TB's launch: largest such fraction over the run"),
        "dps_energy_drift": Var(("eps_lattice",), "the DpS launch: max |H(t) - H(0)| / H(0)"),
        "exact_energy_drift": Var(("eps_lattice",), "the exact TB's launch: max |H(t) - H(0)| / H(0)"),
    },
    "/lattice_states": {
        "eps_lattice": Var(("eps_lattice",), "eps of the ansatz that started the solve (lattice_eps)"),
        "site": Var(("site",), "bead index n on the ring"),
        "mode": Var(("mode",), "index of a Floquet multiplier modulo shift"),
        "x": Var(("eps_lattice", "site"), "x_n(0) of the lattice's TB"),
        "v": Var(("eps_lattice", "site"), "v_n(0) of the lattice's TB"),
        "mu_re": Var(("eps_lattice", "mode"), "real part of a multiplier of S^{-1} DPhi_T"),
        "mu_im": Var(("eps_lattice", "mode"), "imaginary part of a multiplier of S^{-1} DPhi_T"),
        "dps_A_re": Var(("eps_lattice", "site"), "Re A_n(0) of the DpS TB through the ansatz (dps_c, the norm)"),
        "dps_A_im": Var(("eps_lattice", "site"), "Im A_n(0) of that DpS TB"),
        "source_A_re": Var(("site",), "Re A_n(0) of the DpS TB whose ansatz started the lattice's TBs"),
        "source_A_im": Var(("site",), "Im A_n(0) of the DpS TB whose ansatz started the lattice's TBs"),
    },
    "/lattice_rings": {
        "ring": Var(("ring",), "sites N of the ring (the first: lattice_N, the members of /lattice_eps and /lattice)"),
        "eps_lattice": Var(("eps_lattice",), "eps of the ansatz that started the TB on the ring of lattice_N"),
        "c_step": Var(("c_step",), "relative change s of the velocity: c = c0 (1 + s), c0 that of the member at the "
                      "first eps_lattice on the same ring"),
        "ring_site": Var(("ring_site",), "site n (up to the largest ring; NaN beyond each ring)"),
        **{f"{k}{suffix}": Var(dims, f"{text} ({which})", units)
           for suffix, dims, which in (("", ("ring", "eps_lattice"), "the TB at eps_lattice on that ring"),
                                       ("_family", ("ring", "c_step"), "the continuation in c on that ring"))
           for k, (text, units) in {
               "period": ("period T of (tbnc), x_n(t + T) = x_{n-1}(t), in units of t", "1"),
               "eps_tb": ("eps at the TB's amplitude: sqrt(sum |xi_n|^2 / norm)", "1"),
               "dps_c": ("velocity of the DpS TB through (ansatz), 1 / (T eps_tb^(alpha-1)), sites per unit tau", "1"),
               "residual": ("shift-map residual max |S^{-1} Phi_T(z) - z| / max |z|", "1"),
               "iterations": ("Newton iterations", "1"),
               "tail": ("max |xi_n| on the far quarter ring / max |xi_n|, xi_n = (x_n - i v_n)/2", "1"),
               "energy": ("energy (ham) of the TB", "1"),
               "trivial_defect": ("largest |mu - 1| of the four multipliers modulo shift nearest 1", "1"),
               "growth_rate": ("ln max |mu| / T over the other multipliers modulo shift, per unit t", "1"),
               "unstable": ("1 if growth_rate > stability_threshold", "1"),
               "reciprocal_defect": ("max over mu of the distance of 1/mu to the nearest multiplier", "1"),
               "smallest_singular": ("smallest singular value of the bordered Jacobian over its largest", "1"),
           }.items()},
        "c_family": Var(("ring", "c_step"), "velocity c = 1/T of the member of the continuation, sites per unit t"),
        "x": Var(("ring", "eps_lattice", "ring_site"), "x_n(0) of the TB at eps_lattice"),
        "v": Var(("ring", "eps_lattice", "ring_site"), "v_n(0) of the TB at eps_lattice"),
        "x_family": Var(("ring", "c_step", "ring_site"), "x_n(0) of the member of the continuation in c"),
        "v_family": Var(("ring", "c_step", "ring_site"), "v_n(0) of the member of the continuation in c"),
    },
    "/lattice_large": {
        "eps_large": Var(("eps_large",), "eps of the ansatz (lattice_large_eps) on the ring of lattice_N"),
        "site": Var(("site",), "site n of the ring of lattice_N"),
        **{k: Var(("eps_large",), text) for k, text in {
            "period": "period T of (tbnc): the time of the ansatz's closest return to its shifted start, in units of t",
            "eps_tb": "eps at the TB's amplitude: sqrt(sum |xi_n|^2 / norm)",
            "dps_c": "velocity of the DpS TB through (ansatz), 1 / (T eps_tb^(alpha-1)), sites per unit tau",
            "residual": "shift-map residual max |S^{-1} Phi_T(z) - z| / max |z| at the end",
            "iterations": "Newton iterations of the second stage (all unknowns)",
            "tail": "max |xi_n| on the far quarter ring / max |xi_n|",
            "energy": "energy (ham) of the TB",
            "trivial_defect": "largest |mu - 1| of the four multipliers modulo shift nearest 1",
            "growth_rate": "ln max |mu| / T over the other multipliers modulo shift, per unit t",
            "unstable": "1 if growth_rate > stability_threshold",
            "reciprocal_defect": "max over mu of the distance of 1/mu to the nearest multiplier",
            "smallest_singular": "smallest singular value of the bordered Jacobian over its largest",
            "ansatz_period": "time per site T_d eps^(1-alpha) of the DpS member in units of t",
            "start_residual": "shift-map residual of the ansatz at T",
            "core_residual": "shift-map residual after the first stage (the core's unknowns alone)",
            "converged": "1 if the residual reached newton_tol",
        }.items()},
        "x": Var(("eps_large", "site"), "x_n(0) of the TB"),
        "v": Var(("eps_large", "site"), "v_n(0) of the TB"),
    },
    "/lattice_zeros": {
        "zero_ring": Var(("zero_ring",), "sites N of the ring (lattice_zero_rings)"),
        "minimum": Var(("minimum",), "the minimum followed: 0 the branch of the TB at lattice_zero_eps, 1 that of the "
                       "continuation's member at lattice_zero_step"),
        "zero_step": Var(("zero_step",), "relative change s of the velocity on the fine grid: c = c1 (1 + s), c1 that "
                         "of the minimum's member"),
        "iterate": Var(("iterate",), "iterate of the regula falsi"),
        "zero_site": Var(("zero_site",), "site n (up to the largest ring; NaN beyond each ring)"),
        **{f"{k}{suffix}": Var(dims, f"{text} ({which})", units)
           for suffix, dims, which in (("_grid", ("zero_ring", "minimum", "zero_step"), "the fine grid's member"),
                                       ("", ("zero_ring", "minimum"), "the TB where the signed tail vanishes"))
           for k, (text, units) in {
               "c_tb": ("velocity c = 1/T, sites per unit t", "1"),
               "period": ("period T of (tbnc), x_n(t + T) = x_{n-1}(t), in units of t", "1"),
               "eps_tb": ("eps at the TB's amplitude: sqrt(sum |xi_n|^2 / norm)", "1"),
               "dps_c": ("velocity of the DpS TB through (ansatz), 1 / (T eps_tb^(alpha-1)), sites per unit tau", "1"),
               "residual": ("shift-map residual max |S^{-1} Phi_T(z) - z| / max |z|", "1"),
               "sigma": ("signed tail Re(B / xi_n0) |xi_n0| / max |xi_n| at the symmetric time, B the far field's "
                         "plane wave at the antipode (cradle.integrators.lattice_tail)", "1"),
               "tail": ("max |xi_n| on the far quarter ring / max |xi_n| at t = 0", "1"),
               "phase_defect": ("Im(B / xi_n0) |xi_n0| / max |xi_n|: the part of the far field off the symmetric "
                                "phase", "1"),
           }.items()},
        "c_error": Var(("zero_ring", "minimum"), "uncertainty of c: max(|sigma|, residual) over the bracket's slope "
                       "d sigma / dc, sites per unit t"),
        "symmetry_defect": Var(("zero_ring", "minimum"), "distance of eta_n = xi_n / xi_n0 to conj(eta_{2 n0 - n}), "
                               "weighted by |xi_n| / max, at the symmetric time"),
        "trivial_defect": Var(("zero_ring", "minimum"), "largest |mu - 1| of the four multipliers modulo shift nearest "
                              "1"),
        "growth_rate": Var(("zero_ring", "minimum"), "ln max |mu| / T over the other multipliers modulo shift, "
                           "per unit t"),
        "unstable": Var(("zero_ring", "minimum"), "1 if growth_rate > stability_threshold"),
        "reciprocal_defect": Var(("zero_ring", "minimum"), "max over mu of the distance of 1/mu to the nearest "
                                 "multiplier"),
        "bracket_low": Var(("zero_ring", "minimum"), "c of the grid member at the bracket's lower end, sites per "
                           "unit t"),
        "bracket_high": Var(("zero_ring", "minimum"), "c of the grid member at the bracket's upper end, sites per "
                            "unit t"),
        "iterations": Var(("zero_ring", "minimum"), "iterates of the regula falsi"),
        "c_iterate": Var(("zero_ring", "minimum", "iterate"), "velocity c of each iterate of the regula falsi, sites "
                         "per unit t"),
        "sigma_iterate": Var(("zero_ring", "minimum", "iterate"), "signed tail of each iterate"),
        "x": Var(("zero_ring", "minimum", "zero_site"), "x_n(0) of the TB where the signed tail vanishes"),
        "v": Var(("zero_ring", "minimum", "zero_site"), "v_n(0) of the TB where the signed tail vanishes"),
    },
    "/lattice_motion": {
        "eps_lattice": Var(("eps_lattice",), "eps of the launch"),
        "s_lattice": Var(("s_lattice",), "tau / T of the DpS member (the lattice time t = s T / eps^(alpha-1))"),
        "dps_distance": Var(("eps_lattice", "s_lattice"), "the DpS member launched in (nc): position minus start"),
        "exact_distance": Var(("eps_lattice", "s_lattice"), "the exact TB launched the same way: position minus "
                              "start"),
    },
    "/motion": {
        "eps": Var(("eps",), "small parameter eps of (ansatz) of the lattice run (tau = eps^(alpha-1) t)"),
        "s": Var(("s",), "tau / T: the sites the DpS TB travels (lattice time t = s T / eps^(alpha-1))"),
        "speed_ratio": Var(("eps",), "lattice velocity over the DpS TB's c eps^(alpha-1) (least squares, whole run)"),
        "speed_early": Var(("eps",), "the same over the first half of the run"),
        "speed_late": Var(("eps",), "the same over the second half of the run"),
        "deficit": Var(("eps",), "1 - speed_ratio: the lattice's speed deficit against DpS"),
        "radiation_end": Var(("eps",), "energy outside the window around the breather over the total, at the end"),
        "energy_drift": Var(("eps",), "max over every step of |H(t) - H(0)| / H(0) of the lattice run (ham)"),
        "distance": Var(("eps", "s"), "lattice: position of the breather minus its start (sites)"),
        "radiation": Var(("eps", "s"), "lattice: energy outside the window around the breather over the total"),
        "dps_distance": Var(("s",), "DpS (same start, same ring): position minus start (sites)"),
        "dps_radiation": Var(("s",), "DpS: norm outside the window around the breather over the norm"),
    },
    "/robustness": {
        "ring": Var(("ring",), "sites of the ring (N, then check_N)"),
        "rtol": Var(("rtol",), "DOP853 relative tolerance (rtol, then check_rtol), on the ring of N"),
        "growth_rate": Var(("ring", "c"), "ln max |mu| / T over the non-trivial multipliers modulo shift (per unit "
                                          "tau; NaN: member not reached on that ring)"),
        "unstable": Var(("ring", "c"), "1 if growth_rate > stability_threshold (-1: not reached)"),
        "tail": Var(("ring", "c"), "max |A_n| on the far quarter ring / max |A_n|"),
        "theta": Var(("ring", "c"), "phase theta of (tb)"),
        "tail_q": Var(("ring", "c"), "wavenumber q of the tail as a plane wave: arg sum A_{n+1} conj(A_n) on the far "
                                     "quarter ring (q = theta mod 2 pi for a tail of small amplitude)"),
        "tail_mi_rate": Var(("ring", "c"), "largest MI growth rate of the plane wave of the tail's q and rms amplitude "
                                           "on the infinite lattice (per unit tau; 0 for |q| <= pi/2)"),
        "mode_extent": Var(("ring", "c"), "participation ratio of the most unstable mode's |v_n|^2 over N (NaN: "
                                          "stable)"),
        "growth_rate_tol": Var(("rtol", "c"), "growth_rate on the ring of N at that tolerance (NaN: not converged)"),
        "unstable_tol": Var(("rtol", "c"), "the verdict on the ring of N at that tolerance (-1: not converged)"),
        "settled": Var(_C, "1 unstable and 0 stable on every ring and at every tolerance; -1 the verdict depends on "
                           "the ring or the tolerance"),
    },
    "/robustness_limit": {
        "limit_ring": Var(("limit_ring",), "sites of a ring of the fine scan (limit_N)"),
        "c_fine": Var(("c_fine",), "velocity c of the fine scan (c +- limit_halfwidth around every member)"),
        "growth_rate": Var(("limit_ring", "c_fine"), "ln max |mu| / T over the non-trivial multipliers modulo shift "
                                                     "(per unit tau; NaN: not reached on that ring)"),
        "unstable": Var(("limit_ring", "c_fine"), "1 if growth_rate > stability_threshold (-1: not reached)"),
        "theta": Var(("limit_ring", "c_fine"), "phase theta of (tb), in (-pi, pi]"),
        "tail": Var(("limit_ring", "c_fine"), "max |A_n| on the far quarter ring / max |A_n|"),
        "tail_mi_rate": Var(("limit_ring", "c_fine"), "largest MI growth rate of the tail's plane wave on the "
                                                      "infinite lattice (per unit tau; 0 for |q| <= pi/2)"),
        "krein_gap": Var(("limit_ring", "c_fine"), "smallest angle between non-trivial multipliers of opposite "
                                                   "Krein signature on the unit circle (pi: no such pair)"),
        "quartet_defect": Var(("limit_ring", "c_fine"), "largest distance from 1/conj(mu) or conj(mu) to the "
                                                        "nearest multiplier (0 for a symplectic spectrum)"),
        "top_arg": Var(("limit_ring", "c_fine"), "arg of the most unstable multiplier (pi: through -1, 0: through "
                                                 "+1; NaN: stable)"),
        "unstable_fraction": Var(("c", "limit_ring"), "fraction of the member's fine neighbourhood that is unstable "
                                                      "on that ring (NaN: none reached)"),
        "typical_growth": Var(("c", "limit_ring"), "median growth rate over the member's fine neighbourhood"),
        "largest_growth": Var(("c", "limit_ring"), "largest growth rate over the member's fine neighbourhood"),
        "reached": Var(("c", "limit_ring"), "fraction of the member's fine neighbourhood reached on that ring"),
        "decay": Var(_C, "k: least-squares slope of -ln typical_growth against ln N over the rings where it "
                         "exceeds the threshold (NaN: fewer than two; reported, not used by the rule)"),
        "envelope_decay": Var(_C, "the same slope for largest_growth (the windows' envelope)"),
        "verdict": Var(_C, "limit verdict of limit_rule: 1 unstable, 0 stable, -1 undecided"),
        "windows": Var(("limit_ring",), "runs of consecutive unstable points of the fine grid on that ring"),
        "window_width": Var(("limit_ring",), "mean width in c of those runs (points times limit_step)"),
        "ring_largest_growth": Var(("limit_ring",), "largest growth rate over the whole fine grid on that ring"),
        "ring_unstable_fraction": Var(("limit_ring",), "fraction of the reached fine grid that is unstable"),
    },
    "/limit_tail": {
        "fit_ring": Var(("fit_ring",), "sites of a ring of the tail rule's fit (limit_N, then limit_large_N)"),
        "tail_q": Var(_C, "wavenumber q of the tail's plane wave: theta modulo 2 pi, in (-pi, pi]", "rad"),
        "tail_mi_unstable": Var(_C, "1 if the tail's plane wave is modulationally unstable (cos q < 0: at every "
                                    "amplitude), else 0"),
        "theta_spread": Var(_C, "largest |theta - theta on the ring of N| (modulo 2 pi) over the rings of "
                                "/robustness and the tolerances of check_rtol", "rad"),
        "unit_amplitude_mi_rate": Var(_C, "largest MI growth rate of the plane wave e^{i q n} of unit amplitude, "
                                          "closed form (per unit tau; times R^(alpha-1) at amplitude R)"),
        "fastest_sideband": Var(_C, "sideband wavenumber p of that largest rate (NaN: stable)", "rad"),
        "unstable_band_low": Var(_C, "lower edge of the unstable sideband band in [0, pi] (NaN: stable)", "rad"),
        "unstable_band_high": Var(_C, "upper edge of the unstable sideband band in [0, pi] (NaN: stable)", "rad"),
        "tail_mi_rate_min": Var(_C, "smallest MI growth rate of the tail measured on the rings of /robustness (per "
                                    "unit tau: its amplitude changes with N)"),
        "tail_mi_rate_max": Var(_C, "largest MI growth rate of the tail measured on those rings (per unit tau)"),
        "envelope": Var(("c", "fit_ring"), "largest growth rate over the member's neighbourhood, on the points of "
                                           "the member's tail kind common to every ring (per unit tau; NaN: none "
                                           "reached)"),
        "fit_g_inf": Var(_C, "g_inf of envelope = g_inf + b N^-k over the rings (per unit tau; NaN: fewer than 4)"),
        "fit_g_inf_error": Var(_C, "error of fit_g_inf: the larger of its standard error and its change when the "
                                   "smallest or the largest ring is left out (per unit tau)"),
        "fit_g_inf_stderr": Var(_C, "standard error of fit_g_inf from the residuals (per unit tau)"),
        "fit_b": Var(_C, "b of that fit (per unit tau times sites^k)"),
        "fit_k": Var(_C, "exponent k of that fit"),
        "fit_points": Var(_C, "rings in that fit"),
        "fit_degenerate": Var(_C, "1 if k ended on a bound of its range (the error is then no error of g_inf; NaN: "
                                  "no fit)"),
        "verdict": Var(_C, "limit verdict of tail_rule: 1 unstable, 0 stable, -1 undecided"),
        "member_growth": Var(("c", "fit_ring"), "growth rate of the member itself, at c, on each ring (per unit "
                                                "tau; NaN: not reached or c not on that ring's grid)"),
        "member_fit_g_inf": Var(_C, "g_inf of member_growth = g_inf + b N^-k over the rings (per unit tau; NaN: "
                                    "fewer than 4)"),
        "member_fit_g_inf_error": Var(_C, "error of member_fit_g_inf, as fit_g_inf_error (per unit tau)"),
        "member_fit_k": Var(_C, "exponent k of that fit"),
        "member_fit_degenerate": Var(_C, "1 if k ended on a bound of its range (NaN: no fit)"),
        "member_verdict": Var(_C, "limit verdict of the member itself (member_rule): 1 unstable, 0 stable, -1 "
                                  "undecided"),
    },
    "/limit_fold": {
        "fold_ring": Var(("fold_ring",), "sites of a ring of the fold scan (limit_fold_N)"),
        "arc": Var(("arc",), "index along the family: the first member, the natural continuation's, then the "
                             "pseudo-arclength's"),
        "velocity": Var(("fold_ring", "arc"), "velocity c = 1/T (sites per unit tau; NaN: past the last member)"),
        "energy": Var(("fold_ring", "arc"), "Hamiltonian H of (dfnls) at unit norm"),
        "theta": Var(("fold_ring", "arc"), "phase theta of (tb), in (-pi, pi]", "rad"),
        "growth": Var(("fold_ring", "arc"), "ln max |mu| / T over the non-trivial multipliers modulo shift (per "
                                            "unit tau)"),
        "real_growth": Var(("fold_ring", "arc"), "ln mu / T of the largest real non-trivial multiplier mu > 1 (per "
                                                 "unit tau; 0: none)"),
        "tail": Var(("fold_ring", "arc"), "max |A_n| on the far quarter ring / max |A_n|"),
        "residual": Var(("fold_ring", "arc"), "shift-map residual max |R| / max |A|"),
        "fold_site": Var(("fold_site",), "site n of the ring (NaN beyond the ring's own sites)"),
        "A_re": Var(("fold_ring", "arc", "fold_site"), "Re A_n(0) of the member"),
        "A_im": Var(("fold_ring", "arc", "fold_site"), "Im A_n(0) of the member"),
    },
    "/limit_large": {
        "large_ring": Var(("large_ring",), "sites of a larger ring of the tail rule (limit_large_N)"),
        "c_large": Var(("c_large",), "velocity c of its scan (around the members whose tail is MI-stable)"),
        "growth_rate": Var(("large_ring", "c_large"), "ln max |mu| / T over the non-trivial multipliers modulo "
                                                      "shift (per unit tau; NaN: not reached)"),
        "unstable": Var(("large_ring", "c_large"), "1 if growth_rate > stability_threshold (-1: not reached)"),
        "theta": Var(("large_ring", "c_large"), "phase theta of (tb), in (-pi, pi]", "rad"),
        "tail": Var(("large_ring", "c_large"), "max |A_n| on the far quarter ring / max |A_n|"),
        "tail_mi_rate": Var(("large_ring", "c_large"), "largest MI growth rate of the tail's plane wave on the "
                                                       "infinite lattice (per unit tau)"),
        "quartet_defect": Var(("large_ring", "c_large"), "largest distance from 1/conj(mu) or conj(mu) to the "
                                                         "nearest multiplier (0 for a symplectic spectrum)"),
    },
    "/claims": GROUP_VARIABLES,
}


def tail_dips(c: NDArray[np.float64], tail: NDArray[np.float64]) -> list[int]:
    """Indices of the inner grid points where the tail is below :data:`DIP` of both neighbours'."""
    return [i for i in range(1, len(c) - 1) if tail[i] < DIP * min(tail[i - 1], tail[i + 1])]


def claims(c: NDArray[np.float64], tail: NDArray[np.float64], tail_N: NDArray[np.float64], dH_changes: list[float],
           real_changes: list[float], v_changes: list[float], spacing: float) -> list[Row]:
    """The cited papers' statements against the family (qualitative rows)."""
    dips, dips_N = tail_dips(c, tail), tail_dips(c, tail_N)
    both = sorted(set(dips) & set(dips_N))
    text = ", ".join(f"c = {c[i]:.3g}" for i in both) or "none"
    rows = [Row("James 2018 (abstract)", "TB tails for p = 5/2: small, non-vanishing, oscillatory",
                "generally non-vanishing", f"tail {np.min(tail):.2g} .. {np.max(tail):.2g} of the peak over c = "
                f"{c[0]:.3g} .. {c[-1]:.3g}", "agrees" if np.min(tail) > 0 else "disagrees",
                "max |A_n| on the far quarter ring / max |A_n|, each member"),
            Row("James 2018 (abstract)", "near-localised TBs at particular parameters", "exist",
                f"tail dips (below {DIP:g} of both neighbours) on both rings at: {text}; on one ring only at "
                f"{len(set(dips) ^ set(dips_N))} grid points", "agrees" if both else "not comparable",
                "local minima of the tail along the c grid, on the ring of N and of check_N sites")]
    near = (all(any(abs(v - d) <= spacing for v in v_changes) for d in dH_changes)
            and all(any(abs(v - d) <= spacing for d in dH_changes) for v in real_changes))
    rows.append(Row("Xu et al. 2017 (arXiv 1701.04882)", "a stability change where dH/dc changes sign "
                    "(sufficient, not necessary)", "stability changes at sign changes of dH/dc",
                    f"dH/dc changes sign at {', '.join(f'{x:.3g}' for x in dH_changes) or 'none'}; a real "
                    f"multiplier crosses +1 at {', '.join(f'{x:.3g}' for x in real_changes) or 'none'}; any verdict "
                    f"changes at {', '.join(f'{x:.3g}' for x in v_changes) or 'none'}",
                    "agrees" if near else "disagrees", "H and the multipliers modulo shift along the fixed-norm family",
                    tolerance=f"one grid spacing ({spacing:.3g})"))
    for r in rows:
        r.explained_in = EXPLAINED
        r.qualitative = True     # James's abstract and Xu et al.'s criterion print no number
    return rows


def compute(spec: TravellingBreathers, inputs: dict | None = None, log: Log | None = None) -> xr.DataTree:
    """The `travelling-breathers` analysis as a tree of groups (:data:`VARIABLES`); it reads no file."""
    from cradle.data.io import make_tree
    from cradle.models import dps_travelling as M

    say = log or (lambda *a: None)
    t0 = _time.perf_counter()
    fam, c_start = family(spec, spec.N, spec.rtol, say)
    if len(fam) < 3:
        raise RuntimeError(f"travelling breathers: only {len(fam)} members reached")
    c = np.array([b.c for b in fam])
    H = np.array([b.energy for b in fam])
    tail = np.array([M.tail_amplitude(b.A) for b in fam])
    ver = [verdict(b, spec.stability_threshold) for b in fam]
    unstable = np.array([v[2] for v in ver])
    dH = np.gradient(H, c)
    # the checks (robustness of the verdicts): the family on every check ring, every member at every check rtol;
    # /family keeps the first of each
    rob = robustness(spec, fam, say)
    growth_N, unstable_N, tail_N = rob["growth_ring"][1], rob["unstable_ring"][1], rob["tail_ring"][1]
    ver_r = [(np.nan, g, None if u < 0 else bool(u), None) for g, u in zip(rob["growth_tol"][1], rob["unstable_tol"][1],
                                                                          strict=True)]
    profiles = static_profiles(spec.N, spec.alpha, spec.norm)
    dist = [static_distance(b, profiles, spec.static_samples, spec.rtol) for b in fam]
    i_direct = int(np.argmin(np.abs(c - spec.direct_speed)))
    direct = direct_run(fam[i_direct], spec.direct_periods, spec.rtol)
    other = fam[i_direct + 1] if i_direct + 1 < len(fam) else fam[i_direct - 1]
    scal = scaling_check(fam[i_direct], other, spec.scale, spec)
    limit_groups, limit_attrs = robustness_limit(spec, c, say)
    tail_groups, tail_attrs = tail_rule(spec, c, np.array([b.theta for b in fam]), rob,
                                        limit_groups["/robustness_limit"], say)
    fold_groups, fold_attrs = fold_group(spec, say) if spec.limit_fold_N else ({}, {})
    i_motion = int(np.argmin(np.abs(c - spec.motion_speed)))
    motion_groups, motion_attrs = motion(spec, fam[i_motion], say)
    real = np.array([v[3] for v in ver])
    dH_changes, v_changes, real_changes = sign_changes(c, dH), verdict_changes(c, unstable), verdict_changes(c, real)
    rows = claims(c, tail, np.asarray(tail_N), dH_changes, real_changes, v_changes, float(np.max(np.diff(c))))
    for b, v, t in zip(fam, ver, tail, strict=True):
        say(f"travelling-breathers: c = {b.c:.4g}: theta = {b.theta:.10g}, H = {b.energy:.10g}, tail {t:.3g}, "
            f"residual {b.residual:.2g}, trivial defect {v[0]:.2g}, growth {v[1]:.3g}")
    groups: dict = {
        "/": ({}, {"c": c}),
        "/family": ({"period": 1.0 / c, "theta": [math.remainder(b.theta, 2 * math.pi) for b in fam], "energy": H,
                     "dH_dc": dH, "tail": tail, "residual": [b.residual for b in fam],
                     "iterations": [b.iterations for b in fam], "trivial_defect": [v[0] for v in ver],
                     "growth_rate": [v[1] for v in ver], "unstable": unstable.astype(int),
                     "real_mode": real.astype(int),
                     "growth_rate_rtol": [v[1] for v in ver_r],
                     "unstable_rtol": [-1 if v[2] is None else int(v[2]) for v in ver_r],
                     "growth_rate_N": growth_N, "unstable_N": unstable_N, "tail_N": tail_N,
                     "static_distance_site": [d["site"] for d in dist],
                     "static_distance_bond": [d["bond"] for d in dist]}, {}),
        "/profiles": ({"A_re": np.array([b.A.real for b in fam]), "A_im": np.array([b.A.imag for b in fam]),
                       "static_site": profiles["site"][0], "static_bond": profiles["bond"][0]},
                      {"n": np.arange(spec.N)}),
        "/multipliers": ({"mu_re": np.array([b.multipliers.real for b in fam]),
                          "mu_im": np.array([b.multipliers.imag for b in fam])},
                         {"m": np.arange(2 * spec.N)}),
        "/direct": ({"residual": direct["residual"]}, {"k": direct["k"]}),
        "/robustness": ({"growth_rate": rob["growth_ring"], "unstable": rob["unstable_ring"], "tail": rob["tail_ring"],
                         "theta": rob["theta_ring"], "tail_q": rob["tail_q_ring"], "tail_mi_rate": rob["tail_mi_ring"],
                         "mode_extent": rob["extent_ring"], "growth_rate_tol": rob["growth_tol"],
                         "unstable_tol": rob["unstable_tol"], "settled": rob["settled"]},
                        {"ring": rob["ring"], "rtol": rob["rtol"]}),
        "/claims": group(rows),
        **motion_groups,
        **limit_groups,
        **tail_groups,
        **fold_groups,
    }
    near = np.minimum([d["site"] for d in dist], [d["bond"] for d in dist])
    power = float(np.polyfit(np.log(c), np.log(near), 1)[0])
    agree_r = [v[2] == w[2] for v, w in zip(ver, ver_r, strict=True)]
    agree_N = [u == int(v[2]) for u, v in zip(unstable_N, ver, strict=True) if u >= 0]
    attrs = {
        "norm": spec.norm, "N": spec.N, "check_N": spec.check_N[0], "check_rtol": spec.check_rtol[0],
        "stability_threshold": spec.stability_threshold, "c_start": c_start, "omega_static": profiles["site"][1],
        "invariant_velocity": "c P^((1-alpha)/2): the scaling maps (c, P) to (lambda^(alpha-1) c, lambda^2 P)",
        "max_residual": float(max(b.residual for b in fam)),
        "max_trivial_defect": float(max(v[0] for v in ver)),
        "n_unstable": int(unstable.sum()),
        "dH_dc_sign_changes": ", ".join(f"{x:.6g}" for x in dH_changes) or "none",
        "verdict_changes": ", ".join(f"{x:.6g}" for x in v_changes) or "none",
        "real_multiplier_changes": ", ".join(f"{x:.6g}" for x in real_changes) or "none",
        "verdicts_agree_rtol": f"{sum(agree_r)} of {len(agree_r)}",
        "verdicts_agree_N": f"{sum(agree_N)} of {len(agree_N)}",
        **robustness_attrs(c, rob),
        "direct_speed": float(c[i_direct]), "direct_norm_drift": direct["norm_drift"],
        "direct_energy_drift": direct["energy_drift"], "direct_max_residual": float(np.max(direct["residual"])),
        "static_distance_power": power,
        "scaling_lambda": spec.scale, "scaling_profile_error": scal["profile_error"],
        "scaling_theta_error": scal["theta_error"], "scaling_converged": int(scal["converged"]),
        "method": "Gauss-Newton on the shooting map modulo shift R = e^{-i theta} S^{-1} Phi_T(A) - A at fixed T and "
                  "norm, with the phase conditions of the phase rotation and the time shift; DOP853 (scipy) with the "
                  "variational equations; tangent predictor in T",
        "source": "G. James, Phil. Trans. R. Soc. A 376 (2018) 20170138 (abstract); H. Xu, J. Cuevas-Maraver, "
                  "P. G. Kevrekidis, A. Vainchtein, arXiv 1701.04882",
        **motion_attrs,
        **limit_attrs,
        **tail_attrs,
        **fold_attrs,
        "wall_time_s": _time.perf_counter() - t0,
    }
    if spec.lattice:
        lattice, lattice_attrs = lattice_groups(spec, fam, say)
        groups |= lattice
        attrs |= lattice_attrs
        attrs["wall_time_s"] = _time.perf_counter() - t0
    tree = make_tree(groups, VARIABLES, attrs=attrs, params=plain(spec),
                     title="Travelling breathers of the DpS equation")
    return tree


ANALYSIS = Analysis(
    name="travelling-breathers", spec=TravellingBreathers, compute=compute, variables=VARIABLES, claims="/claims",
    title="Travelling breathers of the DpS equation: family in c, tails, multipliers modulo shift")
