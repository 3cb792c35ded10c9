"""What an analysis declares about itself: the one protocol every analysis beyond the paper follows.

An analysis is one module of :mod:`cradle.analyses` that defines ``ANALYSIS = Analysis(...)``:

* ``name``: its one stem (``mi-growth``): config key ``beyond: mi-growth:``, module
  ``cradle/analyses/mi_growth.py``, Snakemake target ``mi_growth``, results folder ``results/mi-growth/``,
  figure ``results/figures/mi-growth.{pdf,png}`` drawn by ``draw`` of ``cradle/figures/mi_growth.py``;
* ``spec``: its declared spec class (:func:`cradle.specs.declare.declared`), the full form; a field
  declared with ``param(..., reduced=...)`` makes the cheaper form ``all`` builds (:func:`form_spec`), whose
  overrides the config may also give under ``reduced:``; what the schema cannot express is its method
  ``check(where, context, out)`` (:mod:`cradle.pipeline.config.checks`), run on the typed section when
  the config is validated (a reduced form reports its own keys, :func:`own_keys`);
* ``reads(spec)``: the files it reads, by name (:class:`Read`: a layout kind and its names), opened and
  verified by the pipeline and handed to ``compute`` under those names;
* ``batches``: optionally, the jobs its work is split into (:class:`Batches`), each written apart and
  handed to ``compute`` as ``batch/<key>``;
* ``compute(spec, inputs, log)``: the output, a DataTree (or Dataset) of netCDF groups named as in the
  paper from its ``variables``;
* ``tables``: the text formats (``("csv", "md")``) its drawing step writes instead of a figure: then
  ``cradle/figures/<module>.py`` defines ``tables(tree) -> {format: text}`` rather than ``draw(tree)``,
  and the files go beside its netCDF file (``results/<name>/<name>.<format>``; the claims table).
* ``claims``: the group of its output (``"/claims"``) that holds rows for the claims table (the cited papers'
  statements against its results, :func:`cradle.analyses.claims_table.group`); the table (``paper-checks``)
  reads the output of the form ``all`` builds of every analysis that declares one (:class:`Read` of kind
  ``analysis``) and collects them.

A spec field ``scenes``, ``homoclinic`` or ``map`` whose declaration allows the text ``"all"`` is filled by
the pipeline with the names of every entry of that config section, in name order
(:func:`cradle.pipeline.config.analysis_spec`).

The registry (:mod:`cradle.analyses.registry`) finds the modules; the config section, its schema, the rules
and the figure table follow from it. Nothing here knows paths or Snakemake.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

from cradle.specs.parse import reduced_defaults

#: the cheaper form ``all`` builds, and the complete one (its own target ``<name>_full``)
REDUCED, FULL = "reduced", "full"

#: where an analysis reports its progress, a line a call (the job's ``log.info``)
Log = Callable[[str], object]


@dataclass(frozen=True)
class Read:
    """One file an analysis reads: a kind of the results layout (``initial``, ``exact``, ``dps``,
    ``metrics``, ``homoclinic``, ...) and the names that fill its template (``scene="tw-weak"``); kind
    ``analysis`` (``analysis="travelling-breathers"``) is another analysis's output, the form ``all`` builds,
    handed over as a tree of its groups."""

    kind: str
    names: tuple[tuple[str, str], ...] = ()

    @classmethod
    def of(cls, kind: str, **names: str) -> Read:
        return cls(kind, tuple(sorted(names.items())))


def scene_reads(scenes: Iterable[str], parts: Iterable[str] = ("initial", "exact", "dps")) -> dict[str, Read]:
    """The files of the named scenes, as ``<scene>/<part>``."""
    return {f"{name}/{part}": Read.of(part, scene=name) for name in scenes for part in parts}


@dataclass(frozen=True)
class Batches:
    """The jobs an analysis splits a form into: ``keys(spec)`` names them (strings that are file names),
    ``run(spec, key, inputs, log)`` computes one (a Dataset) from the files ``reads(spec, key)`` names;
    ``threads``: ``"all"`` when a batch must have the machine to itself (timings), else 1."""

    keys: Callable[[Any], list[str]]
    run: Callable[..., Any]
    reads: Callable[[Any, str], Mapping[str, Read]] = lambda spec, key: {}
    threads: Mapping[str, str | int] = field(default_factory=dict)  # form -> "all" or a count (default 1)


@dataclass(frozen=True)
class Analysis:
    """One analysis beyond the paper (see the module docstring)."""

    name: str
    title: str
    spec: type
    compute: Callable[..., Any]
    variables: Mapping[str, Any]
    reads: Callable[[Any], Mapping[str, Read]] = lambda spec: {}
    batches: Batches | None = None
    tables: tuple[str, ...] = ()  # text formats written by figures/<module>.py tables(tree), in place of a figure
    claims: str = ""  # the group of its output holding rows of the claims table (claims_table.group); "" for none

    @property
    def module(self) -> str:
        """The module stem (``mi_growth``): of the analysis and of its figure."""
        return self.name.replace("-", "_")

    @property
    def target(self) -> str:
        """The Snakemake target (``mi_growth``)."""
        return self.module

    @property
    def forms(self) -> tuple[str, ...]:
        """The forms it is built in, the one ``all`` builds first."""
        names = {f.name for f in dataclasses.fields(self.spec)}
        return (REDUCED, FULL) if "reduced" in names else (FULL,)

    def reads_of(self, spec: Any) -> dict[str, Read]:  # a spec of the class ``self.spec``
        """Everything ``compute`` is handed: the files ``reads`` names and every batch."""
        out = dict(self.reads(spec))
        if self.batches is not None:
            out.update({f"batch/{key}": Read.of("analysis-batch", analysis=self.name, key=key)
                        for key in self.batches.keys(spec)})
        return out


def form_spec(spec: Any, form: str) -> Any:  # a spec of any analysis (a dataclass), and one of its class
    """The spec of one form: the full one, or the reduced one (the declared reduced values, then the keys
    given under ``reduced:``, in place of the full ones); neither has overrides left."""
    if getattr(spec, "reduced", None) is None:   # no reduced form, or a form already
        return spec
    overrides = {**reduced_defaults(type(spec)), **spec.reduced} if form == REDUCED else {}
    return dataclasses.replace(spec, **overrides, reduced=None)


def own_keys(spec: Any) -> list[str]:
    """The fields whose values the reduced form of ``spec`` gives in place of the full ones (declared or given
    under ``reduced:``; none for a spec without a reduced form): its check reports only those."""
    if not isinstance(getattr(spec, "reduced", None), dict):
        return []
    return list(dict.fromkeys([*reduced_defaults(type(spec)), *(spec.reduced or {})]))
