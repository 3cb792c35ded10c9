"""Are the compiled kernels' numbers bitwise those of a reference checkout? Old code against new code.

    python benchmarks/kernel_bitwise.py --old-python OLD_CHECKOUT/.venv/bin/python --old-src OLD_CHECKOUT/src
        [--only SUBSTRING]

Every combination of model terms and methods the pipeline integrates (the scenes of config.yaml with
``terms:`` and the analyses desk-toy, dissipation, disorder, trapping, jkc-variants, dps-validity,
breathers, floquet, work-precision: (nc)/(meca) with every method, continued splitting runs, the damped
(ncdamped) with each damping term alone and both, the imperfect (ncimperfect) with each term alone, some
together and with damping, the DpS (dfnls), (dpsdamped) and (dpsimperfect) with every method, and the
blocks of ``iter_dps``) is run for a short time on the same inputs by the reference checkout (a
subprocess: ``--old-python`` with ``PYTHONPATH=--old-src``) and by this one (a subprocess of this
interpreter with this checkout's ``src``). Every array and number of the solutions is compared byte for
byte (``tobytes``), wall times excepted. Prints one line per case and a summary; exit status 1 on any
difference.
"""
from __future__ import annotations

import argparse
import os
import pickle
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
NEW_SRC = HERE.parent / "src"


def _lattice_state(N: int, amp: float, q: float, seed: int, bc: str):
    """A packet of amplitude ``amp`` and wave number q with a seeded perturbation (free ends: localised)."""
    rng = np.random.default_rng(seed)
    n = np.arange(N)
    env = np.exp(-((n - N / 2) / (N / 5)) ** 2) if bc == "free" else np.ones(N)
    x0 = amp * env * np.cos(q * n) + 0.01 * amp * rng.standard_normal(N)
    v0 = amp * env * np.sin(q * n) + 0.01 * amp * rng.standard_normal(N)
    return x0, v0


def _dps_state(N: int, amp: float, q: float, seed: int, bc: str):
    x0, v0 = _lattice_state(N, amp, q, seed, bc)
    return x0 + 1j * v0


def cases():
    """(name, kind, arguments) of every combination compared; kind 'lattice', 'dps' or 'iter_dps'."""
    out = []
    t = [0.0, 0.7, 1.9, 3.0]
    # (nc)/(meca): every method, both ends, both laws, alpha = 3/2 (fast path) and another exponent
    methods = ["srkn6c", "srkn4c", "srkn6", "srkn4", "strang", "dop853_numba", "dop853", "rk45", "lsoda", "radau"]
    for method in methods:
        for bc in ("periodic", "free"):
            for alpha in (1.5, 2.5):
                for potential in ("hertz", "smooth"):
                    if potential == "smooth" and (bc == "free" or alpha != 1.5):
                        continue
                    out.append((f"nc {method} {bc} alpha={alpha} {potential}", "lattice",
                                dict(N=12, amp=0.4, q=np.pi / 3, bc=bc, t=t,
                                     kw=dict(alpha=alpha, bc=bc, method=method, potential=potential))))
    # a splitting run continued from a stored state (dps-validity, extend, streamed stores)
    for method in ("srkn6c", "srkn6"):
        out.append((f"nc {method} continued t0", "lattice",
                    dict(N=12, amp=0.4, q=np.pi / 3, bc="periodic", t=[1.0, 1.6, 2.5],
                         kw=dict(alpha=1.5, method=method, dt=0.01, t0=1.0, energy0=0.37))))
    # the damped (ncdamped): each term alone and both, ring and free chain (dissipation, desk-toy, trapping)
    damp = [("gamma", {"onsite": 0.05}), ("eta", {"contact": 0.3}), ("gamma+eta", {"onsite": 0.05, "contact": 0.3})]
    for name, d in damp:
        for bc in ("periodic", "free"):
            for alpha in (1.5, 2.5):
                out.append((f"ncdamped {name} {bc} alpha={alpha}", "lattice",
                            dict(N=10, amp=0.5, q=np.pi / 2, bc=bc, t=t,
                                 kw=dict(alpha=alpha, bc=bc, method="dop853_numba", rtol=1e-9), damping=d)))
    # the imperfect cradle (ncimperfect): each term alone, some together, with damping (jkc-variants, disorder)
    terms = [
        ("quartic soft", {"onsite": {"potential": "quartic", "beta": -1.0}}, "free"),
        ("quartic hard", {"onsite": {"potential": "quartic", "beta": 3.0}}, "free"),
        ("pendulum", {"onsite": {"potential": "pendulum", "scale": 0.5}}, "free"),
        ("precompression", {"precompression": {"delta0": 0.05}}, "periodic"),
        ("gaps", {"precompression": {"delta0": -0.02}}, "free"),
        ("disorder omega", {"inhomogeneity": {"sigma": 0.05, "seed": 3}}, "periodic"),
        ("disorder mass", {"inhomogeneity": {"mass_sigma": 0.1, "seed": 4}}, "free"),
        ("disorder all", {"inhomogeneity": {"sigma": 0.05, "mass_sigma": 0.1,
                                            "stiffness": [1.0 + 0.05 * k for k in range(10)]}}, "periodic"),
        ("quartic+precompression+disorder", {"onsite": {"potential": "quartic", "beta": 0.5},
                                             "precompression": {"delta0": 0.02},
                                             "inhomogeneity": {"sigma": 0.03}}, "periodic"),
        ("pendulum+disorder", {"onsite": {"potential": "pendulum", "scale": 0.3},
                               "inhomogeneity": {"sigma": 0.03, "mass_sigma": 0.05}}, "free"),
    ]
    for name, tm, bc in terms:
        for alpha in (1.5, 2.5):
            out.append((f"ncimperfect {name} {bc} alpha={alpha}", "lattice",
                        dict(N=10, amp=0.5, q=np.pi / 2, bc=bc, t=t,
                             kw=dict(alpha=alpha, bc=bc, method="dop853_numba", rtol=1e-9), terms=tm)))
    for name, tm, bc in terms[::3]:
        for dn, d in damp:
            out.append((f"ncimperfect {name} + {dn} {bc}", "lattice",
                        dict(N=10, amp=0.5, q=np.pi / 2, bc=bc, t=t,
                             kw=dict(alpha=1.5, bc=bc, method="dop853_numba", rtol=1e-9), terms=tm, damping=d)))
    # (dfnls), (dpsdamped), (dpsimperfect)
    tau = [0.0, 0.5, 1.3, 2.0]
    for method in ("dop853_numba", "dop853", "rk45"):
        for bc in ("periodic", "free"):
            for alpha in (1.5, 2.5):
                base = dict(N=12, amp=0.5, q=np.pi / 3, bc=bc, tau=tau, kw=dict(alpha=alpha, bc=bc, method=method))
                out.append((f"dfnls {method} {bc} alpha={alpha}", "dps", base))
                for name, d in (("gamma", {"gamma": 0.2}), ("eta", {"eta": 0.3}), ("gamma+eta", {"gamma": 0.2,
                                                                                                "eta": 0.3})):
                    out.append((f"dpsdamped {name} {method} {bc} alpha={alpha}", "dps", dict(base, damping=d)))
                for name, s in (("homogeneous", {}), ("detuning+quartic", {"sigma": 0.05, "beta": 0.3}),
                                ("precompressed", {"delta0": 0.02, "sigma": 0.02}),
                                ("gaps+masses+pendulum", {"delta0": -0.01, "mass_sigma": 0.1, "scale": 0.4})):
                    if "delta0" in s and s["delta0"] > 0 and bc == "free":
                        continue
                    out.append((f"dpsimperfect {name} {method} {bc} alpha={alpha}", "dps", dict(base, sites=s)))
    out.append(("iter_dps blocks", "iter_dps", dict(N=12, amp=0.5, q=np.pi / 3, bc="periodic",
                                                    tau=list(np.linspace(0.0, 3.0, 7)), kw=dict(alpha=1.5))))
    return out


def _numbers(obj) -> dict:
    """Every array and number of a solution object, by field name (wall times left out)."""
    out = {}
    for key, value in vars(obj).items():
        if key == "wall_time_s":
            continue
        if isinstance(value, np.ndarray):
            out[key] = value
        elif isinstance(value, int | float | np.integer | np.floating):
            out[key] = np.asarray(value)
    return out


def run_case(kind: str, a: dict) -> dict:
    """The numbers of one case, computed by whichever cradle is importable."""
    from cradle.integrators import integrate_dps, integrate_lattice

    if kind == "lattice":
        from cradle.models.damping import Damping
        from cradle.models.lattice_terms import Terms
        from cradle.specs.declare import from_plain

        x0, v0 = _lattice_state(a["N"], a["amp"], a["q"], 1, a["bc"])
        kw = dict(a["kw"])
        if "damping" in a:
            kw["damping"] = Damping(**a["damping"])
        if "terms" in a:
            kw["terms"] = from_plain(Terms, a["terms"])
        return _numbers(integrate_lattice(x0, v0, np.array(a["t"]), **kw))
    A0 = _dps_state(a["N"], a["amp"], a["q"], 2, a["bc"])
    if kind == "iter_dps":
        from cradle.integrators.dps_solver import iter_dps

        res = {}
        for i, block in enumerate(iter_dps(A0, np.array(a["tau"]), 3, **a["kw"])):
            res.update({f"block{i}.{k}": v for k, v in _numbers(block).items()})
        return res
    kw = dict(a["kw"])
    if "damping" in a:
        from cradle.models.dps_damped import DpsDamping

        kw["damping"] = DpsDamping(**a["damping"])
    if "sites" in a:
        from cradle.models.dps_sites import dps_sites
        from cradle.models.inhomogeneity import Inhomogeneity, sites

        s = a["sites"]
        si = sites(Inhomogeneity(sigma=s.get("sigma", 0.0), mass_sigma=s.get("mass_sigma", 0.0), seed=5), a["N"])
        kw["sites"] = dps_sites(si.mass, si.omega, si.stiffness, alpha=kw["alpha"], eps=0.3, beta=s.get("beta", 0.0),
                                pendulum_scale=s.get("scale", 0.0), delta0=s.get("delta0", 0.0))
    return _numbers(integrate_dps(A0, np.array(a["tau"]), **kw))


def _emit(path: str, only: str) -> None:
    """Compute every case (those whose name contains ``only``) and pickle {name: numbers or error}."""
    res = {}
    for name, kind, a in cases():
        if only not in name:
            continue
        try:
            res[name] = run_case(kind, a)
        except Exception as exc:   # a refusal is a result too: both checkouts must refuse alike
            res[name] = {"error": np.asarray(f"{type(exc).__name__}: {exc}")}
    with open(path, "wb") as fh:
        pickle.dump(res, fh)


def _run(python: str, src: str, only: str, path: str) -> dict:
    env = dict(os.environ, PYTHONPATH=src)
    subprocess.run([python, str(Path(__file__).resolve()), "--emit", path, "--only", only], env=env, check=True)
    with open(path, "rb") as fh:
        return pickle.load(fh)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--old-python", help="a Python with the reference checkout's dependencies (required)")
    p.add_argument("--old-src", help="the src folder of the reference checkout (required)")
    p.add_argument("--new-python", default=sys.executable)
    p.add_argument("--only", default="")
    p.add_argument("--old-results", help="a pickle of the reference's numbers: read if it exists, else written "
                                         "(the reference checkout does not change between runs)")
    p.add_argument("--emit", help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    if args.emit:   # the child process of _run: the reference's arguments are not its own
        _emit(args.emit, args.only)
        return 0
    if not (args.old_python and args.old_src):
        p.error("--old-python and --old-src are required")
    with tempfile.TemporaryDirectory() as tmp:
        if args.old_results and os.path.exists(args.old_results):
            with open(args.old_results, "rb") as fh:
                old = pickle.load(fh)
        else:
            old = _run(args.old_python, args.old_src, args.only, args.old_results or os.path.join(tmp, "old.pkl"))
        new = _run(args.new_python, str(NEW_SRC), args.only, os.path.join(tmp, "new.pkl"))
    bad = 0
    for name in old:
        o, n = old[name], new.get(name, {})
        diffs = [k for k in sorted(set(o) | set(n))
                 if k not in o or k not in n or o[k].dtype != n[k].dtype or o[k].shape != n[k].shape
                 or o[k].tobytes() != n[k].tobytes()]
        status = "error (both)" if "error" in o and not diffs else ("equal" if not diffs else "DIFFERENT")
        print(f"{status:12s} {name}" + (f": {', '.join(diffs)}" if diffs else ""))
        bad += bool(diffs)
    arrays = sum(len(v) for v in old.values())
    print(f"summary: {len(old)} combinations, {arrays} arrays compared, {len(old) - bad} bitwise equal, "
          f"{bad} different")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
