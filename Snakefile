# cradle: G. James, "Nonlinear waves in Newton's cradle and the discrete
# p-Schrodinger equation", rebuilt. `snakemake -j2` builds every figure listed
# under `figures:` in config.yaml into results/figures/<label>.{pdf,png}.
#
# Stages (workflow/rules): homoclinic & map orbits (homoclinic.smk) -> initial data,
# exact and DpS integration and their comparison, one job per scene (simulate.smk) ->
# figures (figures.smk); the claims table (paper-checks) and the analyses beyond the paper, work-precision
# among them, with their batches (analyses.smk, generated from cradle.analyses.registry); movies of
# the scenes' runs (movies.smk, target `movies`, not in `all`).


import os

# one BLAS thread per job: the dense solves here are small, and with one job per core (-j2 on
# 2 cores) more threads only contend; every job inherits this (set OPENBLAS_NUM_THREADS to override)
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")
# every job watches that this Snakemake is still there, and stops when it is killed (cradle.pipeline.orphan);
# set here for the jobs, never read from the user's environment (so not an `envvars:` requirement)
os.environ.update(CRADLE_SNAKEMAKE_PID=str(os.getpid()))


# config.yaml read first by cradle's bounded reader: Snakemake's own takes minutes over a huge file and
# stops with a traceback on one that is not UTF-8 (files given by --configfile it reads before this file)
if os.path.exists("config.yaml"):
    from snakemake.exceptions import WorkflowError
    from cradle.pipeline.config import ConfigError, read_yaml

    try:
        read_yaml("config.yaml")
    except ConfigError as err:
        raise WorkflowError(str(err)) from None


configfile: "config.yaml"


report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"
include: "workflow/rules/homoclinic.smk"
include: "workflow/rules/simulate.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/analyses.smk"
include: "workflow/rules/movies.smk"


# the paper's figures and its claims table (the analysis paper-checks: its netCDF file and its tables)
PAPER = figure_targets() + [
    L.analysis_output("paper-checks", "full", "full"),
    *L.analysis_drawn(ANALYSES["paper-checks"], "full", "full").values(),
]


# the reduced form of every analysis beyond the paper (cradle.analyses.registry)
BEYOND = [
    f
    for a in ANALYSES.values()
    for f in (L.analysis_output(a.name, a.forms[0], a.forms[0]), *L.analysis_drawn(a, a.forms[0], a.forms[0]).values())
]


#: a temporary file older than this at the start of a run is a killed job's (a job stops within
#: cradle.pipeline.orphan's grace of losing its Snakemake)
STALE_TEMPORARY_S = 60

#: every file under results/ when this run started (cradle.pipeline.restored)
BEFORE_RUN = {}


onstart:
    # a killed run's jobs stop by themselves (cradle.pipeline.orphan); what they were writing stays as a hidden
    # `.NAME.*.tmp` beside its target: removed here, before any job of this run starts (Snakemake's lock: no
    # other run writes in this folder now), once older than the watch's grace
    from cradle.data.io import remove_stale_temporaries
    from cradle.pipeline.restored import snapshot

    remove_stale_temporaries(L.ROOT, STALE_TEMPORARY_S)
    BEFORE_RUN.update(snapshot(L.ROOT))
    # a local build forks its jobs from one process that has imported what they import (cradle.pipeline.warm)
    from cradle.pipeline import warm

    warm.start(workflow)


onsuccess:
    from cradle.pipeline import warm

    warm.stop()


onerror:
    # a failed job's update() outputs come back as copies with a new time: set the old one back, so the
    # next run does not redo the readers of files whose content never changed
    from cradle.pipeline import warm
    from cradle.pipeline.restored import restore_times

    warm.stop()
    restore_times(BEFORE_RUN)


rule all:
    # the paper, and the analyses beyond it in their reduced forms (workflow/rules/analyses.smk)
    default_target: True
    input:
        PAPER,
        BEYOND,


rule paper:
    # every paper figure under `figures:` in config.yaml, and the claims table
    input:
        PAPER,
