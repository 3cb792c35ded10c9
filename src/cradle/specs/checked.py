"""``@checked``: a public function's arguments checked against the shared parameter types.

A spec is validated once, where it is built; below that, code trusts it. A library user who calls a
public function directly (``integrate_lattice``, the initial-data builders, ...) is refused bad
numbers in one line by the same declarations as the config (:data:`.shared.SHARED`)::

    @checked
    def travelling_wave(N: int, q: float, alpha: float, *, bc: str = "periodic", ...): ...

    travelling_wave(20, 0.6, 1.0)
    ConfigError: alpha = 1.0: must be > 1 (Hertz exponent of (vhertz))

Every argument whose name is a shared type (alpha, N, bc, rtol, dt, ...) is checked against its
declaration: type (finite numbers only, booleans are not numbers), minimum, exclusiveMinimum,
maximum, exclusiveMaximum, enum. ``@checked(name=type)`` maps an argument to a shared type of
another name (``method="latticeMethod"``), or to None to leave it unchecked. A None passes where the
argument's default is None. A number arrives as a float and an integer as an int, whatever numeric
type was given, so the function computes with what the config would have given it.

The signature is read once, when the function is decorated. A call then costs about 0.5 us with one
checked argument (``tau0(alpha)``) and 1.5-3 us for integrate_lattice or travelling_wave as the
scene job calls them (measured with timeit on the 2-core development machine; a test holds it under
20 us). Functions that loops call (right-hand sides, one step of a map) are not decorated: they
trust their caller.
"""
from __future__ import annotations

import functools
import inspect
import math
import numbers
import operator
import typing

from .shared import BOUND_HINTS, SHARED
from .values import TYPE_WORDS, ConfigError, bound_text, show

_KEYWORDS = {"description", "type", "enum", "minimum", "exclusiveMinimum", "maximum", "exclusiveMaximum"}
_BOUNDS = {"minimum": (operator.ge, ">="), "exclusiveMinimum": (operator.gt, ">"),
           "maximum": (operator.le, "<="), "exclusiveMaximum": (operator.lt, "<")}


def _refuse(arg: str, value, why: str) -> typing.NoReturn:
    raise ConfigError(f"{arg} = {show(value)}: {why}")


def _plain(value, x):
    """The value a message shows: as given (1, 1.0), or as a Python number (a numpy scalar)."""
    return value if type(value) in (int, float) else x


@functools.cache
def checker(shared: str):
    """``check(arg, value) -> value``: the value of argument ``arg`` as the shared type ``shared``
    declares it (a float for a number, an int for an integer), or a one-line ConfigError."""
    decl = SHARED[shared]
    kind = decl.get("type")
    unknown = set(decl) - _KEYWORDS
    if kind not in ("number", "integer", "string") or unknown:
        raise TypeError(f"@checked cannot check the shared type {shared!r} ({', '.join(sorted(unknown)) or kind})")
    enum = decl.get("enum")
    enum_why = f"must be one of {', '.join(map(str, enum))}" if enum else ""
    bounds = tuple((op, decl[k], f"must be {word} {bound_text(decl[k])}{BOUND_HINTS.get((shared, k), '')}")
                   for k, (op, word) in _BOUNDS.items() if k in decl)
    type_why = f"must be {TYPE_WORDS[kind]}"
    integer = kind == "integer"

    def _string(arg, value):
        if not isinstance(value, str):
            _refuse(arg, value, type_why)
        if enum and value not in enum:
            _refuse(arg, value, enum_why)
        return value

    def _number(arg, value):
        if type(value) is float:   # the common case first
            x = value
        elif isinstance(value, float):   # numpy.float64
            x = float(value)
        elif isinstance(value, numbers.Real) and not isinstance(value, bool):   # numpy's scalars too
            if integer and isinstance(value, numbers.Integral):
                x = int(value)
            else:
                try:
                    x = float(value)
                except OverflowError:   # an int beyond the largest float
                    _refuse(arg, value, "must be a finite number")
        else:
            _refuse(arg, value, type_why)
        if x != x or x in (math.inf, -math.inf):
            _refuse(arg, _plain(value, x), "must be a finite number")
        if integer and type(x) is float:   # 50.0 is the integer 50, as in the config
            if not x.is_integer():
                _refuse(arg, _plain(value, x), type_why)
            x = int(x)
        if enum and x not in enum:
            _refuse(arg, _plain(value, x), enum_why)
        for op, bound, why in bounds:
            if not op(x, bound):
                _refuse(arg, _plain(value, x), why)
        return x

    return _string if kind == "string" else _number


def checked(func=None, /, **types):
    """Decorator: check ``func``'s arguments named after a shared type (module docstring).

    ``types`` maps an argument to the shared type it has when its name differs (``method="dpsMethod"``)
    or to None (not checked). The arguments it checks are ``func.checked_arguments`` (argument ->
    shared type). A declared default must itself pass, as the type it is converted to.
    """
    if func is None:
        return functools.partial(checked, **types)
    where = f"@checked on {func.__module__}.{func.__qualname__}"
    params = inspect.signature(func).parameters
    if set(types) - set(params):
        raise TypeError(f"{where}: no argument {', '.join(sorted(set(types) - set(params)))}")
    steps: list[tuple[int, str, bool, typing.Callable]] = []
    mapped: dict[str, str] = {}
    for i, p in enumerate(params.values()):
        shared = types.get(p.name, p.name)
        if shared is None or (shared not in SHARED and p.name not in types):
            continue
        if shared not in SHARED:
            raise TypeError(f"{where}: {shared!r} is not a shared type (cradle.specs.declare.SHARED)")
        if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
            raise TypeError(f"{where}: *{p.name} cannot be checked as {shared!r}")
        check = checker(shared)
        if p.default is not p.empty and p.default is not None:
            try:
                as_declared = check(p.name, p.default)
            except ConfigError as err:
                raise TypeError(f"{where}: the default {err}") from None
            if type(as_declared) is not type(p.default):
                raise TypeError(f"{where}: write the default {p.name} = {p.default!r} as {as_declared!r}")
        positional = p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)
        steps.append((i if positional else -1, p.name, p.default is None, check))
        mapped[p.name] = shared
    if not steps:
        raise TypeError(f"{where}: no argument of a shared type to check")
    plan = tuple(steps)

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        for pos, name, optional, check in plan:
            if 0 <= pos < len(args):
                value = args[pos]
                if value is None and optional:
                    continue
                new = check(name, value)
                if new is not value:
                    args = (*args[:pos], new, *args[pos + 1:])
            elif name in kwargs:
                value = kwargs[name]
                if value is None and optional:
                    continue
                new = check(name, value)
                if new is not value:
                    kwargs[name] = new
        return func(*args, **kwargs)

    wrapper.__dict__["checked_arguments"] = mapped
    return wrapper
