# Stages 2 and 3, one job per scene: the initial data x0, v0, A0 (ansatzapprox), (perturb),
# (ansatzapproxst2); the exact lattice (nc) and the DpS equation (dfnls) integrated from them and
# stored at the scene's declared times; and their comparison (E(t) of plot4-5, spectra on Gamma*).
# Each of the four is its own netCDF file, but one process computes them: every step takes well
# under a second, while a job's start-up (interpreter, imports, compiled-kernel cache loads) costs
# about one, and the whole paper is meant to rebuild in a minute on two cores.


rule kernels:
    input:
        code=code_of("workflow/scripts/kernels.py"),
    output:
        L.path("kernels"),
    log:
        L.path("log", job="kernels"),
    priority: 40  # first: on an empty compiled-kernel cache it compiles while the other core does stage 1,
    # instead of the first scene jobs each compiling the same kernels at once
    conda:
        "../envs/cradle.yaml"
    message:
        "Compiling the kernels of (nc) and (dfnls), or loading them from the cache (one line per kernel below)"
    script:
        "../scripts/kernels.py"


rule simulate:
    input:
        code=code_of("workflow/scripts/simulate.py"),  # pair scenes solve a profile (homoclinic)
        homoclinic=initial_inputs,
        kernels=L.path("kernels"),  # compiled once, before (the cache key: unchanged content, no rerun)
    output:
        # update(): a failed rerun restores the previous four files instead of leaving none (docs/recovery.md)
        **{part: update(path) for part, path in L.scene_paths("{scene}").items()},
    log:
        L.path("log", job="sim/{scene}"),
    benchmark:
        L.path("benchmark", job="sim/{scene}")
    wildcard_constraints:
        scene=names_regex("scenes"),
    priority: 20  # all scenes before the figures: the two cores stay busy to the end
    conda:
        "../envs/cradle.yaml"
    params:
        # the resolved scene's plain values, sorted (the store description, not the expanded stored
        # times): a changed value reruns the job, a reordered config.yaml does not, a dry run stays readable
        spec=lambda w: plain(cc.scene(config, w.scene)),
    message:
        "Scene '{wildcards.scene}': initial data, lattice (nc) and DpS (dfnls) runs, comparison"
    script:
        "../scripts/simulate.py"
