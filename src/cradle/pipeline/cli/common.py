"""What every ``cradle`` command shares: the program name, the one-line error, reading the config, and what
it expects of the result files (verify, describe)."""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from cradle.pipeline.identity import Expectations

PROG = "cradle"


class CliError(Exception):
    """An error reported as one line, exit status 2."""


def load_config(path: str | Path) -> dict:
    """The config at ``path``, loaded and validated (:func:`cradle.pipeline.config.load`)."""
    from cradle.pipeline import config as cc

    path = Path(path)
    if not path.exists():
        raise CliError(f"no config file {str(path)!r} (give one with --config)")
    return cc.load(path)


def section_of(cfg: dict, name: str) -> str | None:
    """The section (scenes, homoclinic, map) of the config that defines ``name``, or None."""
    for section in ("scenes", "homoclinic", "map"):
        if name in (cfg.get(section) or {}):
            return section
    return None


def known_names(cfg: dict) -> str:
    """Every name of those sections, for an error message."""
    names = [n for s in ("scenes", "homoclinic", "map") for n in (cfg.get(s) or {})]
    return ", ".join(names) or "none"


#: the config ``verify`` and ``describe`` check files against when no --config is given (if it exists)
DEFAULT_CONFIG = "config.yaml"


def expectations(config_arg: str | None) -> Expectations | None:
    """What the config expects of the files of its layout (:class:`cradle.pipeline.identity.Expectations`),
    the ``results/`` folder beside it; None when ``config_arg`` is None and there is no config.yaml. A
    config that cannot be read or is invalid is one note on stderr: the files' checksums are still checked."""
    import sys

    from cradle.pipeline import config as cc
    from cradle.pipeline.identity import Expectations

    path = Path(config_arg or DEFAULT_CONFIG)
    if config_arg is None and not path.is_file():
        return None
    try:
        cfg = cc.validate(cc.read_yaml(path))
    except cc.ConfigError as err:
        print(f"{PROG}: note: identities not checked: {' '.join(str(err).split())}", file=sys.stderr)
        return None
    return Expectations(cfg, path.parent / "results", source=str(path))


def identity_line(expect: Expectations | None, path: str | Path, attrs: dict) -> str:
    """What ``cradle describe`` says of a file's identity (its global attributes ``attrs``): ``MISMATCH ...``
    (the line of :meth:`~cradle.pipeline.identity.Expectations.mismatch`), as expected, or why not checked."""
    if expect is None:
        return f"not checked (no {DEFAULT_CONFIG}; give one with --config)"
    want = expect.expected(path)
    if want is None:
        return f"not checked (no file of {expect.source} is expected at this path)"
    line = expect.mismatch(path, attrs)
    if line:
        return f"MISMATCH {line}"
    return f"{want.describe(False)}, params {(want.params or '')[:12]}, as {expect.source} expects"
