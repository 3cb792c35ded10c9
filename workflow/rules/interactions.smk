# breather-interactions batches (config `beyond: breather_interactions`, cradle.analyses.breather_interactions):
# each job runs every case of its (profile pair, spacing) batches (round robin over `chunks` jobs) in both
# models and keeps each run's outcome, never the fields; the analysis `breather-interactions` (analyses.smk)
# gathers them. Only the full form has batches (the reduced one runs in its analysis job).

rule breather_interactions_batch:
    priority: 10  # as the analyses: long jobs that need no scene start before the figures
    conda:
        "../envs/cradle.yaml"
    message:
        "breather-interactions ({wildcards.form}): batch {wildcards.chunk}"
    input:
        code=code_of("workflow/scripts/interactions_batch.py", "cradle.analyses.breather_interactions"),
    output:
        L.path("interactions-batch", form="{form}", chunk="{chunk}"),
    params:
        spec=lambda w: cc.resolved_breather_interactions(config, w.form),
    log:
        "results/logs/interactions/{form}/batch-{chunk}.log",
    benchmark:
        "results/benchmarks/interactions/{form}/batch-{chunk}.tsv"
    wildcard_constraints:
        form="full",
        chunk=r"\d+",
    script:
        "../scripts/interactions_batch.py"
