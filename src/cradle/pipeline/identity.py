"""Is a results file the one its reader asked for? Its kind, name and parameter hash against the config now.

Every file of the results layout (:mod:`cradle.pipeline.layout`) says what it is: its kind and name
(``cradle_kind``, ``cradle_name``, :func:`cradle.data.provenance.identity`; files written before those
attributes existed state their scene as ``scene`` or their entry as ``name``) and the hash of the plain
parameters its job was given (``params_sha256``, :func:`cradle.data.provenance.params_hash`). The config
says what it should be: :meth:`Expectations.expected` inverts the file's path into its kind and name and resolves
that entry's typed spec from the config now (:func:`cradle.pipeline.config.scene`, ``homoclinic``,
``map_entry``, ``analysis_spec``). :meth:`Expectations.check` compares the two and raises :class:`WrongOutput`,
one line naming the file, what it holds, what was expected and the command that rebuilds it::

    results/sim/tw-weak/exact.nc holds scene 'tw-moderate' (params 5e0d1c2a9b71), expected scene 'tw-weak'
    (params 9a41f0c3d2e8 from config.yaml); rebuild it: snakemake --force results/sim/tw-weak/exact.nc

A copied file, a scene renamed, or a config changed (and changed back) without a rebuild all show. Only
attributes are read: the check costs no data read. A file outside the layout under ``root`` (``cradle-runs/``,
``failed/``, an extended run ``exact-t700.nc``), or naming an entry the config does not have, has no
expectation and is not checked.
"""
from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from cradle.data.io import DamagedOutput, open_dataset, open_tree, rebuild_hint
from cradle.data.provenance import canonical_json, params_hash
from cradle.pipeline import layout
from cradle.specs.declare import plain

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["CONFIG", "Identity", "WrongOutput", "Expectations", "locate", "stored_identity", "job_expectations",
           "open_checked"]

#: how messages name the config of a Snakemake job (config.yaml, with any --configfile and --config)
CONFIG = "the workflow's config"

#: the kinds of a scene's files (named by their scene), and of a config entry's (named by the entry)
SCENE_KINDS = layout.SCENE_PARTS
ENTRY_KINDS = ("homoclinic", "map")
#: how a message calls what a file of each kind belongs to
NOUN = {**dict.fromkeys(SCENE_KINDS, "scene"), "homoclinic": "homoclinic entry", "map": "map entry",
        "analysis": "analysis", "analysis-batch": "batch"}
#: how a message says which file of a scene it is, when the kinds differ
PART = {"initial": "the initial data", "exact": "the exact run", "dps": "the DpS run", "metrics": "the metrics"}


class WrongOutput(DamagedOutput):
    """A readable file that is not the one asked for (another scene's, or made from other parameters than
    the config resolves to now): one line naming it, what it holds, what was expected and its rebuild."""


@dataclass(frozen=True)
class Identity:
    """What a file is: its kind in the layout, its name, and the sha256 of its parameters (None where a
    file does not record it)."""

    kind: str | None
    name: str | None
    params: str | None

    def describe(self, show_kind: bool) -> str:
        """``scene 'tw-weak'``; with ``show_kind``, which of the scene's files: ``the DpS run of scene
        'tw-weak'`` (the other kinds' nouns say their kind: ``homoclinic entry 'bond'``, ``batch ...``)."""
        noun = NOUN.get(self.kind or "", self.kind or "file")
        what = f"{noun} '{self.name}'" if self.name else f"{noun} (name not recorded)"
        return f"{PART[self.kind]} of {what}" if show_kind and self.kind in PART else what


def _templates() -> list[tuple[str, re.Pattern]]:
    """(kind, regex with a named group per name) of every netCDF template of the layout."""
    out = []
    for kind, template in layout.TEMPLATES.items():
        if template.endswith(".nc"):
            pattern = re.escape(template).replace(r"\{", "{").replace(r"\}", "}")
            out.append((kind, re.compile(re.sub(r"{(\w+)}", r"(?P<\1>[^/]+)", pattern))))
    return out


_TEMPLATES = _templates()


def locate(path: str | Path, root: str | Path = layout.ROOT) -> tuple[str, dict] | None:
    """The kind and names (``("exact", {"scene": "tw-weak"})``, ``("analysis", {"analysis": "floquet",
    "form": "full"})``) of the file of the layout under ``root`` that ``path`` is; None if it is none."""
    try:
        rel = Path(path).resolve().relative_to(Path(root).resolve()).as_posix()
    except (ValueError, OSError):
        return None
    for kind, regex in _TEMPLATES:
        m = regex.fullmatch(rel)
        if m is not None and kind != "analysis-batch":
            return kind, m.groupdict()
    from cradle.analyses.registry import ANALYSES  # imported only for a file that is not a scene's or entry's

    m = dict(_TEMPLATES)["analysis-batch"].fullmatch(rel)
    if m is not None:
        names = m.groupdict()
        a = ANALYSES.get(names["analysis"])
        ok = a is not None and a.batches is not None and names["form"] in a.forms
        return ("analysis-batch", names) if ok else None
    for a in ANALYSES.values():
        for form in a.forms:
            if rel == layout.analysis_output(a.name, form, a.forms[0], root="."):
                return "analysis", {"analysis": a.name, "form": form}
    return None


class Expectations:
    """What the files under ``root`` should be by ``config`` (a config mapping, as Snakemake or
    :func:`cradle.pipeline.config.read_yaml` gives it; validated once, on first use), each entry resolved
    once (a scene's four files, one resolution); ``source`` names the config in messages (``config.yaml``)."""

    def __init__(self, config: dict, root: str | Path = layout.ROOT, source: str = "config.yaml") -> None:
        self.config, self.root, self.source = config, Path(root), source
        self._specs: dict[tuple[str, str, str], tuple[Any, str | None]] = {}  # (section, name, form) -> spec, hash

    def expected(self, path: str | Path) -> Identity | None:
        """The identity the file at ``path`` should have, or None when the config expects nothing there."""
        return self._expected(path)[0]

    def _expected(self, path: str | Path) -> tuple[Identity | None, tuple[str, str, str]]:
        """:meth:`expected`, and the key of the entry whose spec it resolved (see :meth:`_digest`)."""
        where = locate(path, self.root)
        if where is None:
            return None, ("", "", "")
        kind, names = where
        if kind in SCENE_KINDS:
            entry = ("scenes", names["scene"], "")
        elif kind in ENTRY_KINDS:
            entry = (kind, names["name"], "")
        else:
            entry = ("beyond", names["analysis"], names["form"])
        name, digest = entry[1], self._digest(entry)
        if kind == "analysis-batch":
            keys = self._batch_keys(entry) if digest else []
            name, digest = f"{name}/{names['key']}", digest if names["key"] in keys else None
        return (None if digest is None else Identity(kind, name, digest)), entry

    def _digest(self, entry: tuple[str, str, str]) -> str | None:
        """params_sha256 of the resolved spec of one ``entry`` (section, name, form: a scene, homoclinic or
        map entry, or an analysis's form), resolved once; None when the config has no such entry."""
        if entry not in self._specs:
            spec = self._spec(*entry)
            self._specs[entry] = (spec, None if spec is None else params_hash(plain(spec)))
        return self._specs[entry][1]

    def _spec(self, section: str, name: str, form: str) -> Any:
        from cradle.pipeline import config as cc

        if section == "beyond":
            try:
                return cc.analysis_spec(self.config, name, form)
            except KeyError:  # a config without that analysis's section expects none of its files
                return None
        if name not in (self.config.get(section) or {}):
            return None
        return {"scenes": cc.scene, "homoclinic": cc.homoclinic, "map": cc.map_entry}[section](self.config, name)

    def _batch_keys(self, entry: tuple[str, str, str]) -> list[str]:
        """The batches of the form of an analysis (``entry``: "beyond", its name, the form); none where the
        form has nothing to split (a work-precision form without scenes refuses itself when built, not here)."""
        from cradle.analyses.registry import ANALYSES
        from cradle.pipeline.config import ConfigError

        batches, spec = ANALYSES[entry[1]].batches, self._specs[entry][0]
        try:
            return [] if batches is None else list(batches.keys(spec))
        except ConfigError:
            return []

    def mismatch(self, path: str | Path, attrs: Mapping[Any, Any]) -> str | None:
        """The one line saying how the file at ``path`` (its global attributes ``attrs``) differs from what
        the config expects there, or None when it is what is expected (or nothing is)."""
        want, entry = self._expected(path)
        if want is None:
            return None
        have = stored_identity(attrs, want.kind)
        same_kind = have.kind is None or have.kind == want.kind
        same_name = have.name is None or have.name == want.name
        if same_kind and same_name and have.params == want.params:
            return None
        differs = ""
        if same_kind and same_name and have.params is not None:  # the same entry made from other values: which
            differs = _differences(attrs.get("parameters"), plain(self._specs[entry][0]), self.source)
        return (f"{path} holds {have.describe(not same_kind)} ({_short(have.params)}), expected "
                f"{want.describe(not same_kind)} ({_short(want.params)} from {self.source}){differs}; "
                f"{self._rebuild(path, want)}")

    def _rebuild(self, path: str | Path, want: Identity) -> str:
        """Snakemake's command for a file under results/, else ``cradle run`` for a scene's or entry's."""
        if "results" in Path(path).parts or want.kind not in (*SCENE_KINDS, *ENTRY_KINDS):
            return rebuild_hint(path)
        config = f" --config {self.source}" if self.source.endswith((".yaml", ".yml")) else ""
        return f"rebuild it: cradle run {want.name} --out {self.root}{config} (see docs/recovery.md)"

    def check(self, path: str | Path, ds: xr.Dataset | xr.DataTree | Mapping[str, Any]) -> None:
        """Raise :class:`WrongOutput` if ``ds`` (the Dataset or DataTree read from ``path``, or its global
        attributes) is not what the config expects at ``path``."""
        line = self.mismatch(path, getattr(ds, "attrs", ds))
        if line is not None:
            raise WrongOutput(line)

    def check_file(self, path: str | Path) -> str | None:
        """:meth:`mismatch` of the file at ``path``, reading its global attributes only (no data); None also
        for a file that cannot be read (its checksums say why: :func:`cradle.data.io.verify_file`)."""
        if self.expected(path) is None:
            return None
        import netCDF4

        try:
            with netCDF4.Dataset(path) as nc:
                attrs = {k: nc.getncattr(k) for k in nc.ncattrs()}
        except (OSError, RuntimeError, ValueError):
            return None
        return self.mismatch(path, attrs)


def _flat(value: Any, prefix: str = "") -> dict[str, object]:
    """A nested mapping of plain values as ``{"initial.omega_tw": 1.01, ...}``."""
    if isinstance(value, dict):
        return {k: v for key, sub in value.items() for k, v in _flat(sub, f"{prefix}{key}.").items()}
    return {prefix[:-1]: value}


def _differences(stored: object, expected: object, source: str, most: int = 3) -> str:
    """``: initial.omega_tw 1.02 in the file, 1.01 in config.yaml`` for the first ``most`` keys whose values
    differ between a file's ``parameters`` (canonical JSON) and the spec resolved now; "" if it stores none."""
    import json

    try:
        have = _flat(json.loads(str(stored)))
    except (TypeError, ValueError):
        return ""
    want = _flat(json.loads(canonical_json(expected)))
    def show(values: dict[str, object],
             key: str) -> str:  # a long list (stored times) shortened: the line stays one line
        text = str(values.get(key, "(absent)"))
        return text if len(text) <= 40 else f"{text[:37]}..."

    keys = sorted(k for k in set(have) | set(want) if have.get(k, "(absent)") != want.get(k, "(absent)"))
    shown = [f"{k} {show(have, k)} in the file, {show(want, k)} in {source}" for k in keys[:most]]
    more = f" and {len(keys) - most} more" if len(keys) > most else ""
    return f": {'; '.join(shown)}{more}" if shown else ""


def _short(digest: str | None) -> str:
    return f"params {digest[:12]}" if digest else "no params recorded"


def stored_identity(attrs: Mapping[Any, Any], kind: str | None = None) -> Identity:
    """What a file's global attributes say it is (``kind``: the kind its path has, which says where a file
    written before ``cradle_name`` existed states its name: ``scene`` or ``name``)."""
    name = attrs.get("cradle_name") or None
    if name is None and kind in SCENE_KINDS:
        name = attrs.get("scene") or None
    elif name is None and kind in ENTRY_KINDS:
        name = attrs.get("name") or None
    digest = attrs.get("params_sha256")
    return Identity(attrs.get("cradle_kind") or None, None if name is None else str(name),
                    None if digest is None else str(digest))


def job_expectations(config: dict) -> Expectations:
    """What a Snakemake job's inputs must be by its ``config`` (``snakemake.config``: validated by the
    Snakefile, so not validated again in the job: :func:`cradle.pipeline.config.assume_validated`)."""
    from cradle.pipeline.config import assume_validated

    return Expectations(assume_validated(config), layout.ROOT, source=CONFIG)


def open_checked(path: str | Path, expect: Expectations, tree: bool = False) -> xr.Dataset | xr.DataTree:
    """A workflow job's input: :func:`cradle.data.io.open_dataset` (``tree``: :func:`~cradle.data.io.open_tree`)
    of ``path``, verified, then refused unless it is what ``expect`` (:func:`job_expectations`) expects there
    (:class:`WrongOutput`)."""
    line = expect.check_file(path)  # attributes only, first: another entry's whole file says so, not "edited"
    if line is not None:
        raise WrongOutput(line)
    ds = open_tree(path) if tree else open_dataset(path)
    expect.check(path, ds)
    return ds
