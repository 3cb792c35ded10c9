"""Declarations of the analyses beyond the paper (``beyond:``), their checks and their resolved specs.

Each analysis is a frozen dataclass (threshold statistics over noise seeds, Bloch-Floquet stability,
the DpS approximation error against eps and T, ...); the analyses on the protocol declare theirs in
their own modules.
The ``check`` method of each spec reports, one line per problem, what the schema cannot express
(:mod:`.checks` runs it on the typed section); ``resolve`` turns the section of a validated config
into the plain dict the analysis module computes from (angles in radians, inherited settings merged),
so that the numerical modules never read or check the config.
"""
from __future__ import annotations

from cradle.specs.declare import declared, param

from .breather_interactions import BreatherInteractions
from .mi_statistics import MIStatistics

BEYOND_DOC = ("Analyses beyond the paper, one section each, keyed by the analysis's name (its module "
              "cradle.analyses.<name>, its targets <name> and <name>_full, its folder results/<name>/); see "
              "docs/analyses.md.")

#: TRANSITION ONLY: the sections of the analyses not yet declared by their own modules (cradle.analyses._legacy)
_LEGACY = {"mi_statistics": MIStatistics, "breather_interactions": BreatherInteractions}


def _specs() -> dict[str, type]:
    """The key of each analysis under ``beyond:`` -> its declared spec class (the registry's, by name)."""
    from cradle.analyses.registry import ANALYSES

    return {**_LEGACY, **{a.name: a.spec for a in ANALYSES.values()}}


#: the sections of ``beyond:``, each checked by its spec class's ``check`` (:mod:`.checks`)
SPECS = _specs()


def _beyond_class():
    """The declared class of the ``beyond:`` section, one key per analysis of the registry (its name),
    declared by the analysis's own spec class."""
    from cradle.analyses.registry import ANALYSES

    namespace: dict = {"__annotations__": {}}
    for key, cls in _LEGACY.items():
        namespace["__annotations__"][key] = cls
        namespace[key] = param(cls())
    for a in ANALYSES.values():
        namespace["__annotations__"][a.module] = a.spec
        namespace[a.module] = param(a.spec(), key=a.name)
    return declared(doc=BEYOND_DOC)(type("Beyond", (), namespace))


Beyond = _beyond_class()
