# Shared helpers: config validation (after any --config overrides), resolved
# parameters per entry, and the code each rule runs (derived from its imports).
import re

from snakemake.exceptions import WorkflowError

from cradle.pipeline import config as cc
from cradle import figures as _figures
from cradle.pipeline.codedeps import code_files
from cradle.pipeline.params import compact_scene

try:
    config.update(cc.validate(config))
except cc.ConfigError as err:
    raise WorkflowError(str(err)) from None

def code_of(*entries):
    """A rule's code inputs: its script (or module) and every cradle source file it can import,
    derived from the imports themselves (cradle.pipeline.codedeps), so an edit reruns exactly the
    jobs whose code reaches it."""
    return [str(e) for e in entries if str(e).endswith(".py")] + code_files(*entries, src="src")


def figure_code(label):
    """Code inputs of the job drawing ``label``: its adapter script and its drawing module."""
    registry = "FIGURES" if label in _figures.FIGURES else "DATASET_FIGURES"
    script = "workflow/scripts/figure.py" if registry == "FIGURES" else "workflow/scripts/dataset_figure.py"
    try:
        drawing = _figures.module_of(label, registry)
    except KeyError as err:
        raise WorkflowError(str(err)) from None
    return code_of(script, f"cradle.figures.{drawing}")


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
    from cradle.analyses import mistatistics as _mis

    spec = _mis.resolved_spec(config, variant)
    return [f"results/mi/batch/{variant}/N{N}-{m}-{c}.nc" for N in spec["N"] for m in _mis.MODELS
            for c in range(int(spec["chunks"]))]
