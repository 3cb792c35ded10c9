"""Figures read only stored data: no module of cradle.figures imports a numerical layer of the package.

Whatever a figure shows that is computed (orbits, breather measurements, sideband peaks, the linear
wave, theory curves) is computed by a stage and stored in the netCDF file the figure reads; a figure
module imports only cradle.figures, numpy, matplotlib and the reading helpers of cradle.pipeline.
"""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

import cradle.figures

FIGURES_DIR = Path(cradle.figures.__file__).parent
NUMERICAL = ("cradle.models", "cradle.measurements", "cradle.analyses", "cradle.integrators")
MODULES = sorted(FIGURES_DIR.glob("*.py"))


def _imports(path: Path) -> list[str]:
    """Every module named by an import statement of ``path`` (at any depth, relative imports resolved)."""
    names = []
    for node in ast.walk(ast.parse(path.read_text(), filename=str(path))):
        if isinstance(node, ast.Import):
            names += [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:  # relative: from . import x / from .spacetime import y, inside cradle.figures
                base = "cradle.figures" if node.level == 1 else "cradle"
                module = f"{base}.{node.module}" if node.module else base
                names += [module] if node.module else [f"{base}.{alias.name}" for alias in node.names]
            else:
                names.append(node.module)
                names += [f"{node.module}.{alias.name}" for alias in node.names]
    return names


def test_there_are_figure_modules():
    assert {p.stem for p in MODULES} >= {"maps", "localised", "spacetime", "spectra", "travelling", "mi_growth"}


@pytest.mark.parametrize("path", MODULES, ids=lambda p: p.name)
def test_figure_module_imports_no_numerical_module(path):
    bad = [name for name in _imports(path) if any(name == n or name.startswith(n + ".") for n in NUMERICAL)]
    assert not bad, f"{path.name} imports numerical modules {bad}: compute in a stage and store the result"


def test_the_check_sees_a_forbidden_import(tmp_path):
    probe = tmp_path / "probe.py"
    probe.write_text("def f():\n    from cradle.measurements.breathers import peak_compression\n"
                     "from cradle import models\nimport cradle.analyses.mi_diagram\n")
    assert {"cradle.measurements.breathers", "cradle.models", "cradle.analyses.mi_diagram"} <= set(_imports(probe))
