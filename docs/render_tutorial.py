"""Run docs/tutorial.py (jupytext percent script) and write docs/tutorial.ipynb with its outputs.

    PYTHONPATH=src python docs/render_tutorial.py      # needs the extra `test` (jupytext, nbclient, ipykernel)

The notebook runs in docs/ (it finds the repository root itself) against results/ when the scene is built
there, else computes the scene into tutorial-runs/.
"""
from pathlib import Path

import jupytext
import nbclient

HERE = Path(__file__).resolve().parent

nb = jupytext.read(HERE / "tutorial.py")
nbclient.NotebookClient(nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(HERE)}}).execute()
jupytext.write(nb, HERE / "tutorial.ipynb")
print(f"wrote {HERE / 'tutorial.ipynb'}")
