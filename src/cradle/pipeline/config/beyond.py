"""Declarations of the analyses beyond the paper (``beyond:``), their checks and their resolved specs.

Each analysis is a frozen dataclass (threshold statistics over noise seeds, Bloch-Floquet stability,
the DpS approximation error against eps and T, ...); the analyses on the protocol declare theirs in
their own modules.
``check`` reports, one line per problem, what the schema cannot express;
``resolve`` turns the section of a validated config into the plain dict the
analysis module computes from (angles in radians, inherited settings merged),
so that the numerical modules never read or check the config.
"""
from __future__ import annotations

from cradle.specs.declare import declared, param

from .breather_interactions import BreatherInteractions
from .mi_statistics import VARIANTS, MIStatistics, MIVariant

BEYOND_DOC = ("Analyses beyond the paper, one section each, keyed by the analysis's name (its module "
              "cradle.analyses.<name>, its targets <name> and <name>_full, its folder results/<name>/); see "
              "docs/analyses.md.")

#: TRANSITION ONLY: the sections of the analyses not yet declared by their own modules (cradle.analyses._legacy)
_LEGACY = {"mi_statistics": MIStatistics, "breather_interactions": BreatherInteractions}


def _legacy_check(b: dict, cfg: dict, out) -> None:
    path = ["beyond"]
    sec = {k: (b.get(k) if isinstance(b.get(k), dict) else {}) for k in _LEGACY}
    for variant in VARIANTS:
        v = sec["mi_statistics"].get(variant)
        if isinstance(v, dict):
            MIVariant.check(v, path + ["mi_statistics", variant], out)
    BreatherInteractions.check(sec["breather_interactions"], path + ["breather_interactions"], out)


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
