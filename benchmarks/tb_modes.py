"""The unstable mode of the DpS travelling breathers whose tail is modulationally stable, ring by ring
(travelling-breathers.md, "Why the finite rings disagree: the unstable mode").

    python benchmarks/tb_modes.py run OUT.jsonl N [N ...] [--carry M,M,...]
    python benchmarks/tb_modes.py carry OUT.jsonl FROM M,M,... [--members C,C,...]
    python benchmarks/tb_modes.py table OUT.jsonl [TABLE.md]

``run``: on each ring N the scan of the analysis's full form (cradle.analyses.travelling_breathers.limit_scan, alpha =
3/2, unit norm, rtol 1e-13) over the grid that reaches the members c = 0.08, 0.10, 0.12, 0.14 along the same path
as the full form (rings up to 64: steps of limit_step = 0.001, newton_tol 1e-11, the path of /robustness_limit; above
64: the grid of /limit_large, steps of 0.002, newton_tol limit_large_newton_tol): the same members, not neighbours.
For each member, at rtol 1e-13 and re-solved at 1e-12 (Newton from it, the same newton_tol): growth rate, the
unstable multiplier's argument, theta, H, tail, residual, and its mode (cradle.measurements.floquet_modes:
participation ratio over N, core fraction under each core definition). One JSON line per (N, c, rtol), with the CPU
of the ring's scan. ``--carry`` takes each member of the largest ring run to the rings M (> it) by
cradle.models.tb_launch.embedded and dps_travelling.newton_core_first (at the large rings' newton_tol), each from the
ring before; ``carry`` does the same from the members a run kept of the ring FROM (in OUT-members/, beside
OUT). Run under nice; the CPU is stated beside other work.

``table``: the markdown table of the lines (per member and ring: growth, arg mu, participation / N, core fractions),
the slopes of each against N (least squares in log-log over the rings where the member is unstable, with their
standard errors), and the reading of cradle.measurements.floquet_modes's MODE_RULE under each threshold of
MODE_RULE_THRESHOLDS; written to TABLE.md when given, printed otherwise.
"""
from __future__ import annotations

import dataclasses
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from cradle.analyses import travelling_breathers as tb  # noqa: E402
from cradle.analyses.protocol import FULL, form_spec  # noqa: E402
from cradle.analyses.travelling_breathers import dps_family as DF, fine_scan as FS  # noqa: E402
from cradle.integrators import dps_travelling as DT  # noqa: E402
from cradle.measurements import floquet_modes as FM  # noqa: E402
from cradle.specs.declare import from_plain  # noqa: E402

MEMBERS = (0.08, 0.10, 0.12, 0.14)
CHECK_RTOL = 1e-12


def members_dir(out: str) -> Path:
    """Where run keeps each member (A, T, theta) for carry: a folder beside OUT (OUT.jsonl -> OUT-members/)."""
    return Path(out).with_name(Path(out).stem + "-members")


def spec_for(N: int) -> tb.TravellingBreathers:
    """The full form's spec, with newton_tol as the full form uses it on the ring of N."""
    spec = form_spec(from_plain(tb.TravellingBreathers, {}), FULL)
    if N > max(spec.limit_N):
        spec = dataclasses.replace(spec, newton_tol=spec.limit_large_newton_tol)
    return spec


def grid_for(spec: tb.TravellingBreathers, N: int) -> np.ndarray:
    """The grid of the full form's scan on the ring of N, cut to the members' neighbourhood (the walk up from the
    first TB and down from it passes the same points in the same order up to the cut)."""
    c = np.asarray(MEMBERS)
    if N > max(spec.limit_N):
        stable = np.array([0.08, 0.12, 0.14])      # large_scan's grid: the members whose tail is MI-stable
        return FS.limit_grid(stable, spec.limit_large_step, spec.limit_halfwidth)
    return FS.limit_grid(c, spec.limit_step, spec.limit_halfwidth)


def measure(b: DT.TravellingBreather, N: int, c: float, rtol: float, cpu: float, keep_dir: Path) -> dict:
    """One member's line: the TB and its unstable mode (the TB kept in ``keep_dir``)."""
    from cradle.models import dps_travelling as M

    assert b.monodromy is not None
    m = FM.mode_measures(b.monodromy, b.A, b.T, DF.TRIVIAL)
    keep = keep_dir / f"N{N}_c{c:g}_rtol{rtol:g}.npz"
    keep.parent.mkdir(parents=True, exist_ok=True)
    np.savez(keep, A=b.A, T=b.T, theta=b.theta)
    m["internal"] = FM.internal_modes(b.monodromy, b.A, DF.TRIVIAL, FM.core_mask(b.A, *FM.CORE_DEFINITIONS[0]))
    return {"N": N, "c": c, "rtol": rtol, "c_exact": b.c, "theta": math.remainder(b.theta, 2 * np.pi),
            "H": b.energy, "tail": M.tail_amplitude(b.A), "residual": b.residual, "cpu_s": cpu, **m}


def resolve(spec: tb.TravellingBreathers, b: DT.TravellingBreather, rtol: float) -> DT.TravellingBreather:
    """The member re-solved at another DOP853 tolerance: Newton from it, at its newton_tol."""
    return DT.newton(b.A, b.T, b.theta, spec.alpha, spec.norm, b.A, spec.newton_tol, rtol=rtol)


def run(out: str, rings: list[int], carry: list[int]) -> None:
    """The scans (and carried rings) of the module docstring, one JSON line per member and tolerance."""
    with open(out, "a") as f:
        def emit(line: dict) -> None:
            f.write(json.dumps(line) + "\n")
            f.flush()
            print(f"N = {line['N']}, c = {line['c']}, rtol {line['rtol']:g}: growth {line['growth']:.3e}, "
                  f"arg {line['arg']:+.4f}, PR/N {line['participation_share']:.3f}, core "
                  f"{line['core_fraction_0']:.3e} {line['core_fraction_2']:.3e}, tail {line['tail']:.2e}, "
                  f"theta {line['theta']:.9f}, internal {line['internal']}, residual {line['residual']:.2e}, "
                  f"CPU {line['cpu_s']:.0f} s",
                  flush=True)

        for N in rings:
            spec = spec_for(N)
            grid = grid_for(spec, N)
            t0 = time.process_time()
            scan = FS.limit_scan(spec, N, grid, print)
            cpu = time.process_time() - t0
            for c in MEMBERS:
                hit = np.flatnonzero(np.abs(grid - c) <= 1e-9)
                b = scan[int(hit[0])] if hit.size else None
                if b is None:
                    print(f"N = {N}, c = {c}: not reached", flush=True)
                    continue
                emit(measure(b, N, c, spec.rtol, cpu, members_dir(out)))
                t1 = time.process_time()
                b2 = resolve(spec, b, CHECK_RTOL)
                if b2.converged:
                    emit(measure(b2, N, c, CHECK_RTOL, time.process_time() - t1, members_dir(out)))
                else:
                    print(f"N = {N}, c = {c}: no convergence at rtol {CHECK_RTOL:g} ({b2.residual:.2e})", flush=True)
    if carry:
        carry_rings(out, max(rings), carry, list(MEMBERS))


def carry_rings(out: str, start: int, rings: list[int], members: list[float]) -> None:
    """Each member kept from the ring of ``start`` (:func:`members_dir`, rtol 1e-13) carried to the rings given in turn:
    embedded (sites at rest added on the far side), Newton the core first, then re-solved at CHECK_RTOL."""
    from cradle.models import tb_launch

    last: dict[float, tuple[np.ndarray, float, float]] = {}
    for c in members:
        z = np.load(members_dir(out) / f"N{start}_c{c:g}_rtol{1e-13:g}.npz")
        last[c] = (np.asarray(z["A"]), float(z["T"]), float(z["theta"]))
    with open(out, "a") as f:
        for N in rings:
            spec = spec_for(N)
            for c in list(last):
                A0, T, theta = last[c]
                t0 = time.process_time()
                b1, _ = DT.newton_core_first(tb_launch.embedded(A0, N), T, theta, spec.alpha, spec.norm,
                                             spec.newton_tol, rtol=spec.rtol)
                if not b1.converged:
                    print(f"N = {N}, c = {c}: carried TB not converged ({b1.residual:.2e})", flush=True)
                    del last[c]
                    continue
                last[c] = (b1.A, b1.T, b1.theta)
                line = measure(b1, N, c, spec.rtol, time.process_time() - t0, members_dir(out)) | {"carried": True}
                f.write(json.dumps(line) + "\n")
                f.flush()
                print(json.dumps(line), flush=True)
                t1 = time.process_time()
                b2 = resolve(spec, b1, CHECK_RTOL)
                if b2.converged:
                    line = measure(b2, N, c, CHECK_RTOL, time.process_time() - t1, members_dir(out)) | {"carried": True}
                    f.write(json.dumps(line) + "\n")
                    f.flush()
                    print(json.dumps(line), flush=True)


def table(path: str, out: str | None) -> None:
    """The markdown table of the module docstring."""
    lines = [json.loads(x) for x in Path(path).read_text().splitlines() if x.strip()]
    spec = spec_for(24)
    text = ["| c | rtol | N | growth (per unit τ) | arg μ | PR / N | core fraction: \\|A\\| > 1e-2 (sites) | "
            "\\|A\\| > 1e-3 (sites) | norm 1 − 1e-6 (sites) | θ | H | tail | CPU (s) |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    fits = []
    for c in MEMBERS:
        for rtol in (spec.rtol, CHECK_RTOL):
            rows = sorted((x for x in lines if x["c"] == c and x["rtol"] == rtol), key=lambda x: x["N"])
            for x in rows:
                unstable = x["growth"] > spec.stability_threshold
                text.append(f"| {c:g} | {rtol:g} | {x['N']}{'*' if x.get('carried') else ''} | "
                            f"{'**' if unstable else ''}{x['growth']:.2e}{'**' if unstable else ''} | "
                            f"{x['arg']:+.3f} | {x['participation_share']:.3f} | "
                            + " | ".join(f"{x[f'core_fraction_{i}']:.2e} ({x[f'core_sites_{i}']:.0f})"
                                         for i in range(3))
                            + f" | {x['theta']:+.9f} | {x['H']:.10f} | {x['tail']:.1e} | {x['cpu_s']:.0f} |")
            if rows:
                fits.append((c, rtol, rows))
    text += ["", "Slopes against N (least squares of ln y on ln N over the rings where the member is unstable; "
             "± one standard error) and the reading of MODE_RULE:", "",
             "| c | rtol | unstable rings | growth ~ N^s | PR / N ~ N^s | core fraction ~ N^s (three cores) | "
             + " | ".join(f"δ = {t:g}{', resolved' if r else ''}" for r in (False, True)
                          for t in FM.MODE_RULE_THRESHOLDS) + " |",
             "|---|---|---|---|---|---|" + "---|" * 2 * len(FM.MODE_RULE_THRESHOLDS)]
    letter = {FM.STABLE: "S", FM.UNSTABLE: "U", FM.UNDECIDED: "?"}
    for c, rtol, rows in fits:
        N = np.array([x["N"] for x in rows], float)
        g = np.array([x["growth"] for x in rows])
        pr = np.array([x["participation_share"] for x in rows])
        cores = np.array([[x[f"core_fraction_{i}"] for i in range(3)] for x in rows]).T
        u = g > spec.stability_threshold
        s = {k: FM.power_slope(N[u], y[u]) for k, y in (("g", g), ("pr", pr), *((f"c{i}", cores[i]) for i in range(3)))}
        verdicts = [letter[FM.mode_verdict(N, g, cores[0], spec.stability_threshold, t, r)[0]]
                    for r in (False, True) for t in FM.MODE_RULE_THRESHOLDS]
        text.append(f"| {c:g} | {rtol:g} | {int(u.sum())} of {u.size} | {s['g'][0]:+.2f} ± {s['g'][1]:.2f} | "
                    f"{s['pr'][0]:+.2f} ± {s['pr'][1]:.2f} | "
                    + ", ".join(f"{s[f'c{i}'][0]:+.2f} ± {s[f'c{i}'][1]:.2f}" for i in range(3))
                    + " | " + " | ".join(verdicts) + " |")
    result = "\n".join(text) + "\n"
    if out:
        Path(out).write_text(result)
    print(result)


def main(argv: list[str]) -> None:
    if argv[0] == "table":
        table(argv[1], argv[2] if len(argv) > 2 else None)
        return
    if argv[0] == "carry":
        members = list(MEMBERS)
        if "--members" in argv:
            i = argv.index("--members")
            members = [float(x) for x in argv[i + 1].split(",")]
            argv = argv[:i] + argv[i + 2:]
        carry_rings(argv[1], int(argv[2]), [int(x) for x in argv[3].split(",")], members)
        return
    out, rest, carry = argv[1], argv[2:], []
    if "--carry" in rest:
        i = rest.index("--carry")
        carry = [int(x) for x in rest[i + 1].split(",")]
        rest = rest[:i] + rest[i + 2:]
    run(out, [int(x) for x in rest], carry)


if __name__ == "__main__":
    main(sys.argv[1:])
