"""The claims table written out: results/paper-checks/paper-checks.{csv,md} from the rows of
results/paper-checks/paper-checks.nc (:mod:`cradle.analyses.paper_checks`).

The "figure" of the analysis paper-checks is two tables (:func:`tables`), written by the generic drawing rule
(``tables`` of :class:`cradle.analyses.protocol.Analysis`): the CSV (one line per statement, the file's text
variables in their order: :data:`cradle.analyses.claims_table.COLUMNS`) and the Markdown page with the verdict
counts, where a row that does not agree links its verdict to the paragraph of the docs that explains it (the
row's ``explained_in``).
"""
from __future__ import annotations

import csv
import io as _io

import xarray as xr

VERDICTS = ("agrees", "disagrees", "not comparable")
#: the docs folder seen from the Markdown table, results/paper-checks/paper-checks.md (cradle.pipeline.layout)
DOCS_FROM_TABLE = "../../docs/"


def verdict_cell(row: dict[str, str]) -> str:
    """The verdict, linked to its explanation when it is not "agrees"; "(no explanation yet)" when none is
    declared."""
    verdict, where = row["verdict"], row.get("explained_in", "")
    if verdict == "agrees" or "explained_in" not in row:
        return verdict
    return f"{verdict} ([why]({DOCS_FROM_TABLE}{where}))" if where else f"{verdict} (no explanation yet)"


def table_rows(tree: xr.DataTree | xr.Dataset) -> list[dict[str, str]]:
    """The rows of the claims table file (a tree, or its root Dataset), each ``{column: text}``."""
    ds = tree.to_dataset() if isinstance(tree, xr.DataTree) else tree
    return [{str(c): str(ds[c].values[i]) for c in ds.data_vars} for i in range(ds.sizes.get("row", 0))]


def to_csv(rows: list[dict[str, str]]) -> str:
    """The rows (``{column: text}``) as CSV, the header first."""
    buf = _io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    columns = list(rows[0]) if rows else []
    w.writerow(columns)
    for r in rows:
        w.writerow([r[c] for c in columns])
    return buf.getvalue()


def to_markdown(rows: list[dict[str, str]]) -> str:
    """The rows (``{column: text}``) as a Markdown page: a title, the verdict counts, the table."""
    def cell(s: object) -> str:
        return str(s).replace("|", "\\|")
    columns = [c for c in (rows[0] if rows else []) if c != "explained_in"]
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    lines += ["| " + " | ".join(verdict_cell(r) if c == "verdict" else cell(r[c]) for c in columns) + " |"
              for r in rows]
    counts = {v: sum(r["verdict"] == v for r in rows) for v in VERDICTS}
    summary = ", ".join(f"{n} {v}" for v, n in counts.items())
    return (f"# The paper's numerical statements against ours\n\n{len(rows)} statements: {summary}.\n\n"
            + "\n".join(lines) + "\n")


def tables(tree: xr.DataTree | xr.Dataset) -> dict[str, str]:
    """format -> text of the claims table: ``csv`` and ``md``."""
    rows = table_rows(tree)
    return {"csv": to_csv(rows), "md": to_markdown(rows)}
