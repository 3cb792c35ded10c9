"""Snakemake conventions: `snakemake --lint`, log:/benchmark: per rule, report captions, cluster profile."""
from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml

from conftest import run_snakemake
from cradle.pipeline.workdir import copy_workflow

ROOT = Path(__file__).resolve().parents[2]
RULES = ROOT / "workflow" / "rules"

def _snakemake(workdir, *args, timeout=120):
    return run_snakemake(workdir, *args, timeout=timeout)


def test_snakemake_lint():
    proc = _snakemake(ROOT, "--lint", "--nolock")
    assert proc.returncode == 0, (proc.stdout + proc.stderr)[-3000:]



def _rules():
    """{rule name: its text} over workflow/rules/*.smk."""
    rules = {}
    for path in sorted(RULES.glob("*.smk")):
        text = path.read_text()
        for m in re.finditer(r"^rule (\w+):\n(.*?)(?=^\S|\Z)", text, re.M | re.S):
            rules[m.group(1)] = m.group(2)
    return rules


def _generated():
    """{kind: the text of the generated rule} of workflow/rules/analyses.smk: batch, compute, figure."""
    text = (RULES / "analyses.smk").read_text()
    blocks = re.split(r"^\s+rule:\n", text, flags=re.M)[1:]
    return {re.search(r'f"\{_a\.target\}_(\w+?)_\{_form\}"', b).group(1): b for b in blocks
            if re.search(r'f"\{_a\.target\}_(\w+?)_\{_form\}"', b)}


def test_every_rule_logs_and_costly_rules_benchmark():
    rules = _rules()
    assert {"homoclinic", "map_orbits", "simulate", "figure"} <= set(rules)
    for name, body in rules.items():
        if re.search(r"^\s+(script|shell|run|notebook|wrapper):", body, re.M):  # target rules run nothing
            assert re.search(r"^\s+log:", body, re.M), f"rule {name} has no log:"
    for name in ("simulate", "figure"):
        assert re.search(r"^\s+benchmark:", rules[name], re.M), f"rule {name} has no benchmark:"
    # the rules of the analyses (the claims table among them) are generated: each logs, the costly ones
    # (batches, compute) benchmark, and a captioned analysis's drawn files go into the report
    generated = _generated()
    assert set(generated) == {"batch", "compute", "figure"}
    for kind, body in generated.items():
        assert re.search(r"^\s+log:", body, re.M), kind
    assert all(re.search(r"^\s+benchmark:", generated[k], re.M) for k in ("batch", "compute"))
    assert "drawn_outputs(" in generated["figure"] and "report(" in (RULES / "analyses.smk").read_text()
    assert (ROOT / "workflow" / "report" / "paper-checks.rst").exists()
    assert "report(" in rules["figure"]


def test_report_captions_render_for_every_figure():
    """The caption template renders (Jinja2 as Snakemake sets it up) to valid reStructuredText for every figure."""
    jinja2 = pytest.importorskip("jinja2")
    docutils_core = pytest.importorskip("docutils.core")
    from types import SimpleNamespace

    from cradle.pipeline import config as cc

    cfg = cc.load(ROOT / "config.yaml")
    env = jinja2.Environment(trim_blocks=True, lstrip_blocks=True)
    template = env.from_string((ROOT / "workflow" / "report" / "figure.rst").read_text())
    for label, options in cfg["figures"].items():
        sm = SimpleNamespace(wildcards=SimpleNamespace(label=label), params=SimpleNamespace(options=options),
                             config=cfg)
        text = template.render(snakemake=sm)
        assert f"**{label}** -- " in text
        for name in options["scenes"]:
            assert f"``{name}``" in text, (label, name)
        html = docutils_core.publish_parts(text, writer="html",
                                           settings_overrides={"halt_level": 2, "report_level": 5})["body"]
        assert label in html
    for rst in ("paper-checks.rst", "workflow.rst"):
        docutils_core.publish_parts((ROOT / "workflow" / "report" / rst).read_text(), writer="html",
                                    settings_overrides={"halt_level": 2, "report_level": 5})


def _workdir(tmp_path):
    return copy_workflow(ROOT, tmp_path / "cradle")


def test_default_profile_is_valid_yaml():
    profile = yaml.safe_load((ROOT / "profiles" / "default" / "config.yaml").read_text())
    assert profile["cores"] == 2 and profile["keep-going"] is True


def test_slurm_profile_dry_run(tmp_path):
    """A dry run with the Slurm profile plans the whole workflow (no cluster needed: nothing is submitted)."""
    pytest.importorskip("snakemake_executor_plugin_slurm", reason="snakemake-executor-plugin-slurm is not installed")
    profile = yaml.safe_load((ROOT / "profiles" / "slurm" / "config.yaml").read_text())
    assert profile["executor"] == "slurm"
    assert {"simulate", "figure"} <= set(profile["set-resources"])
    work = _workdir(tmp_path)
    proc = _snakemake(work, "-n", "--workflow-profile", "profiles/slurm")
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert re.search(r"^simulate\s+\d+$", proc.stdout + proc.stderr, re.M)
