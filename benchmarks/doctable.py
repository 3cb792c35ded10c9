"""Benchmarks write their own tables into the docs: no measured number is typed by hand.

A docs page marks each table a benchmark owns::

    <!-- table: extremes (written by benchmarks/extremes.py) -->
    ...
    <!-- end table: extremes -->

and :func:`publish` replaces what lies between the two markers.
"""
from __future__ import annotations

import re
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"


def git_commit(rev: str = "HEAD", repo: Path = ROOT, short: bool = True) -> str:
    """The commit ``rev`` names in the git checkout ``repo`` (abbreviated unless ``short`` is false): what a table
    says it measured."""
    return subprocess.run(["git", "rev-parse", *(["--short"] if short else []), rev], cwd=repo, capture_output=True,
                          text=True, check=True).stdout.strip()


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


def anchors(markdown: str) -> set[str]:
    """The link targets a Markdown page offers on GitHub: every ``<a id="...">`` and every heading's slug
    (lowercased, punctuation dropped, spaces to hyphens; a repeated slug gets -1, -2, ...)."""
    found = set(re.findall(r'<a id="([^"]+)"', markdown))
    seen: dict[str, int] = {}
    body = re.sub(r"^```.*?^```", "", markdown, flags=re.S | re.M)      # no headings inside code blocks
    for title in re.findall(r"^#{1,6} +(.+?) *#*$", body, re.M):
        slug = re.sub(r"[^\w\- ]", "", title.lower()).replace(" ", "-")
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        found.add(slug if n == 0 else f"{slug}-{n}")
    return found


def link_resolves(page: Path, link: str) -> bool:
    """Whether a relative link written in ``page`` ("other.md#anchor", "#anchor", "other.md") resolves."""
    target, _, anchor = link.partition("#")
    path = (page.parent / target).resolve() if target else page
    return path.exists() and (not anchor or anchor in anchors(path.read_text()))


def cost_rows(method: str, runs: dict[str, list[dict]]) -> list[str]:
    """Rows of an "every term off" cost table (benchmarks/damping_off_cost.py, terms_off_cost.py): per code
    variant, ns per bead and force evaluation (median, min, max over the processes), the median's and the minimum's
    difference from the first variant's, and whether every process gave bitwise the same result and evaluations."""
    import numpy as np

    hashes = {r["sha256"] for rs in runs.values() for r in rs}
    evals = {r["evals"] for rs in runs.values() for r in rs}
    first = next(iter(runs.values()))
    ref = np.median([r["per_bead_eval_s"] for r in first])
    ref_min = min(r["per_bead_eval_s"] for r in first)
    lines = []
    for name, rs in runs.items():
        t = np.array([r["per_bead_eval_s"] for r in rs])
        lines.append(f"| {method} | {name} | {np.median(t) * 1e9:.2f} | {t.min() * 1e9:.2f} | "
                     f"{t.max() * 1e9:.2f} | {(np.median(t) / ref - 1.0) * 100:+.1f} % | "
                     f"{(t.min() / ref_min - 1.0) * 100:+.1f} % | "
                     f"{'yes' if len(hashes) == 1 and len(evals) == 1 else 'NO'} |")
    return lines
