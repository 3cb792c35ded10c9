"""Values the config layer reads and the errors it reports: angles, bounds of times, one-line messages.

Every problem is one line naming the key path and the value::

    config error: scenes.tw-weak.N = 1: must be >= 2
"""
from __future__ import annotations

import copy
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
NAME_PATTERN = "^[A-Za-z0-9][A-Za-z0-9_-]*$"
#: the longest entry name: it is part of file and folder names (``.NAME.nc.digest``, ``simulate-NAME.log``), which
#: every file system keeps under 255 bytes, and of paths, which Windows keeps under 260 characters
NAME_MAX_LENGTH = 64
#: a list's and a string's maximum where its declaration gives none: a config is written by hand (the YAML
#: reader allows 50,000 values in all), and each item is validated one by one
DEFAULT_MAX_ITEMS = 10_000
DEFAULT_MAX_LENGTH = 1_000
#: the largest config file read, in bytes: config.yaml is ~25 kB; a file thousands of times larger is no config
CONFIG_MAX_BYTES = 4 << 20
#: the most values a config file may hold, each alias counted as the values it stands for: config.yaml holds
#: ~1,300; beyond, reading and validating would take seconds (a "billion laughs" alias bomb stands for 9^9)
CONFIG_MAX_VALUES = 50_000
#: the deepest nesting of mappings and lists: config.yaml nests 6 deep; Python's recursion stops near 1,000
CONFIG_MAX_DEPTH = 64

_ANGLE_RE = re.compile(ANGLE_PATTERN)
ANGLE_HINT = "a number (radians) or a multiple of pi like 'pi', 'pi/5', '4pi/5', '-52pi/100', '4*pi/5'"

#: the smallest relative tolerance of an adaptive run: about 1e2 machine epsilons (scipy raises a smaller one to
#: 100 eps), below which a step's error estimate is rounding noise and the steps shrink until they underflow
RTOL_FLOOR = 1e-14
#: the smallest absolute tolerance: the error norm sums squares of (error / tolerance) and of (state / tolerance),
#: which overflow float64 (~1.8e308) for a state of order 1 once the tolerance is below its square root's inverse
#: (atol = 1e-300 raised ZeroDivisionError in DOP853's first step); below ~1e-150 a tolerance is relative alone
ATOL_FLOOR = 1e-150
#: the smallest bound of an exact run's relative energy drift: H is a sum of N terms in double precision, so a
#: drift below about 1e2 machine epsilons is its rounding alone; a smaller bound fails every run
DRIFT_FLOOR = 1e-14
#: the largest seed: runs record their seed as a netCDF attribute (an int64) and analyses add small offsets to it
#: (seed + k); numpy's default_rng takes any integer >= 0, a netCDF attribute no larger than 2^63 - 1
SEED_MAX = 2**62
#: the smallest step factor of a splitting: its step dt_factor 2 pi / omega_max (omega_max >= 1) is then at least
#: about 1e2 spacings of doubles at the end of the longest run (MAX_T_END); a shorter step adds rounding noise to t
#: and the run makes no progress the budget could estimate
DT_FACTOR_FLOOR = 1e-8
#: the largest eps of (ansatz) at which the analysis dps-validity measures DpS against the lattice (its spec's
#: eps_max): DpS's measured range is amplitudes up to 2 eps (cradle.measurements.dps_range); here, in the lowest
#: layer, so that the figures marking a scene outside it read the same value
DPS_EPS_MEASURED = 0.1
TIME_TOL = 1e-9          # two times closer than this are the same time
INTEGER_TOL = 1e-9       # q N / (2 pi) must be this close to an integer on a ring
#: the longest run, a limit of float64: stored times are told apart to TIME_TOL, and below 2^22 (~4.2e6) the
#: spacing of doubles is at most 2^-31 (4.7e-10), half of it; beyond, two stored times may round to one
MAX_T_END = float(2**22)
#: why a time is at most MAX_T_END, as a message says it
T_END_WHY = "float64 tells stored times 1e-9 apart only below 2^22 = 4194304"
#: the largest count of beads or iterations: the largest integer up to which every integer is a double; the
#: budget's estimate (memory, output, time) bounds a run long before it
MAX_COUNT = 2**53


class ConfigError(ValueError):
    """A config that fails the schema or the physical checks.

    ``str(err)`` is one line per problem; ``err.errors`` is the list of lines.
    """

    def __init__(self, errors: str | list[str]) -> None:
        if isinstance(errors, str):
            errors = [errors]
        self.errors = list(errors)
        super().__init__("\n".join(self.errors))


def key_path(parts: Any) -> str:
    """``["scenes", "tw", "store", "snapshots", 1]`` as ``scenes.tw.store.snapshots[1]``."""
    out = ""
    for p in parts:
        out += f"[{p}]" if isinstance(p, int) else (f".{p}" if out else str(p))
    return out or "config"


def show(value: Any) -> str:
    """A short, unambiguous rendering of a value (strings quoted)."""
    if isinstance(value, float):
        text = repr(value)
    elif isinstance(value, (dict, list)):
        if len(value) > 16:   # only the start is shown: a list of a million values is not dumped whole
            value = dict(list(value.items())[:16]) if isinstance(value, dict) else value[:16]
        try:
            text = json.dumps(value, separators=(", ", ": "), default=str)
        except (TypeError, ValueError):
            text = repr(value)
    else:
        text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


#: how a message names a JSON type ("must be a number")
TYPE_WORDS = {"integer": "an integer", "number": "a number", "string": "a string", "object": "a mapping",
              "array": "a list", "boolean": "true or false", "null": "null"}


def bound_text(x: Any) -> str:
    """A bound as a message writes it: 1 not 1.0, 0.01 as is ("must be > 1", "must be <= 0.01")."""
    return repr(x) if isinstance(x, float) and not float(x).is_integer() else str(int(x)) if number(x) else str(x)


def number(x: object) -> TypeGuard[int | float]:
    """A real number (not a boolean)."""
    return isinstance(x, (int, float)) and not isinstance(x, bool)


class Errors:
    """Problems by key path, one line each, in order; at most one kind of complaint per path.

    The validation pass holds its problems (:meth:`hold`: ``at`` the key path they sort by, the object for a key
    missing or unknown; ``finite`` those of numbers that are not finite, said first in the order of the file)
    and :meth:`said` turns them into lines; a check adds its lines in its own order (:meth:`add`).
    """

    def __init__(self) -> None:
        self.lines: list[str] = []
        self.paths: set[str] = set()
        self.held: list[tuple] = []     # (at, path, what, value, force), sorted by ``at`` when said
        self.finite: list[tuple] = []   # the same, said first
        self._keys: tuple[int, frozenset] | None = None   # a view's filter (:meth:`only`)

    def __len__(self) -> int:
        return len(self.lines) + len(self.held) + len(self.finite)

    def hold(self, path: Any, what: str, value: Any = ..., at: Any = None, force: bool = False) -> None:
        self.held.append((tuple(path if at is None else at), tuple(path), what, value, force))

    def said(self) -> Errors:
        """These problems with every one held said: the non-finite numbers, then the others by key path."""
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
        head = p if value is ... else f"{p} = {show(value)}"
        line = f"config error: {head}: {what}"
        if line not in self.lines:
            self.lines.append(line)

    def has(self, path: Any) -> bool:
        return (path if isinstance(path, str) else key_path(path)) in self.paths

    def within(self, path: list) -> bool:
        """Whether a problem was reported at ``path`` or at a key below it."""
        p = key_path(path)
        return any(q == p or q.startswith((p + ".", p + "[")) for q in self.paths)

    def only(self, path: list, keys: Any) -> Errors:
        """A view of these problems that takes only those at one of ``keys`` under ``path`` (a reduced form
        reports the keys it replaces; the others are said with the full form)."""
        view = copy.copy(self)   # the same lines and paths
        view._keys = (len(path), frozenset(keys))
        return view

    def raise_any(self) -> None:
        if self.lines:
            raise ConfigError(self.lines)


def _written(value: Any) -> tuple[str, str, str, str] | None:
    """An angle written as text, blanks dropped: (sign, coefficient without its '*', "pi" or "", denominator
    with its '/'), "" where not written (a number: its text as the coefficient); None for any other value."""
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


def canonical_angle(value: Any) -> Any:
    """One written form per angle value, what a job's parameters carry (so ``pi/5``, ``1pi/5``, ``1*pi/5``,
    `` pi / 5`` and ``0.2pi`` rerun nothing): a multiple of pi as ``[-][k]pi[/m]``, a number written as a
    string as that number. A coefficient and a denominator that are both integers are kept as written
    (``52pi/100`` stays: it is the paper's text, which the files record); a decimal one becomes the reduced
    fraction; a number that is bit for bit a multiple k pi / m (m <= 1000) is that text, so ``0.6283185307179586``
    and ``pi/5`` are one parameter. The form is used only when it gives bit for bit the angle the text gives; a
    value that is not an angle is returned as it is (the schema reports it)."""
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
    text = f"{sign}{k if k != 1 else ''}pi{f'/{m}' if m != 1 else ''}"
    try:
        same = parse_angle(text) == parse_angle(value)
    except ConfigError:
        same = False
    return text if same else value


def _pi_multiple(x: float) -> Any:
    """``x`` as the text ``[-][k]pi[/m]`` (the reduced fraction, m <= 1000) whose angle is ``x`` bit for bit, so
    that ``0.6283185307179586`` and ``pi/5`` are one parameter; else ``x``."""
    if not 0.0 < abs(x) < 1e4:   # beyond, k pi / m of a small m is no angle anyone writes
        return x
    r = fractions.Fraction(x / math.pi).limit_denominator(1000)
    if r == 0:
        return x
    k, m = abs(r.numerator), r.denominator
    text = f"{'-' if r < 0 else ''}{k if k != 1 else ''}pi{f'/{m}' if m != 1 else ''}"
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
    import difflib

    near = difflib.get_close_matches(str(name), list(known), n=1)
    return f"; did you mean {near[0]!r}?" if near else ""
