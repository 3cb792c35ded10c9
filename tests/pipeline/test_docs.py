"""Docs tables belong to the benchmarks that write them (benchmarks/doctable.py)."""
from __future__ import annotations

import importlib.util
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _doctable():
    spec = importlib.util.spec_from_file_location("doctable", ROOT / "benchmarks" / "doctable.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_publish_replaces_exactly_the_marked_block(tmp_path):
    page = tmp_path / "page.md"
    page.write_text("intro\n<!-- table: t (written by x) -->\nold\n| a |\n<!-- end table: t -->\nafter\n")
    _doctable().publish("page.md", "t", "| new |\n", docs=tmp_path)
    assert page.read_text() == "intro\n<!-- table: t (written by x) -->\n| new |\n<!-- end table: t -->\nafter\n"
    with pytest.raises(SystemExit, match="no markers for table 'u'"):
        _doctable().publish("page.md", "u", "x", docs=tmp_path)


def test_every_table_a_benchmark_publishes_has_its_markers():
    """A long benchmark must not fail at its last line: each publish(page, name) target exists."""
    calls = []
    for script in sorted((ROOT / "benchmarks").glob("*.py")):
        for page, name in re.findall(r'publish\("([\w.-]+)", f?"([\w{}.-]+)"', script.read_text()):
            name = name.replace("{args.target}", "paper")  # rebuild.py's default target
            calls.append((page, name))
            assert f"<!-- table: {name} " in (ROOT / "docs" / page).read_text(), (script.name, page, name)
    published = {("performance.md", "vs-scipy"), ("performance.md", "rebuild-paper"), ("extremes.md", "extremes")}
    assert published <= set(calls)


def test_readme_links_resolve():
    text = (ROOT / "README.md").read_text()
    for link in re.findall(r"\]\(([^)#]+)\)", text):
        assert (ROOT / link).exists(), link


def test_every_link_in_the_docs_resolves_to_its_anchor():
    """Links between the pages and to their paragraphs (README.md, docs/*.md and the pages of docs/analyses/): the
    file exists and so does the anchor (a heading's slug or an <a id>); an image a page shows exists."""
    doctable = _doctable()
    assert {"what-was-found", "claims-harmonics"} <= doctable.anchors((ROOT / "docs" / "analyses.md").read_text())
    bad, n = [], 0
    for page in [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")), *sorted((ROOT / "docs").glob("*/*.md"))]:
        for image in re.findall(r"!\[[^]]*\]\(([^)\s]+)\)", page.read_text()):
            n += 1
            if not (page.parent / image).exists():
                bad.append((page.name, image))
        for link in re.findall(r"\]\(([^)\s]+)\)", page.read_text()):
            if "://" in link or not (link.startswith("#") or ".md" in link):
                continue
            n += 1
            if not doctable.link_resolves(page, link):
                bad.append((page.name, link))
    assert n >= 15 and not bad, bad
