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
  neighbourhood per ring, and one rule (:data:`.fine_scan.LIMIT_RULE`) that reads the limit verdict from the two
  largest rings; a window resolved as a Krein collision (:func:`.fine_scan.bubble_scan`,
  :mod:`cradle.measurements.floquet_bubbles`);
* checks: a direct run of the member
  at ``direct_speed`` over ``direct_periods`` periods (norm and H drifts, the residual of (tb) after k periods);
  the scaling symmetry (the TB re-solved at lambda^(1-alpha) T and lambda^2 P from another member's profile,
  against lambda A);
* the cited papers' statements as claims rows (group /claims, the columns of the claims table).

This module declares the analysis (its spec, :func:`compute`, the claims rows and ``ANALYSIS``); each group is
computed in a module of its own, each importing only from those listed before it:

* :mod:`.dps_family`: the DpS family, its verdicts, the c -> 0 end, the direct run, the scaling check
* :mod:`.verdict_checks`: /robustness: the verdicts on the check rings and tolerances
* :mod:`.fine_scan`: /robustness_limit: each member's neighbourhood on rings of growing N (LIMIT_RULE)
* :mod:`.limit_tail`: /limit_tail, /limit_large: the tail rule and the member rule in the limit N -> infinity
* :mod:`.limit_fold`: /limit_fold: the family through its folds by pseudo-arclength
* :mod:`.in_motion`: /motion: a member launched in (nc) through (ansatz)
* :mod:`.lattice_members`: the exact (nc) TBs one at a time
* :mod:`.tail_zeros`: /lattice_zeros: where the (nc) TB's signed tail vanishes
* :mod:`.lattice`: /lattice, /lattice_motion, /lattice_rings, /lattice_large: the exact (nc) TBs' groups
* :mod:`.variables`: the stored variables, group by group
"""
from __future__ import annotations

import itertools
import math
import time as _time
from typing import TYPE_CHECKING

import numpy as np

from cradle.analyses.claims_table import Row, group
from cradle.analyses.protocol import Analysis
from cradle.analyses.travelling_breathers.dps_family import (
    direct_run,
    family,
    scaling_check,
    sign_changes,
    static_distance,
    static_profiles,
    verdict,
    verdict_changes,
)
from cradle.analyses.travelling_breathers.fine_scan import robustness_limit
from cradle.analyses.travelling_breathers.in_motion import motion
from cradle.analyses.travelling_breathers.lattice import lattice_groups
from cradle.analyses.travelling_breathers.limit_fold import fold_group
from cradle.analyses.travelling_breathers.limit_tail import tail_rule
from cradle.analyses.travelling_breathers.variables import VARIABLES
from cradle.analyses.travelling_breathers.verdict_checks import robustness, robustness_attrs
from cradle.specs.declare import declared, param, plain
from cradle.specs.values import RTOL_FLOOR

if TYPE_CHECKING:
    import xarray as xr
    from numpy.typing import NDArray

    from cradle.analyses.protocol import Log
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors

_SPEED = {"type": "number", "exclusiveMinimum": 0, "maximum": 2,
          "description": "One velocity c = 1/T of the family (sites per unit tau at the norm of the spec)."}

_RING = {"type": "integer", "minimum": 8, "maximum": 200, "description": "Sites of a check ring."}
_RTOL = {"type": "number", "minimum": RTOL_FLOOR, "maximum": 1e-8, "description": "A DOP853 relative tolerance."}

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


# ----------------------------------------------------------------- the stored file


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
