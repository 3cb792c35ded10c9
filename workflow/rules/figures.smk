# Stage 4b: one rule instance per paper figure, drawn from netCDF outputs only.


def figure_inputs(w):
    return [f for name in config["figures"][w.label]["scenes"] for f in scene_files(name)]


rule figure:
    message:
        "Drawing figure {wildcards.label}"
    input:
        code=lambda w: sources("__init__", "io", "variables", "compare", "lattice", "figures/__init__")
        + [figure_module(w.label)],
        data=figure_inputs,
    output:
        pdf="results/figures/{label}.pdf",
        png="results/figures/{label}.png",
    params:
        label=lambda w: w.label,
        options=lambda w: config["figures"][w.label],
        scenes=lambda w: {name: kind_of(name) for name in config["figures"][w.label]["scenes"]},
    log:
        "results/logs/figures/{label}.log",
    wildcard_constraints:
        label=names_regex("figures"),
    script:
        "../scripts/figure.py"
