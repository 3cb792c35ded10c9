"""The committed docs/tutorial.ipynb shows what it draws: every code cell that plots, shows or draws a figure has an
image among its outputs (read from the notebook's JSON: no Jupyter needed)."""
from __future__ import annotations

import json
import re
from pathlib import Path

NOTEBOOK = Path(__file__).resolve().parents[1] / "docs" / "tutorial.ipynb"
#: a cell that makes a figure: xarray's or matplotlib's plot, pyplot's show, imshow, cradle.figures.draw
DRAWS = re.compile(r"\.plot(\.\w+)?\(|\bplt\.show\(|\.imshow\(|\bdraw\(")


def test_every_plotting_cell_of_the_rendered_tutorial_has_an_image():
    cells = [c for c in json.loads(NOTEBOOK.read_text())["cells"] if c["cell_type"] == "code"]
    plotting = [c for c in cells if DRAWS.search("".join(c["source"]))]
    assert len(plotting) >= 5   # sections 2, 3, 4, 5 and 6 each draw
    blank = ["".join(c["source"]).splitlines()[0] for c in plotting
             if not any("image/png" in o.get("data", {}) for o in c.get("outputs", []))]
    assert blank == [], f"no image in the cells starting {blank}: python docs/render_tutorial.py"
