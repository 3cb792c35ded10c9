"""Test-session settings.

One BLAS thread: the dense solves here are small (N <= a few hundred), and on a
2-core machine a multithreaded OpenBLAS makes them ~100x slower once the other
core is busy. Set before numpy is first imported.
"""
import os
import shutil
import subprocess
import sys
from pathlib import Path

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

#: the repository root (tests/<layer>/ mirror src/cradle/<layer>/)
ROOT = Path(__file__).resolve().parents[1]


def run_snakemake(workdir, *args, timeout=300):
    """``snakemake ARGS`` in ``workdir`` (the venv's snakemake), captured; warnings silenced."""
    exe = shutil.which("snakemake") or shutil.which("snakemake", path=str(Path(sys.executable).parent))
    cmd = [exe] if exe else [sys.executable, "-m", "snakemake"]
    return subprocess.run(cmd + list(args), cwd=workdir, capture_output=True, text=True, timeout=timeout,
                          env={**os.environ, "PYTHONWARNINGS": "ignore"})
