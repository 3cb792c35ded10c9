"""Declarations of the analyses beyond the paper (``beyond:``), their checks and their resolved specs.

Each analysis is a frozen dataclass (Theorem 1 on exact travelling waves of
(ad), the DpS modulational-instability map (ansatz3), its growth rates in the
scenes' runs, threshold statistics over noise seeds, Bloch-Floquet stability, the DpS approximation
error against eps and T).
``check`` reports, one line per problem, what the schema cannot express;
``resolve`` turns the section of a validated config into the plain dict the
analysis module computes from (angles in radians, inherited settings merged),
so that the numerical modules never read or check the config.
"""
from __future__ import annotations

import math

from .breathers import Breathers
from .dps_validity import DpsValidity
from .floquet import Floquet
from cradle.specs.declare import declared, param
from cradle.specs.values import ConfigError, angle_expr, angle_or_none, did_you_mean, entries, number, parse_angle, show

_ALPHAS = {"$ref": "#/$defs/alpha", "maximum": 10}
_ANGLES = {"$ref": "#/$defs/angle"}
_NAMES = {"$ref": "#/$defs/name"}


@declared(doc="Exact periodic travelling waves of (nc) with V = V0 by a sine-series Newton solver of (ad), against "
              "(wleadingorder) -> results/theorem1/theorem1.nc and results/figures/theorem1.{pdf,png}.")
class Theorem1:
    alpha: list[float] = param([1.5, 2.0, 3.0], "Hertz exponents alpha of V0 to solve for (each > 1).", minItems=1,
                               maxItems=6, items=_ALPHAS)
    q: list[float | str] = param(["pi/5", "pi/2", "4pi/5", "pi"], "Wavenumbers q of the travelling waves, in (0, pi] "
                                 "(numbers or 'pi/5'-style strings); include pi for the (inteq) check.", minItems=1,
                                 maxItems=8, items=_ANGLES)
    a_min: float = param(1e-8, "Smallest amplitude a (first sine coefficient of u, ansatzu).", exclusiveMinimum=0,
                         minimum=1e-12, maximum=1.0)
    a_max: float = param(1.0, "Largest amplitude a; must exceed a_min.", exclusiveMinimum=0, maximum=100.0)
    n_amplitudes: int = param(31, "Number of amplitudes, log-spaced from a_min to a_max.", minimum=3, maximum=200)
    modes: int = param(128, "Number J of sine modes of u (sin(j xi), j = 1..J).", minimum=8, maximum=512)
    grid_log2: int = param(15, "log2 of the number M of grid points on which N(u) is sampled (aliasing error ~ "
                           "M^-(alpha+1)); M must exceed 8 J.", minimum=10, maximum=18)
    slope_eps_max: float = param(0.01, "The slope of the relative frequency correction is fitted where 1e-7 <= "
                                 "a^(alpha-1) <= slope_eps_max.", exclusiveMinimum=0, maximum=1.0)
    convergence_a: float = param(0.1, "Amplitude a of the convergence study in the number of modes.",
                                 exclusiveMinimum=0, maximum=100.0)
    convergence_modes: list[int] = param([16, 32, 64, 128], "Mode counts J of the convergence study (the reference "
                                         "is twice the largest).", minItems=2, maxItems=8,
                                         items={"description": "A number of sine modes.", "type": "integer",
                                                "minimum": 4, "maximum": 256})
    n_xi: int = param(129, "Number of samples of xi in [0, 2 pi] for the profiles v_a and K_h P_h N0(sin) (va).",
                      minimum=9, maximum=2001)
    scenes: list[str] = param([], "Travelling-wave scenes (names under scenes:, initial.kind travelling) whose "
                              "amplitude and time span give exact vs DpS frequency and the phase drift.", maxItems=10,
                              items=_NAMES)

    @staticmethod
    def check(b: dict, path: list, out) -> None:
        """q in (0, pi], a_max > a_min, and a grid fine enough for the modes (2^grid_log2 >= 8 x
        max(modes, 2 x max(convergence_modes)))."""
        for i, q in enumerate(b.get("q") if isinstance(b.get("q"), list) else []):
            x = angle_or_none(q)
            if x is not None and not 0.0 < x <= math.pi + 1e-12:
                out.add(path + ["q", i], "must be in (0, pi]", q)
        lo, hi = b.get("a_min"), b.get("a_max")
        if number(lo) and number(hi) and not hi > lo:
            out.add(path + ["a_max"], f"must exceed a_min = {show(lo)}", hi)
        g, m, cm = b.get("grid_log2"), b.get("modes"), b.get("convergence_modes")
        if isinstance(g, int) and isinstance(m, int) and isinstance(cm, list) and cm and \
                all(isinstance(x, int) for x in cm) and 2 ** g < 8 * max(m, 2 * max(cm)):
            out.add(path + ["grid_log2"], "2^grid_log2 must be >= 8 x max(modes, 2 x max(convergence_modes))", g)

    @staticmethod
    def resolve(cfg: dict, resolved_scene) -> dict:
        """``beyond.theorem1`` with angles in radians (their text in ``q_expr``) and ``scenes`` resolved:
        each named scene a travelling wave, its a given or (freq) inverted, its span its t_end."""
        from cradle.models import dps

        b = dict(cfg["beyond"]["theorem1"])
        b["q_expr"] = [angle_expr(q) for q in b["q"]]
        b["q"] = [parse_angle(q) for q in b["q"]]
        scenes = []
        for i, name in enumerate(b.get("scenes") or []):
            if name not in entries(cfg, "scenes"):
                raise ConfigError(f"config error: beyond.theorem1.scenes[{i}] = {name!r}: unknown scene: no "
                                  f"`scenes:` entry of that name{did_you_mean(name, entries(cfg, 'scenes'))}")
            r = resolved_scene(cfg, name)
            ini = r["initial"]
            if ini.get("kind") != "travelling":
                raise ConfigError(f"config error: beyond.theorem1.scenes[{i}] = {name!r}: not a travelling-wave "
                                  f"scene")
            q, al = float(ini["q"]), float(r["alpha"])
            a = ini.get("a")
            a = float(a) if a is not None else float(dps.amplitude_from_omega(float(ini["omega_tw"]), q, al))
            scenes.append({"name": name, "q": q, "alpha": al, "a": a, "t_end": float(r["t_end"])})
        b["scenes"] = scenes
        return b


@declared(doc="Linear stability of the DpS plane waves (ansatz3): growth-rate map over (q, p) -> "
              "results/mi/mi-diagram.nc and results/figures/mi-diagram.{pdf,png}.")
class MIDiagram:
    alpha: list[float] = param([1.5, 2.0, 3.0], "Exponents alpha of (dfnls) (each > 1).", minItems=1, maxItems=6,
                               items=_ALPHAS)
    n_q: int = param(181, "Number of plane-wave wavenumbers q in [0, pi].", minimum=3, maximum=2001)
    n_p: int = param(361, "Number of perturbation wavenumbers p in [-pi, pi].", minimum=3, maximum=4001)
    check_N: int = param(200, "Ring size N of the direct DpS runs that check the growth rates.", minimum=8,
                         maximum=2000)
    check_pairs: list[list[int]] = param([[70, 10], [100, 27], [80, 20]], "Direct checks [k_q, m_p]: q = 2 pi k_q / N, "
                                         "p = 2 pi m_p / N, 0 < k_q, m_p < N, an unstable pair for every alpha.",
                                         maxItems=10, items={"description": "One pair [k_q, m_p] of integers.",
                                                             "type": "array", "minItems": 2, "maxItems": 2,
                                                             "items": {"description": "k_q or m_p.", "type": "integer",
                                                                       "minimum": 1, "maximum": 1999}})

    @staticmethod
    def check(b: dict, path: list, out) -> None:
        """Each check pair on the ring (0 < k_q, m_p < check_N) and unstable, lambda > 0 (ansatz3), for
        every alpha (a direct run measures a growth rate)."""
        N, pairs, alphas = b.get("check_N"), b.get("check_pairs"), b.get("alpha")
        if not isinstance(N, int) or not isinstance(pairs, list):
            return
        for i, pair in enumerate(pairs):
            if not (isinstance(pair, list) and len(pair) == 2 and all(isinstance(x, int) for x in pair)):
                continue
            k, m = pair
            if not (0 < k < N and 0 < m < N):
                out.add(path + ["check_pairs", i], f"need 0 < k_q, m_p < check_N = {N}", pair)
                continue
            from cradle.analyses.mi_diagram import growth_rate

            for al in alphas if isinstance(alphas, list) else []:
                if number(al) and al > 1 and not growth_rate(2 * math.pi * k / N, 2 * math.pi * m / N, al) > 0:
                    out.add(path + ["check_pairs", i], f"stable for alpha = {al}; a check needs an unstable (q, p)",
                            pair)
                    break

    @staticmethod
    def resolve(cfg: dict) -> dict:
        """``beyond.mi_diagram`` as given (checked when the config was validated)."""
        return dict(cfg["beyond"]["mi_diagram"])


BEYOND_DOC = ("Analyses beyond the paper, one section each, keyed by the analysis's name (its module "
              "cradle.analyses.<name>, its targets <name> and <name>_full, its folder results/<name>/); see "
              "docs/analyses.md.")

#: TRANSITION ONLY: the sections of the analyses not yet declared by their own modules (cradle.analyses._legacy)
_LEGACY = {"theorem1": Theorem1, "mi_diagram": MIDiagram, "floquet": Floquet, "breathers": Breathers,
           "dps_validity": DpsValidity}


def _legacy_check(b: dict, cfg: dict, out) -> None:
    path = ["beyond"]
    sec = {k: (b.get(k) if isinstance(b.get(k), dict) else {}) for k in _LEGACY}
    Theorem1.check(sec["theorem1"], path + ["theorem1"], out)
    MIDiagram.check(sec["mi_diagram"], path + ["mi_diagram"], out)
    Floquet.check(sec["floquet"], path + ["floquet"], out)
    Breathers.check(sec["breathers"], path + ["breathers"], out)
    DpsValidity.check(sec["dps_validity"], path + ["dps_validity"], out)


def _beyond_class():
    """The declared class of the ``beyond:`` section, one key per analysis of the registry (its name),
    declared by the analysis's own spec class."""
    from cradle.analyses.registry import ANALYSES

    namespace: dict = {"__annotations__": {}}
    for key, cls in _LEGACY.items():
        namespace["__annotations__"][key] = cls
        namespace[key] = param(cls(), cls.__schema_doc__)
    for a in ANALYSES.values():
        namespace["__annotations__"][a.module] = a.spec
        namespace[a.module] = param(a.spec(), a.spec.__schema_doc__, key=a.name)

    def check(b, cfg: dict, out) -> None:
        """The checks of every analysis (each reads its schema-filled section)."""
        if not isinstance(b, dict):
            return
        _legacy_check(b, cfg, out)
        for a in ANALYSES.values():
            section = b.get(a.name)
            if hasattr(a.spec, "check") and isinstance(section, dict):
                a.spec.check(section, ["beyond", a.name], cfg, out)

    namespace["check"] = staticmethod(check)
    return declared(doc=BEYOND_DOC)(type("Beyond", (), namespace))


Beyond = _beyond_class()
