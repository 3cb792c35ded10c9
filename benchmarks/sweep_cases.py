"""What one case of each sweep costs against the integrations it runs, measured in the same process.

    PYTHONPATH=src python benchmarks/sweep_cases.py [--before OLD_SRC] [--repeats 5] [--out docs/sweep-cases.md]
    PYTHONPATH=src python benchmarks/sweep_cases.py --only breather-interactions --repeats 3 --no-write
    PYTHONPATH=src python benchmarks/sweep_cases.py --outcomes --before OLD_SRC    # outcome fractions, a sample
    PYTHONPATH=src python benchmarks/sweep_cases.py --batch --before OLD_SRC       # one whole batch

A *case* is the unit a sweep repeats (:data:`SWEEPS`): one call of the analysis's own per-case function with
the settings of its full form (config.yaml's defaults: the spec classes' defaults), exactly as its batch jobs
call it. While it runs, ``cradle.integrators.integrate_lattice`` and ``integrate_dps`` are wrapped by a timer
(looked up where the analyses look them up: the attribute of ``cradle.integrators``, and any module-level name
of the same name in the sweep's modules), so the same call yields both the whole case's time and the time
spent inside the integrators. Each case is run once first (kernels compiled or loaded, caches warm), then
``--repeats`` times; the table shows medians, in CPU time of the process (``time.process_time``: the machine
is shared, and wall time counts the other processes' turns) and in wall time.

``--only NAME`` (repeatable): those sweeps only; their table has its own section of the document, its marker
naming them, beside the table of all sweeps.

``--before OLD_SRC``: the same measurement also with another checkout's ``src`` (e.g. ``git archive <commit>
src | tar -x -C /tmp/before``), each source in a fresh subprocess, alternating old and new ``ROUNDS`` times, so
both are measured in the same hour; the table then has both and the cases' results are checked equal
(bitwise, NaN equal to NaN). ``--outcomes``: the breather-interactions outcome fractions of a sample of
the full form's cases (:func:`outcome_sample`) under each source; ``--batch``: one whole (pair, spacing)
batch of it under each source (:func:`one_batch`: its time, the full sweep's estimated from it, and every
case compared). Each writes its own section of the document (``--out``).

**Adding a sweep**: one entry in
:data:`SWEEPS`, a function returning ``(label, call)`` pairs where ``call()`` runs one representative case of
the sweep's full form and returns its results as a dict of numbers (compared between sources); the modules it
names in ``modules`` get their ``integrate_*`` names wrapped too.
"""
from __future__ import annotations

import argparse
import datetime as _dt
import importlib
import json
import os
import platform
import statistics
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from doctable import git_commit

ROOT = Path(__file__).resolve().parents[1]
INTEGRATORS = ("integrate_lattice", "integrate_dps")
ROUNDS = 2
FULL_CASES = 4176      # cases of the breather-interactions full form (15 batches, refinement included)


# ----------------------------------------------------------------- the sweeps' representative cases


def _breather_interactions():
    """Two 600-period runs of 50 beads (the full form), seed 0, one case of each outcome the classification
    spends differently on: site-site at spacing 6, theta = 0 (merge in both models) and pi/2 (repel), and
    at spacing 8, theta = pi (bound: the crossing tracker runs)."""
    from cradle.analyses import breather_interactions as B

    spec = B.BreatherInteractions()

    def case(spacing, theta):
        return lambda: B.run_case(spec, "site-site", spacing, theta, 1.0, spec.amplitude, 0)

    return [(f"site-site, spacing {s:g}, theta = {name}, seed 0 ({what})", case(s, th))
            for s, name, th, what in ((6.0, "0", 0.0, "merge"), (6.0, "pi/2", np.pi / 2, "repel"),
                                      (8.0, "pi", np.pi, "bound"))]


def _dps_validity():
    """One (family, alpha, eps) of the full form: the running sup error of :func:`sup_error` to the largest T,
    as :func:`cradle.analyses.dps_validity.batch` calls it: the breather at alpha = 2 and the fifth eps of the
    grid, and the noisy unstable wave at alpha = 1.5 and its smallest eps (with the dt / 2 check run)."""
    from cradle.analyses import dps_validity as D

    spec = D.DpsValidity()
    out = []
    for fam, alpha, ie in (("breather-bond", 2.0, 4), ("mi-4pi5-noise", 1.5, 0)):
        eps = float(D.eps_grid(spec, list(spec.alpha).index(alpha))[ie])
        A0, _N, _info = D.family_amplitude(fam, alpha, spec)

        def call(A0=A0, eps=eps, alpha=alpha, check=ie == 0):
            r = D.sup_error(A0, eps, alpha, spec.T, sample_every=spec.sample_every, dt_factor=spec.dt_factor,
                            rtol=spec.dps_rtol, chunk=spec.chunk, check=check)
            return {k: r[k] for k in ("abs_error", "energy_drift", "halving_deviation")}

        out.append((f"{fam}, alpha = {alpha:g}, eps = {eps:.3g}" + (" (+ dt/2 check)" if ie == 0 else ""), call))
    return out


def _mi_statistics():
    """One run of the full form: N = 200, q = 0.55 pi (the middle of the grid), the first seed, each model."""
    from cradle.analyses import mi_statistics as M

    spec = M.MIStatistics()
    N, k = 200, 55

    def case(model):
        def call():
            t, r, kp, info = M.run_ratio(model, N, k, spec.seed0, spec)
            return {"ratio": r, "k_peak": kp, "crossing_time": M.crossing_time(t, r, spec.fraction)}
        return call

    return [(f"{m}, N = {N}, q = {2 * k / N:g} pi, seed0", case(m)) for m in ("exact", "dps")]


def _disorder():
    """One (sigma, seed) of a (family, Delta) batch of the full form, as :func:`cradle.analyses.disorder.family_batch`
    runs it (:func:`~cradle.analyses.disorder.run_case`, then the fidelity series put on its grid): every family at
    the smallest Delta, 0.01 (the longest runs: 600 periods, 7,543 samples, the most measuring per integration),
    and the wave at the largest, 0.3 (385 samples: the fixed costs weigh most); sigma = 0.03, the first seed. The
    batch's exact breather and the homogeneous reference pair (sigma = 0, run once per batch or seed) are made
    before the timing."""
    from cradle.analyses import disorder as D
    from cradle.data.variables import MODELS

    spec = D.Disorder()
    sigma, seed = 0.03, spec.first_seed

    def before_run_case(spec, family, shift, t, sigma, seed, b, ref):   # a source from before run_case: the loop's body
        init = D.initial_data(spec, family, shift, seed, b)
        run = D.run_models(spec, init, t, sigma, seed)
        return run, D.measure_family(spec, family, shift, t, run, ref if sigma > 0 else None, init)

    run_case = getattr(D, "run_case", before_run_case)

    def case(family, shift):
        t = D.time_grid(spec, shift)
        b = D.exact_breather(spec, shift) if family in ("kicked", "static") else None
        run0, res0 = run_case(spec, family, shift, t, 0.0, seed, b, None)
        ref = dict(run0, measures=res0)
        s_grid = np.linspace(0.0, spec.slow_periods, D.SERIES_POINTS)

        def call():
            run, res = run_case(spec, family, shift, t, sigma, seed, b, ref)
            out = {f"{m}.{k}": v for m in MODELS for k, v in res[m].items() if k in D.MEASURES[family]}
            if family == "wave":
                out.update({f"{m}.series": np.interp(s_grid, t / (2.0 * np.pi / shift), res[m]["_series"])
                            for m in MODELS})
            return dict(out, drift=run["drift"], l2=run["l2"])
        return call

    return [(f"{f}, Delta = {d:g}, sigma = {sigma:g}, seed {seed}", case(f, d))
            for f, d in (("wave", 0.01), ("mi", 0.01), ("kicked", 0.01), ("static", 0.01), ("wave", 0.3))]


def _trapping():
    """One run of the full form, as :func:`cradle.analyses.trapping.run_batch` runs it
    (:func:`~cradle.analyses.trapping.run_one`): the striker at a = 1 (the scan amplitude) and a = 0.1 (the
    longest run: 3,795 samples of 260 beads), the breather at a = 0.3 undamped and with the on-site damping, each
    in the target at sigma = 0.1, the first seed; and the striker's homogeneous damped run (seed -1: the damped
    integrator without terms, another path). The site energies e (samples x beads) are compared by their SHA-256."""
    import hashlib

    from cradle.analyses import trapping as T
    from cradle.models.damping import Damping

    spec = T.Trapping()

    def case(kind, a, sigma, seed, gamma):
        def call():
            damping = Damping(onsite=gamma, contact=0.0) if gamma > 0 else None
            r = T.run_one(spec, kind, a, spec.length, sigma, seed, damping)
            out = {k: v for k, v in r.items() if k not in ("t", "e")}
            return dict(out, e_sha256=hashlib.sha256(np.ascontiguousarray(r["e"]).tobytes()).hexdigest())
        return call

    first = spec.seed
    return [(f"{k}, a = {a:g}, length {spec.length}, sigma = {s:g}, seed {sd}" + (f", gamma = {g:g}" if g else ""),
             case(k, a, s, sd, g))
            for k, a, s, sd, g in (("striker", 1.0, 0.1, first, 0.0), ("striker", 0.1, 0.1, first, 0.0),
                                   ("breather", 0.3, 0.1, first, 0.0), ("breather", 0.3, 0.1, first, 1e-3),
                                   ("striker", 1.0, 0.0, -1, 1e-3))]


#: sweep -> (the function giving its representative cases, modules whose integrate_* names are wrapped)
SWEEPS: dict[str, tuple[Callable, tuple[str, ...]]] = {
    "breather-interactions": (_breather_interactions, ("cradle.analyses.pair_runs",)),
    "dps-validity": (_dps_validity, ("cradle.analyses.dps_validity",)),
    "mi-statistics": (_mi_statistics, ("cradle.analyses.mi_statistics",)),
    "disorder": (_disorder, ("cradle.analyses.disorder",)),
    "trapping": (_trapping, ("cradle.analyses.trapping",)),
}


# ----------------------------------------------------------------- timing in one process


class _Timer:
    """Wraps the integrators: CPU and wall time spent inside them since the last reset."""

    def __init__(self):
        self.cpu = self.wall = 0.0
        self.calls = 0

    def wrap(self, modules):
        """Time ``integrate_*`` of cradle.integrators and of ``modules`` (each wrapped once)."""
        import cradle.integrators as ci

        targets = [ci] + [importlib.import_module(m) for m in modules]
        for mod in targets:
            for name in INTEGRATORS:
                fn = getattr(mod, name, None)
                if fn is not None and not getattr(fn, "_timed", False):
                    setattr(mod, name, self._wrap(fn))

    def _wrap(self, fn):
        def timed(*a, **kw):
            c0, w0 = time.process_time(), time.perf_counter()
            try:
                return fn(*a, **kw)
            finally:
                self.cpu += time.process_time() - c0
                self.wall += time.perf_counter() - w0
                self.calls += 1

        timed._timed = True  # type: ignore[attr-defined]
        return timed

    def reset(self):
        self.cpu = self.wall = 0.0
        self.calls = 0


def _plain(v):
    a = np.asarray(v)
    return a.tolist() if a.dtype.kind in "fiub" else str(v)


def measure(names, repeats: int) -> dict:
    """{sweep: [{label, case_cpu, int_cpu, case_wall, int_wall, calls, result}]} in this process."""
    out = {}
    timer = _Timer()
    for name in names:
        cases, modules = SWEEPS[name]
        timer.wrap(modules)
        rows = []
        for label, call in cases():
            result = call()                                   # warm-up: kernels, caches
            runs = []
            for _ in range(repeats):
                timer.reset()
                c0, w0 = time.process_time(), time.perf_counter()
                call()
                runs.append((time.process_time() - c0, timer.cpu, time.perf_counter() - w0, timer.wall))
            med = [statistics.median(r[i] for r in runs) for i in range(4)]
            ratio = statistics.median(r[0] / r[1] for r in runs)
            rows.append({"label": label, "case_cpu": med[0], "int_cpu": med[1], "case_wall": med[2],
                         "int_wall": med[3], "ratio": ratio, "calls": timer.calls,
                         "result": {k: _plain(v) for k, v in result.items()}})
            print(f"  {name}: {label}: case {med[0]:.3f} s CPU, integrations {med[1]:.3f} s, ratio {ratio:.3f}",
                  file=sys.stderr, flush=True)
        out[name] = rows
    return out


# ----------------------------------------------------------------- outcome fractions on a sample


def outcome_sample(n_theta: int = 4) -> dict:
    """The breather-interactions outcomes of a sample of the full form's cases (every pair and spacing,
    ``n_theta`` phases, seed 0): {model: [outcome code per case]}."""
    from cradle.analyses import breather_interactions as B

    spec = B.BreatherInteractions()
    out: dict[str, list] = {m: [] for m in B.MODELS}
    for pair, spacing in B.batches(spec):
        for theta in 2 * np.pi * np.arange(n_theta) / n_theta:
            r = B.run_case(spec, pair, spacing, float(theta), 1.0, spec.amplitude, 0)
            for m in B.MODELS:
                out[m].append(int(r[f"outcome_{m}"]))
    return out


def one_batch(pair: str = "site-site", spacing: float = 6.0) -> dict:
    """Every case of one (pair, spacing) batch of the breather-interactions full form, as its batch job runs
    them (:func:`cradle.analyses.breather_interactions.run_batch`): CPU and wall time and the case rows."""
    from cradle.analyses import breather_interactions as B

    spec = B.BreatherInteractions()
    B.run_case(spec, pair, spacing, 0.0, 1.0, spec.amplitude, 0)          # kernels loaded
    c0, w0 = time.process_time(), time.perf_counter()
    rows = B.run_batch(spec, pair, spacing)
    cpu, wall = time.process_time() - c0, time.perf_counter() - w0
    return {"cpu": cpu, "wall": wall, "n_batches": len(B.batches(spec)),
            "rows": [{k: _plain(v) for k, v in r.items()} for r in rows]}


def batch_table(new: dict, old: dict | None) -> str:
    lines = ["| source | cases | CPU [s] | wall [s] | CPU per case [s] | full sweep, estimated CPU [min] |",
             "|---|---:|---:|---:|---:|---:|"]
    for who, got in (("before", old), ("now", new)):
        if got is None:
            continue
        n = len(got["rows"])
        lines.append(f"| {who} | {n} | {got['cpu']:.1f} | {got['wall']:.1f} | {got['cpu'] / n:.3f} | "
                     f"{got['cpu'] / n * FULL_CASES / 60:.1f} |")
    if old is not None:
        same = sum(all(_same(a[k], b[k]) for k in a) for a, b in zip(old["rows"], new["rows"], strict=True))
        lines.append(f"\nCases whose every field (parameters, outcomes, times, velocities, norm transfer) is "
                     f"bitwise the same before and now: {same} of {len(new['rows'])}.")
    return "\n".join(lines)


def outcome_table(new: dict, old: dict | None) -> str:
    from cradle.measurements.interactions import OUTCOMES

    lines = ["| source | model | cases | " + " | ".join(OUTCOMES) + " |", "|---|---|---:|" + "---:|" * len(OUTCOMES)]
    for who, got in (("before", old), ("now", new)):
        if got is None:
            continue
        for m, codes in got.items():
            c = np.bincount(codes, minlength=len(OUTCOMES))
            lines.append(f"| {who} | {m} | {len(codes)} | " + " | ".join(f"{x / len(codes):.3f}" for x in c) + " |")
    if old is not None:
        same = sum(a == b for m in new for a, b in zip(new[m], old[m], strict=True))
        lines.append(f"\nCases whose outcome is the same before and now: {same} of {sum(map(len, new.values()))}.")
    return "\n".join(lines)


# ----------------------------------------------------------------- the report


def _same(a, b) -> bool:
    return np.array_equal(np.asarray(a, dtype=object if isinstance(a, str) else float),
                          np.asarray(b, dtype=object if isinstance(b, str) else float),
                          equal_nan=not isinstance(a, str))


def table(new: dict, old: dict | None) -> str:
    head = ["sweep", "case", "integrations [s]", "whole case [s]", "case / integrations"]
    if old:
        head[2:2] = ["before: integrations [s]", "before: whole case [s]", "before: ratio"]
        head.append("results equal")
    lines = ["| " + " | ".join(head) + " |", "|" + "|".join(["---"] * 2 + ["---:"] * (len(head) - 2)) + "|"]
    for name, rows in new.items():
        for i, r in enumerate(rows):
            cells = [name, r["label"]]
            if old:
                o = old[name][i]
                cells += [f"{o['int_cpu']:.3f}", f"{o['case_cpu']:.3f}", f"{o['ratio']:.2f}"]
            cells += [f"{r['int_cpu']:.3f}", f"{r['case_cpu']:.3f}", f"**{r['ratio']:.2f}**"]
            if old:
                o = old[name][i]
                eq = all(_same(o["result"][k], v) for k, v in r["result"].items())
                cells.append("bitwise" if eq else "DIFFERENT")
            lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def _child(src: str, names, repeats: int, extra=()) -> dict:
    env = {**os.environ, "PYTHONPATH": src}
    cmd = [sys.executable, __file__, "--json", "--repeats", str(repeats)] + [a for n in names for a in ("--only", n)]
    cmd += list(extra)
    done = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True)
    sys.stderr.write(done.stderr)
    return json.loads(done.stdout)


def _merge(runs: list[dict]) -> dict:
    """Several processes' measurements of the same cases: the median of their medians."""
    out = {}
    for name in runs[0]:
        rows = []
        for i, r0 in enumerate(runs[0][name]):
            r = dict(r0)
            for key in ("case_cpu", "int_cpu", "case_wall", "int_wall", "ratio"):
                r[key] = statistics.median(run[name][i][key] for run in runs)
            rows.append(r)
        out[name] = rows
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--only", action="append", choices=list(SWEEPS), help="a sweep (repeatable; default all)")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--before", help="src folder of the checkout to compare with")
    ap.add_argument("--out", default=str(ROOT / "docs" / "sweep-cases.md"))
    ap.add_argument("--json", action="store_true", help="print the measurements as JSON (one process)")
    ap.add_argument("--no-write", action="store_true")
    ap.add_argument("--outcomes", action="store_true", help="breather-interactions: outcome fractions on a sample")
    ap.add_argument("--batch", action="store_true", help="breather-interactions: one whole batch (pair, spacing)")
    a = ap.parse_args(argv)
    names = a.only or list(SWEEPS)
    t0 = time.perf_counter()
    if a.json:
        print(json.dumps(outcome_sample() if a.outcomes else one_batch() if a.batch else measure(names, a.repeats)))
        return
    section = "outcomes" if a.outcomes else "batch" if a.batch else "table"
    if section != "table":
        sources = ([a.before] if a.before else []) + [str(ROOT / "src")]
        got = {src: _child(src, names, 0, extra=[f"--{section}"]) for src in sources}
        show = outcome_table if a.outcomes else batch_table
        text = show(got[str(ROOT / "src")], got.get(a.before))
    else:
        if a.before:
            new_src = str(ROOT / "src")
            olds, news = [], []
            for _ in range(ROUNDS):
                olds.append(_child(a.before, names, a.repeats))
                news.append(_child(new_src, names, a.repeats))
            old, new = _merge(olds), _merge(news)
        else:
            old, new = None, measure(names, a.repeats)
        text = table(new, old)
    print(text)
    if a.no_write:
        return
    commit = git_commit()
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    when = _dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC")
    args = " ".join("OLD_SRC" if x == a.before else x for x in (argv if argv is not None else sys.argv[1:]))
    stamp = (f"Measured {when} at commit {commit} ({platform.machine()}, {os.cpu_count()} cores, load average "
             f"{load:.1f} at the end; {time.perf_counter() - t0:.0f} s): `python benchmarks/sweep_cases.py {args}`"
             + (f" (OLD_SRC: {a.before})" if a.before else "")
             + (f"; medians over {a.repeats} repeats after a warm-up call"
                + (f", in {ROUNDS} processes per source alternating" if a.before else "") + "; CPU time of the process"
                if section == "table" else "") + ".")
    _write(a.out, section, stamp, text, a.only if section == "table" else None)


SECTIONS = {"table": ("<!-- sweep-cases table -->", "<!-- end -->"),
            "outcomes": ("<!-- sweep-cases outcomes -->", "<!-- end outcomes -->"),
            "batch": ("<!-- sweep-cases batch -->", "<!-- end batch -->")}


def _write(out: str, section: str, stamp: str, text: str, only=None) -> None:
    """Replace one section of the document ``out`` (between its markers), or start the document. A table of
    some sweeps only (``--only``) has its own section, its start marker naming them
    (``<!-- sweep-cases table: disorder, trapping -->``), so that it leaves the table of all sweeps alone."""
    path = Path(out)
    start, end = SECTIONS[section]
    if only:
        start = start.replace(" -->", f": {', '.join(only)} -->")
    doc = path.read_text() if path.exists() else "# Sweep cases: cost against their integrations\n"
    if start not in doc:
        doc += f"\n{start}\n{end}\n"
    before, _, rest = doc.partition(start)
    after = rest.partition(end)[2]
    path.write_text(f"{before}{start}\n{stamp}\n\n{text}\n{end}{after}")
    print(f"wrote {out} ({section})", file=sys.stderr)


if __name__ == "__main__":
    main()
