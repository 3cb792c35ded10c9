"""scipy's adaptive solvers stepped by hand, storing at given output times: what the lattice and DpS runs with
scipy's solvers share (:mod:`cradle.integrators.lattice_adaptive`, :mod:`cradle.integrators.dps_solver`,
:mod:`cradle.integrators.dps_damped_solver`)."""
from __future__ import annotations

import time
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from collections.abc import Callable

    from cradle.integrators._types import Floats


def stepped(scipy_class: str, fun: Callable[[float, Floats], Floats], y0: Floats, tau_out: Floats, rtol: float,
            atol: float | Floats, store: Callable[[int, Floats], None], on_step: Callable[[Floats, float], None],
            progress: Callable[[float, float], None] | None, method: str, clock: str = "tau",
            **extra: Any) -> tuple[int, int]:
    """Step scipy's ``scipy_class`` solver (DOP853, RK45, LSODA, Radau; ``extra``: its other arguments, e.g. ``jac``)
    manually from 0 to tau_out[-1]: ``store(i, y)`` at every output time (y0 at 0, the step's end where it lands on
    one, else its dense output), ``on_step(y, tau)`` after every accepted step, ``progress(tau, tau_final)`` about
    once a second and at the end; ``clock``: the time's name in a failure's message. Returns (accepted steps,
    right-hand side evaluations)."""
    T = tau_out.size
    idx = 0
    if tau_out[0] == 0.0:
        store(0, y0)
        idx = 1
    n_steps = nfev = 0
    tau_final = float(tau_out[-1])
    if idx < T:
        from scipy import integrate

        solver = getattr(integrate, scipy_class)(fun, 0.0, y0, tau_final, rtol=rtol, atol=atol, **extra)
        t_last = time.perf_counter()
        while solver.status == "running":
            msg = solver.step()
            if solver.status == "failed":
                raise RuntimeError(f"{method} failed at {clock}={solver.t!r}: {msg}")
            n_steps += 1
            y = solver.y
            on_step(y, solver.t)
            dense = None
            while idx < T and tau_out[idx] <= solver.t:
                if tau_out[idx] == solver.t:
                    store(idx, y)
                else:
                    if dense is None:
                        dense = solver.dense_output()
                    store(idx, dense(tau_out[idx]))
                idx += 1
            if progress is not None and time.perf_counter() - t_last >= 1.0:
                t_last = time.perf_counter()
                progress(float(solver.t), tau_final)
        nfev = int(solver.nfev)
    if progress is not None:
        progress(tau_final, tau_final)
    return n_steps, nfev
