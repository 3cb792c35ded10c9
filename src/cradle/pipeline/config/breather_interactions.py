"""Declaration of ``beyond.breather_interactions``: collisions of two DpS-family breathers in (nc) and (dfnls)
(cradle.analyses.breather_interactions)."""
from __future__ import annotations

from cradle.scenes.context import Context, Where
from cradle.specs.declare import declared, param
from cradle.specs.values import Errors


def form_section(b: dict, form: str) -> dict:
    """An analysis section of one form: its full keys, with the keys given under ``reduced`` in place for
    ``form == "reduced"`` (a null there keeps the full value)."""
    out = {k: v for k, v in b.items() if k != "reduced"}
    if form == "reduced":
        out.update({k: v for k, v in (b.get("reduced") or {}).items() if v is not None})
    return out


_PAIRS = {"type": "string", "enum": ["site-site", "bond-bond", "site-bond"]}
_SPACING = {"type": "integer", "minimum": 1, "maximum": 24}
_THETA = {"type": "number", "minimum": 0, "exclusiveMaximum": 6.283185307179586}


@declared(doc="The reduced form `snakemake all` builds (results/interactions/breather-interactions.nc): these keys "
              "replace those of the full form, `snakemake breather_interactions_full` (results/interactions/full/).")
class BreatherInteractionsReduced:
    pairs: list[str] = param(["site-site"], "Profile pairs.", minItems=1, maxItems=3, items=_PAIRS)
    spacings: list[int] = param([2, 6], "Centre spacings.", minItems=1, maxItems=24, items=_SPACING)
    n_theta: int = param(2, "Number of base phases theta.", minimum=1, maximum=96)
    refine: int = param(0, "Bisection levels of theta where the outcome changes.", minimum=0, maximum=4)
    n_seeds: int = param(1, "Noise seeds per case.", minimum=1, maximum=64)
    periods: float = param(100.0, "Run length in breather periods.", exclusiveMinimum=0, maximum=5000)
    ratios: list[float] = param([1.0], "Amplitude ratios.", minItems=1, maxItems=8, items={"type": "number"})
    amplitudes: list[float] = param([0.01], "Overall amplitudes.", minItems=1, maxItems=8, items={"type": "number"})
    chunks: int = param(1, "Jobs of the sweep (reduced: computed in the analysis job itself).", minimum=1,
                        maximum=1)


@declared(doc="Collisions of two breathers of the DpS family (omega_sw ~ 1.1) on a ring, exact (nc) against DpS "
              "(dfnls), over profile pair, spacing, relative phase, amplitude ratio, amplitude and noise seeds "
              "-> results/interactions/full/breather-interactions.nc (target breather_interactions_full) and "
              "results/figures/full/breather-interactions.{pdf,png}; the reduced form (`reduced`) is built by all.")
class BreatherInteractions:
    N: int = param(50, "Ring size (periodic).", minimum=16, maximum=400)
    alpha: float = param(1.5, "Hertz exponent alpha of V0 (> 1).", ref="alpha", maximum=10)
    amplitude: float = param(0.01, "Peak |x_n(0)| of the first copy alone in the theta sweep (omega_sw ~ 1.1).",
                             exclusiveMinimum=0, maximum=0.1)
    pairs: list[str] = param(["site-site", "bond-bond", "site-bond"], "Profile pairs of the two copies of (dpsstn) "
                             "solutions.", minItems=1, maxItems=3, items=_PAIRS)
    spacings: list[int] = param([4, 5, 6, 7, 8], "Centre spacings (site-bond: each + 1/2), the interacting range "
                                "of docs/loc1-readings.md.", minItems=1, maxItems=24, items=_SPACING)
    n_theta: int = param(24, "Number of base phases theta = 2 pi j / n_theta of the second copy on the carrier.",
                         minimum=1, maximum=96)
    refine: int = param(1, "Bisection levels between neighbouring base thetas whose outcome (exact, modal over seeds) "
                        "differs.", minimum=0, maximum=4)
    n_seeds: int = param(8, "Noise seeds per case.", minimum=1, maximum=64)
    noise: float = param(0.01, "Noise on A_n(0), relative to the amplitude (Gaussian, sd noise * amplitude / 2).",
                         minimum=0, maximum=1)
    seed_base: int = param(20261122, "First entry of the seed sequence (seed_base, seed) of numpy's default_rng.",
                           minimum=0)
    periods: float = param(600.0, "Run length in breather periods 2 pi / omega_sw (the paper: up to 600).",
                           exclusiveMinimum=0, maximum=5000)
    ratios: list[float] = param([0.8, 1.0, 1.25], "Amplitude ratios (second copy / first) of the amplitude sweep, at "
                                "the base amplitude.", minItems=1, maxItems=8,
                                items={"type": "number", "exclusiveMinimum": 0, "maximum": 10})
    amplitudes: list[float] = param([0.005, 0.01, 0.02], "Overall amplitudes of the amplitude sweep, at ratio 1.",
                                    minItems=1, maxItems=8,
                                    items={"type": "number", "exclusiveMinimum": 0, "maximum": 0.1})
    amplitude_thetas: list[float] = param([0.0, 3.141592653589793], "Phases (radians) of the amplitude sweep.",
                                          minItems=1, maxItems=8, items=_THETA)
    chunks: int = param(4, "Jobs the full sweep is split into (round robin over (pair, spacing)).", minimum=1,
                        maximum=64)
    reduced: BreatherInteractionsReduced = param(BreatherInteractionsReduced())

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Spacings distinct; the pair must fit the ring."""
        for at, sp in ((where, self.spacings), (where + ["reduced"], self.reduced.spacings)):
            if len(set(map(str, sp))) != len(sp):
                out.add(at + ["spacings"], "must be distinct", sp)
            if any(s + 10 > self.N for s in sp):
                out.add(at + ["spacings"], f"must leave room for both breathers: spacing + 10 <= N = {self.N}", sp)

    @staticmethod
    def resolve(cfg: dict, form: str = "full") -> dict:
        """The section of one form: the full keys, with the reduced ones in place for ``reduced``."""
        b = form_section(cfg["beyond"]["breather_interactions"], form)
        b["amplitude_thetas"] = [float(t) for t in b["amplitude_thetas"]]
        return b
