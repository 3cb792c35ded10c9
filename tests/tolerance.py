"""Tolerances derived from the problem: rounding bounds of computed eigenvalues.

A computed eigenvalue is known only to its conditioning times the backward error of the algorithm
that produced it, and that backward error, not the digits one machine's BLAS kernels happen to
give, is what an assertion on an eigenvalue may rely on.
"""
import numpy as np
import scipy.linalg as sl

EPS = np.finfo(float).eps


def eigenvalue_bounds(A, backward: float = 0.0):
    """(eigenvalues of A, a bound on the error of each as LAPACK computes it).

    The QR algorithm is backward stable: the computed eigenvalues are exact for A + E with
    ||E||_2 <= c(n) eps ||A||_2, c(n) a modest polynomial in n, taken as n (Golub and Van Loan, 7.5.6).
    ``backward`` adds the backward error of how A itself was formed. A simple eigenvalue moves by at
    most kappa_i ||E|| to first order, kappa_i = ||x_i|| ||y_i|| / |y_i^H x_i| (right and left
    eigenvectors, Wilkinson's condition number); an eigenvalue of a (near-)Jordan pair moves by at
    most ~ sqrt(||E|| ||A||), so the bound is the smaller of the two (doubled for the second-order terms).
    """
    A = np.asarray(A)
    lam, vl, vr = sl.eig(A, left=True, right=True)
    kappa = np.linalg.norm(vl, axis=0) * np.linalg.norm(vr, axis=0) / np.abs(np.sum(vl.conj() * vr, axis=0))
    norm = float(np.linalg.norm(A, 2))
    E = A.shape[0] * EPS * norm + backward
    return lam, 2.0 * np.minimum(kappa * E, np.sqrt(E * norm))


def bound_of(lam_computed, lam, bounds):
    """The bound of the eigenvalue of ``lam`` nearest each of ``lam_computed`` (another call's values)."""
    lam_computed = np.atleast_1d(lam_computed)
    return bounds[np.argmin(np.abs(lam_computed[:, None] - lam[None, :]), axis=1)]


def sqrt_bounds(ev, bounds):
    """Bounds on +-sqrt(ev) from bounds on ev: |sqrt(z + d) - sqrt(z)| = |d| / |sqrt(z + d) + sqrt(z)|
    <= min(sqrt(2 |d|), |d| / sqrt|z|) (principal branches, both in the right half-plane)."""
    ev = np.abs(ev)
    with np.errstate(divide="ignore"):
        return np.minimum(np.sqrt(2 * bounds), np.where(ev > 0, bounds / np.sqrt(ev), np.inf))
