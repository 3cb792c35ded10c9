# ---
# jupyter:
#   jupytext:
#     formats: ipynb,py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # cradle tutorial: from a stored scene to a figure of your own
#
# This notebook walks through what a researcher does first with the rebuilt results of
# G. James, *Nonlinear waves in Newton's cradle and the discrete p-Schrödinger equation* (2011):
#
# 1. open a scene's two runs (the lattice (nc) and its DpS approximation (dfnls) through (ansatz)) with
#    `cradle.open_scene`;
# 2. plot exact against DpS;
# 3. read the provenance and the energy drift every file carries;
# 4. change a parameter and rebuild one figure (`plot4-5`);
# 5. extend a run to a later time;
# 6. call `integrate_lattice` on initial data of your own and make a figure of your own.
#
# The source is `docs/tutorial.py` (a jupytext "percent" script); `docs/tutorial.ipynb` is rendered from it,
# with its outputs, by `python docs/render_tutorial.py` (`jupytext --to ipynb docs/tutorial.py` renders it
# without outputs). Run it from the repository root or from `docs/`. It reads the
# workflow's `results/` when the scene is built there (`snakemake -j2 paper`) and otherwise computes the
# scene itself with `cradle run` into `tutorial-runs/` (a few seconds); it never writes into `results/`.
# The test suite runs it on a shortened scene (`tests/test_tutorial.py`).

# %% tags=["parameters"]
RESULTS = "results"        # the workflow's results folder
CONFIG = "config.yaml"     # the workflow's config
SCENE = "tw-weak"          # plot4-5: a weakly nonlinear travelling wave, N = 50, q = pi/5, omega_tw = 1.01
T_EXTEND = 700.0           # section 5: the exact run continued to this time
WORK = "tutorial-runs"     # everything this notebook writes goes here

# %%
import os
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import yaml

import cradle
from cradle.pipeline.cli import main as cradle_cli

# the repository root: this notebook lives in docs/, and may be started from there or from the root
ROOT = next(p for p in (Path.cwd(), Path.cwd().parent) if (p / "Snakefile").exists() or (p / CONFIG).exists())
os.chdir(ROOT)
RESULTS, CONFIG, WORK = Path(RESULTS), Path(CONFIG), Path(WORK)
print("repository:", ROOT)

# %% [markdown]
# ## 1. Open a scene
#
# A scene is one initial condition run twice: the exact lattice (nc) in `results/sim/<scene>/exact.nc` and
# the DpS approximation in `dps.nc`, compared in `results/metrics/<scene>.nc`. `cradle.open_scene` reads the
# three into one `xarray.Dataset`; `x` (displacements) and `force` (bond forces, bond n joins beads n and
# n+1) get a `model` dimension. If the workflow has not built the scene, `cradle run` computes it here
# (the same code as the workflow's `simulate` job).

# %%
if (RESULTS / "sim" / SCENE / "exact.nc").exists() and (RESULTS / "sim" / SCENE / "dps.nc").exists():
    SOURCE = RESULTS
else:
    SOURCE = WORK / "runs"
    assert cradle_cli(["run", SCENE, "--out", str(SOURCE), "--config", str(CONFIG)]) == 0
ds = cradle.open_scene(SCENE, root=SOURCE)
ds  # noqa: B018 - the notebook shows the Dataset

# %% [markdown]
# ## 2. Exact against DpS
#
# The profiles x_n(t) of both models at the last stored time, and the relative error
# E(t) = ||x^app(t) - x(t)||_inf / a of figure plot4-5 (stored in the metrics file).

# %%
t_last = float(ds.t[-1])
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.2), constrained_layout=True)
ds.x.sel(t=t_last).plot.line(x="n", hue="model", ax=ax1, marker="o", ms=3, add_legend=False)
ax1.legend(list(ds.model.values), title="model", loc="center left", bbox_to_anchor=(1.0, 0.5))  # beside the data
ax1.set_title(f"x_n(t = {t_last:g})")
ds.E.plot(ax=ax2)
ax2.set_title("relative error E(t) of the DpS approximation")
plt.show()
print(f"E at the end: {float(ds.E[-1]):.3g}; largest: {float(ds.E.max()):.3g}")

# %% [markdown]
# ## 3. Provenance and energy drift
#
# Every file carries the parameters that made it, the integrator and its accuracy, the measured energy drift
# and wall time, and its provenance. Attributes that differ between the two runs are prefixed `exact_` and
# `dps_`. The lattice Hamiltonian (ham) is stored as `energy`: its drift at the stored times is bounded by the
# drift over every step that the run recorded (`exact_energy_drift`).

# %%
for key in ("scene", "alpha", "N", "bc", "exact_integrator", "exact_dt", "exact_energy_drift",
            "exact_max_energy_drift_allowed", "exact_wall_time_s", "dps_integrator", "dps_rtol",
            "git_commit", "params_sha256", "command", "software_versions"):
    print(f"{key:32s} {ds.attrs.get(key)}")
drift = (ds.energy - ds.energy[0]) / ds.energy[0]
drift.attrs = {"long_name": "relative energy drift"}   # not the Hamiltonian's own label
print(f"max |H(t) - H(0)| / H(0) at the stored times: {float(abs(drift).max()):.3g} "
      f"(over every step: {ds.attrs['exact_energy_drift']:.3g})")
assert float(abs(drift).max()) <= ds.attrs["exact_energy_drift"] * (1 + 1e-9)
drift.plot(figsize=(6, 2.5))
plt.title("relative energy drift of the exact run")
plt.show()

# %% [markdown]
# The command line prints the same, grouped: `cradle describe results/sim/tw-weak/exact.nc`.
#
# ## 4. Change a parameter and rebuild one figure
#
# In the workflow, change the value in `config.yaml` (or in a copy given with `--configfile`) and ask for the
# figure: `snakemake -j2 results/figures/plot4-5.png`. Only the scene's `simulate` job and the figures that
# read it rerun (`snakemake -n` shows which). Here we do the same by hand, outside `results/`: raise the
# frequency omega_tw of the travelling wave (so its amplitude a, by (freq)), run the scene, and draw plot4-5
# from the new files with the workflow's own drawing function.

# %%
from IPython.display import Image, display

from cradle.figures import draw
from cradle.pipeline.outputs import load_inputs

cfg = yaml.safe_load(CONFIG.read_text())
old = cfg["scenes"][SCENE]["initial"]["omega_tw"]
cfg["scenes"][SCENE]["initial"]["omega_tw"] = 1.02
WORK.mkdir(parents=True, exist_ok=True)
(WORK / "changed.yaml").write_text(yaml.safe_dump(cfg, sort_keys=False))
changed = WORK / "changed"
assert cradle_cli(["run", SCENE, "--out", str(changed), "--config", str(WORK / "changed.yaml")]) == 0
stems = draw("plot4-5", load_inputs({SCENE: "scenes"}, changed), cfg["figures"]["plot4-5"],
             changed / "figures" / "plot4-5")
print(f"omega_tw {old} -> 1.02:", *map(str, stems))
display(Image(filename=str(changed / "figures" / "plot4-5.png"), width=700))

# %% [markdown]
# ## 5. Extend a run
#
# `cradle extend` continues a finished exact run from its last stored state and appends the new times to a
# new file. With a splitting integrator (the default `srkn6c`) the continued run takes exactly the steps one
# longer run would have taken, so the stored part is unchanged bit for bit.

# %%
exact_nc = SOURCE / "sim" / SCENE / "exact.nc"
longer = WORK / "exact-longer.nc"
assert cradle_cli(["extend", str(exact_nc), "--t-end", str(T_EXTEND), "--out", str(longer)]) == 0
from cradle.data.io import open_dataset

short, long_ = open_dataset(exact_nc), open_dataset(longer)
same = np.array_equal(long_.x.sel(t=short.t).values, short.x.values)
print(f"{exact_nc}: t up to {float(short.t[-1]):g}; {longer}: up to {float(long_.t[-1]):g}; "
      f"stored part bitwise equal: {same}")
assert same
drift_long = (long_.energy - long_.energy[0]) / long_.energy[0]
drift_long.attrs = {"long_name": "relative energy drift"}
drift_long.plot(figsize=(6, 2.5))
plt.axvline(float(short.t[-1]), color="0.5", ls=":")
plt.title("energy drift, original run and its extension (after the dotted line)")
plt.show()

# %% [markdown]
# ## 6. Your own initial data, your own figure
#
# `cradle.integrate_lattice(x0, v0, t_out, alpha=...)` integrates (nc) from any state (`help(cradle)` lists the
# rest of the public API: initial data, the DpS integrator, their comparison, ...). The classic experiment of a
# Newton's cradle: 30 beads at rest, touching, free ends, the first one hit with velocity 0.1. Without the
# pendulums, the kick would run down the chain as Nesterenko's compact solitary wave; in (nc) each bead is
# also pulled back to its rest position (the linear term x_n), and the kick instead becomes a localised
# excitation that drifts slowly down the chain, leaving small oscillations behind. We draw the bond forces in
# the space-time layout of the paper's figures (grey levels, white = beads apart), measure how fast the
# largest compression moves, and check that the energy (ham) is conserved.

# %%
N = 30
x0, v0 = np.zeros(N), np.zeros(N)
v0[0] = 0.1
t_out = np.linspace(0.0, 300.0, 3001)
sol = cradle.integrate_lattice(x0, v0, t_out, alpha=1.5, bc="free")
print(f"{sol.method}: {sol.n_steps} steps, energy drift {sol.energy_drift:.2g}, wall {sol.wall_time_s:.2f} s")
assert sol.energy_drift < 1e-6                                       # (ham) is conserved by the splitting
compression = np.maximum(-(sol.x[:, 1:] - sol.x[:, :-1]), 0.0)     # bond n: beads n and n+1
force = -compression ** 1.5                                          # V0'(x_{n+1} - x_n) of (vhertz)
fig, ax = plt.subplots(figsize=(6, 4), constrained_layout=True)
im = ax.imshow(force, origin="lower", aspect="auto", cmap="gray", extent=(-0.5, N - 1.5, t_out[0], t_out[-1]))
fig.colorbar(im, label="bond force $V_0'(x_{n+1}-x_n)$")
ax.set(xlabel="bond $n$", ylabel="$t$", title="bead 0 hit with velocity 0.1 (free ends)")
WORK.mkdir(parents=True, exist_ok=True)
fig.savefig(WORK / "my-figure.png", dpi=120)
plt.show()
where = np.argmax(compression, axis=1).astype(float)             # the most compressed bond at each t
fit = (t_out >= 20) & (t_out <= 250)
speed = np.polyfit(t_out[fit], where[fit], 1)[0]
print(f"most compressed bond against t, least-squares slope on t in [20, 250]: {speed:.3f} bonds per unit time")

# %% [markdown]
# ## Where next
#
# - `cradle animate loc1-pair --gif` (or `snakemake -j2 results/movies/loc1-pair.mp4`): the beads in motion.
# - `docs/usage.md`: every config key, every output; `docs/analyses.md`: the analyses beyond the paper.
# - `cradle scenes` lists every scene and figure, and what each needs.
