"""The typed spec of one entry or analysis of a config: what a job computes from, and what its files record.

A scene, homoclinic or map entry is a frozen instance of :mod:`cradle.scenes.spec` (:func:`scene`,
:func:`homoclinic`, :func:`map_entry`: resolved against ``defaults:``); an analysis's spec is that of one of
its forms (:func:`analysis_spec`). Each reads the typed config (:func:`.validate.typed`, remembered: a job's
repeated calls cost one validation).
"""
from __future__ import annotations

from typing import Any

from cradle.analyses.protocol import Read
from cradle.scenes.spec import HomoclinicEntry, MapEntry, Scene
from cradle.specs.values import ConfigError

from .checks import with_all
from .validate import entry, typed


def scene(config: dict[str, Any], name: str) -> Scene:
    """Scene ``name`` of ``config``, validated and resolved: ``alpha`` and ``max_energy_drift`` from
    ``defaults:`` unless it gives them, its ``exact`` and ``dps`` keys over those of ``defaults:``, SI values in
    (nc)'s units."""
    return entry(config, "scenes", name)


def homoclinic(config: dict[str, Any], name: str) -> HomoclinicEntry:
    """Homoclinic entry ``name`` of ``config``, validated, its ``alpha`` filled from ``defaults:``."""
    return entry(config, "homoclinic", name)


def map_entry(config: dict[str, Any], name: str) -> MapEntry:
    """Map entry ``name`` of ``config``, validated, its ``alpha`` filled from ``defaults:``."""
    return entry(config, "map", name)


def analysis_spec(config: dict[str, Any], name: str, form: str) -> Any:
    """The typed spec of analysis ``name`` (:mod:`cradle.analyses.registry`) in one form; a key named after a
    section of entries (scenes, homoclinic, map) given as ``all`` becomes the names of every entry of that
    section, in name order (moving a block of config.yaml changes nothing the analysis reads)."""
    from cradle.analyses.registry import ANALYSES, form_spec

    a = ANALYSES[name]
    if form not in a.forms:
        raise ConfigError(f"config error: beyond.{a.name}: unknown form {form!r} (forms: {', '.join(a.forms)})")
    cfg = typed(config)
    names = {section: sorted(getattr(cfg, section)) for section in ("scenes", "homoclinic", "map")}
    return form_spec(with_all(getattr(cfg.beyond, a.module), names), form)


def analysis_reads(config: dict[str, Any], name: str, form: str) -> dict[str, Read]:
    """What analysis ``name`` reads in one form (:meth:`cradle.analyses.protocol.Analysis.reads_of`): name ->
    :class:`~cradle.analyses.protocol.Read` (every scene it names a ``scenes:`` entry: the validation said so)."""
    from cradle.analyses.registry import ANALYSES

    return ANALYSES[name].reads_of(analysis_spec(config, name, form))
