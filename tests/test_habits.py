"""The checked habits: ruff, mypy (check_untyped_defs, disallow_untyped_defs) and snakefmt are clean, each with
its committed configuration in pyproject.toml, so the README's test command (and .ci/run) runs them besides the
tests."""
import subprocess
import sys

import pytest

from conftest import ROOT


def _clean(tool: str, *args: str) -> None:
    """Run ``python -m tool args`` from the repository root (where pyproject.toml holds its configuration)
    with the Python running the tests, the venv of `pip install -e '.[test]'`; fail with its output."""
    pytest.importorskip(tool, reason=f"{tool} checks the code: pip install -e '.[test]'")
    proc = subprocess.run([sys.executable, "-m", tool, *args], cwd=ROOT, capture_output=True, text=True,
                          timeout=600, check=False)
    if proc.returncode != 0:
        pytest.fail(f"{' '.join((tool, *args))}: exit {proc.returncode}\n{proc.stdout}{proc.stderr}", pytrace=False)


def test_ruff_is_clean():
    """[tool.ruff]: rules E, F, W, I, B, UP, NPY over every Python file of the repository."""
    _clean("ruff", "check", "--no-fix", ".")


def test_mypy_is_clean():
    """[tool.mypy]: src/cradle with check_untyped_defs and disallow_untyped_defs (every function annotated);
    incremental, so a rerun reads .mypy_cache/."""
    _clean("mypy")


def test_snakefmt_is_clean():
    """[tool.snakefmt]: the Snakefile and the rule files are as snakefmt writes them."""
    _clean("snakefmt", "--check", "--compact-diff", "Snakefile", "workflow/rules")
