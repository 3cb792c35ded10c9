"""The map from the paper's labels to its numbers (benchmarks/paper_labels.py, docs/paper-map.md): counted from
the LaTeX source, and holding every label the project writes."""
from __future__ import annotations

import importlib.util
import re
import sys
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[1]


def _module():
    spec = importlib.util.spec_from_file_location("paper_labels", ROOT / "benchmarks" / "paper_labels.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules["paper_labels"] = module          # dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


PL = _module()
MAP = {lab.label: lab for lab in PL.read_csv()}
CONFIG = yaml.safe_load((ROOT / "config.yaml").read_text())

#: where the project writes labels: the code, the workflow, config.yaml and the docs
SCANNED = sorted({*ROOT.glob("src/**/*.py"), *ROOT.glob("workflow/**/*.smk"), *ROOT.glob("workflow/**/*.py"),
                  ROOT / "Snakefile", ROOT / "config.yaml", *ROOT.glob("docs/*.md"), *ROOT.glob("docs/*/*.md"),
                  ROOT / "docs" / "tutorial.py",
                  ROOT / "README.md"})

#: an equation label as the project writes it: a lowercase name in parentheses, not the argument of a call
#: (E(t), f(x)) and without a hyphen (the paper's equation labels have none; (alpha-1) is maths)
PARENTHESISED = re.compile(r"(?<![\w)\]\.'\"])\(([a-z][a-z0-9]+)\)")
#: a figure label in text: the paper's prefixes followed by a number (plot4-5, fft106, traj3, loc1); the
#: labels without a number (plotcomplin, fftseuil, bcsc, fini) are found as config keys
FIGURE_LIKE = re.compile(r"(?<![\w./-])((?:plot|fft|traj|loc)[a-z]*\d+[a-z\d]*(?:-\d+)*)(?![\w-])")
#: names of Greek letters in parentheses are maths, (tau), not labels
GREEK = {"alpha", "beta", "gamma", "delta", "epsilon", "eps", "mu", "nu", "omega", "phi", "pi", "rho", "sigma",
         "tau", "theta", "xi", "zeta", "kappa", "lambda"}


def _declared_names() -> set[str]:
    """The project's own names, declared in config.yaml: scenes, map orbits, homoclinic solutions, analyses."""
    names = set()
    for section in ("scenes", "map", "homoclinic", "beyond"):
        names |= set(CONFIG.get(section) or {})
    return names


def _distance(a: str, b: str) -> int:
    prev = list(range(len(b) + 1))
    for i, ca in enumerate(a, 1):
        cur = [i]
        for j, cb in enumerate(b, 1):
            cur.append(min(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (ca != cb)))
        prev = cur
    return prev[-1]


def _near_a_label(token: str) -> list[str]:
    """The paper's labels a token is a slip away from: one edit for labels of 4 to 6 letters, two from 7
    (shorter labels are too close to ordinary words to tell a slip)."""
    return [lab for lab in MAP if len(lab) >= 4 and 0 < _distance(token, lab) <= (1 if len(lab) < 7 else 2)]


def _occurrences(pattern):
    for path in SCANNED:
        for m in pattern.finditer(path.read_text()):
            yield m.group(1), path.relative_to(ROOT)


def test_the_map_is_the_source_counted():
    if not PL.TEX.exists():
        pytest.skip(f"{PL.TEX} absent (a fresh clone has no ../shared): tested against the committed "
                    "docs/paper-labels.csv only")
    labels = PL.parse(PL.TEX.read_text())
    assert PL.to_csv(labels) == PL.CSV.read_text(), "rerun python benchmarks/paper_labels.py"
    assert len(labels) == len(set(re.findall(r"\\label\{([^}]*)\}", PL.strip_comments(PL.TEX.read_text()))))


def test_the_docs_table_is_the_committed_map():
    page = (ROOT / "docs" / "paper-map.md").read_text()
    block = re.search(r"<!-- table: paper-labels [^>]*-->\n(.*?)<!-- end table: paper-labels -->", page, re.S)
    assert block and block.group(1) == PL.markdown(list(MAP.values())), "rerun python benchmarks/paper_labels.py"
    # the hand-written table of the most used labels prints the map's numbers
    for labels, printed in re.findall(r"^\| (`[^|]+`) \| (\([^|]*\)) \|", page, re.M):
        names = re.findall(r"`([^`]+)`", labels)
        assert printed == ", ".join(MAP[n].printed for n in names), (labels, printed)


def test_counting_follows_latex():
    tex = r"""\documentclass{amsart}
\newtheorem{theorem}{Theorem}
\newtheorem{lemma}[theorem]{Lemma}
\begin{document}
\section{\label{one}One}
\begin{equation}\label{a}x\end{equation}
% \begin{equation}\label{commented}x\end{equation}
\begin{eqnarray}
\label{b} x &=& y \\
\nonumber &=& z \\
\label{c} &=& w
\end{eqnarray}
\begin{eqnarray*} x \\ y \end{eqnarray*}
$$ z $$
\begin{theorem}\label{t}\begin{equation}\label{d}x\end{equation}\end{theorem}
\begin{lemma}\label{l}x\end{lemma}
\subsection{\label{two}Two}
\begin{figure}\caption{\label{f}}\end{figure}
\section{\label{three}Three}
\begin{equation}\label{e}x\end{equation}
\end{document}"""
    got = {lab.label: (lab.kind, lab.number, lab.section) for lab in PL.parse(tex)}
    assert got == {"one": ("section", "1", "1"), "a": ("equation", "1", "1"), "b": ("equation", "2", "1"),
                   "c": ("equation", "3", "1"), "t": ("theorem", "1", "1"), "d": ("equation", "4", "1"),
                   "l": ("lemma", "2", "1"), "two": ("subsection", "1.1", "1.1"), "f": ("figure", "1", "1.1"),
                   "three": ("section", "2", "2"), "e": ("equation", "5", "2")}
    within = tex.replace(r"\begin{document}", "\\numberwithin{equation}{section}\n\\begin{document}")
    assert PL.parse(within)[-1].number == "2.1"
    with pytest.raises(ValueError, match="subequations"):
        PL.parse(tex.replace(r"\end{document}", r"\begin{subequations}\end{subequations}\end{document}"))


def test_every_equation_label_written_is_the_papers():
    """(nc), (dfnls), ...: a parenthesised name that is one of the paper's labels is in the map; one that is a
    slip away from a label is an error (a typo, or a label the paper does not have)."""
    used, slips = set(), []
    for token, path in _occurrences(PARENTHESISED):
        if token in MAP:
            used.add(token)
        elif token not in GREEK and _near_a_label(token):
            slips.append((str(path), token, _near_a_label(token)))
    assert not slips
    assert {"nc", "dfnls", "ansatz", "dpsstn", "ansatzapprox", "ansatzapproxst2", "perturb", "freq", "ad",
            "comp1", "comp2", "wleadingorder", "ham", "vhertz", "breatherdps", "inteq"} <= used
    assert all(MAP[t].kind in ("equation", "figure", "section", "subsection") for t in used)


def test_every_figure_label_used_is_the_papers():
    """The figures of config.yaml and cradle.figures.FIGURES (less the analyses' own, named by their
    analysis) and every figure-like name in the text (less the names config.yaml declares) are the paper's
    figures."""
    from cradle.analyses.registry import ANALYSES
    from cradle.figures import FIGURES

    figures = {lab for lab, entry in MAP.items() if entry.kind == "figure"}
    assert set(CONFIG["figures"]) <= figures
    assert set(FIGURES) - {a.name for a in ANALYSES.values()} <= figures
    own = _declared_names()
    named = {(token, str(path)) for token, path in _occurrences(FIGURE_LIKE) if token not in own}
    assert {t for t, _ in named} <= figures, sorted((t, p) for t, p in named if t not in figures)
    assert len({t for t, _ in named}) >= 10          # the scan sees the text


def test_the_readme_sections_hold_their_figures():
    """The README's table 'section of the paper | labels' puts each label in the (sub)section the paper does."""
    rows = re.findall(r"^\| (\d\.\d) [^|]*\| ([^|]*)\|", (ROOT / "README.md").read_text(), re.M)
    assert len(rows) == 4
    for section, cell in rows:
        for label in re.findall(r"`([^`]+)`", cell):
            assert MAP[label].section == section, (label, section, MAP[label].section)


def test_numbers_quoted_in_the_readme_are_the_maps():
    """'(nc) is (1)', 'plot4-5 Figure 5': a number the README quotes for a label is the map's."""
    text = (ROOT / "README.md").read_text()
    quoted = re.findall(r"\((\w+)\)(?: is)? (\(\d+\))", text) + re.findall(r"([\w-]+) (Figure \d+)", text)
    assert len(quoted) >= 4
    for label, printed in quoted:
        assert MAP[label].printed == printed, (label, printed)
