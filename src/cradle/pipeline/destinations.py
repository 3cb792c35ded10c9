"""May a command write there? The one rule every writing command (``cradle run``, ``extend``, ``animate``) asks.

A destination is refused, before anything is computed or written, when it is

* an output of the workflow (a path of :mod:`cradle.pipeline.layout` under a folder named ``results``) that is
  not the one the command itself makes: another scene's runs, a figure, an analysis, another scene's movie;
* or an existing file the command cannot tell it made: a netCDF file that holds something else than what the
  command writes (its ``cradle_kind`` and ``cradle_name``), any other file without the command's own record.

``--overwrite`` (``overwrite=True``) writes anyway. The refusal is one line naming the file, what it is and the
flag: :class:`Refused`.
"""
from __future__ import annotations

import re
from pathlib import Path

from cradle.pipeline import layout

__all__ = ["Refused", "workflow_output", "holds", "check"]

class Refused(ValueError):
    """A destination the command may not write without ``--overwrite``; one line."""


def _template_regex(template: str) -> re.Pattern:
    pattern = re.escape(template).replace(r"\{", "{").replace(r"\}", "}")
    return re.compile(re.sub(r"{(\w+)}", r"(?P<\1>[^/]+)", pattern))


#: the layout's files that are not netCDF (figures, movies, logs, ...); its netCDF files are found by
#: :func:`cradle.pipeline.identity.locate`, which knows the analyses' folders too
_OTHER = [(kind, _template_regex(t)) for kind, t in layout.TEMPLATES.items() if not t.endswith(".nc")]


def workflow_output(path: str | Path) -> tuple[str, dict] | None:
    """The kind and names (``("exact", {"scene": "tw-moderate"})``) of the workflow output ``path`` is: a path of
    the layout under the nearest enclosing folder named ``results``; None for any other path (a file of its own
    there, such as an extended run ``exact-t700.nc``, is not the workflow's)."""
    from cradle.pipeline.identity import locate

    full = Path(path).resolve()
    root = next((p for p in full.parents if p.name == layout.ROOT), None)
    if root is None:
        return None
    found = locate(full, root)
    if found is not None:
        return found
    rel = full.relative_to(root).as_posix()
    for kind, regex in _OTHER:
        m = regex.fullmatch(rel)
        if m is not None:
            return kind, m.groupdict()
    return None


def _what(kind: str, names: dict) -> str:
    """How a message calls a workflow output."""
    from cradle.pipeline.identity import NOUN, Identity

    name = names.get("scene") or names.get("name") or names.get("label") or names.get("analysis")
    if kind in NOUN:  # the netCDF files: "the exact run of scene 'tw-moderate'", "analysis 'floquet'"
        return f"{Identity(kind, name, None).describe(True)} in the workflow's results"
    return f"the workflow's {kind} '{name}'" if name else f"the workflow's {kind}"


def holds(path: Path) -> tuple[str | None, str | None]:
    """(cradle_kind, cradle_name) of a netCDF file, or (None, None) when it is not one cradle can read."""
    try:
        import netCDF4

        with netCDF4.Dataset(path) as nc:
            attrs = {k: nc.getncattr(k) for k in nc.ncattrs()}
    except (OSError, RuntimeError, ValueError):
        return None, None
    kind, name = attrs.get("cradle_kind"), attrs.get("cradle_name")
    return (None if kind is None else str(kind)), (None if name is None else str(name))


def _creatable(path: Path) -> None:
    """Raise :class:`Refused` unless ``path``'s folder exists or can be made: its nearest existing ancestor is a
    folder this process may write in (said before any work, not by the write at the end)."""
    import os

    if path.is_dir():
        raise Refused(f"cannot write {path}: it is a folder")
    ancestor = path.parent
    while not ancestor.exists() and ancestor != ancestor.parent:
        ancestor = ancestor.parent
    if not ancestor.is_dir():
        raise Refused(f"cannot write {path}: {ancestor} is a file, not a folder")
    if not os.access(ancestor, os.W_OK | os.X_OK):
        raise Refused(f"cannot write {path}: no permission to write in {ancestor}")


def check(path: str | Path, *, command: str, makes: tuple[str, dict] | None = None,
          identity: tuple[str, str] | None = None, owner: str | None = None, overwrite: bool = False) -> None:
    """Raise :class:`Refused` unless ``command`` may write ``path``.

    ``makes``: the workflow output the command makes there by itself ((kind, names) as :func:`workflow_output`
    gives it: ``cradle run tw-weak --out results`` makes tw-weak's files), allowed; ``identity``: the
    (cradle_kind, cradle_name) of the netCDF file it writes, which an existing netCDF file must hold; ``owner``:
    what the record of an existing non-netCDF file must name (:func:`cradle.data.digests.record_owner`)."""
    path = Path(path)
    _creatable(path)
    if overwrite:
        return
    where = workflow_output(path)
    if where is not None and where == makes:  # the command's own product (cradle run SCENE --out results)
        return
    if where is not None:
        raise Refused(f"refusing to write {path}: it is {_what(*where)} (its rule writes it; snakemake --force "
                      f"{path} rebuilds it); give --overwrite to replace it anyway")
    if not path.exists():
        return
    if identity is not None:
        have = holds(path)
        if have != identity:
            held = (f"{have[0]} '{have[1]}'" if have[0] else "not a cradle netCDF file")
            raise Refused(f"refusing to write {path}: it exists and holds {held}, not {identity[0]} "
                          f"'{identity[1]}' that {command} writes; give --overwrite to replace it")
        return
    from cradle.data.digests import read_owner

    if owner is None or read_owner(path) != owner:
        raise Refused(f"refusing to write {path}: it exists and {command} did not make it; give --overwrite to "
                      f"replace it")
