"""Compare two results folders netCDF file by netCDF file: are the numbers bitwise the same?

    python benchmarks/compare_outputs.py OLD_RESULTS NEW_RESULTS [--map OLD_REGEX=NEW_TEMPLATE ...]
        [--group-map OLD_REGEX=GROUP_TEMPLATE ...] [--var-map [FILE_REGEX::]OLD_REGEX=NEW_TEMPLATE ...]
        [--coord-names model,scene] [--table FILE]

Every ``*.nc`` under OLD_RESULTS is paired with a file under NEW_RESULTS: the same relative path, or
the first rename rule whose regex matches the whole relative path (``--map`` rules first, then
:data:`RENAMES`, the layout renames made so far); ``re.Match.expand`` builds the new path, e.g.
``--map 'mi/(mi-.*)\\.nc=\\1/\\1.nc'``. Each file is read with netCDF4, every group, raw (no masking,
scaling or character decoding), so every variable is seen: coordinates, 0-d scalars, strings.

Two paired variables are equal when they have the same dimensions (names and sizes), dtype and bytes
(a float NaN equals a NaN in the same place whatever its payload), and the same ``units``. Other
attributes (provenance, parameters, timings) are not compared. Exceptions, all explicit:

* a measured timing (:func:`is_wall_clock`: units of seconds and a name or long_name saying wall,
  clock, elapsed, run time, ...; today work-precision's ``wall_time``) is checked for dimensions and
  units only;
* ``--group-map`` compares an old file with one group of its new file (several old files gathered into
  one new file, a group each): for an old file whose relative path the regex matches whole, its variables
  are paired with those under the group the template names (``--group-map
  'work-precision/([^/]+)\\.nc=/\\1'`` with ``--map 'work-precision/[^/]+\\.nc=work-precision/work-precision.nc'``),
  and only that group's variables count as "only in new" (then :data:`GROUPS`, the gatherings made so far);
* ``--var-map`` renames variables (and the dimensions they name) inside files: the regex is matched
  against the variable's path in its file (``/wall_time``, ``/cases/pair``); ``FILE_REGEX::`` limits the
  rule to old files whose relative path it matches;
* ``--coord-names model,scene``: an old integer coordinate ``model`` whose names are in an attribute
  ``model_names`` (``"exact, dps"``, on the variable, its group or a parent group) equals a new string
  coordinate holding those names in that order.

Prints (or writes to ``--table``) a markdown report: files only in OLD, only in NEW, one row per
paired file, then one row per differing variable with its largest absolute difference. Exit status 0
when everything is equal, 1 on any difference.
"""
from __future__ import annotations

import argparse
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path

import netCDF4
import numpy as np

#: the results-layout renames made so far, OLD_REGEX -> NEW_TEMPLATE on relative paths (after --map)
RENAMES: list[tuple[str, str]] = [
    # issue 21, one name per analysis: results/<name>/<name>.nc (and <name>/full/, <name>/batch/<form>/)
    (r"mi/(full/)?(mi-diagram|mi-growth|mi-statistics)\.nc", r"\2/\1\2.nc"),
    (r"mi/batch/(reduced|full)/(N\d+-\w+-\d+)\.nc", r"mi-statistics/batch/\1/\2.nc"),
    (r"interactions/(full/)?breather-interactions\.nc", r"breather-interactions/\1breather-interactions.nc"),
    (r"interactions/batch/full/(\d+)\.nc", r"breather-interactions/batch/full/\1.nc"),
    (r"validity/(full/)?dps-validity\.nc", r"dps-validity/\1dps-validity.nc"),  # dps-validity on the protocol
    # work-precision on the protocol: one file per scene gathered into one, a group per scene (GROUPS)
    (r"work-precision/(full/)?(?!work-precision\.nc)[^/]+\.nc", r"work-precision/\1work-precision.nc"),
]
#: old files that became a group of a gathered file, OLD_REGEX -> GROUP_TEMPLATE (after --group-map)
GROUPS: list[tuple[str, str]] = [
    (r"work-precision/(?:full/)?(?!work-precision\.nc)([^/]+)\.nc", r"/\1"),
]

#: units of a wall-clock duration
SECONDS = {"s", "sec", "second", "seconds"}
#: what a wall-clock duration's name or long_name says (the paper's times t are dimensionless: units "1")
WALL_CLOCK = re.compile(r"wall|clock|elapsed|run_?time|runtime|cpu|time taken|timing", re.IGNORECASE)


@dataclass
class Rule:
    """A rename: ``pattern`` matched against a whole path, ``template`` expanded from the match."""

    pattern: re.Pattern
    template: str
    files: re.Pattern | None = None

    @classmethod
    def parse(cls, text: str, scoped: bool = False) -> Rule:
        files = None
        if scoped and "::" in text:
            scope, text = text.split("::", 1)
            files = re.compile(scope)
        old, sep, new = text.partition("=")
        if not sep or not old:
            raise argparse.ArgumentTypeError(f"{text!r}: expected OLD_REGEX=NEW_TEMPLATE")
        return cls(re.compile(old), new, files)

    def apply(self, path: str, file: str | None = None) -> str | None:
        if self.files is not None and (file is None or not self.files.fullmatch(file)):
            return None
        m = self.pattern.fullmatch(path)
        return m.expand(self.template) if m else None


def rename(rules: list[Rule], path: str, file: str | None = None) -> str:
    """``path`` through the first rule that matches it (unchanged when none does)."""
    for rule in rules:
        new = rule.apply(path, file)
        if new is not None:
            return new
    return path


@dataclass
class Variable:
    """One netCDF variable read raw: its path in the file, dimensions, units and values."""

    path: str
    dims: tuple[tuple[str, int], ...]
    units: str | None
    long_name: str
    values: np.ndarray
    names: list[str] | None = None  # from a ``<name>_names`` attribute (integer-coded coordinates)

    @property
    def name(self) -> str:
        return self.path.rsplit("/", 1)[-1]


def _attr(obj, key):
    return obj.getncattr(key) if key in obj.ncattrs() else None


def _names_attribute(var, group, name: str) -> list[str] | None:
    """The names of an integer-coded coordinate: attribute ``<name>_names`` of the variable or a group above it."""
    key, holders = f"{name}_names", [var]
    while group is not None:
        holders.append(group)
        group = group.parent
    for obj in holders:
        value = _attr(obj, key)
        if value is not None:
            return [s.strip() for s in str(value).split(",")]
    return None


def read_variables(path: Path) -> dict[str, Variable]:
    """Every variable of every group of the netCDF file ``path``, by its path in the file, read raw."""
    out: dict[str, Variable] = {}
    with netCDF4.Dataset(path) as ds:
        # raw values: a fill value or a packing must not hide a changed byte
        ds.set_auto_maskandscale(False)
        ds.set_auto_chartostring(False)
        stack = [ds]
        while stack:
            group = stack.pop()
            prefix = "" if group.path == "/" else group.path
            for name, var in group.variables.items():
                units = _attr(var, "units")
                out[f"{prefix}/{name}"] = Variable(
                    path=f"{prefix}/{name}",
                    dims=tuple((d, _dim_len(group, d)) for d in var.dimensions),
                    units=None if units is None else str(units),
                    long_name=str(_attr(var, "long_name") or ""),
                    values=np.asarray(var[...]),
                    names=_names_attribute(var, group, name),
                )
            stack.extend(group.groups.values())
    return out


def _dim_len(group, dim: str) -> int:
    # a variable may use a dimension of a parent group
    while dim not in group.dimensions:
        group = group.parent
    return len(group.dimensions[dim])


def is_wall_clock(var: Variable) -> bool:
    """Whether ``var`` is a measured duration in wall-clock seconds (compared for shape and units only)."""
    return var.units in SECONDS and bool(WALL_CLOCK.search(f"{var.name} {var.long_name}"))


def _is_text(a: np.ndarray) -> bool:
    return a.dtype.kind in "OUS"


def _decoded(a: np.ndarray) -> np.ndarray:
    """Strings as Python str (vlen strings come as objects; fixed-width bytes decoded)."""
    if a.dtype.kind == "S":
        return np.vectorize(lambda b: b.decode("utf-8"), otypes=[object])(a) if a.size else a.astype(object)
    return a.astype(object)


def max_abs_difference(a: np.ndarray, b: np.ndarray) -> str:
    """Largest |a - b| over places where both are numbers, and how many places differ in NaN-ness."""
    if _is_text(a) or _is_text(b):
        if _is_text(a) and _is_text(b):
            return f"{int(np.sum(_decoded(a) != _decoded(b)))} of {a.size} strings differ"
        return "text vs numbers"
    x, y = a.astype(np.float64), b.astype(np.float64)
    nx, ny = np.isnan(x), np.isnan(y)
    both = ~nx & ~ny
    text = f"{np.max(np.abs(x[both] - y[both])):.3g}" if both.any() else "-"
    if (nx != ny).any():
        text += f" ({int(np.sum(nx != ny))} NaN places differ)"
    return text


def same_values(a: np.ndarray, b: np.ndarray) -> bool:
    """Same dtype and bytes; a NaN equals a NaN in the same place, strings compare as text."""
    if a.dtype != b.dtype or a.shape != b.shape:
        return False
    if a.dtype.kind == "O":
        return bool(np.all(_decoded(a) == _decoded(b))) if a.size else True
    if a.tobytes() == b.tobytes():
        return True
    if a.dtype.kind == "f":
        # only NaN payloads may differ: the same NaN places, and every other byte the same
        na, nb = np.isnan(a), np.isnan(b)
        return bool(np.array_equal(na, nb)) and a[~na].tobytes() == b[~nb].tobytes()
    return False


def coded_names(old: Variable, new: Variable) -> str | None:
    """An old integer-coded coordinate against a new string one: None when they say the same names."""
    if old.names is None:
        return f"no attribute {old.name}_names to decode the old codes"
    if old.values.dtype.kind not in "iu":
        return f"old values are {old.values.dtype}, not integer codes"
    codes = old.values.ravel()
    if codes.size and (codes.min() < 0 or codes.max() >= len(old.names)):
        return f"codes {codes.tolist()} out of range of {old.names}"
    expected = [old.names[c] for c in codes]
    values = netCDF4.chartostring(new.values) if new.values.dtype == "S1" else new.values
    got = _decoded(np.asarray(values)).ravel().tolist()
    return None if got == expected else f"names {got} != {expected}"


def is_coded(old: Variable, new: Variable, coord_names: set[str]) -> bool:
    """Whether ``old`` is an integer-coded coordinate named in --coord-names and ``new`` holds strings."""
    return old.name in coord_names and old.values.dtype.kind in "iu" and new.values.dtype.kind in "OUS"


@dataclass
class FileReport:
    """The comparison of one pair of files."""

    old: str
    new: str
    compared: int = 0
    timings: list[str] = field(default_factory=list)
    coded: list[str] = field(default_factory=list)
    differences: list[tuple[str, str, str]] = field(default_factory=list)  # variable, problem, max |diff|
    group: str | None = None  # the group of the new file compared (--group-map)


def compare_variable(old: Variable, new: Variable, new_dims: tuple, coord_names: set[str]) -> tuple[str, str] | None:
    """(problem, max |diff|) when ``new`` differs from ``old``, None when they are the same."""
    if is_coded(old, new, coord_names):
        # a char array holds one string per row of its last dimension
        width = 1 if new.values.dtype == "S1" else 0
        if new_dims != new.dims[:len(new.dims) - width]:
            return f"dimensions {old.dims} -> {new.dims}", ""
        problem = coded_names(old, new)
        return (problem, "") if problem else None
    if new_dims != new.dims:
        return f"dimensions {old.dims} -> {new.dims}", ""
    if old.units != new.units:
        return f"units {old.units!r} -> {new.units!r}", ""
    if is_wall_clock(old):
        return None
    if old.values.dtype != new.values.dtype:
        return f"dtype {old.values.dtype} -> {new.values.dtype}", ""
    if not same_values(old.values, new.values):
        return "values", max_abs_difference(old.values, new.values)
    return None


def _under(path: str, group: str) -> bool:
    return path.startswith("/" + group.strip("/") + "/")


def in_group(variables: dict[str, Variable], group: str) -> dict[str, Variable]:
    """The variables under ``group`` (``/tw-weak``), by their paths relative to it (``/error``)."""
    cut = len(group.strip("/")) + 1
    return {path[cut:]: var for path, var in variables.items() if _under(path, group)}


def compare_file(old_path: Path, new_path: Path, old_rel: str, new_rel: str, var_rules: list[Rule],
                 coord_names: set[str], group: str | None = None) -> FileReport:
    """Every variable of ``old_path`` against its counterpart in ``new_path`` (in its group ``group``)."""
    report = FileReport(old_rel, new_rel if group is None else f"{new_rel}:{group}", group=group)
    old_vars, new_vars = read_variables(old_path), read_variables(new_path)
    if group is not None:
        new_vars = in_group(new_vars, group)
    matched = set()
    for path, old in old_vars.items():
        new_path_in_file = rename(var_rules, path, old_rel)
        new = new_vars.get(new_path_in_file)
        label = path if new_path_in_file == path else f"{path} -> {new_path_in_file}"
        if new is None:
            report.differences.append((label, "only in old", ""))
            continue
        matched.add(new_path_in_file)
        group = path.rsplit("/", 1)[0]
        # a renamed coordinate renames its dimension
        new_dims = tuple((rename(var_rules, f"{group}/{d}", old_rel).rsplit("/", 1)[-1], n) for d, n in old.dims)
        problem = compare_variable(old, new, new_dims, coord_names)
        report.compared += 1
        if is_wall_clock(old):
            report.timings.append(path)
        if is_coded(old, new, coord_names):
            report.coded.append(path)
        if problem is not None:
            report.differences.append((label, *problem))
    for path in sorted(set(new_vars) - matched):
        report.differences.append((path, "only in new", ""))
    return report


def ungrouped(new_root: Path, pairs, reports: list[FileReport]) -> list[str]:
    """``file:/variable`` for each variable of a new file compared by groups (--group-map) that lies in
    none of the groups compared: a group no old file stands for."""
    groups: dict[str, list[str]] = {}
    for (_, new), report in zip(pairs, reports, strict=True):
        if report.group is not None:
            groups.setdefault(new, []).append(report.group)
    return [f"{new}:{path}" for new, names in groups.items() for path in read_variables(new_root / new)
            if not any(_under(path, g) for g in names)]


def pair_files(old_root: Path, new_root: Path, file_rules: list[Rule]):
    """(pairs of relative paths, old files without a new one, new files without an old one)."""
    old_files = sorted(p.relative_to(old_root).as_posix() for p in old_root.rglob("*.nc"))
    new_files = {p.relative_to(new_root).as_posix() for p in new_root.rglob("*.nc")}
    pairs, only_old = [], []
    for rel in old_files:
        target = rename(file_rules, rel)
        if target in new_files:
            pairs.append((rel, target))
        else:
            only_old.append(rel if target == rel else f"{rel} (as {target})")
    only_new = sorted(new_files - {new for _, new in pairs})
    return pairs, only_old, only_new


def compare_folders(old_root: Path, new_root: Path) -> tuple[list[FileReport], list[str], list[str]]:
    """Every ``*.nc`` under ``old_root`` against the file at the same relative path under ``new_root``, with
    no rename of files or variables: (a report per pair, old files without a new one, new files without an
    old one)."""
    pairs, only_old, only_new = pair_files(old_root, new_root, [])
    return [compare_file(old_root / o, new_root / n, o, n, [], set()) for o, n in pairs], only_old, only_new


def _cell(text: str) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def markdown(old_root: Path, new_root: Path, reports: list[FileReport], only_old: list[str], only_new: list[str],
             renames: list[Rule], var_rules: list[Rule], coord_names: set[str], group_rules=()) -> str:
    """The report: summary, unpaired files, one row per pair, one row per difference."""
    differing = [r for r in reports if r.differences]
    equal = not differing and not only_old and not only_new
    lines = [f"# netCDF outputs: `{old_root}` vs `{new_root}`", "",
             f"**{'ALL EQUAL' if equal else 'DIFFERENCES'}**: {len(reports)} file pairs, "
             f"{sum(r.compared for r in reports)} variables compared, {len(differing)} files differ, "
             f"{len(only_old)} only in old, {len(only_new)} only in new.", ""]
    if renames:
        lines.append("File renames: " + ", ".join(f"`{r.pattern.pattern}` -> `{r.template}`" for r in renames))
    if group_rules:
        lines.append("Old files compared with a group of their new file: "
                     + ", ".join(f"`{r.pattern.pattern}` -> group `{r.template}`" for r in group_rules))
    if var_rules:
        lines.append("Variable renames: " + ", ".join(
            f"`{(r.files.pattern + '::') if r.files else ''}{r.pattern.pattern}` -> `{r.template}`" for r in var_rules))
    if coord_names:
        lines.append("Integer-coded coordinates compared with string ones by name: "
                     + ", ".join(f"`{c}`" for c in sorted(coord_names)))
    timings = [f"`{r.old}:{t}`" for r in reports for t in r.timings]
    lines.append("Wall-clock timings (dimensions and units only): " + (", ".join(timings) or "none"))
    lines.append("")
    for title, files in (("Only in old", only_old), ("Only in new", only_new)):
        if files:
            lines += [f"## {title}", ""] + [f"- `{f}`" for f in files] + [""]
    lines += ["## Files", "", "| old | new | variables | timings | differ |", "|---|---|---:|---:|---:|"]
    for r in reports:
        lines.append(f"| `{r.old}` | {'=' if r.new == r.old else f'`{r.new}`'} | {r.compared} | {len(r.timings)} | "
                     f"{len(r.differences) or ''} |")
    if differing:
        lines += ["", "## Differences", "", "| file | variable | difference | max abs difference |",
                  "|---|---|---|---|"]
        for r in differing:
            for var, problem, diff in r.differences:
                lines.append(f"| `{r.old}` | `{_cell(var)}` | {_cell(problem)} | {_cell(diff)} |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("old", type=Path, help="the reference results folder")
    parser.add_argument("new", type=Path, help="the results folder to check")
    parser.add_argument("--map", action="append", default=[], type=Rule.parse, metavar="OLD_REGEX=NEW_TEMPLATE",
                        help="rename of a file's relative path (tried in order, before the built-in RENAMES)")
    parser.add_argument("--group-map", action="append", default=[], type=Rule.parse,
                        metavar="OLD_REGEX=GROUP_TEMPLATE",
                        help="compare an old file with this group of its new file (e.g. one group per old file)")
    parser.add_argument("--var-map", action="append", default=[], type=lambda s: Rule.parse(s, scoped=True),
                        metavar="[FILE_REGEX::]OLD_REGEX=NEW_TEMPLATE",
                        help="rename of a variable's path inside a file (/name, /group/name)")
    parser.add_argument("--coord-names", default="", metavar="NAME,...",
                        help="coordinates that went from integer codes plus a NAME_names attribute to strings")
    parser.add_argument("--table", type=Path, help="write the markdown report here (default: stdout)")
    args = parser.parse_args(argv)
    for root in (args.old, args.new):
        if not root.is_dir():
            parser.error(f"{root}: not a folder")
    file_rules = args.map + [Rule.parse(f"{old}={new}") for old, new in RENAMES]
    group_rules = args.group_map + [Rule.parse(f"{old}={new}") for old, new in GROUPS]
    coord_names = {c.strip() for c in args.coord_names.split(",") if c.strip()}
    pairs, only_old, only_new = pair_files(args.old, args.new, file_rules)
    reports = [compare_file(args.old / o, args.new / n, o, n, args.var_map, coord_names,
                            group=next((g for g in (r.apply(o) for r in group_rules) if g is not None), None))
               for o, n in pairs]
    only_new += ungrouped(args.new, pairs, reports)
    text = markdown(args.old, args.new, reports, only_old, only_new, file_rules, args.var_map, coord_names,
                    group_rules)
    if args.table:
        args.table.write_text(text)
        print(text.splitlines()[2])
    else:
        sys.stdout.write(text)
    return 1 if only_old or only_new or any(r.differences for r in reports) else 0


if __name__ == "__main__":
    sys.exit(main())
