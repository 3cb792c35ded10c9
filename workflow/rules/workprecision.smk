# Work-precision of the lattice integrators (config `work_precision:`). Two forms, as the analyses of
# analyses.smk: the reduced one `all` builds (`snakemake -j2 work_precision`: the scenes, methods and
# settings of work_precision.reduced -> results/work-precision/<scene>.nc, results/figures/work-precision.*)
# and the full one (`snakemake -j2 work_precision_full` -> results/work-precision/full/). One job per
# scene (reference runs, then every method on its ladder), then the figure. A scene job times
# integrators in its own single-threaded Python process. The full form's jobs take every core given to
# Snakemake (threads: workflow.cores), so no other job runs beside them and their times are the
# machine's; the reduced form's job takes one core and runs beside the others, as `all` needs its two
# cores busy (its times are those of a shared machine: the full form is the measurement).
import json
import os

from cradle.pipeline.config.sections import WorkPrecision as _WP

WP_FORMS = ("reduced", "full")  # the first is the form `all` builds (cradle.pipeline.layout.form_folder)
WP_DIR = {form: L.form_folder("work-precision", form, WP_FORMS[0]) for form in WP_FORMS}

for _form in WP_FORMS:
    _scenes = _WP.scenes_of(config, _form) if config.get("work_precision") else []

    rule:
        name:
            f"work_precision_scene_{_form}"
        conda:
            "../envs/cradle.yaml"
        message:
            f"Work-precision of the lattice integrators on scene '{{wildcards.scene}}' ({_form})"
        input:
            code=code_of("cradle.analyses.work_precision"),
            initial=L.path("initial", scene="{scene}"),
        output:
            f"{WP_DIR[_form]}/{{scene}}.nc",
        params:
            spec=lambda w, form=_form: json.dumps(cc.resolved_work_precision(config, w.scene, form), sort_keys=True),
        log:
            L.path("log", job=f"work-precision/{_form}/{{scene}}"),
        benchmark:
            L.path("benchmark", job=f"work-precision/{_form}/{{scene}}")
        wildcard_constraints:
            scene="|".join(re.escape(k) for k in _scenes) or "(?!)",
        threads: workflow.cores if _form == "full" else 1
        priority: 10  # as the analyses: before the figures, so that it does not end the build alone
        shell:
            "OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1 "
            f"{PYTHON} -m cradle.analyses.work_precision scene --spec {{params.spec:q}} --initial {{input.initial:q}} "
            "--out {output:q} --log {log:q}"

    rule:
        name:
            f"work_precision_figure_{_form}"
        conda:
            "../envs/cradle.yaml"
        message:
            f"Drawing figure work-precision ({_form})"
        input:
            code=code_of("cradle.analyses.work_precision", "cradle.figures.work_precision"),
            data=[f"{WP_DIR[_form]}/{s}.nc" for s in _scenes],
        output:
            **{ext: update(f) for ext, f in L.form_figure_paths("work-precision", "work-precision", _form,
                                                                 WP_FORMS[0]).items()},
        params:
            stem=lambda w, output: os.path.splitext(output.pdf)[0],
        log:
            L.path("log", job=f"figures/{_form}/work-precision"),
        shell:
            f"{PYTHON} -m cradle.analyses.work_precision figure --out {{params.stem:q}} --log {{log:q}} {{input.data:q}}"


rule work_precision:
    input:
        rules.work_precision_figure_reduced.output,


rule work_precision_full:
    input:
        rules.work_precision_figure_full.output,
