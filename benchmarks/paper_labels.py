"""The paper's labels and the numbers they print as, counted from its LaTeX source.

    python benchmarks/paper_labels.py [--tex ../shared/paper/newtons-cradle-dps.tex]

The project names the paper's equations and figures by their LaTeX labels ((nc), (dfnls), plot4-5, ...);
a reader holding the printed paper needs the numbers. This script counts them the way LaTeX does and writes

* ``docs/paper-labels.csv``: one line per ``\\label`` (label, kind, number, section), the committed copy the
  tests read when the source is absent (a fresh clone has no ``../shared``);
* the table ``paper-labels`` of ``docs/paper-map.md`` (between its markers, :mod:`doctable`).

Counting (:func:`parse`): comments stripped; the document class ``amsart`` numbers equations and figures
consecutively through the paper unless the preamble says ``\\numberwithin{equation}{section}`` (then
"section.n"); an ``equation`` takes one number, every row of ``eqnarray``/``align``/``gather`` one unless the row
holds ``\\nonumber``/``\\notag``, a ``multline`` one; starred environments none; a figure one per
``\\begin{figure}``; sections and subsections as ``\\section``/``\\subsection`` step them; theorem-like
environments by the counters their ``\\newtheorem`` declares. A construct this counting does not know
(``subequations``, ``\\tag``, ``\\setcounter``, ``\\appendix``) stops it with its name rather than guessing.
"""
from __future__ import annotations

import argparse
import csv
import io
import re
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: where the source sits beside a checkout (the fresh clone of CI may not have it)
TEX = ROOT.parent / "shared" / "paper" / "newtons-cradle-dps.tex"
CSV = ROOT / "docs" / "paper-labels.csv"
FIELDS = ("label", "kind", "number", "section")

#: displayed-maths environments whose rows are numbered one by one
ROWS = {"eqnarray", "align", "gather", "flalign", "alignat"}
#: environments that take exactly one number
SINGLE = {"equation", "multline"}
UNSUPPORTED = ("subequations", r"\tag", r"\setcounter", r"\addtocounter", r"\appendix", r"\eqno")

_TOKEN = re.compile(r"\\(begin|end)\{([^}]*)\}|\\(section|subsection)\*?\{|\\label\{([^}]*)\}|(\\\\)"
                    r"|\\(nonumber|notag)\b")


@dataclass(frozen=True)
class Label:
    label: str
    kind: str        # equation, figure, section, subsection, or a theorem-like environment
    number: str      # as printed: "12" for (12), "4.1" for a subsection
    section: str     # the (sub)section it lives in, e.g. "4.1"

    @property
    def printed(self) -> str:
        """How the paper prints a reference to it: (12), Figure 3, Section 4.1, Theorem 1."""
        if self.kind == "equation":
            return f"({self.number})"
        return f"{self.kind.capitalize()} {self.number}"


def strip_comments(text: str) -> str:
    """The source without its comments (an unescaped % to the end of the line)."""
    return re.sub(r"(?<!\\)%[^\n]*", "", text)


def _theorem_counters(preamble: str) -> dict[str, str]:
    """environment -> the counter it steps, from ``\\newtheorem{env}[shared]{Title}`` (its own if none shared)."""
    out = {}
    for env, shared, within in re.findall(r"\\newtheorem\{(\w+)\}(?:\[(\w+)\])?\{[^}]*\}(?:\[(\w+)\])?", preamble):
        if within:
            raise ValueError(f"\\newtheorem{{{env}}} numbered within {within}: not counted by this script")
        out[env] = shared or env
    return out


def parse(tex: str) -> list[Label]:
    """Every ``\\label`` of the source with the number LaTeX gives it, in the order of the source."""
    tex = strip_comments(tex)
    preamble, sep, body = tex.partition(r"\begin{document}")
    if not sep:
        raise ValueError("no \\begin{document}")
    body = body.partition(r"\end{document}")[0]
    for construct in UNSUPPORTED:
        if construct in body:
            raise ValueError(f"{construct} in the source: not counted by this script")
    within = re.search(r"\\numberwithin\{equation\}\{(\w+)\}", preamble)
    if within and within.group(1) != "section":
        raise ValueError(f"equations numbered within {within.group(1)}: not counted by this script")
    theorems = _theorem_counters(preamble)
    count = {"equation": 0, "figure": 0, "section": 0, "subsection": 0, **{c: 0 for c in theorems.values()}}
    stack: list[str] = []
    row_labels: list[str] = []          # labels of the current row of a row-numbered environment
    row_numbered = True
    out: list[Label] = []
    last_section = ""                   # the sectioning command most recently stepped

    def where() -> str:
        s, ss = count["section"], count["subsection"]
        return f"{s}.{ss}" if ss else str(s)

    def eq_number() -> str:
        return f"{count['section']}.{count['equation']}" if within else str(count["equation"])

    def close_row():
        nonlocal row_numbered
        if row_numbered:
            count["equation"] += 1
            out.extend(Label(lab, "equation", eq_number(), where()) for lab in row_labels)
        elif row_labels:
            raise ValueError(f"label {row_labels[0]!r} on an unnumbered row")
        row_labels.clear()
        row_numbered = True

    for m in _TOKEN.finditer(body):
        what, env, sect, label, newline, nonum = m.groups()
        inner = stack[-1] if stack else ""
        if what == "begin":
            stack.append(env)
            if env in SINGLE:
                count["equation"] += 1
            elif env == "figure":
                count["figure"] += 1
            elif env in theorems:
                count[theorems[env]] += 1
            elif env in ROWS:
                row_labels.clear()
                row_numbered = True
        elif what == "end":
            if not stack or stack[-1] != env:
                raise ValueError(f"\\end{{{env}}} closes {stack[-1] if stack else 'nothing'}")
            if env in ROWS:
                close_row()
            stack.pop()
        elif sect:
            count[sect] += 1
            if sect == "section":
                count["subsection"] = 0
                if within:
                    count["equation"] = 0
            last_section = sect
        elif newline and inner in ROWS:
            close_row()
        elif nonum and inner in ROWS:
            row_numbered = False
        elif label is not None:
            if inner in ROWS:
                row_labels.append(label)
            elif inner in SINGLE:
                out.append(Label(label, "equation", eq_number(), where()))
            elif "figure" in stack:
                out.append(Label(label, "figure", str(count["figure"]), where()))
            elif inner in theorems:
                out.append(Label(label, inner, str(count[theorems[inner]]), where()))
            elif not stack or inner == "document":
                # \section{\label{x}...}: the label names the sectioning command just stepped
                out.append(Label(label, last_section, where(), where()))
            else:
                raise ValueError(f"label {label!r} inside {inner}: not counted by this script")
    names = [lab.label for lab in out]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        raise ValueError(f"labels defined twice: {sorted(dup)}")
    return out


def to_csv(labels: list[Label]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(FIELDS)
    for lab in labels:
        w.writerow([getattr(lab, f) for f in FIELDS])
    return buf.getvalue()


def read_csv(path: Path = CSV) -> list[Label]:
    """The committed copy of the map."""
    with path.open(newline="") as f:
        return [Label(**row) for row in csv.DictReader(f)]


def markdown(labels: list[Label]) -> str:
    """The map as a Markdown table in the order of the paper."""
    lines = ["| label | the paper prints | kind | in section |", "|---|---|---|---|"]
    lines += [f"| `{lab.label}` | {lab.printed} | {lab.kind} | {lab.section} |" for lab in labels]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tex", type=Path, default=TEX)
    args = ap.parse_args(argv)
    if not args.tex.exists():
        print(f"{args.tex}: no such file (the paper's LaTeX source)", file=sys.stderr)
        return 1
    labels = parse(args.tex.read_text())
    CSV.write_text(to_csv(labels))
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from doctable import publish

    publish("paper-map.md", "paper-labels", markdown(labels))
    kinds = {k: sum(lab.kind == k for lab in labels) for k in dict.fromkeys(lab.kind for lab in labels)}
    print(f"{len(labels)} labels: " + ", ".join(f"{n} {k}" for k, n in kinds.items()))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
