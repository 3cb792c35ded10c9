# Stage 4a: exact against approximate, E(t) of plot4-5 and spectra on Gamma*.


rule metrics:
    conda:
        "../envs/cradle.yaml"
    message:
        "Comparing exact and DpS solutions of scene '{wildcards.scene}'"
    input:
        code=sources(*CORE, "compare"),
        exact="results/sim/{scene}/exact.nc",
        dps="results/sim/{scene}/dps.nc",
    output:
        "results/metrics/{scene}.nc",
    params:
        spec=lambda w: cc.resolved_scene(config, w.scene),
    log:
        "results/logs/metrics/{scene}.log",
    wildcard_constraints:
        scene=names_regex("scenes"),
    script:
        "../scripts/metrics.py"
