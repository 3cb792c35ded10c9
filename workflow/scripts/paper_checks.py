"""Snakemake adapter: the paper-claims table -> results/paper_checks.{csv,md}."""
from pathlib import Path

from cradle.analyses import paper_checks as checks
from cradle.data.io import write_text
from cradle.pipeline.runner import setup_logging

sm = snakemake  # noqa: F821 (injected by Snakemake)
setup_logging(sm.log[0])
rows = checks.paper_checks(Path(sm.output.csv).parent, sm.params.scenes, sm.params.homoclinic)
write_text(checks.to_csv(rows), sm.output.csv)
write_text(checks.to_markdown(rows), sm.output.md)
