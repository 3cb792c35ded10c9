"""Values the config layer reads (angles, limits of float64) and its one-line errors."""
from __future__ import annotations

import copy
import difflib
import fractions
import json
import math
import re
from typing import Any, TypeGuard

_NUM = r"(\d+(\.\d*)?|\.\d+)"
# Angles: a number, or [sign] [coefficient [*]] pi [/ denominator], e.g. pi, pi/5, 4pi/5, -52pi/100, 4*pi/5.
ANGLE_PATTERN = (
    r"^\s*[-+]?\s*((" + _NUM + r"\s*\*?\s*)?pi(\s*/\s*" + _NUM + r")?|" + _NUM + r"([eE][-+]?\d+)?)\s*$"
)
_ANGLE_RE = re.compile(ANGLE_PATTERN)
ANGLE_HINT = "a number (radians) or a multiple of pi like 'pi', 'pi/5', '4pi/5', '-52pi/100', '4*pi/5'"
NAME_PATTERN = "^[A-Za-z0-9][A-Za-z0-9_-]*$"
#: an entry name is part of file names, which every file system keeps under 255 bytes (Windows paths: 260)
NAME_MAX_LENGTH = 64
#: a list's and a string's maximum where its declaration gives none: a config is written by hand
DEFAULT_MAX_ITEMS = 10_000
DEFAULT_MAX_LENGTH = 1_000
#: the largest config file read, in bytes (config.yaml is ~25 kB)
CONFIG_MAX_BYTES = 4 << 20
#: the most values a file may hold, an alias counted as the values it stands for (a "billion laughs" bomb)
CONFIG_MAX_VALUES = 50_000
#: the deepest nesting of mappings and lists (Python's recursion stops near 1,000)
CONFIG_MAX_DEPTH = 64
#: about 1e2 machine epsilons: below, a step's error estimate is rounding noise and the steps underflow
RTOL_FLOOR = 1e-14
#: the error norm squares state / atol, which overflows float64 for a state of order 1 below about 1e-154
#: (atol = 1e-300 raised ZeroDivisionError in DOP853's first step)
ATOL_FLOOR = 1e-150
#: about 1e2 machine epsilons: a smaller bound of an exact run's relative energy drift fails every run
DRIFT_FLOOR = 1e-14
#: runs record their seed as a netCDF int64 attribute and analyses add small offsets to it
SEED_MAX = 2**62
#: the splitting step dt_factor 2 pi / omega_max stays about 1e2 spacings of doubles at MAX_T_END or more
DT_FACTOR_FLOOR = 1e-8
#: the largest eps of (ansatz) at which dps-validity measures DpS (cradle.measurements.dps_range): figures read it
DPS_EPS_MEASURED = 0.1
TIME_TOL = 1e-9          # two times closer than this are the same time
INTEGER_TOL = 1e-9       # q N / (2 pi) must be this close to an integer on a ring
#: below 2^22 the spacing of doubles is at most half of TIME_TOL: stored times stay apart
MAX_T_END = float(2**22)
T_END_WHY = "float64 tells stored times 1e-9 apart only below 2^22 = 4194304"
#: the largest integer up to which every integer is a double (the budget bounds a run long before)
MAX_COUNT = 2**53


class ConfigError(ValueError):
    """A refused config or argument: ``str(err)`` one line per problem, ``err.errors`` the lines."""

    def __init__(self, errors: str | list[str]) -> None:
        self.errors = [errors] if isinstance(errors, str) else list(errors)
        super().__init__("\n".join(self.errors))


def key_path(parts: Any) -> str:
    """``["scenes", "tw", "store", "snapshots", 1]`` as ``scenes.tw.store.snapshots[1]``."""
    out = ""
    for p in parts:
        out += f"[{p}]" if isinstance(p, int) else (f".{p}" if out else str(p))
    return out or "config"


def show(value: Any) -> str:
    """A short, unambiguous rendering of a value (strings quoted, a long list cut)."""
    if not isinstance(value, (dict, list)):
        try:
            text = repr(value)
        except ValueError:   # an integer past Python's 4300 digits
            text = f"an integer of about {round(value.bit_length() * math.log10(2))} digits"
    else:
        if len(value) > 16:   # only the start: a list of a million values is not dumped whole
            value = dict(list(value.items())[:16]) if isinstance(value, dict) else value[:16]
        try:
            text = json.dumps(value, separators=(", ", ": "), default=str)
        except (TypeError, ValueError):
            text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


#: how a message names a JSON type ("must be a number")
TYPE_WORDS = {"integer": "an integer", "number": "a number", "string": "a string", "object": "a mapping",
              "array": "a list", "boolean": "true or false", "null": "null"}


def bound_text(x: Any) -> str:
    """A bound as a message writes it: 1 not 1.0, 0.01 as is."""
    return repr(x) if isinstance(x, float) and not float(x).is_integer() else str(int(x)) if number(x) else str(x)


def number(x: object) -> TypeGuard[int | float]:
    """A real number (not a boolean)."""
    return isinstance(x, (int, float)) and not isinstance(x, bool)


class Errors:
    """Problems by key path, one line each, at most one per path: held by the pass (sorted by ``at`` when
    :meth:`said`, non-finite numbers first) or added by a check in its own order."""

    def __init__(self) -> None:
        self.lines: list[str] = []
        self.paths: set[str] = set()
        self.held: list[tuple] = []     # (at, path, what, value, force)
        self.finite: list[tuple] = []
        self._keys: tuple[int, frozenset] | None = None   # a view's filter (:meth:`only`)

    def __len__(self) -> int:
        return len(self.lines) + len(self.held) + len(self.finite)

    def hold(self, path: Any, what: str, value: Any = ..., at: Any = None, force: bool = False) -> None:
        self.held.append((tuple(path if at is None else at), tuple(path), what, value, force))

    def said(self) -> Errors:
        for _, path, what, value, force in [*self.finite, *sorted(self.held, key=lambda p: [str(k) for k in p[0]])]:
            self.add(list(path), what, value, force=force)
        self.held, self.finite = [], []
        return self

    def add(self, path: Any, what: str, value: Any = ..., *, force: bool = False) -> None:
        if self._keys is not None:
            depth, keys = self._keys
            if not (isinstance(path, list) and len(path) > depth and path[depth] in keys):
                return
        p = path if isinstance(path, str) else key_path(path)
        if p in self.paths and not force:
            return
        self.paths.add(p)
        line = f"config error: {p if value is ... else f'{p} = {show(value)}'}: {what}"
        if line not in self.lines:
            self.lines.append(line)

    def has(self, path: Any) -> bool:
        return key_path(path) in self.paths

    def within(self, path: list) -> bool:
        """Whether a problem was reported at ``path`` or below it."""
        p = key_path(path)
        return any(q == p or q.startswith((p + ".", p + "[")) for q in self.paths)

    def only(self, path: list, keys: Any) -> Errors:
        """A view of these problems taking only those at one of ``keys`` under ``path``."""
        view = copy.copy(self)   # the same lines and paths
        view._keys = (len(path), frozenset(keys))
        return view

    def raise_any(self) -> None:
        if self.lines:
            raise ConfigError(self.lines)


def _written(value: Any) -> tuple[str, str, str, str] | None:
    """An angle's text without blanks as (sign, coefficient, "pi" or "", "/denominator"); None if no angle."""
    if not isinstance(value, str) or not _ANGLE_RE.match(value) or "\n" in value:
        return None
    s = re.sub(r"\s+", "", value)
    coef, pi, denom = s.lstrip("+-").partition("pi")
    return "-" if s.startswith("-") else "", coef.rstrip("*"), pi, denom


def parse_angle(value: Any) -> float:
    """An angle in radians from a number or a string 'pi', 'pi/5', '4pi/5', '-52pi/100', '4*pi/5', '0.3'."""
    parts = _written(value)
    if number(value):
        x = float(value)
    elif parts is None:
        raise ConfigError(f"cannot read {value!r} as an angle: expected {ANGLE_HINT}")
    else:
        sign, coef, pi, denom = parts
        d = float(denom[1:]) if denom else 1.0
        if d == 0.0:
            raise ConfigError(f"cannot read {value!r} as an angle: division by zero")
        x = (float(coef) if coef else 1.0) * math.pi / d if pi else float(coef)
        x = -x if sign else x
    if not math.isfinite(x):
        raise ConfigError(f"cannot read {value!r} as an angle: not finite")
    return x


def _pi_text(sign: str, k: int, m: int) -> str:
    return f"{sign}{k if k != 1 else ''}pi{f'/{m}' if m != 1 else ''}"


def canonical_angle(value: Any) -> Any:
    """One written form per angle value, what a job's parameters carry (docs/developing.md "Specs"): integer
    k pi / m kept as written, a decimal one reduced, a number that is bit for bit k pi / m (m <= 1000) that
    text; a value that is not an angle as it is."""
    if number(value) and not isinstance(value, int):
        return _pi_multiple(float(value))
    parts = _written(value)
    if parts is None:
        return value
    sign, coef, pi, denom = parts
    if not pi:
        return _pi_multiple(float(sign + coef))
    coef, denom = coef or "1", denom[1:] or "1"
    if coef.isdigit() and denom.isdigit():
        k, m = int(coef), int(denom)
    elif float(denom):
        ratio = fractions.Fraction(coef) / fractions.Fraction(denom)
        k, m = ratio.numerator, ratio.denominator
    else:
        return value
    text = _pi_text(sign, k, m)
    try:
        same = parse_angle(text) == parse_angle(value)
    except ConfigError:
        same = False
    return text if same else value


def _pi_multiple(x: float) -> Any:
    """``x`` as ``[-][k]pi[/m]`` (m <= 1000) when that text is ``x`` bit for bit; else ``x``."""
    if not 0.0 < abs(x) < 1e4:   # beyond, k pi / m of a small m is no angle anyone writes
        return x
    r = fractions.Fraction(x / math.pi).limit_denominator(1000)
    if r == 0:
        return x
    text = _pi_text("-" if r < 0 else "", abs(r.numerator), r.denominator)
    return text if parse_angle(text) == x else x


def angle_or_none(value: Any) -> float | None:
    """An angle in radians, or None if it does not read as one (the schema reports it)."""
    try:
        return parse_angle(value)
    except ConfigError:
        return None


def angle_expr(value: Any) -> str:
    """The text of an angle as given (a number as its repr), kept next to its value in radians."""
    return value if isinstance(value, str) else repr(float(value))


def did_you_mean(name: Any, known: Any) -> str:
    """'; did you mean 'x'?' for the closest known name, or ''."""
    near = difflib.get_close_matches(str(name), list(known), n=1)
    return f"; did you mean {near[0]!r}?" if near else ""
