# The paper's numerical statements against ours (results/paper_checks.{csv,md}),
# computed from the outputs of every scene and the site-centred homoclinic.


rule paper_checks:
    conda:
        "../envs/cradle.yaml"
    message:
        "Tabulating the paper's claims against ours"
    input:
        code=code_of("workflow/scripts/paper_checks.py"),
        data=checks_inputs,
    output:
        csv=report(
            L.path("checks", ext="csv"),
            caption="../report/paper_checks.rst",
            category="Paper claims",
            labels={"table": "paper claims against ours"},
        ),
        md=L.path("checks", ext="md"),
    params:
        scenes=list(config["scenes"]),
        homoclinic=list(config["homoclinic"]),
    log:
        "results/logs/paper_checks.log",
    benchmark:
        "results/benchmarks/paper_checks.tsv"
    script:
        "../scripts/paper_checks.py"
