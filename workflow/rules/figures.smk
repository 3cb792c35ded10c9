# Stage 4b: one rule instance per paper figure, drawn from netCDF outputs only.

# each figure's code stamp, written now (code_of)
for _label in config.get("figures", {}):
    figure_code(_label)


rule figure:
    input:
        code=lambda w: figure_code(w.label),
        data=figure_inputs,
    output:
        # update(): Snakemake keeps a backup of the previous figure and restores it if this job fails
        # (a damaged input), instead of deleting it first (docs/recovery.md)
        pdf=update(L.path("figure", label="{label}", ext="pdf")),
        png=update(
            report(
                L.path("figure", label="{label}", ext="png"),
                caption="../report/figure.rst",
                category="Figures",
                labels={"figure": "{label}"},
            )
        ),
    log:
        L.path("log", job="figures/{label}"),
    benchmark:
        L.path("benchmark", job="figures/{label}")
    wildcard_constraints:
        label=names_regex("figures"),
    conda:
        "../envs/cradle.yaml"
    params:
        label=lambda w: w.label,
        # sorted plain values: a reordered figure entry reruns nothing
        options=lambda w: plain(config["figures"][w.label]),
        scenes=lambda w: {name: kind_of(name) for name in config["figures"][w.label]["scenes"]},
    message:
        "Drawing figure {wildcards.label}"
    script:
        "../scripts/figure.py"
