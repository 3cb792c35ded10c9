# Beyond the paper (config `beyond:`): Theorem 1 measured on exact travelling waves of (ad), and the
# modulational-instability map of the DpS plane waves. Targets: `snakemake -j2 theorem1 mi_diagram`,
# or the files results/theorem1/theorem1.nc, results/mi/mi-diagram.nc and
# results/figures/{theorem1,mi-diagram}.{pdf,png}. Each computation runs in well under a minute on
# one core; a figure rule reruns alone when only the drawing code changes.
from cradle.analyses import modulational as _mi
from cradle.analyses import theorem1 as _t1

# should `theorem1` or `mi-diagram` ever be listed under `figures:`, these rules draw them
ruleorder: theorem1_figure > figure
ruleorder: mi_diagram_figure > figure


rule theorem1_compute:
    conda:
        "../envs/cradle.yaml"
    message:
        "Theorem 1 measured: exact travelling waves of (ad) against (wleadingorder)"
    input:
        code=code_of("workflow/scripts/theorem1.py"),
    output:
        "results/theorem1/theorem1.nc",
    params:
        spec=lambda w: _t1.resolved_spec(config),
    log:
        "results/logs/theorem1/theorem1.log",
    benchmark:
        "results/benchmarks/theorem1/theorem1.tsv"
    script:
        "../scripts/theorem1.py"


rule theorem1_figure:
    conda:
        "../envs/cradle.yaml"
    message:
        "Drawing figure theorem1"
    input:
        code=figure_code("theorem1"),
        data="results/theorem1/theorem1.nc",
    output:
        pdf=update("results/figures/theorem1.pdf"),
        png=update("results/figures/theorem1.png"),
    params:
        label="theorem1",
    log:
        "results/logs/figures/theorem1.log",
    script:
        "../scripts/dataset_figure.py"


rule theorem1:
    input:
        rules.theorem1_compute.output,
        rules.theorem1_figure.output,


rule mi_diagram_compute:
    conda:
        "../envs/cradle.yaml"
    message:
        "Modulational instability of the DpS plane waves: growth-rate map and direct checks"
    input:
        code=code_of("workflow/scripts/mi_diagram.py"),
    output:
        "results/mi/mi-diagram.nc",
    params:
        spec=lambda w: _mi.resolved_spec(config),
    log:
        "results/logs/mi/mi-diagram.log",
    benchmark:
        "results/benchmarks/mi/mi-diagram.tsv"
    script:
        "../scripts/mi_diagram.py"


rule mi_diagram_figure:
    conda:
        "../envs/cradle.yaml"
    message:
        "Drawing figure mi-diagram"
    input:
        code=figure_code("mi-diagram"),
        data="results/mi/mi-diagram.nc",
    output:
        pdf=update("results/figures/mi-diagram.pdf"),
        png=update("results/figures/mi-diagram.png"),
    params:
        label="mi-diagram",
    log:
        "results/logs/figures/mi-diagram.log",
    script:
        "../scripts/dataset_figure.py"


rule mi_diagram:
    input:
        rules.mi_diagram_compute.output,
        rules.mi_diagram_figure.output,
