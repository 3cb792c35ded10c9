"""One naming scheme in every analysis output: a coordinate whose values name things (a model, a family, a damping
term, a zone) holds the names as strings, so ``ds.sel(model="(nc)")`` works; integer coordinates are counts and
indices.

The rule, read from what a file says of its own coordinates (:func:`naming_integer_coordinates`): an integer
coordinate is fine when it counts or numbers things (beads, bonds, seeds, cases, sizes, swings: "bead index",
"number N of beads", "seed of ..."); it names things, and fails, when

* it carries CF's ``flag_values`` or ``flag_meanings`` (the CF way of saying each value stands for a category);
* its long name or comment sends the reader to a list of names elsewhere ("names in family_names");
* its long name says what a value stands for ("0 launch, 1 target", "below (0) or above (1)", "0: first bead");
* or its dimension is one that names a category (:data:`NAMING_DIMS`: model, family, term, zone, ...).

A dimension of :data:`NAMING_DIMS` without any coordinate (its own or its parent group's) fails as well: there
is nothing to ``sel`` by.

The walk covers the outputs this suite computes on tiny specs (the analyses that read no scene: desk-toy,
dissipation, dps-validity, trapping from its batches; breathers in its reduced form) and, when a results folder
is at hand (``$CRADLE_RESULTS`` or ./results), every analysis file in it.
"""
from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cradle.analyses.registry import ANALYSES
from cradle.data.io import open_tree
from cradle.pipeline import layout
from cradle.specs.declare import from_plain

ROOT = Path(__file__).resolve().parents[2]
RESULTS = Path(os.environ.get("CRADLE_RESULTS", ROOT / "results"))

#: dimensions whose coordinate names categories, never counts
NAMING_DIMS = frozenset({"model", "family", "term", "zone", "scene", "definition", "method", "kind", "side",
                         "end", "cradle", "pair", "stat", "incident"})
#: a long name or comment that points to names kept elsewhere
_POINTS_TO_NAMES = re.compile(r"names in|\w_names\b")
#: a long name that says what a value stands for: "0 launch", "(0)", "0: first", "0 the lattice"
_ENUMERATES = re.compile(r"(?<![\w.+^])0(?::|\)| [a-z(])")


def naming_integer_coordinates(tree: xr.DataTree) -> list[str]:
    """``group/coordinate: why`` for every integer coordinate of ``tree`` whose values name things (module
    docstring)."""
    bad = []
    for node in tree.subtree:
        ds = node.to_dataset(inherit=False)
        for name in ds.coords:
            var = ds[name]
            if not (np.issubdtype(var.dtype, np.integer) or np.issubdtype(var.dtype, np.bool_)):
                continue
            text = f"{var.attrs.get('long_name', '')} {var.attrs.get('comment', '')}"
            why = ("flag_values/flag_meanings" if {"flag_values", "flag_meanings"} & set(var.attrs) else
                   "names kept elsewhere" if _POINTS_TO_NAMES.search(text) else
                   "values stand for names" if _ENUMERATES.search(text) else
                   "a dimension of names" if str(name) in NAMING_DIMS else None)
            if why is not None:
                bad.append(f"{node.path}/{name} ({var.values[:4].tolist()}, {text.strip()!r}): {why}")
        seen = node.to_dataset(inherit=True).coords
        bad += [f"{node.path}/{dim}: a dimension of names without its names" for dim in ds.dims
                if str(dim) in NAMING_DIMS and dim not in seen]
    return bad


def test_the_rule_tells_names_from_counts():
    """The long names the analyses' integer coordinates had before their names became strings are caught; counts
    and indices pass."""
    def tree(name, values, **attrs):
        return xr.DataTree(xr.Dataset(coords={name: (name, np.asarray(values), attrs)}))

    named = [tree("model", [0, 1, 2], long_name="model index: 0 the lattice (nc), then the hard-sphere cradle"),
             tree("f", [0, 1], long_name="breather family index (names in family_names)"),
             tree("side", [0, 1], long_name="grid breather below (0) or above (1) the exchange in omega_b"),
             tree("z", [0, 1, 2], long_name="zone of the chain: 0 launch, 1 target, 2 lead"),
             tree("e", [0, 1], long_name="0: first bead of the target, 1: one past its last"),
             tree("term", [0, 1], long_name="index of the damping term (0 on-site, 1 contact)"),
             tree("s", [0, 1], long_name="outcome", flag_values=[0, 1], flag_meanings="merge bound")]
    for t in named:
        assert len(naming_integer_coordinates(t)) == 1, t
    counts = [tree("n", [0, 1, 2], long_name="bead index (bond n joins beads n and n+1)"),
              tree("swing", [1, 2], long_name="out-swing k = 1, 2, ...: the largest swing at t = k pi / omega_0"),
              tree("period", [0, 1], long_name="swing period k: [2 pi k, 2 pi (k+1)) / omega_0"),
              tree("halfwidth", [4, 8], long_name="half-width w of the core window (2w+1 beads)"),
              tree("seed", [1, 2], long_name="seed of np.random.default_rng of the disorder draw"),
              tree("model", ["(nc)", "hard spheres e = 1"], long_name="model")]
    for t in counts:
        assert naming_integer_coordinates(t) == [], t
    bare = xr.DataTree(xr.Dataset({"lifetime": (("family",), [1.0, 2.0])}))
    assert naming_integer_coordinates(bare) == ["//family: a dimension of names without its names"]


# ------------------------------------------------------------------------ the outputs computed here

def _desk_toy():
    from cradle.analyses import desk_toy as dk

    spec = from_plain(dk.DeskToyRuns, {"chains": [4], "lifted": [1], "swings": 2, "samples": 64,
                                       "restitution": [1.0, 0.9], "rtol": 1e-12, "thresholds": [0.9, 0.5]})
    tree = dk.compute(spec, {})
    group = tree["n4-lifted1"]
    assert group["x"].sel(model="(nc)").shape == group["x"].isel(model=0).shape
    assert list(group["model"].values) == dk.model_names(spec) == ["(nc)", "hard spheres e = 1",
                                                                   "hard spheres e = 0.9"]
    return tree


def _dissipation():
    from cradle.analyses import dissipation as dis
    from cradle.analyses.protocol import FULL, form_spec

    spec = form_spec(from_plain(dis.Dissipation, {
        "N": 16, "wave_mode": 2, "waves": [1.01], "onsite": [0.05, 0.1], "contact": [1.0, 3.0], "t_end": 40.0,
        "window": 10.0,
        "validity_eps": [0.01, 0.005], "validity_T": [0.5]}), FULL)
    tree = dis.compute(spec)
    lt = tree["lifetimes"]
    assert list(lt["family"].values) == ["breather", "wave-1.01"] and list(lt["term"].values) == ["onsite", "contact"]
    assert float(lt["eps"].sel(family="breather")) == float(lt["eps"].values[0])
    assert tree["steel"]["lifetime_closed_steel"].sel(family="wave-1.01", term="onsite").size == 2   # two levels
    return tree


def _dps_validity():
    from cradle.analyses import dps_validity as dv

    spec = from_plain(dv.DpsValidity, {"N_wave": 10, "N_breather": 32, "N_noise": 50, "noise_amplitude": 0.01,
                                       "seed": 20261122, "alpha": [1.5], "eps_min": [1e-3], "eps_max": 1e-2,
                                       "n_eps": 3, "T": [1.0], "families": ["tw-pi5", "tw-4pi5"],
                                       "sample_every": 0.2, "dt_factor": 0.01, "dps_rtol": 1e-11, "chunk": 20000})
    tree = dv.compute(spec, {})
    for group in ("errors", "fits", "checks"):
        assert list(tree[group]["family"].values) == ["tw-pi5", "tw-4pi5"], group
    assert tree["errors"]["rel_error"].sel(family="tw-4pi5").shape == (1, 3, 1)
    return tree


def _trapping():
    from cradle.analyses import trapping as tr

    spec = from_plain(tr.Trapping, {"launch": 5, "back": 10, "length": 12, "lengths": [], "lead": 30, "edge": 5,
                                    "tau_end": 40.0, "times": [30.0, 40.0], "windows": [10.0, 20.0],
                                    "striker": [1.0], "breather": [0.3], "sigmas": [0.1], "seeds": 1})
    inputs = {f"batch/{key}": tr.run_batch(spec, key) for key in tr.batch_keys(spec)}
    tree = tr.compute(spec, inputs)
    runs = tree["runs"]
    assert list(runs["zone"].values) == ["launch", "target", "lead"]
    assert np.array_equal(runs["zone_energy"].sel(zone="target").values, runs["zone_energy"].values[..., 1])
    assert list(tree["examples"]["end"].values) == ["start", "stop"]
    return tree


def _breathers():
    """The reduced form `all` builds (config.yaml), the smallest that has families and exchanges."""
    from cradle.pipeline import config as cc

    a = ANALYSES["breathers"]
    tree = a.compute(cc.analysis_spec(cc.load(ROOT / "config.yaml"), "breathers", a.forms[0]), {})
    assert list(tree["family"].values) == [s.strip() for s in str(tree.attrs["family_names"]).split(",")]
    assert list(tree["exchanges"]["side"].values) == ["below", "above"]
    assert tree["families"]["energy"].sel(family="ring bond").shape == (tree.sizes["omega"],)
    return tree


COMPUTED = {"breathers": _breathers, "desk-toy": _desk_toy, "dissipation": _dissipation, "dps-validity": _dps_validity,
            "trapping": _trapping}


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(COMPUTED))
def test_outputs_computed_here_name_things_by_strings(name):
    tree = COMPUTED[name]()
    assert naming_integer_coordinates(tree) == []


def _result_files() -> list[Path]:
    out = []
    for name, a in sorted(ANALYSES.items()):
        for form in a.forms:
            path = Path(layout.analysis_output(name, form, a.forms[0], RESULTS))
            if path.exists():
                out.append(path)
    return out


@pytest.mark.parametrize("path", _result_files(), ids=lambda p: str(p.relative_to(RESULTS)))
def test_every_analysis_file_of_the_results_names_things_by_strings(path):
    """Files written before this rule fail here too: rebuild them (`snakemake --forcerun <analysis>`)."""
    assert naming_integer_coordinates(open_tree(path)) == []
