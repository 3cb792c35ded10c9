"""Compact job parameters for workflow rules (no stored-time arrays in ``params:``).

A resolved scene (:func:`cradle.pipeline.config.resolved_scene`) carries ``times``, every stored
time expanded from ``store`` and ``t_end``; passed as a rule's ``params:``, Snakemake would print
it in every dry run and reason. :func:`compact_scene` drops it (a changed store or t_end still
changes the params, so the job still reruns); the job's script calls :func:`expand_scene` to get
the same times back. Light on purpose: the Snakefile imports it.

Only the analyses' rule uses it now, for the analyses that still read plain resolved scenes; the
simulate rule passes ``plain(cc.scene(config, name))`` (:func:`cradle.specs.declare.plain`), whose
stored times are a property of the typed :class:`cradle.scenes.spec.Scene`, not a field.
"""
from __future__ import annotations


def compact_scene(spec: dict) -> dict:
    """A resolved scene without its ``times`` (they follow from ``store`` and ``t_end``)."""
    return {k: v for k, v in spec.items() if k != "times"}


def expand_scene(spec: dict) -> dict:
    """The resolved scene of a :func:`compact_scene`: ``times`` from ``store`` and ``t_end``,
    exactly as :func:`cradle.pipeline.config.resolved_scene` computes them."""
    from cradle.specs.values import store_times

    return {**spec, "times": store_times(spec["store"], spec["t_end"])}
