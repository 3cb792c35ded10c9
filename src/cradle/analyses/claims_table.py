"""The claims table's rows: the row, its columns and the verdict rule "within the paper's printed precision"
(:mod:`cradle.analyses.paper_checks` computes the rows; :mod:`cradle.figures.paper_checks` writes them out as
CSV and Markdown).

An analysis beyond the paper whose output holds rows for the table (the cited papers' statements against its
results) stores them as one group, :func:`group` (variables :data:`GROUP_VARIABLES`: the :data:`COLUMNS` and
:data:`QUALITATIVE`), and names that group in its declaration (``claims=`` of
:class:`cradle.analyses.protocol.Analysis`); the table collects every such group (:func:`read_group`)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from cradle.data.variables import Var

if TYPE_CHECKING:
    import xarray as xr

#: A harmonic is "present" in a spectrum when its height is at least this
#: fraction of the carrier (and, for a harmonic, a coherent peak: checks.PEAK_OVER_BAND)
HARMONIC_PRESENT = 0.01

COLUMNS = ("label", "quantity", "paper", "ours", "tolerance", "verdict", "measured", "explained_in")
#: the variable of an analysis's claims group beside the columns: 1 for a qualitative statement (the cited paper
#: prints no number; the verdict is a yes/no judged as the row's tolerance says), 0 for a numerical one
QUALITATIVE = "qualitative"


@dataclass
class Row:
    label: str
    quantity: str
    paper: str
    ours: str
    verdict: str
    measured: str
    tolerance: str = ""
    #: the paragraph of the docs that explains the verdict, "<page>.md#<anchor>" under docs/; every row that
    #: disagrees needs one (tests/analyses/test_checks.py), declared beside its claim (:func:`explained`)
    explained_in: str = ""
    #: a qualitative statement (the cited paper prints no number for it): marked so in the table's tolerance cell
    qualitative: bool = False


def explained(where: str, rows: list[Row]) -> list[Row]:
    """The rows of one claim, each pointing at the paragraph ``where`` ("<page>.md#<anchor>" under docs/) that
    explains its verdict, unless a row names its own."""
    for r in rows:
        r.explained_in = r.explained_in or where
    return rows


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


def _fmt(x: object, digits: int = 4) -> str:
    if isinstance(x, (bool, np.bool_)):
        return "yes" if x else "no"
    if x is None or (isinstance(x, float) and not np.isfinite(x)):
        return "none"
    return f"{x:.{digits}g}"


class Results:
    """The outputs the table reads, by kind and name, from the Datasets :func:`reads` names."""

    def __init__(self, inputs: dict) -> None:
        self.inputs = inputs

    def initial(self, scene: str) -> xr.Dataset:
        return self.inputs[f"{scene}/initial"]

    def sim(self, scene: str, model: str) -> xr.Dataset:
        return self.inputs[f"{scene}/{model}"]

    def metrics(self, scene: str) -> xr.Dataset:
        return self.inputs[f"{scene}/metrics"]

    def homoclinic(self, name: str) -> xr.Dataset:
        return self.inputs[f"homoclinic/{name}"]


#: the variables of an analysis's claims group (:func:`group`)
GROUP_VARIABLES = {"row": Var(("row",), "index of a cited paper's statement"),
                   **{c: Var(("row",), f"claims-table column {c} (cradle.analyses.claims_table.COLUMNS)")
                      for c in COLUMNS},
                   QUALITATIVE: Var(("row",), "1 if the statement is qualitative (the cited paper prints no number)")}


def group(rows: list[Row]) -> tuple[dict, dict]:
    """(data, coords) of an analysis's claims group (:data:`GROUP_VARIABLES`) holding ``rows``."""
    data: dict = {c: np.array([getattr(r, c) for r in rows], dtype=object) for c in COLUMNS}
    data[QUALITATIVE] = np.array([int(r.qualitative) for r in rows], dtype=np.int64)
    return data, {"row": np.arange(len(rows))}


def read_group(ds: xr.Dataset) -> list[Row]:
    """The rows of a stored claims group (:func:`group`); a group stored without :data:`QUALITATIVE` holds
    numerical statements only."""
    n = ds.sizes.get("row", 0)
    flag = np.asarray(ds[QUALITATIVE].values) if QUALITATIVE in ds else np.zeros(n, dtype=np.int64)
    return [Row(**{c: str(ds[c].values[i]) for c in COLUMNS}, qualitative=bool(flag[i])) for i in range(n)]
