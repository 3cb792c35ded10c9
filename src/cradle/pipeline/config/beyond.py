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
from .breather_interactions import BreatherInteractions
from .dps_validity import DpsValidity
from .floquet import Floquet
from .mi_statistics import VARIANTS, MIStatistics, MIVariant
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


@declared(doc="Growth rates of the modulational instability measured in the scenes' own runs (exact lattice and DpS, "
              "rerun from results/initial/<scene>.nc with the scene's integrators, sampled every sample_every), "
              "fitted on the sideband pairs of the |A_hat| spectrum and compared with the linear DpS rate "
              "(cradle.analyses.mi_diagram.growth_rate) -> results/mi/mi-growth.nc and "
              "results/figures/mi-growth.{pdf,png}.")
class MIGrowth:
    scenes: list[str] = param([], "Scenes (names under scenes:, travelling waves on a periodic ring) whose runs are "
                              "measured; the target mi_growth needs at least one.", minItems=0, maxItems=12,
                              items=_NAMES)
    sample_every: float = param(0.5, "Sampling interval in t of the spectra (the scenes store only snapshots, so "
                                "their runs are repeated on this grid).", exclusiveMinimum=0, maximum=10.0)
    saturation: float = param(0.2, "The fit window ends when the largest sideband pair first reaches this fraction "
                              "of the carrier (end of the linear phase).", exclusiveMinimum=0, maximum=1.0)
    decades: float = param(1.0, "The fit window covers the last `decades` decades of growth of the dominant pair "
                           "before the window end (fewer if the run grew less: then no exponential phase is "
                           "claimed).", exclusiveMinimum=0, maximum=4.0)
    r2_min: float = param(0.95, "Smallest coefficient of determination of the log-linear fit for the growth to be "
                          "called exponential.", exclusiveMinimum=0, maximum=1.0)

    @staticmethod
    def check(b: dict, path: list, cfg: dict, out) -> None:
        """Every named scene that exists is a travelling wave on a periodic ring. Names of missing scenes
        are reported by :meth:`resolve`, when the target is built, so that a config with fewer scenes
        (a test's) still validates."""
        scenes = entries(cfg, "scenes")
        for i, name in enumerate(b.get("scenes") if isinstance(b.get("scenes"), list) else []):
            sc = scenes.get(name) if isinstance(name, str) else None
            if sc is None:
                continue
            ini = sc.get("initial") if isinstance(sc.get("initial"), dict) else {}
            if ini.get("kind") != "travelling" or sc.get("bc") != "periodic":
                out.add(path + ["scenes", i], "must be a travelling-wave scene on a periodic ring (initial.kind "
                                              "travelling, bc periodic)", name)

    @staticmethod
    def resolve(cfg: dict) -> dict:
        """``beyond.mi_growth``; it must name at least one scene, and only existing ones."""
        spec = dict(cfg["beyond"]["mi_growth"])
        scenes = entries(cfg, "scenes")
        if not spec["scenes"]:
            raise ConfigError("config error: beyond.mi_growth.scenes is empty: name at least one scene to measure")
        for i, name in enumerate(spec["scenes"]):
            if name not in scenes:
                raise ConfigError(f"config error: beyond.mi_growth.scenes[{i}] = {name!r}: unknown scene: no "
                                  f"`scenes:` entry of that name{did_you_mean(name, scenes)}")
        return spec


@declared(doc="Analyses beyond the paper: Theorem 1 measured on exact travelling waves of (ad) "
              "(cradle.analyses.theorem1, target theorem1) and the modulational-instability map of the DpS plane "
              "waves (cradle.analyses.mi_diagram, target mi_diagram). Also the modulational-instability growth "
              "rates measured in the scenes' runs (cradle.analyses.mi_growth, target mi_growth), the threshold "
              "statistics over noise seeds (cradle.analyses.mi_statistics, targets mi_statistics and "
              "mi_statistics_full) and the Bloch-Floquet stability of the exact waves (cradle.analyses.floquet, "
              "target floquet), the exact breathers (cradle.analyses.breathers, targets breathers and "
              "breathers_full), the collisions of two breathers in both models "
              "(cradle.analyses.breather_interactions, targets breather_interactions and breather_interactions_full), "
              "and the DpS approximation error against eps and T (cradle.analyses.dps_validity, "
              "targets dps_validity and dps_validity_full).")
class Beyond:
    theorem1: Theorem1 = param(Theorem1(), Theorem1.__schema_doc__)
    mi_diagram: MIDiagram = param(MIDiagram(), MIDiagram.__schema_doc__)
    mi_growth: MIGrowth = param(MIGrowth(), MIGrowth.__schema_doc__)
    mi_statistics: MIStatistics = param(MIStatistics(), MIStatistics.__schema_doc__)
    floquet: Floquet = param(Floquet(), Floquet.__schema_doc__)
    breathers: Breathers = param(Breathers(), Breathers.__schema_doc__)
    breather_interactions: BreatherInteractions = param(BreatherInteractions(),
                                                        BreatherInteractions.__schema_doc__)
    dps_validity: DpsValidity = param(DpsValidity(), DpsValidity.__schema_doc__)

    @staticmethod
    def check(b, cfg: dict, out) -> None:
        """The checks of every analysis (each reads its schema-filled section)."""
        if not isinstance(b, dict):
            return
        path = ["beyond"]
        sec = {k: (b.get(k) if isinstance(b.get(k), dict) else {}) for k in
               ("theorem1", "mi_diagram", "mi_growth", "mi_statistics", "floquet", "breathers",
                "breather_interactions", "dps_validity")}
        Theorem1.check(sec["theorem1"], path + ["theorem1"], out)
        MIDiagram.check(sec["mi_diagram"], path + ["mi_diagram"], out)
        MIGrowth.check(sec["mi_growth"], path + ["mi_growth"], cfg, out)
        for variant in VARIANTS:
            v = sec["mi_statistics"].get(variant)
            if isinstance(v, dict):
                MIVariant.check(v, path + ["mi_statistics", variant], out)
        Floquet.check(sec["floquet"], path + ["floquet"], out)
        Breathers.check(sec["breathers"], path + ["breathers"], out)
        BreatherInteractions.check(sec["breather_interactions"], path + ["breather_interactions"], out)
        DpsValidity.check(sec["dps_validity"], path + ["dps_validity"], out)
