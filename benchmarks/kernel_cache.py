"""Cold compile against warm load of the kernels one scene uses (docs/compiled-kernels.md).

    python benchmarks/kernel_cache.py [--scene tw-strong] [--pairs 3]

Each pair runs, in fresh processes with ``CRADLE_KERNEL_CACHE`` pointed at an
empty temporary folder: ``cradle run SCENE`` twice (cold, then warm: wall
time and the exact and DpS stage times from its log), then, with the folder
emptied again, the first call of srkn6c and of dop853_numba on a tiny input
twice (compiling or loading alone). Prints the range over the pairs.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

FIRST_CALLS = r"""
import json, time
import numpy as np
from cradle.integrators import integrate_dps, integrate_lattice
n = np.arange(8)
t0 = time.perf_counter()
integrate_lattice(0.5 * np.cos(np.pi / 4 * n), 0.5 * np.sin(np.pi / 4 * n), [0.0, 0.1], alpha=1.5, method="srkn6c")
t1 = time.perf_counter()
integrate_dps(0.1 * np.exp(1j * np.pi / 4 * n), [0.0, 0.1], alpha=1.5, method="dop853_numba")
t2 = time.perf_counter()
print(json.dumps({"first call, srkn6c": t1 - t0, "first call, dop853_numba": t2 - t1}))
"""


def _env(cache: Path) -> dict:
    return dict(os.environ, CRADLE_KERNEL_CACHE=str(cache),
                PYTHONPATH=f"{ROOT / 'src'}{os.pathsep}{os.environ.get('PYTHONPATH', '')}")


def scene_run(scene: str, cache: Path, out: Path) -> dict:
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "cradle", "run", scene, "--out", str(out)], cwd=ROOT,
                          env=_env(cache), capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if proc.returncode:
        sys.exit(proc.stderr[-3000:])
    stages = dict(re.findall(r"(exact|dps) \S+: done in ([\d.]+) s", proc.stdout + proc.stderr))
    return {"cradle run (wall)": wall, "exact stage": float(stages["exact"]), "DpS stage": float(stages["dps"])}


def first_calls(cache: Path) -> dict:
    proc = subprocess.run([sys.executable, "-c", FIRST_CALLS], cwd=ROOT, env=_env(cache), capture_output=True,
                          text=True, check=True)
    return json.loads(proc.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default="tw-strong")
    ap.add_argument("--pairs", type=int, default=3)
    args = ap.parse_args(argv)
    rows: dict = {}
    with tempfile.TemporaryDirectory(prefix="cradle-kernel-cache-") as tmp:
        cache = Path(tmp) / "cache"
        for _ in range(args.pairs):
            for fn in (lambda label: scene_run(args.scene, cache, Path(tmp) / label), lambda label: first_calls(cache)):
                shutil.rmtree(cache, ignore_errors=True)
                for label in ("cold", "warm"):
                    for key, value in fn(label).items():
                        rows.setdefault(key, {"cold": [], "warm": []})[label].append(value)
        size = sum(f.stat().st_size for f in cache.rglob("*") if f.is_file())
    print(f"| {args.scene} | cold (compile) | warm (load) |\n|---|---:|---:|")
    for key, runs in rows.items():
        print(f"| {key} | " + " | ".join(f"{min(v):.2f} – {max(v):.2f} s" for v in runs.values()) + " |")
    print(f"\ncompiled kernels of these runs: {size / 2**20:.1f} MiB; load average {os.getloadavg()[0]:.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
