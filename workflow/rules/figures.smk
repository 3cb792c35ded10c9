# Stage 4b: one rule instance per paper figure, drawn from netCDF outputs only.


rule figure:
    conda:
        "../envs/cradle.yaml"
    message:
        "Drawing figure {wildcards.label}"
    input:
        code=lambda w: figure_code(w.label),
        data=figure_inputs,
    output:
        # update(): Snakemake keeps a backup of the previous figure and restores it if this job fails
        # (a damaged input), instead of deleting it first (docs/recovery.md)
        pdf=update("results/figures/{label}.pdf"),
        png=update(report(
            "results/figures/{label}.png",
            caption="../report/figure.rst",
            category="Figures",
            labels={"figure": "{label}"},
        )),
    params:
        label=lambda w: w.label,
        options=lambda w: config["figures"][w.label],
        scenes=lambda w: {name: kind_of(name) for name in config["figures"][w.label]["scenes"]},
    log:
        "results/logs/figures/{label}.log",
    benchmark:
        "results/benchmarks/figures/{label}.tsv"
    wildcard_constraints:
        label=names_regex("figures"),
    script:
        "../scripts/figure.py"
