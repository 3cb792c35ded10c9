"""What every ``cradle`` command shares: the program name, the one-line error, and reading the config."""
from __future__ import annotations

from pathlib import Path

PROG = "cradle"


class CliError(Exception):
    """An error reported as one line, exit status 2."""


def load_config(path):
    """The config at ``path``, loaded and validated (:func:`cradle.pipeline.config.load`)."""
    from cradle.pipeline import config as cc

    path = Path(path)
    if not path.exists():
        raise CliError(f"no config file {str(path)!r} (give one with --config)")
    return cc.load(path)


def section_of(cfg, name):
    """The section (scenes, homoclinic, map) of the config that defines ``name``, or None."""
    for section in ("scenes", "homoclinic", "map"):
        if name in (cfg.get(section) or {}):
            return section
    return None


def known_names(cfg):
    """Every name of those sections, for an error message."""
    names = [n for s in ("scenes", "homoclinic", "map") for n in (cfg.get(s) or {})]
    return ", ".join(names) or "none"
