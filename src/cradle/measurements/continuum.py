"""Distances of computed profiles to the Gaussians of the continuum limit alpha -> 1+, and the fitted power.

:mod:`cradle.models.continuum` derives the limits; here: the distance in the max norm after the stated
rescaling (:func:`sup_distance`), and the power of eps = alpha - 1 at which it vanishes (:func:`fit_power`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray


def sup_distance(profile: ArrayLike, gaussian: ArrayLike) -> float:
    """max_n |profile_n / max profile - gaussian_n / max gaussian|: both scaled to unit maximum on the same grid."""
    p = np.asarray(profile, dtype=float)
    G = np.asarray(gaussian, dtype=float)
    return float(np.max(np.abs(p / np.max(p) - G / np.max(G))))


def complex_distance(profile: ArrayLike, model: ArrayLike) -> float:
    """max_n |profile_n e^{-i phi0} / max|profile| - model_n / max|model||, the global phase phi0 = arg sum_n
    conj(model_n) profile_n (the least-squares one): the distance of a complex envelope to a model's, phase
    gradient included; for real, positive profiles it is :func:`sup_distance`."""
    p = np.asarray(profile, dtype=complex)
    m = np.asarray(model, dtype=complex)
    phase = np.exp(-1j * np.angle(np.sum(np.conj(m) * p)))
    return float(np.max(np.abs(p * phase / np.max(np.abs(p)) - m / np.max(np.abs(m)))))


@dataclass(frozen=True)
class PowerFit:
    """ln D = power ln eps + ln K + k eps^q (q = 1 unless :func:`fit_power` is told otherwise), fitted by least
    squares: the power, its standard error, the spread of the power when the smallest or the largest eps is left
    out, the constant K, the first correction k, and the points used."""

    power: float
    stderr: float
    spread: float
    K: float
    k: float
    points: int

    @property
    def uncertainty(self) -> float:
        """The larger of the standard error and the leave-one-end-out spread."""
        return max(self.stderr, self.spread)


def _lstsq(eps: NDArray[np.float64], D: NDArray[np.float64],
           correction: float = 1.0) -> tuple[NDArray[np.float64], float]:
    A = np.column_stack((np.log(eps), np.ones_like(eps), eps if correction == 1.0 else eps**correction))
    coef, *_ = np.linalg.lstsq(A, np.log(D), rcond=None)
    dof = eps.size - 3
    if dof <= 0:
        return coef, float("nan")
    r = np.log(D) - A @ coef
    cov = np.linalg.inv(A.T @ A) * float(r @ r) / dof
    return coef, float(np.sqrt(cov[0, 0]))


def fit_power(eps: ArrayLike, D: ArrayLike, correction: float = 1.0) -> PowerFit:
    """The power p of D ~ K eps^p (1 + k eps^q) over the given points (at least 4: three parameters and one degree of
    freedom for the standard error), with the first correction, of power q = ``correction`` (1: a correction in
    eps), fitted so that the largest eps do not bias p."""
    e = np.asarray(eps, dtype=float)
    d = np.asarray(D, dtype=float)
    if e.size < 4:
        raise ValueError(f"fit_power needs at least 4 points, got {e.size}")
    order = np.argsort(e)
    e, d = e[order], d[order]
    coef, se = _lstsq(e, d, correction)
    spread = max(abs(float(_lstsq(e[1:], d[1:], correction)[0][0] - coef[0])),
                 abs(float(_lstsq(e[:-1], d[:-1], correction)[0][0] - coef[0])))
    return PowerFit(power=float(coef[0]), stderr=se, spread=spread, K=float(np.exp(coef[1])), k=float(coef[2]),
                    points=int(e.size))
