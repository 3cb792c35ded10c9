"""The ``beyond:`` section of config.yaml, generated from the registry of analyses: one key per analysis
(its name), declared by the spec class of its own module (:mod:`cradle.analyses.protocol`), checked by that
class's ``check``."""
from __future__ import annotations

from cradle.specs.declare import declared, param

BEYOND_DOC = ("Analyses beyond the paper, one section each, keyed by the analysis's name (its module "
              "cradle.analyses.<name>, its targets <name> and <name>_full, its folder results/<name>/); see "
              "docs/analyses.md.")


def _beyond_class():
    """The declared class of the ``beyond:`` section, one key per analysis of the registry (its name),
    declared by the analysis's own spec class."""
    from cradle.analyses.registry import ANALYSES

    namespace: dict = {"__annotations__": {}}
    for a in ANALYSES.values():
        namespace["__annotations__"][a.module] = a.spec
        namespace[a.module] = param(a.spec(), a.spec.__schema_doc__, key=a.name)

    def check(b, cfg: dict, out) -> None:
        """The checks of every analysis (each reads its schema-filled section)."""
        if not isinstance(b, dict):
            return
        for a in ANALYSES.values():
            section = b.get(a.name)
            if hasattr(a.spec, "check") and isinstance(section, dict):
                a.spec.check(section, ["beyond", a.name], cfg, out)

    namespace["check"] = staticmethod(check)
    return declared(doc=BEYOND_DOC)(type("Beyond", (), namespace))


Beyond = _beyond_class()
