"""Drawing leaves the session's matplotlib alone: the backend a user (a notebook) chose and pyplot's open figures
are what they were after importing cradle.figures, drawing and saving paper figures and rendering movie frames."""
from __future__ import annotations

import subprocess
import sys

CODE = """
import matplotlib
matplotlib.use("svg")                      # a session's own choice (a notebook's is its inline backend)
import matplotlib.pyplot as plt
plt.figure()                               # and a figure of its own
import numpy as np, xarray as xr
from pathlib import Path
from cradle.figures import draw, drawer
from cradle.figures.movie import MovieSpec, render
from cradle.pipeline import config as cc
from cradle.scenes import stages

cfg = cc.validate({"scenes": {"small": {"N": 20, "bc": "periodic",
                                        "initial": {"kind": "travelling", "q": "4pi/5", "omega_tw": 1.1},
                                        "t_end": 20.0, "store": {"every": 0.5}}}})
spec = cc.scene(cfg, "small")
init = stages.initial_data(spec, "small")
ex, ap = stages.exact_run(spec, init, "small"), stages.dps_run(spec, init, "small")
data = {"small": {"exact": ex, "dps": ap, "metrics": stages.metrics(spec, ex, ap, "small")}}
draw("plot4-5", data, {"scenes": ["small"], "times": [20.0]}, Path(OUT) / "plot4-5")
drawer("fft106")(data, {"scenes": ["small"], "times": [0.0, 5.0, 10.0, 15.0, 20.0]})
both = lambda v: xr.DataArray(np.stack([v, v]), dims=("model", "t", "n"))
scene = xr.Dataset({"x": both(ex["x"].values), "force": both(ex["force"].values)},
                   coords={"model": ["exact", "dps"], "t": ex["t"].values, "n": ex["n"].values}, attrs=dict(ex.attrs))
frames = render(scene, MovieSpec(fps=2, duration=1.0, width=320, height=180))
next(frames), next(frames)
print(matplotlib.get_backend(), plt.get_fignums(), sorted(p.name for p in Path(OUT).iterdir()))
"""


def test_drawing_keeps_the_chosen_backend_and_pyplots_figures(tmp_path):
    out = subprocess.run([sys.executable, "-c", f"OUT = {str(tmp_path)!r}\n" + CODE], capture_output=True,
                         text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.split() == ["svg", "[1]", "['plot4-5.pdf',", "'plot4-5.png']"]
