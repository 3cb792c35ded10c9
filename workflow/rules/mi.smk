# mi-statistics batches (config `beyond: mi_statistics`, cradle.analyses.mi_statistics): each job runs every
# seed of a chunk of q values for one (N, model) of a form (reduced, full) and keeps each run's
# sideband-ratio series, never the fields; the analysis `mi-statistics` (analyses.smk) aggregates them.
from cradle.analyses import mi_statistics as _mis

rule mi_statistics_batch:
    priority: 10  # as the analyses: long jobs that need no scene start before the figures
    conda:
        "../envs/cradle.yaml"
    message:
        "mi-statistics ({wildcards.variant}): N = {wildcards.N}, {wildcards.model}, chunk {wildcards.chunk}"
    input:
        code=code_of("workflow/scripts/mi_statistics.py"),
    output:
        L.path("mi-batch", variant="{variant}", N="{N}", model="{model}", chunk="{chunk}"),
    params:
        spec=lambda w: cc.resolved_mi_statistics(config, w.variant),
        q_indices=lambda w: _mis.chunk_indices(cc.resolved_mi_statistics(config, w.variant), int(w.N), int(w.chunk)),
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
