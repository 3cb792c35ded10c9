# Stage 1: stationary DpS (dpsstn): homoclinic solutions, and orbits of the map G.


rule homoclinic:
    input:
        code=code_of("workflow/scripts/homoclinic.py"),
    output:
        update(L.path("homoclinic", name="{name}")),  # a failed rerun restores the previous file
    log:
        L.path("log", job="homoclinic/{name}"),
    benchmark:  # measured against cradle.pipeline.budget's estimate by benchmarks/estimates.py
        L.path("benchmark", job="homoclinic/{name}")
    wildcard_constraints:
        name=names_regex("homoclinic"),
    priority: 30  # stage 1 first: it unlocks the breather scenes
    conda:
        "../envs/cradle.yaml"
    params:
        spec=lambda w: plain(cc.homoclinic(config, w.name)),
    message:
        "Solving (dpsstn) for the homoclinic solution '{wildcards.name}'"
    script:
        "../scripts/homoclinic.py"


rule map_orbits:
    input:
        code=code_of("workflow/scripts/map_orbits.py"),
    output:
        update(L.path("map", name="{name}")),  # a failed rerun restores the previous file
    log:
        L.path("log", job="map/{name}"),
    benchmark:
        L.path("benchmark", job="map/{name}")
    wildcard_constraints:
        name=names_regex("map"),
    priority: 30  # stage 1 first, not left to the end beside one figure
    conda:
        "../envs/cradle.yaml"
    params:
        spec=lambda w: plain(cc.map_entry(config, w.name)),
    message:
        "Iterating the map G (comp1)-(comp2) for '{wildcards.name}'"
    script:
        "../scripts/map_orbits.py"
