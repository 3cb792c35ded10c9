"""Test-session settings.

Every writer checks its digest against the file read back (cradle.data.io.SELF_CHECK_ENV).

One BLAS thread: the dense solves here are small (N <= a few hundred), and on a
2-core machine a multithreaded OpenBLAS makes them ~100x slower once the other
core is busy. Set before numpy is first imported.
"""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")
# every file a test writes (in process or in a Snakemake job) digested both as its writer hands it over and as a
# reader reads it back, the two compared (cradle.data.io.SELF_CHECK_ENV)
os.environ["CRADLE_DIGEST_SELF_CHECK"] = "1"

#: the repository root (tests/<layer>/ mirror src/cradle/<layer>/)
ROOT = Path(__file__).resolve().parents[1]

#: test modules whose tests share an expensive module or session fixture (a copy of the tree where the full DAG has
#: run, the reduced forms computed in process): each is given whole to one pytest-xdist worker, which builds it once
ONE_WORKER = ("tests/pipeline/test_codedeps.py", "tests/figures/test_figures_render.py")


#: the longest tests (each 10 s to a minute), started first and longest first, so that the two workers end
#: together rather than one running the last long test alone; one of a module of :data:`ONE_WORKER` uses none
#: of its shared fixtures and is given to either worker
LONGEST = ("tests/test_habits.py::test_mypy_is_clean",
           "tests/pipeline/test_pipeline.py::test_snakemake_end_to_end_on_tiny_config",
           "tests/integrators/test_kernel_cache.py::test_edit_of_kernels_reaches_onset_kernels_and_restore_comes_back",
           "tests/pipeline/test_codedeps.py::test_a_comment_reruns_nothing_and_code_reruns_its_importers",
           "tests/pipeline/test_pipeline.py::test_a_failed_forced_rerun_restores_the_previous_outputs",
           "tests/pipeline/test_config_fuzz.py::test_config_fuzz",
           "tests/pipeline/test_interrupt.py::test_killed_run_leaves_nothing_and_rerun_matches",
           "tests/analyses/test_floquet.py::test_direct_simulation_grows_at_the_top_floquet_rate",
           "tests/test_tutorial.py::test_tutorial_runs_on_a_short_scene")


#: a test that takes longer than this (seconds, its call alone) is named with its time as it ends, so that a
#: person watching the dots sees what the suite is waiting for
NAMED_ABOVE_S = 10.0


def pytest_collection_modifyitems(items):
    """The quick tests first (a screenful of dots in the first minutes), then :data:`LONGEST` (longest first,
    so that the two workers end together), then the other tests marked ``slow``; within each, the collection
    order (the workers hand out the modules of :data:`ONE_WORKER` before single tests)."""
    rank = {nodeid: i for i, nodeid in enumerate(LONGEST)}

    def key(item):
        if item.nodeid in rank:
            return (1, rank[item.nodeid])
        return (2, 0) if item.get_closest_marker("slow") else (0, 0)

    items.sort(key=key)


def pytest_configure(config):
    global _CONFIG
    _CONFIG = config


_CONFIG = None


def pytest_runtest_logreport(report):
    """Name each test longer than :data:`NAMED_ABOVE_S` on its own line as it ends (under pytest-xdist too:
    the reports reach the controlling process)."""
    if report.when != "call" or report.duration < NAMED_ABOVE_S or _CONFIG is None:
        return
    reporter = _CONFIG.pluginmanager.get_plugin("terminalreporter")
    if reporter is not None and not getattr(_CONFIG, "workerinput", None):
        reporter.write_line(f"  {report.duration:5.0f} s  {report.outcome:7s} {report.nodeid}")


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config, log):
    """pytest-xdist's scheduling by scope, a scope being a module of :data:`ONE_WORKER` (but its tests of
    :data:`LONGEST`) or else a single test (xdist's own ``xdist_group`` mark does not reach the scheduler under
    pytest 9: it renames the node id). xdist hands out the scopes with the most tests first (the modules),
    then the others in the order of :func:`pytest_collection_modifyitems`."""
    from xdist.scheduler import LoadScopeScheduling

    class OneWorkerModules(LoadScopeScheduling):
        def _split_scope(self, nodeid: str) -> str:
            module = nodeid.split("::", 1)[0]
            return module if module in ONE_WORKER and nodeid not in LONGEST else nodeid

    return OneWorkerModules(config, log)


def copy_workflow(work, skip=()):
    """The repository's tracked files copied into ``work`` (a scratch workflow), but those under the folders
    ``skip`` (e.g. ``("tests/", "docs/")``)."""
    files = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, text=True,
                           check=True).stdout.split("\0")
    for f in filter(None, files):
        if (ROOT / f).is_file() and not f.startswith(tuple(skip)):
            (work / f).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / f, work / f)


def run_snakemake(workdir, *args, timeout=300):
    """``snakemake ARGS`` in ``workdir`` (the venv's snakemake), captured; warnings silenced."""
    exe = shutil.which("snakemake") or shutil.which("snakemake", path=str(Path(sys.executable).parent))
    cmd = [exe] if exe else [sys.executable, "-m", "snakemake"]
    return subprocess.run(cmd + list(args), cwd=workdir, capture_output=True, text=True, timeout=timeout,
                          env={**os.environ, "PYTHONWARNINGS": "ignore"})
