# cradle: G. James, "Nonlinear waves in Newton's cradle and the discrete
# p-Schrodinger equation", rebuilt. `snakemake -j2` builds every figure listed
# under `figures:` in config.yaml into results/figures/<label>.{pdf,png}.
#
# Stages (workflow/rules): homoclinic & map orbits -> initial data ->
# exact and DpS integration -> metrics -> figures.


configfile: "config.yaml"


include: "workflow/rules/common.smk"
include: "workflow/rules/homoclinic.smk"
include: "workflow/rules/initial.smk"
include: "workflow/rules/integrate.smk"
include: "workflow/rules/metrics.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/checks.smk"


PAPER = figure_targets() + ["results/paper_checks.csv", "results/paper_checks.md"]


rule all:
    default_target: True
    input:
        PAPER,


rule paper:
    # every paper figure under `figures:` in config.yaml, and the claims table
    input:
        PAPER,
