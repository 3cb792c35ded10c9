# Shared helpers: config validation (after any --config overrides), resolved
# parameters per entry, and the src/cradle sources each rule depends on.
import re
from pathlib import Path

from snakemake.exceptions import WorkflowError

from cradle import config as cc
from cradle import figures as _figures

try:
    config.update(cc.validate(config))
except cc.ConfigError as err:
    raise WorkflowError(str(err)) from None

SRC = Path("src/cradle")


def sources(*modules):
    """The cradle source files a rule uses (a change to them reruns the rule)."""
    files = []
    for m in modules:
        p = SRC / m
        files += sorted(str(f) for f in p.glob("*.py")) if p.is_dir() else [str(p.with_suffix(".py"))]
    return files


CORE = ("__init__", "io", "variables", "stages", "runner", "lattice", "dps")


def names_regex(section):
    """Wildcard constraint matching exactly the entries of one config section."""
    return "|".join(re.escape(k) for k in config.get(section, {})) or "(?!)"


def kind_of(name):
    """Which section a name read by a figure lives in: map, homoclinic or scenes."""
    for section in ("map", "homoclinic", "scenes"):
        if name in config.get(section, {}):
            return section
    raise WorkflowError(f"unknown scene {name!r}")


def scene_files(name):
    """The netCDF files a figure reads for one name of its `scenes:` list."""
    kind = kind_of(name)
    if kind == "map":
        return [f"results/map/{name}.nc"]
    if kind == "homoclinic":
        return [f"results/homoclinic/{name}.nc"]
    return [f"results/sim/{name}/exact.nc", f"results/sim/{name}/dps.nc", f"results/metrics/{name}.nc"]


def figure_targets(labels=None):
    labels = config["figures"] if labels is None else labels
    return [f"results/figures/{label}.{ext}" for label in labels for ext in ("pdf", "png")]


def figure_module(label):
    """The figures/*.py module that draws ``label`` (found in the sources, nothing imported)."""
    try:
        return str(SRC / "figures" / f"{_figures.module_of(label)}.py")
    except KeyError as err:
        raise WorkflowError(str(err)) from None


def initial_inputs(w):
    """A breather scene reads its homoclinic solution."""
    ini = config["scenes"][w.scene]["initial"]
    return [f"results/homoclinic/{ini['homoclinic']}.nc"] if ini["kind"] == "breather" else []


def figure_inputs(w):
    return [f for name in config["figures"][w.label]["scenes"] for f in scene_files(name)]


def checks_inputs(w):
    files = [f for name in config["scenes"] for f in scene_files(name)]
    files += [f"results/initial/{name}.nc" for name in config["scenes"]]
    return files + [f"results/homoclinic/{name}.nc" for name in config["homoclinic"]]


def mi_growth_inputs(w):
    """The initial data and the two runs of every scene measured by mi-growth."""
    files = []
    for name in config["beyond"]["mi_growth"]["scenes"]:
        files += [f"results/initial/{name}.nc", f"results/sim/{name}/exact.nc", f"results/sim/{name}/dps.nc"]
    return files


def mi_batches(variant):
    """The batch files of one mi-statistics variant (reduced, full)."""
    from cradle import mistatistics as _mis

    spec = _mis.resolved_spec(config, variant)
    return [f"results/mi/batch/{variant}/N{N}-{m}-{c}.nc" for N in spec["N"] for m in _mis.MODELS
            for c in range(int(spec["chunks"]))]
