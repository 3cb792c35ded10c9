# The paper's numerical statements against ours (results/paper_checks.{csv,md}),
# computed from the outputs of every scene and the site-centred homoclinic.


def checks_inputs(w):
    files = [f for name in config["scenes"] for f in scene_files(name)]
    files += [f"results/initial/{name}.nc" for name in config["scenes"]]
    return files + [f"results/homoclinic/{name}.nc" for name in config["homoclinic"]]


rule paper_checks:
    message:
        "Tabulating the paper's claims against ours"
    input:
        code=sources(*CORE, "checks", "breathers", "sidebands", "compare", "stationary"),
        data=checks_inputs,
    output:
        csv="results/paper_checks.csv",
        md="results/paper_checks.md",
    params:
        scenes=list(config["scenes"]),
        homoclinic=list(config["homoclinic"]),
    log:
        "results/logs/paper_checks.log",
    script:
        "../scripts/paper_checks.py"
