"""The two models side by side as one Dataset: a lattice run (nc) and a DpS run (dfnls) read through the
ansatz (ansatz), with the relative error E(t) of figure plot4-5 and the spectra |x_hat_k(t)| on Gamma*
(:mod:`cradle.measurements.compare`), from arrays a user computed (:func:`compare_models`)."""
from __future__ import annotations

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike

from cradle.data.io import make_dataset
from cradle.data.variables import MODEL, MODELS, VARIABLES, Var
from cradle.measurements import compare

#: the variables of :func:`compare_models`, declared as every stored variable is
COMPARISON = {
    "model": MODEL,
    "t": VARIABLES["t"],
    "n": VARIABLES["n"],
    "k": VARIABLES["k"],
    "x": Var(("model", "t", "n"), "bead displacement x_n(t): the lattice run (exact), x^app of (ansatz) (dps)"),
    "E": VARIABLES["E"],
    "spectrum": Var(("model", "t", "k"), "|x_hat_k(t)| on Gamma* of the model's displacements"),
}


def compare_models(t: ArrayLike, x: ArrayLike, A: ArrayLike, *, eps: float, a: float | None = None) -> xr.Dataset:
    """The lattice (nc) against its DpS approximation (dfnls)/(ansatz) as one Dataset.

    ``t`` (T,): the times of (nc); ``x`` (T, N): the lattice displacements x_n(t) (``LatticeSolution.x``);
    ``A`` (T, N): the DpS amplitudes A_n at tau = eps^(alpha-1) t (``DpsSolution.A``); ``eps``: the small
    parameter of (ansatz); ``a``: the scale of E(t) (the wave's amplitude; default max_n |x_n(t_0)|).

    Returns ``x`` and ``spectrum`` along a ``model`` dimension of names (``"exact"``, ``"dps"``, the
    latter x^app = eps (A e^{it} + c.c.)), ``E`` (t) and the scale and extremes of E as attributes,
    with the same values as a scene's metrics file (:func:`cradle.scenes.stages.metrics`)::

        ds = compare_models(t, lattice.x, dps.A, eps=data.eps, a=data.info["a"])
        ds.x.sel(model="dps", t=100.0)
    """
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    A = np.asarray(A)
    if x.ndim != 2 or x.shape[0] != t.size or np.shape(A) != x.shape:
        raise ValueError(f"compare_models: x {x.shape} and A {np.shape(A)} must both have shape (len(t), N) "
                         f"= ({t.size}, N)")
    x_app = compare.approximate_displacement(A, t, eps)
    scale = float(np.max(np.abs(x[0]))) if a is None else float(a)
    E = compare.relative_error(x, x_app, scale)
    k, xh_exact = compare.spatial_dft(x)
    _, xh_dps = compare.spatial_dft(x_app)
    return make_dataset({"x": np.stack([x, x_app]), "E": E, "spectrum": np.stack([np.abs(xh_exact), np.abs(xh_dps)])},
                        coords={"model": np.array(MODELS, dtype=object), "t": t, "n": np.arange(x.shape[1]), "k": k},
                        attrs={"eps": float(eps), "E_scale": scale, "E_max": float(np.max(E)),
                               "E_final": float(E[-1])},
                        variables=COMPARISON, title="exact lattice (nc) against DpS (dfnls)/(ansatz)")
