"""Compile-time dispatch of the kernels on the type of what they are given: one loop, specialised per model.

A kernel that needs "the right-hand side of this system" or "this term's force" calls a *generic operation*
(a stub decorated with :func:`generic`) with a ``typing.NamedTuple`` as its first argument; each model or term
registers its own numba implementation for its NamedTuple class with :func:`implements`. numba resolves the
call when it compiles the kernel for that argument type, so every combination of types gets its own machine
code, with no integer kind and no branch over the models in the loop; a type that is absent costs nothing.
NamedTuple types are named by their class (module and name), so numba's on-disk cache (``cache=True``)
keeps the specialisations from process to process, keyed like every kernel (:mod:`cradle.integrators._cache`).
"""
from __future__ import annotations

import inspect
from collections.abc import Callable
from typing import Any

from numba import njit
from numba.extending import overload

#: (operation name, NamedTuple class) -> the njit implementation registered for it
_IMPLEMENTATIONS: dict[tuple[str, Any], Any] = {}
#: the operation (what kernels call) -> its stub (the signature its implementations share)
_STUBS: dict[Callable, Callable] = {}


def _unannotated(sig: inspect.Signature) -> inspect.Signature:
    """``sig`` without its annotations (which numba would compare)."""
    return sig.replace(parameters=[p.replace(annotation=inspect.Parameter.empty) for p in sig.parameters.values()],
                       return_annotation=inspect.Signature.empty)


def generic(stub: Callable) -> Callable:
    """Make ``stub`` (a Python function whose first argument is the dispatching NamedTuple) a generic
    operation of the kernels: inside compiled code, ``stub(obj, ...)`` runs the implementation registered for
    ``type(obj)``. Called from Python it does the same (for tests and drivers)."""
    name = f"{stub.__module__}.{stub.__qualname__}"

    def typer(*args: Any) -> Callable | None:
        impl = _IMPLEMENTATIONS.get((name, getattr(args[0], "instance_class", None)))
        return None if impl is None else impl.py_func

    typer.__signature__ = _unannotated(inspect.signature(stub))  # type: ignore[attr-defined]

    def python_call(obj: Any, *args: Any) -> Any:
        return _IMPLEMENTATIONS[(name, type(obj))](obj, *args)

    python_call.__name__ = stub.__name__
    python_call.__qualname__ = stub.__qualname__
    python_call.__doc__ = stub.__doc__
    python_call.__wrapped__ = stub  # type: ignore[attr-defined]
    _STUBS[python_call] = stub
    overload(python_call, inline="always")(typer)
    return python_call


def implements(operation: Callable, cls: type) -> Callable:
    """Register the decorated njit function as ``operation``'s implementation for NamedTuple class ``cls``."""
    stub = _STUBS[operation]
    name = f"{stub.__module__}.{stub.__qualname__}"

    def register(fn: Any) -> Any:  # a numba dispatcher
        want = list(inspect.signature(stub).parameters)
        got = list(inspect.signature(fn.py_func).parameters)
        if got != want:   # numba matches an implementation to its operation by the arguments' names
            raise TypeError(f"{fn.py_func.__qualname__}{tuple(got)} implements {stub.__qualname__}{tuple(want)}: "
                            f"the arguments must be named alike")
        # numba compares an implementation's signature with its operation's, annotations included: each
        # implementation annotates its own unit's class, so both are compared by their names only
        fn.py_func.__signature__ = _unannotated(inspect.signature(fn.py_func))
        _IMPLEMENTATIONS[(name, cls)] = fn
        return fn

    return register


def absent(operation: Callable, cls: type, *returned: str) -> None:
    """Register for ``cls`` (a slot's absent unit) the implementation of ``operation`` that computes nothing: it
    returns the arguments named in ``returned`` as they came (one: that value; several: a tuple; none: nothing;
    a literal such as ``"0.0"`` stands for itself), so a kernel given the absent unit does no arithmetic for it."""
    stub = _STUBS[operation]
    params = list(inspect.signature(stub).parameters)
    body = f"return {', '.join(returned)}" if returned else "pass"
    namespace: dict[str, Any] = {}
    exec(f"def {stub.__name__}({', '.join(params)}):\n    {body}\n", namespace)   # noqa: S102 (our own text)
    # not cache=True: numba caches only functions of source files; the kernels that call it are cached with it
    _IMPLEMENTATIONS[(f"{stub.__module__}.{stub.__qualname__}", cls)] = njit(namespace[stub.__name__])
