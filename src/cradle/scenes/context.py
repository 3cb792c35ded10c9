"""What the check of one config entry sees of the others: :class:`Context`.

The schema of config.yaml checks each key alone. What it cannot express (a wave that fits the ring, a
breather built from an existing homoclinic entry with the same N and bc, a figure's times stored by
its scenes, an analysis's grids fine enough for its modes, ...) is the ``check`` method of the
entry's declared class, :class:`Checked`. :func:`cradle.pipeline.config.validate.validate` builds every
entry the schema passed as its typed object and runs ``check(where, context, out)``: ``where`` the
entry's key path, ``out`` the :class:`~cradle.specs.values.Errors` the one-line messages go to,
``context`` the entries it may refer to. An entry with a schema error is not checked further (its
errors are said), so a check reads attributes of the types they are declared with.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Protocol

from cradle.specs.values import Errors

from .spec import HomoclinicEntry, Scene

#: a key path: ``["scenes", "tw-weak", "store", "snapshots", 1]``
Where = list[str | int]

#: the name-keyed sections whose entries a figure reads, in the order their names are claimed
ENTRY_SECTIONS = ("map", "homoclinic", "scenes")


@dataclass(frozen=True)
class Context:
    """The entries one entry's check may refer to.

    ``given``: for each of :data:`ENTRY_SECTIONS`, every entry name the config gives (those with
    schema errors too: a name that exists is not unknown); ``scenes``: the scenes the schema passed,
    resolved against ``defaults:``; ``homoclinic``: the homoclinic entries the schema passed, ``alpha``
    filled from ``defaults:``.
    """

    given: Mapping[str, tuple[str, ...]]
    scenes: Mapping[str, Scene]
    homoclinic: Mapping[str, HomoclinicEntry]

    @property
    def names(self) -> dict[str, str]:
        """Every map, homoclinic and scene name -> its section (the first that uses it)."""
        out: dict[str, str] = {}
        for section in ENTRY_SECTIONS:
            for name in self.given.get(section, ()):
                out.setdefault(name, section)
        return out


class Checked(Protocol):
    """A declared class with the checks its schema cannot express."""

    def check(self, where: Where, context: Context, out: Errors) -> None:
        """Report each problem of this entry, at ``where`` (its key path) or below, to ``out``."""
