"""``@checked``: a public function's arguments named after a shared type checked against it, by the
config's own pass (docs/developing.md "Specs")::

    @checked
    def travelling_wave(N: int, q: float, alpha: float, *, bc: str = "periodic", ...): ...
"""
from __future__ import annotations

import functools
import inspect
import numbers
from collections.abc import Callable
from typing import Any

from .parse import leaf
from .shared import SHARED
from .values import ConfigError, Errors, show

_CHECKABLE = {"description", "type", "enum", "minimum", "exclusiveMinimum", "maximum", "exclusiveMaximum"}


@functools.cache
def checker(shared: str) -> Callable[[str, Any], Any]:
    """``check(arg, value)``: the value as the shared type ``shared`` declares it, or a one-line ConfigError."""
    node = SHARED[shared]
    kind, unknown = node.get("type"), set(node) - _CHECKABLE
    if kind not in ("number", "integer", "string") or unknown:
        raise TypeError(f"@checked cannot check the shared type {shared!r} ({', '.join(sorted(unknown)) or kind})")

    # the values accepted, by type and value (not a zero: -0.0 == 0.0): a function sees the same few again
    accepted: dict[tuple[type, Any], Any] = {}

    def check(arg: str, value: Any) -> Any:
        try:
            return accepted[type(value), value]
        except (KeyError, TypeError):   # not seen, or unhashable
            pass
        x = value
        if isinstance(value, numbers.Real) and not isinstance(value, bool) and kind != "string":
            try:   # numpy's scalars as Python numbers
                x = int(value) if kind == "integer" and isinstance(value, numbers.Integral) else float(value)
            except OverflowError:   # an int beyond the largest float
                raise ConfigError(f"{arg} = {show(value)}: must be a finite number") from None
        found = Errors()
        x = leaf(node, x, (shared,), found, coerce=False)   # the shared type's name: the words of its bounds
        if found:
            _, _, what, shown, _ = (found.finite or found.held)[0]
            raise ConfigError(f"{arg} = {show(value if type(value) in (int, float) else shown)}: {what}")
        x = float(x) if kind == "number" else x
        if value != 0 and len(accepted) < 1024:
            try:
                accepted[type(value), value] = x
            except TypeError:
                pass
        return x

    return check


def checked(func: Callable[..., Any] | None = None, /, **types: str | None) -> Any:
    """Decorator: check ``func``'s arguments named after a shared type, or mapped to one by ``types``
    (``method="dpsMethod"``, or None: not checked); ``func.checked_arguments`` lists them."""
    if func is None:
        return functools.partial(checked, **types)
    where = f"@checked on {func.__module__}.{func.__qualname__}"
    params = inspect.signature(func).parameters
    if set(types) - set(params):
        raise TypeError(f"{where}: no argument {', '.join(sorted(set(types) - set(params)))}")
    plan: list[tuple[int, str, bool, Callable[[str, Any], Any]]] = []
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
        plan.append((i if positional else -1, p.name, p.default is None, check))
        mapped[p.name] = shared
    if not plan:
        raise TypeError(f"{where}: no argument of a shared type to check")

    @functools.wraps(func)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        for pos, name, optional, check in plan:
            if 0 <= pos < len(args):
                if not (args[pos] is None and optional):
                    args = (*args[:pos], check(name, args[pos]), *args[pos + 1:])
            elif name in kwargs and not (kwargs[name] is None and optional):
                kwargs[name] = check(name, kwargs[name])
        return func(*args, **kwargs)

    wrapper.__dict__["checked_arguments"] = mapped
    return wrapper
