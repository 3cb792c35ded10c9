"""compare_models: the two models as one Dataset, with the values of a scene's metrics stage."""
from __future__ import annotations

import numpy as np
import pytest

from cradle.measurements.comparison import compare_models
from cradle.pipeline import config as cc
from cradle.scenes import stages


def test_compare_models_is_the_metrics_stage_along_a_model_dimension():
    name = "tw-tiny"
    cfg = cc.validate({"defaults": {"alpha": 1.5},
                       "scenes": {name: {"N": 20, "bc": "periodic",
                                         "initial": {"kind": "travelling", "q": "pi/5", "omega_tw": 1.01},
                                         "t_end": 20.0, "store": {"every": 0.5}}}})
    spec = cc.scene(cfg, name)
    init = stages.initial_data(spec, name)
    ex, ap = stages.exact_run(spec, init, name), stages.dps_run(spec, init, name)
    met = stages.metrics(spec, ex, ap, name)
    A = ap["A_re"].values + 1j * ap["A_im"].values
    ds = compare_models(ex["t"].values, ex["x"].values, A, eps=init.attrs["eps"], a=init.attrs["a"])
    assert list(ds["model"].values) == ["exact", "dps"]
    np.testing.assert_array_equal(ds["x"].sel(model="dps").values, ap["x"].values)
    np.testing.assert_array_equal(ds["E"].values, met["E"].values)
    for model in ("exact", "dps"):
        np.testing.assert_array_equal(ds["spectrum"].sel(model=model).values, met[f"spectrum_{model}"].values)
    np.testing.assert_array_equal(ds["k"].values, met["k"].values)
    assert ds.attrs["E_max"] == met.attrs["E_max"] and ds["x"].attrs["long_name"]
    with pytest.raises(ValueError, match=r"x \(41, 20\) and A \(40, 20\) must both have shape"):
        compare_models(ex["t"].values, ex["x"].values, A[:-1], eps=0.01)
