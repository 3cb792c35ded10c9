# cradle: G. James, "Nonlinear waves in Newton's cradle and the discrete
# p-Schrodinger equation", rebuilt. `snakemake -j2` builds every figure listed
# under `figures:` in config.yaml into results/figures/<label>.{pdf,png}.
#
# Stages (workflow/rules): homoclinic & map orbits (homoclinic.smk) -> initial data,
# exact and DpS integration and their comparison, one job per scene (simulate.smk) ->
# figures (figures.smk) and the claims table (checks.smk); the analyses beyond the paper
# (analyses.smk, their batches too) and work-precision (workprecision.smk); movies of
# the scenes' runs (movies.smk, target `movies`, not in `all`).


import os

# one BLAS thread per job: the dense solves here are small, and with one job per core (-j2 on
# 2 cores) more threads only contend; every job inherits this (set OPENBLAS_NUM_THREADS to override)
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


configfile: "config.yaml"


report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"
include: "workflow/rules/homoclinic.smk"
include: "workflow/rules/simulate.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/workprecision.smk"
include: "workflow/rules/checks.smk"
include: "workflow/rules/analyses.smk"
include: "workflow/rules/legacy_analyses.smk"
include: "workflow/rules/movies.smk"


PAPER = figure_targets() + [L.path("checks", ext=ext) for ext in ("csv", "md")]


# the reduced form of every analysis beyond the paper (cradle.analyses.registry), and work-precision
BEYOND = [
    f
    for a in ANALYSES.values()
    for f in (L.analysis_output(a.name, a.forms[0], a.forms[0]), *L.analysis_figures(a.name, a.forms[0], a.forms[0]).values())
]
BEYOND += [f for a in LEGACY.values() for f in (a.output(a.forms[0]), *a.figure(a.forms[0]).values())]
BEYOND += figure_targets(["work-precision"])


rule all:
    # the paper, and the analyses beyond it in their reduced forms (workflow/rules/analyses.smk, workprecision.smk)
    default_target: True
    input:
        PAPER,
        BEYOND,


rule paper:
    # every paper figure under `figures:` in config.yaml, and the claims table
    input:
        PAPER,
