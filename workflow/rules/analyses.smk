# Analyses beyond the paper, generated from the registry (cradle.analyses.registry): for each analysis
# and form, `<target>_batch_<form>` (its batches, if it has any), `<target>_compute_<form>` (its netCDF
# file) and `<target>_figure_<form>` (its figure, drawn by cradle/figures/<module>.py); target `<target>`
# builds the form `all` builds (results/<name>/<name>.nc, results/figures/<name>.*), `<target>_full` the
# full one (the same files when the analysis has one form, else results/<name>/full/). Config:
# `beyond: <name>:` in config.yaml. Every rule passes the spec as plain values, so a changed number
# reruns exactly its jobs.
from cradle.analyses.registry import ANALYSES, FULL
from cradle.specs.declare import plain as _plain


def analysis_spec(a, form):
    """The typed spec of one form of analysis ``a`` (refused in one line when bad)."""
    try:
        return cc.analysis_spec(config, a.name, form)
    except cc.ConfigError as err:
        raise WorkflowError(str(err)) from None


def analysis_reads(a, form, reads):
    """name -> file of what an analysis (or one of its batches) reads."""
    return {name: L.read_path(read, form) for name, read in reads.items()}


def analysis_inputs(a, form):
    """A compute job's inputs: its code, and its reads by name (cradle.analyses.protocol); a scene it
    names must exist."""
    try:
        reads = cc.analysis_reads(config, a.name, form)
    except cc.ConfigError as err:
        raise WorkflowError(str(err)) from None
    code = code_of("workflow/scripts/analysis_compute.py", f"cradle.analyses.{a.module}")
    return {"code": code, **analysis_reads(a, form, reads)}


for _a in ANALYSES.values():
    _main = _a.forms[0]
    for _form in _a.forms:
        if _a.batches is not None:

            rule:
                name:
                    f"{_a.target}_batch_{_form}"
                priority: 10  # long jobs that need no scene start before the figures
                conda:
                    "../envs/cradle.yaml"
                message:
                    f"{_a.name} ({_form}): batch {{wildcards.key}}"
                input:
                    unpack(
                        lambda w, a=_a, form=_form: {
                            "code": code_of(
                                "workflow/scripts/analysis_batch.py", f"cradle.analyses.{a.module}"
                            ),
                            **analysis_reads(a, form, a.batches.reads(analysis_spec(a, form), w.key)),
                        }
                    ),
                output:
                    L.path("analysis-batch", analysis=_a.name, form=_form, key="{key}"),
                params:
                    analysis=_a.name,
                    spec=lambda w, a=_a, form=_form: _plain(analysis_spec(a, form)),
                log:
                    L.path("log", job=f"{_a.name}/{_form}/batch-{{key}}"),
                benchmark:
                    L.path("benchmark", job=f"{_a.name}/{_form}/batch-{{key}}")
                threads: (lambda n: workflow.cores if n == "all" else int(n))(_a.batches.threads.get(_form, 1))
                wildcard_constraints:
                    key=r"[A-Za-z0-9][A-Za-z0-9_.-]*",
                script:
                    "../scripts/analysis_batch.py"

        rule:
            name:
                f"{_a.target}_compute_{_form}"
            priority: 10  # before the figures of the paper: the longest jobs start early
            conda:
                "../envs/cradle.yaml"
            message:
                f"{_a.title} ({_form})"
            input:
                unpack(lambda w, a=_a, form=_form: analysis_inputs(a, form)),
            output:
                L.analysis_output(_a.name, _form, _main),
            params:
                analysis=_a.name,
                # resolved when the job is planned: an analysis not asked for is not resolved
                spec=lambda w, a=_a, form=_form: _plain(analysis_spec(a, form)),
            log:
                L.path("log", job=f"{_a.name}/{_form}/{_a.name}"),
            benchmark:
                L.path("benchmark", job=f"{_a.name}/{_form}/{_a.name}")
            script:
                "../scripts/analysis_compute.py"

        rule:
            name:
                f"{_a.target}_figure_{_form}"
            conda:
                "../envs/cradle.yaml"
            message:
                f"Drawing figure {_a.name} ({_form})"
            input:
                code=code_of("workflow/scripts/analysis_figure.py", f"cradle.figures.{_a.module}"),
                data=L.analysis_output(_a.name, _form, _main),
            output:  # update(): the previous figure is restored if the job fails (docs/recovery.md)
                **{ext: update(f) for ext, f in L.analysis_figures(_a.name, _form, _main).items()},
            params:
                module=_a.module,
                # the reduced form says so on the figure, and where the full one is
                note=f"reduced form: `snakemake -j2 {_a.target}_full` builds the full one" if _form != FULL else "",
            log:
                L.path("log", job=f"figures/{_form}/{_a.name}"),
            script:
                "../scripts/analysis_figure.py"

    rule:
        name:
            _a.target
        input:
            L.analysis_output(_a.name, _main, _main),
            *L.analysis_figures(_a.name, _main, _main).values(),

    rule:
        name:
            f"{_a.target}_full"
        input:
            L.analysis_output(_a.name, FULL, _main),
            *L.analysis_figures(_a.name, FULL, _main).values(),
