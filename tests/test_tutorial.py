"""docs/tutorial.ipynb (rendered from docs/tutorial.py) runs from start to end on a shortened scene, and the
rendered notebook has the script's cells."""
from __future__ import annotations

import time
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "docs" / "tutorial.py"
NOTEBOOK = ROOT / "docs" / "tutorial.ipynb"

jupytext = pytest.importorskip("jupytext", reason="jupytext reads docs/tutorial.py: pip install -e '.[test]'")
nbclient = pytest.importorskip("nbclient", reason="nbclient runs the notebook: pip install -e '.[test]'")
pytest.importorskip("ipykernel", reason="the notebook's Python kernel: pip install -e '.[test]'")

# tw-weak of config.yaml (plot4-5), run to t = 20 instead of 621.95
TINY = {
    "defaults": {"alpha": 1.5},
    "scenes": {"tw-weak": {"N": 50, "bc": "periodic",
                           "initial": {"kind": "travelling", "q": "pi/5", "omega_tw": 1.01, "phi": 0.0},
                           "t_end": 20.0, "store": {"snapshots": [20.0], "every": 0.5}}},
    "figures": {"plot4-5": {"scenes": ["tw-weak"], "times": [20.0]}},
}


def _sources(nb):
    return [(c.cell_type, c.source.strip()) for c in nb.cells]


def test_rendered_notebook_has_the_cells_of_the_script():
    script, rendered = jupytext.read(SCRIPT), jupytext.read(NOTEBOOK)
    assert _sources(rendered) == _sources(script), "docs/tutorial.ipynb is stale: jupytext --to ipynb docs/tutorial.py"


@pytest.mark.slow
def test_tutorial_runs_on_a_short_scene(tmp_path):
    (tmp_path / "tiny.yaml").write_text(yaml.safe_dump(TINY, sort_keys=False))
    nb = jupytext.read(SCRIPT)
    params = [c for c in nb.cells if "parameters" in c.metadata.get("tags", [])]
    assert len(params) == 1
    params[0].source = ('RESULTS = "results"\nCONFIG = "tiny.yaml"\nSCENE = "tw-weak"\nT_EXTEND = 30.0\n'
                        'WORK = "tutorial-runs"\n')
    t0 = time.perf_counter()
    nbclient.NotebookClient(nb, timeout=120, kernel_name="python3",
                            resources={"metadata": {"path": str(tmp_path)}}).execute()
    wall = time.perf_counter() - t0
    work = tmp_path / "tutorial-runs"
    for rel in ("runs/sim/tw-weak/exact.nc", "changed/figures/plot4-5.png", "exact-longer.nc", "my-figure.png"):
        assert (work / rel).exists(), rel
    out = "".join(o.get("text", "") for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", []))
    assert "stored part bitwise equal: True" in out
    assert wall < 60, f"the tutorial took {wall:.0f} s on the short scene"
