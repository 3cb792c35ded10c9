"""The claims table's rows and their rendering (results/paper_checks.{csv,md}): the row, the verdict rule
"within the paper's printed precision", and the CSV and Markdown writers (:mod:`cradle.analyses.paper_checks`
computes the rows)."""
from __future__ import annotations

import csv
import io as _io
from dataclasses import dataclass

import numpy as np

#: A harmonic is "present" in a spectrum when its height is at least this
#: fraction of the carrier (and, for a harmonic, a coherent peak: checks.PEAK_OVER_BAND)
HARMONIC_PRESENT = 0.01

COLUMNS = ("label", "quantity", "paper", "ours", "tolerance", "verdict", "measured")


@dataclass
class Row:
    label: str
    quantity: str
    paper: str
    ours: str
    verdict: str
    measured: str
    tolerance: str = ""


def printed_tol(paper: str) -> str:
    """The tolerance of agrees_printed, as the row states it."""
    return f"+-{printed_unit(paper):g} (one unit of the paper's last printed digit)"


def printed_unit(text: str) -> float:
    """One unit of the last printed digit of a number written like '2.11', '3.8e-3', '175'."""
    mant, _, exp = text.lower().partition("e")
    decimals = len(mant.split(".")[1]) if "." in mant else 0
    return 10.0 ** (-decimals) * 10.0 ** (int(exp) if exp else 0)


def agrees_printed(paper: str, ours: float) -> str:
    if ours is None or not np.isfinite(ours):
        return "not comparable"
    return "agrees" if abs(ours - float(paper)) <= printed_unit(paper) * (1 + 1e-9) else "disagrees"


def _fmt(x, digits=4) -> str:
    if isinstance(x, (bool, np.bool_)):
        return "yes" if x else "no"
    if x is None or (isinstance(x, float) and not np.isfinite(x)):
        return "none"
    return f"{x:.{digits}g}"


def to_csv(rows) -> str:
    buf = _io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(COLUMNS)
    for r in rows:
        w.writerow([getattr(r, c) for c in COLUMNS])
    return buf.getvalue()


def to_markdown(rows) -> str:
    def cell(s):
        return str(s).replace("|", "\\|")
    lines = ["| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    lines += ["| " + " | ".join(cell(getattr(r, c)) for c in COLUMNS) + " |" for r in rows]
    counts = {v: sum(r.verdict == v for r in rows) for v in ("agrees", "disagrees", "not comparable")}
    summary = ", ".join(f"{n} {v}" for v, n in counts.items())
    return (f"# The paper's numerical statements against ours\n\n{len(rows)} statements: {summary}.\n\n"
            + "\n".join(lines) + "\n")
