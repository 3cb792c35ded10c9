"""The layout rules of docs/developing.md, read from the sources with ``ast``.

1. Layers: a package of src/cradle imports only its own package and the packages of lower layers
   (imports inside functions count; ``if TYPE_CHECKING:`` blocks do not); the two packages of one
   layer do not import each other.
2. No import cycle between the modules (files) of src/cradle.
3. Below the pipeline no code takes or indexes a mapping as a spec: ``spec["alpha"]``,
   ``cfg.get("N")``, ``f(**spec)``, ``getattr(obj, f"resolved_{name}")``.

``python tests/test_structure.py`` prints every violation and the counts the structural issues quote
(spec-mapping reads, parameter-check call sites, modules and lines of src/cradle, of the config code, of
config.yaml and of the generated schema).
"""
from __future__ import annotations

import ast
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src"
CRADLE = SRC / "cradle"

#: layer of each package (docs/developing.md); "cradle" is cradle/__init__.py and cradle/__main__.py, the top
LAYERS = {"specs": 0, "data": 0, "models": 1, "integrators": 2, "measurements": 2, "scenes": 3, "analyses": 4,
          "figures": 5, "pipeline": 6, "cradle": 6}
#: packages of one layer that may import each other: the top modules are the pipeline's command line
PEERS = {frozenset({"pipeline", "cradle"})}

#: names a spec taken as a mapping goes by (a name, or the last attribute of a chain: self.spec, job.params)
SPEC_NAMES = {"spec", "cfg", "config", "ini", "initial", "params", "section", "b", "sec"}
#: the hand-written per-function parameter checks the declarations replace
CHECKS = {"check_alpha", "check_bc", "check_positive", "check_choice"}


def modules() -> dict[str, Path]:
    """Every module of src/cradle by dotted name (a package by its own name: cradle.data for data/__init__.py)."""
    out = {}
    for path in sorted(CRADLE.rglob("*.py")):
        parts = path.relative_to(SRC).with_suffix("").parts
        out[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return out


MODULES = modules()


def package(module: str) -> str:
    """The layer package of a module: cradle.pipeline.config.loading -> pipeline; cradle, cradle.__main__ -> cradle."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and parts[1] in LAYERS else "cradle"


def _is_type_checking(node: ast.If) -> bool:
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def _walk(tree: ast.AST) -> Iterator[ast.AST]:
    """Every node, skipping the bodies of ``if TYPE_CHECKING:`` (annotations only, never run)."""
    stack = [tree]
    while stack:
        node = stack.pop()
        yield node
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.If) and _is_type_checking(child):
                stack.extend(child.orelse)
            else:
                stack.append(child)


def _called(call: ast.Call) -> str | None:
    """The name a call calls: f(...) -> f, mod.f(...) -> f."""
    func = call.func
    return func.id if isinstance(func, ast.Name) else func.attr if isinstance(func, ast.Attribute) else None


def _is_text(node: ast.AST) -> bool:
    return isinstance(node, ast.JoinedStr) or (isinstance(node, ast.Constant) and isinstance(node.value, str))


def _parse(path: Path) -> ast.Module:
    return ast.parse(path.read_text(), filename=str(path))


def _resolve(module: str, node: ast.ImportFrom) -> str:
    """The absolute module a ``from X import ...`` names (relative imports resolved against ``module``)."""
    if not node.level:
        return node.module or ""
    is_package = MODULES[module].name == "__init__.py"
    base = module.split(".")
    base = base[:len(base) - node.level + (1 if is_package else 0)]
    return ".".join(base + ([node.module] if node.module else []))


@dataclass(frozen=True)
class Import:
    """One import of a cradle module by another, where it is written."""

    source: str
    target: str
    line: int

    def __str__(self) -> str:
        return f"{MODULES[self.source].relative_to(ROOT)}:{self.line}: {self.source} -> {self.target}"


def imports(module: str) -> list[Import]:
    """The cradle modules ``module`` imports: ``import``, ``from ... import`` (a name that is a module counts as
    that module) and ``importlib.import_module("cradle....")`` with a literal name, at any depth."""
    out = []
    for node in _walk(_parse(MODULES[module])):
        targets: list[str] = []
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = _resolve(module, node)
            targets = [f"{base}.{a.name}" if f"{base}.{a.name}" in MODULES else base for a in node.names]
        elif isinstance(node, ast.Call) and _called(node) == "import_module" and node.args and _is_text(node.args[0]):
            if isinstance(node.args[0], ast.Constant):  # a built name (f-string) cannot be followed
                targets = [str(node.args[0].value)]
        for target in dict.fromkeys(targets):
            if target == "cradle" or target.startswith("cradle."):
                # import cradle.a.b.name: the longest prefix that is a module
                while target not in MODULES and "." in target:
                    target = target.rsplit(".", 1)[0]
                out.append(Import(module, target, node.lineno))
    return sorted(out, key=lambda imp: (imp.line, imp.target))


ALL_IMPORTS = [imp for module in MODULES for imp in imports(module)]


def layer_violations() -> list[Import]:
    """Imports of a package of the same layer (not a peer) or of a higher one."""
    bad = []
    for imp in ALL_IMPORTS:
        src, dst = package(imp.source), package(imp.target)
        if src == dst or frozenset({src, dst}) in PEERS:
            continue
        if LAYERS[dst] >= LAYERS[src]:
            bad.append(imp)
    return bad


def import_cycles() -> list[list[str]]:
    """The strongly connected components of the module import graph with more than one module (or a self-import)."""
    graph: dict[str, set[str]] = {m: set() for m in MODULES}
    for imp in ALL_IMPORTS:
        graph[imp.source].add(imp.target)
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    cycles = []

    def connect(v: str) -> None:  # Tarjan's algorithm
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                connect(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1 or v in graph[v]:
                cycles.append(sorted(component))

    sys.setrecursionlimit(max(sys.getrecursionlimit(), 10 * len(MODULES)))
    for v in sorted(graph):
        if v not in index:
            connect(v)
    return sorted(cycles)


#: what follows a Dataset's variable and never a spec's value: ds["x"].values, b["N"].attrs
DATA_ATTRIBUTES = {"values", "data", "attrs", "dims", "sizes", "coords", "sel", "isel", "item", "to_numpy"}
#: annotations that make a name data, not a spec: def f(initial: xr.Dataset)
DATA_TYPES = ("Dataset", "DataArray", "DataTree", "ndarray")


def _spec_name(node: ast.AST) -> str | None:
    """The name a value goes by, when it is one of SPEC_NAMES: ``spec``, ``self.spec``, ``job.params``."""
    name = node.id if isinstance(node, ast.Name) else node.attr if isinstance(node, ast.Attribute) else None
    return name if name in SPEC_NAMES else None


def _data_names(function: ast.AST) -> set[str]:
    """The parameters of ``function`` annotated as Datasets or arrays."""
    args = function.args
    return {a.arg for a in [*args.posonlyargs, *args.args, *args.kwonlyargs]
            if a.annotation is not None and any(t in ast.unparse(a.annotation) for t in DATA_TYPES)}


def spec_mapping_uses(source: str) -> list[tuple[int, str, str]]:
    """(line, kind, code) for each place the module ``source`` reads a spec as a mapping: ``spec["k"]``,
    ``spec.get("k")``, ``**spec``, or reaches an attribute by a built name ``getattr(x, f"...")``. A Dataset is
    not a spec: a subscript followed by ``.values`` (``.attrs``, ...) or of a parameter annotated as a Dataset
    is data."""
    tree = ast.parse(source)
    parent = {child: node for node in ast.walk(tree) for child in ast.iter_child_nodes(node)}
    data: dict[ast.AST, set[str]] = {}  # per function, its Dataset parameters

    def is_spec(node: ast.AST) -> bool:
        name = _spec_name(node)
        scope = parent.get(node)
        while scope is not None and not isinstance(scope, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            scope = parent.get(scope)
        if scope is not None and isinstance(node, ast.Name):
            if scope not in data:
                data[scope] = _data_names(scope)
            if node.id in data[scope]:
                return False
        return name is not None

    out = []
    for node in _walk(tree):
        kind = None
        after = parent.get(node)
        if isinstance(after, ast.Attribute) and after.attr in DATA_ATTRIBUTES:
            pass
        elif isinstance(node, ast.Subscript) and _is_text(node.slice) and is_spec(node.value):
            kind = "index"
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "get"
              and node.args and _is_text(node.args[0]) and is_spec(node.func.value)):
            kind = "get"
        elif isinstance(node, ast.Call) and any(k.arg is None and is_spec(k.value) for k in node.keywords):
            kind = "**"
        elif isinstance(node, ast.Dict) and any(k is None and is_spec(v)
                                                for k, v in zip(node.keys, node.values, strict=True)):
            kind = "**"
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "getattr"
              and len(node.args) >= 2 and isinstance(node.args[1], ast.JoinedStr)):
            kind = "getattr"
        if kind:
            out.append((node.lineno, node.col_offset, kind, ast.unparse(node)[:80]))
    return [(line, kind, code) for line, _, kind, code in sorted(out)]


def spec_mapping_violations() -> list[str]:
    """Every spec-as-mapping use below the pipeline, as ``path:line: kind: code``."""
    return [f"{path.relative_to(ROOT)}:{line}: {kind}: {code}"
            for module, path in MODULES.items() if package(module) not in ("pipeline", "cradle")
            for line, kind, code in spec_mapping_uses(path.read_text())]


def test_each_package_imports_only_lower_layers():
    bad = layer_violations()
    assert not bad, f"{len(bad)} imports against the layers (docs/developing.md):\n" + "\n".join(map(str, bad))


def test_specs_imports_nothing_of_cradle():
    bad = [imp for imp in ALL_IMPORTS if package(imp.source) == "specs" and package(imp.target) != "specs"]
    assert not bad, "\n".join(map(str, bad))


def test_no_import_cycle_between_modules():
    cycles = import_cycles()
    assert not cycles, f"{len(cycles)} import cycles:\n" + "\n".join(" <-> ".join(c) for c in cycles)


def test_below_the_pipeline_no_spec_is_a_mapping():
    bad = spec_mapping_violations()
    assert not bad, f"{len(bad)} specs read as mappings below the pipeline:\n" + "\n".join(bad)


def test_the_rules_see_what_they_should():
    """The checks above on snippets: they flag the patterns and pass Dataset access and plain dicts."""
    def uses(code):
        return [kind for _, kind, _ in spec_mapping_uses(code)]

    assert uses("spec['alpha']\nself.cfg.get('N', 3)\nf(**params)\n{**spec}\ngetattr(cc, f'resolved_{t}')\n"
                "x = initial[f'{k}_0']\n") == ["index", "get", "**", "**", "getattr", "index"]
    assert uses("ds['x']\nds.attrs['q']\nspec.alpha\nspec[0]\nspec[key]\ngetattr(obj, name)\nf(**kwargs)\n"
                "if TYPE_CHECKING:\n    spec['a']\n"
                "for b in batches:\n    b['N'].values[0] + b['t'].attrs['units']\n"
                "def f(spec: dict, initial: xr.Dataset):\n    return initial['x0']\n") == []
    assert package("cradle.pipeline.config.loading") == "pipeline" and package("cradle.__main__") == "cradle"
    assert package("cradle") == "cradle" and package("cradle.data") == "data"


def _lines(paths) -> int:
    return sum(len(p.read_text().splitlines()) for p in paths)


def counts() -> dict[str, int]:
    """The before/after numbers of the structural issue, measured on this tree."""
    checks = sum(1 for path in MODULES.values() for node in ast.walk(_parse(path))
                 if isinstance(node, ast.Call) and _called(node) in CHECKS)
    config = [*(CRADLE / "pipeline" / "config").glob("*.py"), CRADLE / "scenes" / "spec.py",
              *(CRADLE / "specs").glob("*.py")]
    uses = [use for path in MODULES.values() for use in spec_mapping_uses(path.read_text())]
    return {
        "spec-mapping reads below the pipeline ([...], .get)": sum(
            1 for line in spec_mapping_violations() if ": index: " in line or ": get: " in line),
        "spec-mapping reads in all of src/cradle ([...], .get)": sum(kind in ("index", "get") for _, kind, _ in uses),
        "check_alpha/check_bc/check_positive/check_choice call sites": checks,
        "modules of src/cradle": len(MODULES),
        "lines of src/cradle (*.py)": _lines(MODULES.values()),
        "lines of config code (pipeline/config/*.py, scenes/spec.py, specs/*.py)": _lines(
            p for p in config if p.exists()),
        "lines of config.yaml": _lines([ROOT / "config.yaml"]),
        "lines of the generated schema (config.schema.json)": _lines(CRADLE.rglob("config.schema.json")),
    }


if __name__ == "__main__":
    for title, items in (("layer rule", list(map(str, layer_violations()))),
                         ("import cycles", [" <-> ".join(c) for c in import_cycles()]),
                         ("spec as a mapping below the pipeline", spec_mapping_violations())):
        print(f"## {title}: {len(items)}")
        print("\n".join(items) + "\n")
    for name, value in counts().items():
        print(f"{name}: {value}")
