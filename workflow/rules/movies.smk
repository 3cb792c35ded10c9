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
