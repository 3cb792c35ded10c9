"""Rule code inputs are the true code dependencies (cradle.pipeline.codedeps).

Two checks. (1) For every job of the full DAG, the src/cradle files among its
inputs are exactly the modules its entry points can import, as found by an
independent import analysis (the standard library's :mod:`modulefinder`,
which scans byte code, nested functions included). Since Snakemake reruns a
job when an input is newer than its outputs, this is "an edit to module M
plans exactly the jobs that import M" for every M at once. (2) That promise,
measured: in a scratch copy with every output present and up to date, an edit
to one module makes a dry run plan exactly the jobs that import it (a few
modules, one per layer).
"""
from __future__ import annotations

import csv
import io
import os
import shutil
import subprocess
import time
from modulefinder import ModuleFinder
from pathlib import Path

import pytest

from conftest import run_snakemake
from cradle import figures
from cradle.analyses.registry import ANALYSES
from cradle.pipeline.codedeps import code_files

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "src"


def _snakemake(workdir, *args):
    return run_snakemake(workdir, *args)


def _summary(workdir, *targets) -> list[dict]:
    """snakemake --detailed-summary: one row per output file (rule, inputs, plan)."""
    proc = _snakemake(workdir, "--detailed-summary", "--nolock", *targets)
    assert proc.returncode == 0, proc.stderr[-3000:]
    text = proc.stdout[proc.stdout.index("output_file\t"):]
    return list(csv.DictReader(io.StringIO(text), delimiter="\t"))


def _oracle(*entries) -> set[str]:
    """src/cradle files reachable from the entries, by modulefinder (not by codedeps)."""
    finder = ModuleFinder(path=[str(SRC)])
    for entry in entries:
        if entry.endswith(".py"):
            finder.run_script(str(ROOT / entry))
        else:
            finder.import_hook(entry)
    return {str(Path(m.__file__).relative_to(ROOT)) for name, m in finder.modules.items()
            if (name == "cradle" or name.startswith("cradle.")) and m.__file__}


def _entries(row) -> tuple[str, ...]:
    """What a job runs: its script (read from its inputs) and, for a figure, the drawing module."""
    inputs = row["input-file(s)"].split(",")
    scripts = [f for f in inputs if f.startswith("workflow/scripts/")]
    if scripts:
        entries = tuple(scripts)
    else:  # shell rules run `python -m <module>`
        entries = tuple(sorted({f[len("src/"):-len(".py")].replace("/", ".") for f in inputs
                                if f.startswith("src/cradle/analyses/") or f.startswith("src/cradle/figures/")
                                and not f.endswith("__init__.py")}))
    label = Path(row["output_file"]).stem
    for script, package in (("analysis_compute", "analyses"), ("analysis_batch", "analyses"),
                            ("analysis_figure", "figures")):
        # the generated rules (analyses.smk) run the modules of the analysis whose files they write: results/<name>/...
        # (its netCDF files and batches), results/figures/<name>.* or results/<name>/<form>/<name>.* (its figures)
        if f"workflow/scripts/{script}.py" in scripts:
            name = label if package == "figures" else Path(row["output_file"]).parts[1]
            entries += (f"cradle.{package}.{ANALYSES[name].module}",)
    if "workflow/scripts/figure.py" in scripts:
        entries += (f"cradle.figures.{figures.module_of(label)}",)
    return entries


TARGETS = ("all", "mi_statistics_full", "paper")


@pytest.fixture(scope="module")
def scratch(tmp_path_factory):
    """A copy of the tracked tree where every job of the full DAG has run (``--touch``: outputs
    present, newer than the code, and the inputs of each job recorded)."""
    work = tmp_path_factory.mktemp("codedeps") / "cradle"
    files = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, text=True,
                           check=True).stdout.split("\0")
    for f in filter(None, files):
        if (ROOT / f).is_file():
            (work / f).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / f, work / f)
    for row in _summary(work, *TARGETS):
        if row["rule"] not in TARGETS:
            (work / row["output_file"]).parent.mkdir(parents=True, exist_ok=True)
            (work / row["output_file"]).touch()
    proc = _snakemake(work, "--touch", "--forceall", "--cores", "1", *TARGETS)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return work


@pytest.fixture(scope="module")
def full_dag(scratch):
    return [r for r in _summary(scratch, *TARGETS) if r["rule"] not in TARGETS]


def test_code_inputs_are_exactly_the_imports_of_every_job(full_dag):
    checked = 0
    for row in full_dag:
        inputs = {f for f in row["input-file(s)"].split(",") if f.startswith("src/")}
        entries = _entries(row)
        assert inputs == _oracle(*entries), (row["output_file"], sorted(inputs ^ _oracle(*entries)))
        checked += 1
    assert checked > 100


def test_codedeps_follows_relative_and_lazy_imports(tmp_path):
    pkg = tmp_path / "cradle"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "sub" / "__init__.py").write_text("")
    (pkg / "sub" / "a.py").write_text("from . import b\n\ndef f():\n    from ..c import g\n")
    (pkg / "sub" / "b.py").write_text("import numpy\n")
    (pkg / "c.py").write_text("def g():\n    pass\n")
    (pkg / "d.py").write_text("")  # imported by nobody
    got = [Path(p).relative_to(tmp_path).as_posix() for p in code_files("cradle.sub.a", src=tmp_path)]
    assert got == ["cradle/__init__.py", "cradle/c.py", "cradle/sub/__init__.py", "cradle/sub/a.py",
                   "cradle/sub/b.py"]
    with pytest.raises(ValueError, match="no module"):
        code_files("cradle.nope", src=tmp_path)


def _downstream(rows, outputs: set[str]) -> set[str]:
    """``outputs`` and every output of a job that reads one of them, transitively (per job: a job
    whose one output is planned is planned whole)."""
    jobs = {}
    for r in rows:  # one job per (rule, log file): the rows are per output file
        jobs.setdefault((r["rule"], r["log-file(s)"]), []).append(r)
    planned = set(outputs)
    while True:
        more = {r["output_file"] for job in jobs.values() for r in job
                if any(o in planned for x in job for o in x["input-file(s)"].split(",")) or
                any(x["output_file"] in planned for x in job)} - planned
        if not more:
            return planned
        planned |= more


@pytest.mark.slow
@pytest.mark.parametrize("module", ["src/cradle/data/provenance.py", "src/cradle/figures/spacetime.py",
                                    "src/cradle/measurements/sidebands.py", "src/cradle/integrators/_kernels.py",
                                    "src/cradle/analyses/mi_diagram.py"])
def test_an_edit_plans_exactly_the_jobs_that_import_it(scratch, full_dag, module):
    assert all(r["plan"] == "no update" for r in full_dag)
    path = scratch / module
    text, before = path.read_text(), path.stat()
    path.write_text(text + "\n# an edit\n")  # Snakemake compares checksums too: a touch is no edit
    later = time.time() + 1000
    os.utime(path, (later, later))
    try:
        planned = {r["output_file"] for r in _summary(scratch, *TARGETS) if r["plan"] == "update pending"}
    finally:
        path.write_text(text)
        os.utime(path, ns=(before.st_atime_ns, before.st_mtime_ns))
    importers = {r["output_file"] for r in full_dag if module in _oracle(*_entries(r))}
    assert planned == _downstream(full_dag, importers)  # the importers, and what reads their outputs
    if module.endswith("provenance.py"):  # the writer and reader of every file: everything reruns
        assert planned == {r["output_file"] for r in full_dag}
    assert planned
