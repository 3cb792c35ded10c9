"""Every job's cost estimate (cradle.pipeline.budget) against what the job measured.

    python benchmarks/estimates.py [--results results]

Reads Snakemake's per-job benchmark files (``results/benchmarks/{sim,homoclinic,map}/NAME.tsv``:
wall seconds and max RSS; for a job forked from the warm process, the peak its log states) of the last
build and the estimates of config.yaml's entries, and
writes the table ``estimates`` of docs/performance.md, with the ratio estimate / measured. Run it
after a build from clean (``snakemake -j2``): a job's wall time includes waiting for the other
core, so compare builds made the same way.
"""
from __future__ import annotations

import argparse
import csv
import re
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from doctable import publish  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def measured(path: Path, log: Path | None = None) -> tuple[float, float] | None:
    """Wall seconds and peak memory (bytes) of a job: Snakemake's benchmark file, whose memory is that of the
    job's own process; a job forked from the warm process (cradle.pipeline.warm) ran in a child of another
    process, and its log says its peak (with the imported modules' pages, as a fresh process would have)."""
    if not path.exists():
        return None
    with open(path) as f:
        row = next(csv.DictReader(f, delimiter="\t"))
    rss = float(row["max_rss"]) * 2**20
    if log is not None and log.exists():
        for line in log.read_text().splitlines():
            if m := re.search(r"forked job: peak resident memory ([\d.]+) MB", line):
                rss = float(m.group(1)) * 2**20
    return float(row["s"]), rss


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--results", default=str(ROOT / "results"))
    args = ap.parse_args(argv)
    from cradle.pipeline import budget, config as cc

    cfg = cc.load(ROOT / "config.yaml")
    rows, ratios = [], {"time": [], "memory": []}
    for e in budget.estimates(cc.typed(cfg)):
        section, name = e.key.split(".", 1)
        folder = {"scenes": "sim", "homoclinic": "homoclinic", "map": "map"}.get(section)
        got = (measured(Path(args.results) / "benchmarks" / folder / f"{name}.tsv",
                        Path(args.results) / "logs" / folder / f"{name}.log") if folder else None)
        if got is None:
            continue
        s, rss = got
        ratios["time"].append(e.seconds / s)
        ratios["memory"].append(e.memory_bytes / rss)
        rows.append(f"| {e.key} | {budget.fmt_duration(e.seconds)} | {budget.fmt_duration(s)} | {e.seconds / s:.2g} "
                    f"| {budget.fmt_bytes(e.memory_bytes)} | {budget.fmt_bytes(rss)} | {e.memory_bytes / rss:.2g} |")
    if not rows:
        sys.exit(f"no benchmark files under {args.results}/benchmarks: build first (snakemake -j2)")
    summary = ", ".join(f"{k}: estimate / measured from {min(v):.2g} to {max(v):.2g}" for k, v in ratios.items())
    text = (f"Estimates of config.yaml's jobs against their last measured build ({time.strftime('%Y-%m-%d')}; "
            f"{summary}):\n\n| job | estimated time | measured wall | ratio | estimated peak | measured max RSS "
            "| ratio |\n|---|---|---|---|---|---|---|\n" + "\n".join(rows))
    publish("performance.md", "estimates", text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
