"""Rule code inputs are the true code dependencies (cradle.pipeline.codedeps).

Two checks. (1) For every job of the full DAG, the src/cradle files whose stamps are among its
inputs are exactly the modules its entry points can import, as found by an
independent import analysis (the standard library's :mod:`modulefinder`,
which scans byte code, nested functions included). Since Snakemake reruns a
job when an input is newer than its outputs, this is "an edit to module M
plans exactly the jobs that import M" for every M at once. (2) That promise,
measured: in a scratch copy with every output present and up to date, an edit
to one module makes a dry run plan exactly the jobs that import it (a few
modules, one per layer), and an edit to its comments or docstrings plans nothing.
"""
from __future__ import annotations

import ast
import contextlib
import csv
import io
import os
import time
import warnings
from functools import cache
from modulefinder import ModuleFinder
from pathlib import Path

import pytest

from conftest import copy_workflow, run_snakemake
from cradle import figures
from cradle.analyses.registry import ANALYSES
from cradle.pipeline.codedeps import STAMPS, code_files, code_stamps, fingerprint, stamp_all, stamped_files

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "src"


def _snakemake(workdir, *args):
    return run_snakemake(workdir, *args)


def _summary(workdir, *targets) -> list[dict]:
    """snakemake --detailed-summary: one row per output file (rule, inputs, plan). Snakemake's command line
    run in this process (the same rows as a ``snakemake`` process gives, in 40 % of its time: Snakemake and
    cradle are imported once), in ``workdir``; the environment the Snakefile sets for its jobs is put back."""
    from snakemake.cli import main

    out, err, code = io.StringIO(), io.StringIO(), None
    cwd, env = os.getcwd(), dict(os.environ)
    os.chdir(workdir)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            main(["--detailed-summary", "--nolock", *targets])
    except SystemExit as exit:
        code = exit.code
    finally:
        os.chdir(cwd)
        os.environ.clear()
        os.environ.update(env)
    assert code == 0, err.getvalue()[-3000:]
    text = out.getvalue()[out.getvalue().index("output_file\t"):]
    return [{**row, "work": str(workdir)} for row in csv.DictReader(io.StringIO(text), delimiter="\t")]


@cache
def _oracle(*entries) -> frozenset[str]:
    """src/cradle files reachable from the entries, by modulefinder (not by codedeps); once per set of
    entries (the tests ask for it job by job, and the jobs share some 40 of them), from the sources of
    this checkout, which no test edits."""
    finder = ModuleFinder(path=[str(SRC)])
    for entry in entries:
        if entry.endswith(".py"):
            finder.run_script(str(ROOT / entry))
        else:
            finder.import_hook(entry)
    return frozenset(str(Path(m.__file__).relative_to(ROOT)) for name, m in finder.modules.items()
                     if (name == "cradle" or name.startswith("cradle.")) and m.__file__)


def _code_inputs(row) -> list[str]:
    """A job's inputs, its code stamp (``.snakemake/cradle-code/jobs/<entries>.sha256``) read as the files it
    names (``src/cradle/a/b.py``, ``workflow/scripts/figure.py``)."""
    out = []
    for f in row["input-file(s)"].split(","):
        out += stamped_files(Path(row["work"]) / f) if f.startswith(f"{STAMPS.as_posix()}/") else [f]
    return out


def _entries(row) -> tuple[str, ...]:
    """What a job runs: its script (read from its inputs) and, for a figure, the drawing module."""
    inputs = _code_inputs(row)
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
    copy_workflow(work)
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
        # one code input a job (Snakemake sizes every input of every ready job each time it picks one)
        assert sum(f.startswith(f"{STAMPS.as_posix()}/") for f in row["input-file(s)"].split(",")) == 1, row
        inputs = {f for f in _code_inputs(row) if f.startswith("src/")}
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


def test_a_fingerprint_ignores_comments_and_docstrings_and_sees_code(tmp_path):
    path = tmp_path / "m.py"
    code = 'def f(x):\n    return 2 * x\n\n\nclass C:\n    def g(self):\n        return f(1)\n'
    path.write_text(code)
    base = fingerprint(path)
    path.write_text('"""A module."""\n# a comment\n' + code.replace("    return 2", '    """Twice x."""\n    return 2')
                    .replace("class C:", "class C:  # why\n    \"\"\"A class.\"\"\"\n"))
    assert fingerprint(path) == base   # comments, docstrings and the lines they move: the same code
    path.write_text(code.replace("2 * x", "3 * x"))
    assert fingerprint(path) != base
    path.write_text(code + "X = 1\n")
    assert fingerprint(path) != base
    path.write_text(code.replace("return f(1)", '"""Now a docstring."""'))   # a body that was code
    assert fingerprint(path) != base


def test_a_stamp_is_rewritten_only_when_the_code_changes(tmp_path):
    pkg = tmp_path / "src" / "cradle"
    pkg.mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("X = 1\n")
    stamps = tmp_path / "stamps"
    got = code_stamps("cradle.a", src=tmp_path / "src", stamps=stamps)
    stamp = stamps / "jobs" / "cradle.a.sha256"
    assert got == [str(stamp)]
    assert stamped_files(stamp) == [str(tmp_path / "src" / "cradle" / f) for f in ("__init__.py", "a.py")]
    before = stamp.stat().st_mtime_ns
    os.utime(stamp, ns=(before - 10**9, before - 10**9))
    (pkg / "a.py").write_text('"""A docstring."""\nX = 1  # a comment\n')
    code_stamps("cradle.a", src=tmp_path / "src", stamps=stamps)
    assert stamp.stat().st_mtime_ns == before - 10**9   # untouched: no job sees a newer input
    (pkg / "a.py").write_text("X = 2\n")
    code_stamps("cradle.a", src=tmp_path / "src", stamps=stamps)
    assert stamp.stat().st_mtime_ns > before - 10**9 and fingerprint(pkg / "a.py") in stamp.read_text()



def test_every_stamp_exists_before_the_dag_is_built(tmp_path):
    """The Snakefile writes every module's and script's stamp when it is read (stamp_all), and every job's code
    stamp (the rules' code_of, and those the input functions ask for, asked for first by the rule files): the
    stamps an input function asks for later are the same files, already there when Snakemake takes its
    inventory (a stamp first written by an input function was reported missing when its folder already
    existed; the full DAG of a fresh copy, the ``scratch`` fixture, fails so). Here: the two kinds of stamp."""
    pkg = tmp_path / "src" / "cradle" / "figures"
    pkg.mkdir(parents=True)
    for f in (pkg.parent / "__init__.py", pkg / "__init__.py", pkg / "maps.py"):
        f.write_text("X = 1\n")
    scripts = tmp_path / "workflow" / "scripts"
    scripts.mkdir(parents=True)
    (scripts / "figure.py").write_text("import cradle.figures.maps\n")
    stamps = tmp_path / "stamps"
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        assert stamp_all("src", "workflow/scripts", stamps) == 4
        written = sorted(p.name for p in stamps.iterdir())
        job = code_stamps("workflow/scripts/figure.py", "cradle.figures.maps", src="src", stamps=stamps)
        named = sorted(stamped_files(job[0]))
    finally:
        os.chdir(cwd)
    assert written == ["cradle.__init__.sha256", "cradle.figures.__init__.sha256", "cradle.figures.maps.sha256",
                       "workflow.scripts.figure.sha256"]
    assert job == [str(stamps / "jobs" / "workflow.scripts.figure+cradle.figures.maps.sha256")]
    assert named == ["src/cradle/__init__.py", "src/cradle/figures/__init__.py", "src/cradle/figures/maps.py",
                     "workflow/scripts/figure.py"]


def test_a_later_read_reuses_the_index_for_unchanged_files_only(tmp_path, monkeypatch):
    """stamp_all saves each file's fingerprint and imports beside the stamps; a later read of the Snakefile
    (another process: nothing in memory) parses only the files written since, even one rewritten to the
    same size with its modification time set back (its change time moved), and gives the same stamps."""
    from cradle.pipeline import codedeps

    pkg = tmp_path / "src" / "cradle"
    pkg.mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("from . import b\nX = 1\n")
    (pkg / "b.py").write_text("Y = 2\n")
    scripts, stamps = tmp_path / "scripts", tmp_path / "stamps"
    scripts.mkdir()
    monkeypatch.setattr(codedeps, "RECENT_NS", -10**18)   # these files were just written: save them anyway
    monkeypatch.setattr(codedeps, "_KNOWN", {})
    assert codedeps.stamp_all(tmp_path / "src", scripts, stamps) == 3
    first = {p.name: p.read_text() for p in stamps.iterdir()}
    parsed = []
    real_parse = ast.parse
    monkeypatch.setattr(ast, "parse", lambda text, name: parsed.append(Path(name).name) or real_parse(text, name))
    monkeypatch.setattr(codedeps, "_KNOWN", {})   # a new process
    codedeps.stamp_all(tmp_path / "src", scripts, stamps)
    assert parsed == [] and {p.name: p.read_text() for p in stamps.iterdir()} == first
    assert codedeps.code_files("cradle.a", src=tmp_path / "src") == [str(pkg / f) for f in ("__init__.py", "a.py",
                                                                                            "b.py")]
    before = (pkg / "a.py").stat()
    (pkg / "a.py").write_text("from . import b\nX = 3\n")   # the same size, and its time set back
    os.utime(pkg / "a.py", ns=(before.st_atime_ns, before.st_mtime_ns))
    monkeypatch.setattr(codedeps, "_KNOWN", {})
    codedeps.stamp_all(tmp_path / "src", scripts, stamps)
    assert parsed == ["a.py"]
    assert (stamps / "cradle.a.sha256").read_text() != first["cradle.a.sha256"]
    assert fingerprint(pkg / "a.py") in (stamps / "cradle.a.sha256").read_text()


def _no_code_edit(text: str) -> str:
    """``text`` (a module with a docstring) with its docstring edited and comments added."""
    assert text.lstrip().startswith(('"""', 'r"""'))
    return "# a comment\n" + text.replace('"""', '"""An edited docstring. ', 1) + "\n# an edit\n"


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
    later = time.time() + 1000
    try:
        # a comment and a docstring: the same code, nothing planned
        path.write_text(_no_code_edit(text))
        os.utime(path, (later, later))
        assert all(r["plan"] == "no update" for r in _summary(scratch, *TARGETS))
        path.write_text(text + "\n_AN_EDIT = 1\n")  # Snakemake compares checksums too: a touch is no edit
        os.utime(path, (later, later))
        planned = {r["output_file"] for r in _summary(scratch, *TARGETS) if r["plan"] == "update pending"}
    finally:
        path.write_text(text)
        os.utime(path, ns=(before.st_atime_ns, before.st_mtime_ns))
    importers = {r["output_file"] for r in full_dag if module in _oracle(*_entries(r))}
    assert planned == _downstream(full_dag, importers)  # the importers, and what reads their outputs
    if module.endswith("provenance.py"):  # the writer and reader of every file: everything reruns
        assert planned == {r["output_file"] for r in full_dag}
    assert planned


@pytest.mark.slow
def test_a_comment_reruns_nothing_and_code_reruns_its_importers(tmp_path):
    """One small target, measured: plot4-5's jobs up to date (``--touch``); a comment and a docstring in
    models/dps.py (and a comment in the scene's script) plan nothing, a change to its code plans its jobs."""
    from cradle.pipeline import layout as L

    work = tmp_path / "cradle"
    copy_workflow(work, skip=("tests/", "docs/", "benchmarks/"))
    target = "results/figures/plot4-5.png"
    outputs = [L.path("kernels"), *L.scene_paths("tw-weak").values(), *L.figure_paths("plot4-5").values()]
    for out in map(str, outputs):
        (work / out).parent.mkdir(parents=True, exist_ok=True)
        (work / out).touch()
    proc = _snakemake(work, "--touch", "--forceall", "--cores", "1", target)
    assert proc.returncode == 0, proc.stderr[-3000:]

    def planned() -> str:
        proc = _snakemake(work, "-n", target)
        assert proc.returncode == 0, proc.stderr[-3000:]
        return proc.stdout + proc.stderr

    dps, script = work / "src/cradle/models/dps.py", work / "workflow/scripts/simulate.py"
    text = dps.read_text()
    later = time.time() + 1000
    dps.write_text(_no_code_edit(text))
    script.write_text(script.read_text() + "# a comment\n")
    for path in (dps, script):
        os.utime(path, (later, later))
    assert "Nothing to be done" in planned()
    dps.write_text(text + "\n_AN_EDIT = 1\n")
    os.utime(dps, (later, later))
    plan = planned()
    assert f"Updated input files: {STAMPS.as_posix()}/jobs/workflow.scripts.kernels.sha256" in plan
    assert "Nothing to be done" not in plan
    for job in ("kernels", "simulate"):   # the code stamps of both jobs that reach dps.py name its new code
        assert fingerprint(dps) in (work / STAMPS / "jobs" / f"workflow.scripts.{job}.sha256").read_text()
