# Shared helpers: config validation (after any --config overrides), resolved
# parameters per entry, and the code each rule runs (derived from its imports).
import re
import shlex
import sys

from snakemake.exceptions import WorkflowError

from cradle.pipeline import config as cc
from cradle import figures as _figures
from cradle.pipeline import layout as L
from cradle.pipeline.codedeps import code_stamps, stamp_all
from cradle.specs.declare import from_plain, plain
from cradle.pipeline.config.movies import Movies

#: the Python that runs this workflow: shell rules call it rather than whatever `python` is first on PATH
#: (a venv's snakemake run without activating the venv would otherwise reach a Python without cradle)
PYTHON = shlex.quote(sys.executable)

try:
    for _file in workflow.configfiles:  # Snakemake's own loader keeps the last of two equal keys silently
        cc.read_yaml(_file)
    config.update(cc.validate(config))
except cc.ConfigError as err:
    raise WorkflowError(str(err)) from None


# every stamp written now, before Snakemake's inventory of the files (cradle.pipeline.codedeps.stamp_all)
stamp_all()


#: entries -> their code stamp, each written once per read of the Snakefile
_CODE = {}


def code_of(*entries):
    """A rule's code input: the stamp of the code of its script (or module) and of every cradle source file
    it can import, derived from the imports themselves (cradle.pipeline.codedeps); the stamp holds the
    fingerprint of each module's code and is rewritten only when one changes, so an edit to the code reruns
    exactly the jobs whose code reaches it, and an edit to a comment or a docstring reruns nothing. Every
    stamp is asked for when the Snakefile is read (the rules, and the input functions' stamps below and in
    analyses.smk), before Snakemake's inventory of the files."""
    if entries not in _CODE:
        _CODE[entries] = code_stamps(*entries, src="src")
    return _CODE[entries]


def figure_code(label):
    """Code inputs of the job drawing paper figure ``label``: its adapter script and its drawing module."""
    try:
        drawing = _figures.module_of(label)
    except KeyError as err:
        raise WorkflowError(str(err)) from None
    return code_of("workflow/scripts/figure.py", f"cradle.figures.{drawing}")


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
    if kind in ("map", "homoclinic"):
        return [L.path(kind, name=name)]
    return list(L.scene_paths(name, parts=L.RUN_PARTS).values())


def figure_targets(labels=None):
    labels = config["figures"] if labels is None else labels
    return [f for label in labels for f in L.figure_paths(label).values()]


def initial_inputs(w):
    """A breather scene reads its homoclinic solution."""
    ini = config["scenes"][w.scene]["initial"]
    return [L.path("homoclinic", name=ini["homoclinic"])] if ini["kind"] == "breather" else []


def figure_inputs(w):
    return [f for name in config["figures"][w.label]["scenes"] for f in scene_files(name)]


def checks_inputs(w):
    files = [f for name in config["scenes"] for f in scene_files(name)]
    files += [L.path("initial", scene=name) for name in config["scenes"]]
    return files + [L.path("homoclinic", name=name) for name in config["homoclinic"]]


def movie_targets():
    """The movies (mp4 and gif) of every scene under `movies.scenes` (workflow/rules/movies.smk)."""
    try:
        scenes = Movies.resolve(config)["scenes"]
    except cc.ConfigError as err:
        raise WorkflowError(str(err)) from None
    return [L.path("movie", scene=s, ext=ext) for s in scenes for ext in ("mp4", "gif")]


# the minute movies of the desk toys under movies.desk_toy_minute.toys (rule desk_toy_minute_movies, movies.smk)
def desk_toy_minute_movie_targets():
    from cradle.analyses.desk_toy_minute_movie import MinuteMovie

    try:
        toys = from_plain(
            MinuteMovie, dict(Movies.resolve(config).get("desk_toy_minute") or {}), where="movies.desk_toy_minute"
        ).toys
    except cc.ConfigError as err:
        raise WorkflowError(str(err)) from None
    return [L.path("movie", scene=f"desk-toy-minute-{t}", ext=ext) for t in toys for ext in ("mp4", "gif")]


# the movies of the desk toys of the desk-toy analysis's full form (rule desk_toy_movies, movies.smk)
def desk_toy_movie_targets():
    from cradle.analyses.desk_toy import label

    spec = analysis_spec(ANALYSES["desk-toy"], FULL)
    toys = [label(n, k) for n in spec.chains for k in spec.lifted]
    return [L.path("movie", scene=f"desk-toy-{t}", ext=ext) for t in toys for ext in ("mp4", "gif")]
