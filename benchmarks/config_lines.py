"""What the code that declares, loads, validates and resolves the config is made of: the table ``config-lines``
of docs/developing.md.

    python benchmarks/config_lines.py [--no-docs]

Counts the lines of the files issue "One validator, one kernel per model" measures (``pipeline/config``,
``specs``, ``scenes/spec.py``; target: under 1,250) by what each top-level statement, and each method of a declared
class, does: a declared key with its description, a rule across keys, reading a file safely, the validation engine,
the schema and reference generators, ... Each line is counted once, by the statement it lies in; the lines between
statements (blank lines, module docstrings, imports) are their module's own row. Not a timing: any machine.
"""
from __future__ import annotations

import argparse
import ast
import io
import sys
import tokenize
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from doctable import git_commit, publish  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src" / "cradle"
FILES = sorted([*(SRC / "pipeline" / "config").glob("*.py"), *(SRC / "specs").glob("*.py"),
                SRC / "scenes" / "spec.py"])

#: the rows, in the order of the table, with what each holds
KINDS = {
    "declared keys": "the declared classes: each key's type, bound, default and description (the schema's and the "
                     "reference's only source), the shared types, the constants they name",
    "rules across keys": "each class's `check` and its helpers, the checks across entries and sections "
                         "(checks.py)",
    "reading a file": "the bounded, strict YAML read (size, values, depth, UTF-8, a key given twice, huge integers)",
    "values": "angles read and written canonically, the float64 limits, the one-line errors (`Errors`, `show`)",
    "validation engine": "plain values to typed objects against the declared keywords, every problem one line "
                         "(parse.py, declare.py), and `@checked` for public functions' arguments",
    "pass and resolve": "the pass over config.yaml's sections, defaults merged in, SI converted, entries resolved "
                        "for a job, remembered configs",
    "generators": "the JSON Schema and docs/config-reference.md written from the declarations (not run when a "
                  "config is validated)",
    "command line": "`python -m cradle.pipeline.config`",
    "module heads": "module docstrings, imports, `__all__`, blank lines between statements",
}
#: a function or class's kind by (file stem, name); a file's other statements take FILE_KIND's
BY_NAME = {("loading", "main"): "command line",
           ("spec", "in_nc_units"): "pass and resolve", ("spec", "_scaled"): "pass and resolve",
           ("spec", "SI_KEYS"): "pass and resolve", ("spec", "Context"): "rules across keys",
           ("sections", "_holds"): "rules across keys", ("values", "ConfigError"): "values"}
FILE_KIND = {"checks": "rules across keys", "loading": "reading a file", "movies": "declared keys",
             "reference": "generators", "sections": "declared keys", "validate": "pass and resolve",
             "checked": "validation engine", "declare": "validation engine", "parse": "validation engine",
             "schema": "generators", "shared": "declared keys", "values": "values", "spec": "declared keys",
             "__init__": "module heads", "__main__": "command line"}
#: the methods of a declared class that are rules across its keys
RULES = ("check", "_check", "well_placed")


def _name(node: ast.stmt) -> str:
    if isinstance(node, (ast.FunctionDef, ast.ClassDef, ast.AsyncFunctionDef)):
        return node.name
    targets = node.targets if isinstance(node, ast.Assign) else [getattr(node, "target", None)]
    return next((t.id for t in targets if isinstance(t, ast.Name)), "")


def classify(path: Path) -> Counter:
    """Lines of ``path`` by kind."""
    source = path.read_text()
    tree, stem = ast.parse(source), path.stem
    kinds: dict[int, str] = {}

    def mark(node: ast.AST, kind: str) -> None:
        first = min([node.lineno, *(d.lineno for d in getattr(node, "decorator_list", []))])
        for line in range(first, node.end_lineno + 1):
            kinds[line] = kind

    for node in tree.body:
        if isinstance(node, (ast.Import, ast.ImportFrom)) or (isinstance(node, ast.Expr) and node is tree.body[0]):
            continue
        name = _name(node)
        kind = BY_NAME.get((stem, name), FILE_KIND[stem])
        mark(node, kind)
        if isinstance(node, ast.ClassDef) and kind == "declared keys":
            for item in node.body:
                if isinstance(item, ast.FunctionDef) and item.name.startswith(RULES):
                    mark(item, "rules across keys")
    total = len(source.splitlines())
    return Counter(kinds.get(line, "module heads") for line in range(1, total + 1))


def code_lines(path: Path) -> set[int]:
    """The lines of ``path`` that hold code: a token other than a comment, and not a docstring (of the module, a
    class or a function)."""
    source = path.read_text()
    docs: set[int] = set()
    for node in ast.walk(ast.parse(source)):
        body = getattr(node, "body", None)
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and body and \
                isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) and \
                isinstance(body[0].value.value, str):
            docs.update(range(body[0].lineno, body[0].end_lineno + 1))
    layout = {tokenize.COMMENT, tokenize.NL, tokenize.NEWLINE, tokenize.INDENT, tokenize.DEDENT, tokenize.ENDMARKER}
    lines: set[int] = set()
    for token in tokenize.generate_tokens(io.StringIO(source).readline):
        if token.type not in layout:
            lines.update(range(token.start[0], token.end[0] + 1))
    return lines - docs


def readings() -> list[tuple[str, int]]:
    """The count under each reading of "lines of code" (the issue does not say which it means)."""
    generators = {p for p in FILES if FILE_KIND.get(p.stem) == "generators"}
    code = {p: len(code_lines(p)) for p in FILES}
    return [("physical lines (`wc -l`, the table above)", sum(len(p.read_text().splitlines()) for p in FILES)),
            ("lines holding code (no blank line, comment or docstring)", sum(code.values())),
            ("the same without the two generators", sum(n for p, n in code.items() if p not in generators)),
            ("statements (Python's `ast`, compound ones counted once each)",
             sum(isinstance(n, ast.stmt) for p in FILES for n in ast.walk(ast.parse(p.read_text()))))]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-docs", action="store_true", help="print the table only")
    args = ap.parse_args(argv)
    counts: Counter = Counter()
    for path in FILES:
        counts += classify(path)
    total = sum(counts.values())
    head = git_commit()
    rows = [f"| {kind} | {counts[kind]} | {what} |" for kind, what in KINDS.items()]
    text = (f"`python benchmarks/config_lines.py` at commit {head}: {len(FILES)} files, {total} lines "
            f"(target of the issue: under 1,250)\n\n| what | lines | holds |\n|---|---:|---|\n" + "\n".join(rows)
            + f"\n| **all** | **{total}** | |\n\nThe same files under each reading of \"lines\":\n\n"
            "| reading | count |\n|---|---:|\n" + "\n".join(f"| {what} | {n} |" for what, n in readings()) + "\n")
    print(text)
    if not args.no_docs:
        publish("developing.md", "config-lines", text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
