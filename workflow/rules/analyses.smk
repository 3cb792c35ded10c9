# Analyses beyond the paper, generated from the registry (cradle.analyses.registry): for each analysis
# and form, `<target>_batch_<form>` (its batches, if it has any), `<target>_compute_<form>` (its netCDF
# file) and `<target>_figure_<form>` (its figure, drawn by cradle/figures/<module>.py, or the tables that
# module writes: the claims table); target `<target>` builds the form `all` builds (results/<name>/<name>.nc,
# results/figures/<name>.*), `<target>_full` the full one (the same files when the analysis has one form,
# else results/<name>/full/). A workflow/report/<name>.rst captions the form's drawn files in the Snakemake
# report. Config:
# `beyond: <name>:` in config.yaml. Every rule passes the spec as plain values, so a changed number
# reruns exactly its jobs.
from pathlib import Path as _Path

from cradle.analyses.registry import ANALYSES, FULL
from cradle.specs.declare import plain as _plain

#: report captions, one per analysis that has one (workflow/report/<name>.rst)
_REPORT = _Path(workflow.current_basedir).parent / "report"


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


def drawn_outputs(a, form, main):
    """ext -> the files of an analysis's drawing step (its figure, or its tables), each restored if the job
    fails (update(): docs/recovery.md); those of the form `all` builds in the report when captioned.
    """
    out = {}
    for ext, f in L.analysis_drawn(a, form, main).items():
        out[ext] = update(f)
        if form == main and (_REPORT / f"{a.name}.rst").exists():
            out[ext] = report(out[ext], caption=f"../report/{a.name}.rst", category=a.title)
    return out


for _a in ANALYSES.values():
    # the code stamps the input functions below ask for, written now (code_of)
    code_of("workflow/scripts/analysis_compute.py", f"cradle.analyses.{_a.module}")
    code_of("workflow/scripts/analysis_batch.py", f"cradle.analyses.{_a.module}")
    _main = _a.forms[0]
    for _form in _a.forms:
        if _a.batches is not None:

            rule:
                name:
                    f"{_a.target}_batch_{_form}"
                input:
                    unpack(
                        lambda w, a=_a, form=_form: {
                            "code": code_of("workflow/scripts/analysis_batch.py", f"cradle.analyses.{a.module}"),
                            **analysis_reads(a, form, a.batches.reads(analysis_spec(a, form), w.key)),
                        }
                    ),
                output:
                    update(L.path("analysis-batch", analysis=_a.name, form=_form, key="{key}")),  # restored on failure
                log:
                    L.path("log", job=f"{_a.name}/{_form}/batch-{{key}}"),
                benchmark:
                    L.path("benchmark", job=f"{_a.name}/{_form}/batch-{{key}}")
                wildcard_constraints:
                    key=r"[A-Za-z0-9][A-Za-z0-9_.-]*",
                priority: 10  # long jobs that need no scene start before the figures
                conda:
                    "../envs/cradle.yaml"
                threads: (lambda n: workflow.cores if n == "all" else int(n))(_a.batches.threads.get(_form, 1))
                params:
                    analysis=_a.name,
                    spec=lambda w, a=_a, form=_form: _plain(analysis_spec(a, form)),
                message:
                    f"{_a.name} ({_form}): batch {{wildcards.key}}"
                script:
                    "../scripts/analysis_batch.py"

        rule:
            name:
                f"{_a.target}_compute_{_form}"
            input:
                unpack(lambda w, a=_a, form=_form: analysis_inputs(a, form)),
            output:
                update(L.analysis_output(_a.name, _form, _main)),  # a failed rerun restores the previous file
            log:
                L.path("log", job=f"{_a.name}/{_form}/{_a.name}"),
            benchmark:
                L.path("benchmark", job=f"{_a.name}/{_form}/{_a.name}")
            priority: 10  # before the figures of the paper: the longest jobs start early
            conda:
                "../envs/cradle.yaml"
            params:
                analysis=_a.name,
                # resolved when the job is planned: an analysis not asked for is not resolved
                spec=lambda w, a=_a, form=_form: _plain(analysis_spec(a, form)),
            message:
                f"{_a.title} ({_form})"
            script:
                "../scripts/analysis_compute.py"

        rule:
            name:
                f"{_a.target}_figure_{_form}"
            input:
                code=code_of("workflow/scripts/analysis_figure.py", f"cradle.figures.{_a.module}"),
                data=L.analysis_output(_a.name, _form, _main),
            output:
                **drawn_outputs(_a, _form, _main),
            log:
                L.path("log", job=f"figures/{_form}/{_a.name}"),
            conda:
                "../envs/cradle.yaml"
            params:
                module=_a.module,
                tables=list(_a.tables),
                # the reduced form says so on the figure, and where the full one is
                note=f"reduced form: `snakemake -j2 {_a.target}_full` builds the full one" if _form != FULL else "",
            message:
                (f"Writing the tables of {_a.name} ({_form})" if _a.tables else f"Drawing figure {_a.name} ({_form})")
            script:
                "../scripts/analysis_figure.py"

    rule:
        name:
            _a.target
        input:
            L.analysis_output(_a.name, _main, _main),
            *L.analysis_drawn(_a, _main, _main).values(),

    rule:
        name:
            f"{_a.target}_full"
        input:
            L.analysis_output(_a.name, FULL, _main),
            *L.analysis_drawn(_a, FULL, _main).values(),
