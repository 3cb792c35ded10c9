# Work-precision of the lattice integrators (part of `all`): `snakemake -j2 work_precision`.
# One job per scene of the `work_precision:` config section (reference runs, then every method on
# its ladder) -> results/work-precision/<scene>.nc; then the figure
# results/figures/work-precision.{pdf,png}. A scene job times integrators: it takes every core
# given to Snakemake (threads: workflow.cores), so no other job runs beside it, and it runs in its own
# single-threaded Python process (~40 s each, ~2 min for the whole target on 2 cores).
import json


WP_SCENES = list((config.get("work_precision") or {}).get("scenes") or {})


rule work_precision_scene:
    conda:
        "../envs/cradle.yaml"
    message:
        "Work-precision of the lattice integrators on scene '{wildcards.scene}'"
    input:
        code=code_of("cradle.analyses.workprecision"),
        initial="results/initial/{scene}.nc",
    output:
        "results/work-precision/{scene}.nc",
    params:
        spec=lambda w: json.dumps(cc.resolved_work_precision(config, w.scene), sort_keys=True),
    log:
        "results/logs/work-precision/{scene}.log",
    benchmark:
        "results/benchmarks/work-precision/{scene}.tsv"
    wildcard_constraints:
        scene="|".join(re.escape(k) for k in WP_SCENES) or "(?!)",
    threads: workflow.cores
    shell:
        "OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1 "
        "python -m cradle.analyses.workprecision scene --spec {params.spec:q} --initial {input.initial:q} "
        "--out {output:q} --log {log:q}"


rule work_precision_figure:
    conda:
        "../envs/cradle.yaml"
    message:
        "Drawing figure work-precision"
    input:
        code=code_of("cradle.analyses.workprecision", "cradle.figures.workprecision"),
        data=expand("results/work-precision/{scene}.nc", scene=WP_SCENES),
    output:
        pdf=update("results/figures/work-precision.pdf"),
        png=update("results/figures/work-precision.png"),
    log:
        "results/logs/figures/work-precision.log",
    shell:
        "python -m cradle.analyses.workprecision figure --out results/figures/work-precision "
        "--log {log:q} {input.data:q}"


rule work_precision:
    input:
        rules.work_precision_figure.output,
