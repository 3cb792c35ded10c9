# Spectral (Bloch-Floquet) stability of the exact travelling waves (config `beyond: floquet:`, part of
# `all`): `snakemake -j2 floquet` writes results/floquet/floquet.nc and results/figures/floquet.{pdf,png}.
# The compute job (cradle.analyses.floquet: Hill's method in the co-moving frame, the lattice threshold in q
# against the DpS q_c = pi/2, a brute-force ring monodromy and a direct run as checks) takes ~2-3 min
# on one core; the figure rule reruns alone when only the drawing code changes.
from cradle.analyses import floquet as _fq

# should `floquet` ever be listed under `figures:`, this rule draws it
ruleorder: floquet_figure > figure


rule floquet_compute:
    conda:
        "../envs/cradle.yaml"
    message:
        "Bloch-Floquet stability of the exact travelling waves against the DpS threshold"
    input:
        code=code_of("workflow/scripts/floquet.py"),
    output:
        "results/floquet/floquet.nc",
    params:
        spec=lambda w: _fq.resolved_spec(config),
    log:
        "results/logs/floquet/floquet.log",
    benchmark:
        "results/benchmarks/floquet/floquet.tsv"
    script:
        "../scripts/floquet.py"


rule floquet_figure:
    conda:
        "../envs/cradle.yaml"
    message:
        "Drawing figure floquet"
    input:
        code=figure_code("floquet"),
        data="results/floquet/floquet.nc",
    output:
        pdf=update("results/figures/floquet.pdf"),
        png=update("results/figures/floquet.png"),
    params:
        label="floquet",
    log:
        "results/logs/figures/floquet.log",
    script:
        "../scripts/dataset_figure.py"


rule floquet:
    input:
        rules.floquet_compute.output,
        rules.floquet_figure.output,
