"""The spec of the `breathers` analysis (``beyond: breathers:``): exact breathers of (nc), their Floquet
stability, Peierls-Nabarro barrier and mobility, against the DpS breathers (ansatzapproxst2), and its reduced
form (:mod:`cradle.analyses.breathers`, :mod:`.breather_mobility` and :mod:`.breather_exchanges` compute
from it)."""
from __future__ import annotations

import itertools
from typing import TYPE_CHECKING

from cradle.specs.declare import declared, param

if TYPE_CHECKING:
    from cradle.scenes.spec import Context, Where
    from cradle.specs.values import Errors

_OMEGA = {"type": "number", "exclusiveMinimum": 1, "maximum": 10, "description": "One breather frequency omega_b."}
_KINDS = {"type": "string", "enum": ["site", "bond"], "description": "A breather family: site- or bond-centred."}
_KICK = {"type": "number", "exclusiveMinimum": 0, "maximum": 10, "description": "One kick size (relative)."}


@declared(doc="Exact time-periodic, time-reversible breathers of (nc) by reversible shooting and Newton "
              "continuation in omega_b from the DpS breather (ansatzapproxst2), site- and bond-centred, on the ring "
              "of plot18 and the free-end chain of fini; Floquet multipliers, Peierls-Nabarro barrier, a kicked "
              "breather and the distance to DpS -> results/breathers/breathers.nc and "
              "results/figures/breathers.{pdf,png}.")
class Breathers:
    alpha: float = param(1.5, "Hertz exponent alpha of V0 (> 1).", ref="alpha", maximum=10)
    N: int = param(50, "Beads of the ring (plot18: 50).", minimum=6, maximum=400,
                   reduced=10)
    free_N: int = param(10, "Beads of the free-end chain (fini: 10; 0: none); bond-centred family only (an even "
                        "free chain has no site-centred symmetry).", minimum=0, maximum=400,
                        reduced=0)
    kinds: list[str] = param(["site", "bond"], "Families on the ring.", minItems=1, maxItems=2, items=_KINDS)
    omegas: list[float] = param([1.001, 1.002, 1.005, 1.01, 1.02, 1.03, 1.05, 1.07, 1.1, 1.15, 1.2, 1.3, 1.4, 1.5, 1.6,
                                 1.8, 2.0, 2.5, 3.0], "Continuation grid of omega_b (increasing, > 1); the first is "
                                "started from DpS.", minItems=1, maxItems=200, items=_OMEGA,
                                reduced=[1.05, 1.1, 1.3, 1.6])
    newton_tol: float = param(1e-11, "Newton stops when max|F| <= newton_tol max|x(0)|.", exclusiveMinimum=0,
                              maximum=1e-4)
    rtol: float = param(1e-13, "DOP853 relative tolerance of the shooting and of the monodromy.", minimum=2.3e-14,
                        maximum=1e-6,
                        reduced=1e-13)
    check_rtol: float = param(2.5e-14, "Tolerance of the resolution check of the period residual.",
                              minimum=2.3e-14, maximum=1e-6,
                              reduced=2.5e-14)
    stability_threshold: float = param(1e-7, "Growth rate (per unit t) above which a breather is called unstable.",
                                       exclusiveMinimum=0, maximum=1)
    pn_omega: float = param(1.1, "omega_b of the site breather where the Peierls-Nabarro barrier is reported; one "
                            "of omegas.", exclusiveMinimum=1, maximum=10)
    fit_omega_max: float = param(1.1, "The DpS-distance power law is fitted over omega_b <= fit_omega_max.",
                                 exclusiveMinimum=1, maximum=10)
    exchange_steps: int = param(4, "Regula falsi steps locating each stability exchange (pinning pair through +1) "
                                "between grid points (0: none).", minimum=0, maximum=50,
                                reduced=0)
    kick_family: str = param("bond", "Ring family of the kicked breather.", enum=["site", "bond"])
    kick_omega: float = param(1.1, "omega_b of the kicked breather; one of omegas.", exclusiveMinimum=1, maximum=10)
    kicks: list[float] = param([3e-5, 1e-4, 1e-3, 1e-2, 1e-1], "Kick sizes: velocity along the pinning mode / "
                               "max|x(0)|.", maxItems=20, items=_KICK,
                               reduced=[1e-2, 1e-1])
    kick_t_end: float = param(3000.0, "Duration of a kicked run.", exclusiveMinimum=0, maximum=1e6,
                              reduced=300.0)
    kick_window: float = param(5.0, "Beads from the energy centre beyond which energy counts as radiated.",
                               exclusiveMinimum=0, maximum=100)
    direct_omega: float | None = param(2.5, "omega_b of the direct growth check (default: the most unstable "
                                       "ring breather).", exclusiveMinimum=1, maximum=10)
    direct_growth_factor: float = param(30.0, "The direct run lasts until the unstable mode grows by this factor "
                                        "(1: no direct run).", minimum=1, maximum=1e8,
                                        reduced=1.0)

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Each form: omegas increasing, pn_omega and kick_omega among them."""
        om = self.omegas
        if any(y <= x for x, y in itertools.pairwise(om)):
            out.add(where + ["omegas"], "must be strictly increasing", om)
        for key, v in (("pn_omega", self.pn_omega), ("kick_omega", self.kick_omega)):
            if float(v) not in [float(x) for x in om]:
                out.add(where + [key], f"must be one of omegas = {om}", v)
