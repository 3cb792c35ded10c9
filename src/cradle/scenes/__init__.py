"""A scene's physics: homoclinic solutions, initial data, the exact (nc) and DpS (dfnls) runs and their
comparison (:mod:`.stages`), the same block by block for a large store (:mod:`.streamed`), and the error
a stage raises (:mod:`.failure`). Specs and Datasets in, Datasets out: no paths, no Snakemake."""
