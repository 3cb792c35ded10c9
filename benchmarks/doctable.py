"""Benchmarks write their own tables into the docs: no measured number is typed by hand.

A docs page marks each table a benchmark owns::

    <!-- table: extremes (written by benchmarks/extremes.py) -->
    ...
    <!-- end table: extremes -->

and :func:`publish` replaces what lies between the two markers.
"""
from __future__ import annotations

import re
from pathlib import Path

DOCS = Path(__file__).resolve().parents[1] / "docs"


def publish(page: str, name: str, text: str, docs: Path = DOCS) -> Path:
    """Put ``text`` between the markers of table ``name`` in ``docs/page``; the markers must exist."""
    path = docs / page
    source = path.read_text()
    pattern = re.compile(rf"(<!-- table: {re.escape(name)}\b[^>]*-->\n).*?(<!-- end table: {re.escape(name)} -->)",
                         re.S)
    if not pattern.search(source):
        raise SystemExit(f"{path}: no markers for table {name!r}")
    path.write_text(pattern.sub(lambda m: m.group(1) + text.strip("\n") + "\n" + m.group(2), source))
    return path
