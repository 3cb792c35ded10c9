# TRANSITION ONLY: the analyses not yet on the protocol (cradle.analyses._legacy), as before.
# For each analysis and form: `<name>_compute_<form>` writes its netCDF file, `<name>_figure_<form>` draws
# it; target `<name>` builds the form `all` builds (results/<folder>/<name>.nc, results/figures/<name>.*),
# and `<name>_full` the full form (the same files when the analysis has one form; else
# results/<folder>/full/). Config: `beyond:` in config.yaml.
from cradle.analyses._legacy import LEGACY, FULL

for _a in LEGACY.values():
    for _form in _a.forms:

        rule:
            name:
                f"{_a.target}_compute_{_form}"
            priority: 10  # before the figures of the paper: the longest jobs start early
            conda:
                "../envs/cradle.yaml"
            message:
                f"{_a.title} ({_form})"
            input:
                code=code_of("workflow/scripts/analysis.py", f"cradle.analyses.{_a.module}"),
                data=lambda w, a=_a, form=_form: a.inputs(config, form),
            output:
                _a.output(_form),
            params:
                analysis=_a.name,
                # resolved when the job is planned: an analysis not asked for is not resolved
                spec=lambda w, a=_a, form=_form: a.spec(config, form),
                scenes=lambda w, a=_a: {n: compact_scene(cc.resolved_scene(config, n)) for n in a.scenes(config)},
            log:
                L.path("log", job=f"{_a.folder}/{_form}/{_a.name}"),
            benchmark:
                L.path("benchmark", job=f"{_a.folder}/{_form}/{_a.name}")
            script:
                "../scripts/analysis.py"

        rule:
            name:
                f"{_a.target}_figure_{_form}"
            conda:
                "../envs/cradle.yaml"
            message:
                f"Drawing figure {_a.name} ({_form})"
            input:
                code=figure_code(_a.name),
                data=_a.output(_form),
            output:  # update(): the previous figure is restored if the job fails (docs/recovery.md)
                **{ext: update(f) for ext, f in _a.figure(_form).items()},
            params:
                label=_a.name,
                # the reduced form says so on the figure, and where the full one is
                note=f"reduced form: `snakemake -j2 {_a.target}_full` builds the full one"
                if _form != FULL else "",
            log:
                L.path("log", job=f"figures/{_form}/{_a.name}"),
            script:
                "../scripts/dataset_figure.py"

    rule:
        name:
            _a.target
        input:
            _a.output(_a.forms[0]),
            *_a.figure(_a.forms[0]).values(),

    rule:
        name:
            f"{_a.target}_full"
        input:
            _a.output(FULL),
            *_a.figure(FULL).values(),
