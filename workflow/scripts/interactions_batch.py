"""Snakemake adapter for breather-interactions: one batch of cases -> results/interactions/batch/<form>/<chunk>.nc
(rule breather_interactions_batch); the batches are gathered by the analysis rules (workflow/scripts/analysis.py)."""
import logging

from cradle.analyses import breather_interactions
from cradle.pipeline.runner import run

sm = snakemake  # injected by Snakemake
log = logging.getLogger("cradle")
spec, w = dict(sm.params.spec), sm.wildcards
run(lambda: breather_interactions.batch_dataset(spec, int(w.chunk), log=log.info), sm.output[0],
    sm.log[0], label=f"breather-interactions {w.form} batch {w.chunk}")
