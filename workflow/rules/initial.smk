# Stage 2: initial data x0, v0, A0 of each scene (ansatzapprox), (perturb), (ansatzapproxst2).


rule initial:
    conda:
        "../envs/cradle.yaml"
    message:
        "Initial data of scene '{wildcards.scene}'"
    input:
        code=sources(*CORE, "initial", "homoclinic"),  # pair scenes solve their profile in-process
        homoclinic=initial_inputs,
    output:
        "results/initial/{scene}.nc",
    params:
        spec=lambda w: cc.resolved_scene(config, w.scene),
    log:
        "results/logs/initial/{scene}.log",
    wildcard_constraints:
        scene=names_regex("scenes"),
    script:
        "../scripts/initial.py"
