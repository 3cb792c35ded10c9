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
    # the movies of every scene under `movies.scenes` in config.yaml, and the minute movies of
    # movies.desk_toy_minute.toys
    input:
        movie_targets(),
        desk_toy_minute_movie_targets(),


# The desk toys of the full form of the desk-toy analysis (cradle.analyses.desk_toy) in motion, drawn to scale in mm
# with each impact in slow motion: a run of the movie's own, stored densely around the impacts
# (cradle.analyses.desk_toy_movie, settings `movies.desk_toy`), drawn by cradle.figures.desk_toy_movie: (nc) beside
# the hard spheres of the first restitution -> results/movies/desk-toy-<toy>.{mp4,gif} and three frames of the
# first impact, results/movies/stills/desk-toy-<toy>-{before,during,after}.png; <toy> a desk toy of the full form
# (n5-lifted1, ...). Not in `all`: `snakemake -j2 desk_toy_movies` builds every one (`cradle animate n5-lifted1
# --desk-toy FILE.nc` draws one of any desk-toy file's spec).
rule desk_toy_movie:
    input:
        code=code_of(
            "workflow/scripts/desk_toy_movie.py",
            "cradle.figures.desk_toy_movie",
            "cradle.analyses.desk_toy_movie",
        ),
    output:
        mp4=L.path("movie", scene="desk-toy-{toy}", ext="mp4"),
        gif=L.path("movie", scene="desk-toy-{toy}", ext="gif"),
        stills=[L.path("movie-still", scene="desk-toy-{toy}", frame=f) for f in ("before", "during", "after")],
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
        spec=lambda w: plain(analysis_spec(ANALYSES["desk-toy"], FULL)),
    message:
        "Drawing the movie of desk toy {wildcards.toy}"
    script:
        "../scripts/desk_toy_movie.py"


rule desk_toy_movies:
    # every desk toy of the full form of the desk-toy analysis
    input:
        desk_toy_movie_targets(),


# The minute as a movie (issue 38): a desk toy of the desk-toy-minute analysis's full form in real time, the first
# impacts, the break-up of one-out-one-out and chosen moments in slow motion (cradle.analyses.desk_toy_minute_movie,
# settings `movies.desk_toy_minute`), drawn by cradle.figures.desk_toy_minute_movie ->
# results/movies/desk-toy-minute-<toy>.{mp4,gif} and three frames, results/movies/stills/desk-toy-minute-<toy>-
# {impact,breakup,late}.png. Part of `movies` (the toys under movies.desk_toy_minute.toys), not of `all`.
rule desk_toy_minute_movie:
    input:
        code=code_of(
            "workflow/scripts/desk_toy_minute_movie.py",
            "cradle.figures.desk_toy_minute_movie",
            "cradle.analyses.desk_toy_minute_movie",
        ),
    output:
        mp4=L.path("movie", scene="desk-toy-minute-{toy}", ext="mp4"),
        gif=L.path("movie", scene="desk-toy-minute-{toy}", ext="gif"),
        stills=[L.path("movie-still", scene="desk-toy-minute-{toy}", frame=f) for f in ("impact", "breakup", "late")],
    log:
        L.path("log", job="movies/desk-toy-minute-{toy}"),
    benchmark:
        L.path("benchmark", job="movies/desk-toy-minute-{toy}")
    wildcard_constraints:
        toy=r"n[0-9]+-lifted[0-9]+",
    conda:
        "../envs/cradle.yaml"
    params:
        movies=lambda w: plain(dict(config["movies"])),
        spec=lambda w: plain(analysis_spec(ANALYSES["desk-toy-minute"], FULL)),
    message:
        "Drawing the minute movie of desk toy {wildcards.toy}"
    script:
        "../scripts/desk_toy_minute_movie.py"


rule desk_toy_minute_movies:
    # the minute movies of the desk toys under movies.desk_toy_minute.toys
    input:
        desk_toy_minute_movie_targets(),
