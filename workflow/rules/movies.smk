# Movies of the cradle in motion (cradle.figures.movie): a scene's stored exact (nc) and DpS (dfnls) runs
# side by side -> results/movies/<scene>.mp4 and a small .gif. Not part of `all` (a movie takes tens of
# seconds to draw and encode); `snakemake -j2 movies` builds those listed under `movies.scenes`, and
# any scene's movie is built by its path, e.g. `snakemake -j2 results/movies/loc1-pair.mp4`.
rule movie:
    input:
        code=code_of("workflow/scripts/movie.py", "cradle.figures.movie"),
        data=lambda w: [L.path(part, scene=w.scene) for part in ("exact", "dps")],
    output:
        mp4=report(
            L.path("movie", scene="{scene}", ext="mp4"),
            caption="../report/movie.rst",
            category="Movies",
            labels={"movie": "{scene}"},
        ),
        gif=L.path("movie", scene="{scene}", ext="gif"),
    log:
        L.path("log", job="movies/{scene}"),
    benchmark:
        L.path("benchmark", job="movies/{scene}")
    wildcard_constraints:
        scene=names_regex("scenes"),
    conda:
        "../envs/cradle.yaml"
    params:
        movies=lambda w: plain(dict(config["movies"])),
    message:
        "Drawing the movie of scene {wildcards.scene}"
    script:
        "../scripts/movie.py"


rule movies:
    # the movies of every scene under `movies.scenes` in config.yaml
    input:
        movie_targets(),


# The desk toys of the full form of the desk-toy analysis (cradle.analyses.desk_toy) in motion: (nc) above, the
# hard spheres e = 1 below (cradle.analyses.desk_toy.movie_dataset, drawn by cradle.figures.movie.animate) -> results/movies/desk-toy-<toy>.{mp4,gif},
# <toy> a group of results/desk-toy/full/desk-toy.nc (n5-lifted1, ...). Not in `all`: `snakemake -j2
# desk_toy_movies` builds every one (`cradle animate n5-lifted1 --desk-toy FILE.nc` draws one from any form).
rule desk_toy_movie:
    input:
        code=code_of(
            "workflow/scripts/desk_toy_movie.py",
            "cradle.figures.movie",
            "cradle.analyses.desk_toy",
        ),
        data=L.analysis_output("desk-toy", FULL, ANALYSES["desk-toy"].forms[0]),
    output:
        mp4=L.path("movie", scene="desk-toy-{toy}", ext="mp4"),
        gif=L.path("movie", scene="desk-toy-{toy}", ext="gif"),
    log:
        L.path("log", job="movies/desk-toy-{toy}"),
    benchmark:
        L.path("benchmark", job="movies/desk-toy-{toy}")
    wildcard_constraints:
        toy=r"n[0-9]+-lifted[0-9]+",
    conda:
        "../envs/cradle.yaml"
    params:
        movies=lambda w: plain(dict(config["movies"])),
    message:
        "Drawing the movie of desk toy {wildcards.toy}"
    script:
        "../scripts/desk_toy_movie.py"


rule desk_toy_movies:
    # every desk toy of the full form of the desk-toy analysis
    input:
        desk_toy_movie_targets(),
