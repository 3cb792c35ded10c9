"""The ``beyond:`` section of config.yaml, generated from the registry of analyses: one key per analysis
(its name), declared by the spec class of its own module (:mod:`cradle.analyses.protocol`), checked by that
class's ``check`` method on the typed section (:mod:`.checks`)."""
from __future__ import annotations

from cradle.specs.declare import declared, param, schema_doc

BEYOND_DOC = ("Analyses beyond the paper, one section each, keyed by the analysis's name (its module "
              "cradle.analyses.<name>, its targets <name> and <name>_full, its folder results/<name>/); see "
              "docs/analyses.md.")


def _specs() -> dict[str, type]:
    """The key of each analysis under ``beyond:`` -> its declared spec class (the registry's, by name)."""
    from cradle.analyses.registry import ANALYSES

    return {a.name: a.spec for a in ANALYSES.values()}


#: the sections of ``beyond:``, each checked by its spec class's ``check`` (:mod:`.checks`)
SPECS = _specs()


def _beyond_class():
    """The declared class of the ``beyond:`` section, one key per analysis of the registry (its name),
    declared by the analysis's own spec class."""
    from cradle.analyses.registry import ANALYSES

    namespace: dict = {"__annotations__": {}}
    for a in ANALYSES.values():
        namespace["__annotations__"][a.module] = a.spec
        namespace[a.module] = param(a.spec(), schema_doc(a.spec), key=a.name)
    return declared(doc=BEYOND_DOC)(type("Beyond", (), namespace))


Beyond = _beyond_class()
