# Modulational instability measured (config `beyond: mi_growth, mi_statistics`; cradle.analyses.migrowth,
# cradle.analyses.mistatistics, figures in cradle.figures.mi).
#
# * `snakemake -j2 mi_growth` (seconds): the scenes of beyond.mi_growth.scenes rerun from their initial
#   data, growth rates fitted in both models against the linear DpS theory -> results/mi/mi-growth.nc,
#   results/figures/mi-growth.{pdf,png}.
# * `snakemake -j2 mi_statistics` (part of `all`, ~30 s): the reduced threshold sweep ->
#   results/mi/mi-statistics.nc, results/figures/mi-statistics.{pdf,png}.
# * `snakemake -j2 mi_statistics_full` (a few minutes on 2 cores): the full sweep, the same code ->
#   results/mi/full/mi-statistics.nc, results/mi/full/mi-statistics.{pdf,png}.
# Each batch job runs every seed of a chunk of q values for one (N, model): results/mi/batch/<variant>/.
from cradle.analyses import migrowth as _mig
from cradle.analyses import mistatistics as _mis

ruleorder: mi_growth_figure > figure
ruleorder: mi_statistics_figure_reduced > figure

MI_VARIANT_DIR = {"reduced": "results/mi", "full": "results/mi/full"}


rule mi_growth_compute:
    conda:
        "../envs/cradle.yaml"
    message:
        "Modulational-instability growth rates measured in the scenes' runs, exact and DpS"
    input:
        code=code_of("workflow/scripts/mi_growth.py"),
        data=mi_growth_inputs,
    output:
        "results/mi/mi-growth.nc",
    params:
        spec=lambda w: _mig.resolved_spec(config),
        scenes=lambda w: {n: compact_scene(cc.resolved_scene(config, n))
                          for n in config["beyond"]["mi_growth"]["scenes"]},
    log:
        "results/logs/mi/mi-growth.log",
    benchmark:
        "results/benchmarks/mi/mi-growth.tsv"
    script:
        "../scripts/mi_growth.py"


rule mi_growth_figure:
    conda:
        "../envs/cradle.yaml"
    message:
        "Drawing figure mi-growth"
    input:
        code=figure_code("mi-growth"),
        data="results/mi/mi-growth.nc",
    output:
        pdf=update("results/figures/mi-growth.pdf"),
        png=update("results/figures/mi-growth.png"),
    params:
        label="mi-growth",
    log:
        "results/logs/figures/mi-growth.log",
    script:
        "../scripts/dataset_figure.py"


rule mi_growth:
    input:
        rules.mi_growth_compute.output,
        rules.mi_growth_figure.output,


rule mi_statistics_batch:
    conda:
        "../envs/cradle.yaml"
    message:
        "mi-statistics ({wildcards.variant}): N = {wildcards.N}, {wildcards.model}, chunk {wildcards.chunk}"
    input:
        code=code_of("workflow/scripts/mi_statistics.py"),
    output:
        "results/mi/batch/{variant}/N{N}-{model}-{chunk}.nc",
    params:
        spec=lambda w: _mis.resolved_spec(config, w.variant),
        q_indices=lambda w: _mis.chunk_indices(_mis.resolved_spec(config, w.variant), int(w.N), int(w.chunk)),
    log:
        "results/logs/mi/{variant}/N{N}-{model}-{chunk}.log",
    benchmark:
        "results/benchmarks/mi/{variant}/N{N}-{model}-{chunk}.tsv"
    wildcard_constraints:
        variant="reduced|full",
        N=r"\d+",
        model="exact|dps",
        chunk=r"\d+",
    script:
        "../scripts/mi_statistics.py"


MI_FIGURE_STEM = {"reduced": "results/figures/mi-statistics", "full": "results/mi/full/mi-statistics"}

for _variant in ("reduced", "full"):

    rule:
        name:
            f"mi_statistics_aggregate_{_variant}"
        conda:
            "../envs/cradle.yaml"
        message:
            f"mi-statistics ({_variant}): thresholds from every batch"
        input:
            code=code_of("workflow/scripts/mi_statistics.py"),
            batches=mi_batches(_variant),
        output:
            f"{MI_VARIANT_DIR[_variant]}/mi-statistics.nc",
        params:
            spec=_mis.resolved_spec(config, _variant),
        log:
            f"results/logs/mi/{_variant}/mi-statistics.log",
        script:
            "../scripts/mi_statistics.py"

    rule:
        name:
            f"mi_statistics_figure_{_variant}"
        conda:
            "../envs/cradle.yaml"
        message:
            f"Drawing figure mi-statistics ({_variant})"
        input:
            code=figure_code("mi-statistics"),
            data=f"{MI_VARIANT_DIR[_variant]}/mi-statistics.nc",
        output:
            pdf=update(f"{MI_FIGURE_STEM[_variant]}.pdf"),  # kept if the job fails (docs/recovery.md)
            png=update(f"{MI_FIGURE_STEM[_variant]}.png"),
        params:
            label="mi-statistics",
        log:
            f"results/logs/mi/{_variant}/figure.log",
        script:
            "../scripts/dataset_figure.py"


rule mi_statistics:
    input:
        "results/mi/mi-statistics.nc",
        "results/figures/mi-statistics.pdf",
        "results/figures/mi-statistics.png",


rule mi_statistics_full:
    input:
        "results/mi/full/mi-statistics.nc",
        "results/mi/full/mi-statistics.pdf",
        "results/mi/full/mi-statistics.png",
