"""Test-session settings.

One BLAS thread: the dense solves here are small (N <= a few hundred), and on a
2-core machine a multithreaded OpenBLAS makes them ~100x slower once the other
core is busy. Set before numpy is first imported.
"""
import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")
