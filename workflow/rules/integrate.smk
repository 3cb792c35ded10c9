# Stage 3: the exact lattice (nc) and the DpS equation (dfnls), each from the
# scene's initial data, stored only at the scene's declared times.


rule exact:
    conda:
        "../envs/cradle.yaml"
    message:
        "Integrating the lattice (nc) for scene '{wildcards.scene}'"
    input:
        code=sources(*CORE, "integrators"),
        initial="results/initial/{scene}.nc",
    output:
        "results/sim/{scene}/exact.nc",
    params:
        spec=lambda w: cc.resolved_scene(config, w.scene),
    log:
        "results/logs/sim/{scene}/exact.log",
    benchmark:
        "results/benchmarks/sim/{scene}/exact.tsv"
    wildcard_constraints:
        scene=names_regex("scenes"),
    script:
        "../scripts/exact.py"


rule dps:
    conda:
        "../envs/cradle.yaml"
    message:
        "Integrating the DpS equation (dfnls) for scene '{wildcards.scene}'"
    input:
        code=sources(*CORE, "integrators", "compare"),
        initial="results/initial/{scene}.nc",
    output:
        "results/sim/{scene}/dps.nc",
    params:
        spec=lambda w: cc.resolved_scene(config, w.scene),
    log:
        "results/logs/sim/{scene}/dps.log",
    benchmark:
        "results/benchmarks/sim/{scene}/dps.tsv"
    wildcard_constraints:
        scene=names_regex("scenes"),
    script:
        "../scripts/dps.py"
