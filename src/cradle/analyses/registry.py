"""The analyses beyond the paper, found rather than listed: every module of :mod:`cradle.analyses` that
defines ``ANALYSIS`` (:class:`cradle.analyses.protocol.Analysis`).

Adding an analysis is adding its module (and its figure, ``cradle/figures/<module>.py``); the config
section ``beyond:``, its schema, the Snakemake rules and the figure table are generated from
:data:`ANALYSES`, in the order of the modules' names.
"""
from __future__ import annotations

import importlib
import pkgutil

import cradle.analyses as _package
from cradle.analyses.protocol import FULL, REDUCED, Analysis, form_spec

__all__ = ["ANALYSES", "FULL", "REDUCED", "Analysis", "form_spec", "discover"]


def discover() -> dict[str, Analysis]:
    """name -> analysis, for every module of this package that declares one."""
    found: dict[str, Analysis] = {}
    for info in sorted(pkgutil.iter_modules(_package.__path__), key=lambda m: m.name):
        if info.name in ("registry", "protocol") or info.name.startswith("_"):
            continue
        analysis = getattr(importlib.import_module(f"{_package.__name__}.{info.name}"), "ANALYSIS", None)
        if isinstance(analysis, Analysis):
            if analysis.module != info.name:
                raise ValueError(f"cradle.analyses.{info.name} declares the analysis {analysis.name!r}: its module "
                                 f"must be named {analysis.module}.py (one name per analysis)")
            found[analysis.name] = analysis
    return found


ANALYSES: dict[str, Analysis] = discover()
