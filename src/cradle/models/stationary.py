"""The stationary DpS equation (dpsstn) and its area-preserving map G (comp1)-(comp2).

With ``g(s) = s |s|^(alpha-1)`` the renormalised stationary DpS equation reads

    -sign(mu) a_n = g(a_{n+1} - a_n) - g(a_n - a_{n-1})                    (dpsstn)

The auxiliary variable ``b_n = g(a_n - a_{n-1})`` (homeo) turns it, for
``mu = 1``, into the two-dimensional recurrence

    a_{n+1} = a_n + b_{n+1} |b_{n+1}|^(1/alpha - 1)                        (comp1)
    b_{n+2} = b_{n+1} - a_{n+1}                                             (comp2)

i.e. the map ``U_{n+1} = G(U_n)`` with ``U_n = (a_n, b_{n+1})``. G is
area-preserving (det DG = 1 away from b = 0), odd (G(-U) = -G(U)) and
reversible with respect to ``R(a, b) = (a, -a - b)``: ``R G^{-1} = G R``.
Its orbits are figures traj3 and traj2 of the paper.

Everything here is pure numpy and vectorised over leading axes: a point U
is an array of shape ``(..., 2)`` holding ``(a, b)`` in its last axis. One step
of the map (:func:`G`, :func:`G_inverse`, :func:`jacobian`) trusts its caller
(alpha > 1: loops call it); orbits and the residual check alpha (``@checked``).
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cradle.models.dps import p_laplacian
from cradle.specs.checked import checked


def g(s: ArrayLike, alpha: float) -> NDArray[np.float64]:
    """The nonlinearity ``g(s) = s |s|^(alpha-1) = sign(s) |s|^alpha`` of (dpsstn), (homeo)."""
    s = np.asarray(s, dtype=float)
    return np.sign(s) * np.abs(s) ** alpha


def g_inverse(b: ArrayLike, alpha: float) -> NDArray[np.float64]:
    """Inverse of :func:`g`: ``b |b|^(1/alpha - 1) = sign(b) |b|^(1/alpha)``, as in (comp1).

    Written with ``sign`` so that it is finite (= 0) at ``b = 0``.
    """
    b = np.asarray(b, dtype=float)
    return np.sign(b) * np.abs(b) ** (1.0 / alpha)


def _split(U: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    U = np.asarray(U, dtype=float)
    if U.shape[-1:] != (2,):
        raise ValueError(f"U must have shape (..., 2), got {U.shape}")
    return U[..., 0], U[..., 1]


def G(U: ArrayLike, alpha: float) -> NDArray[np.float64]:
    """One step ``U_n = (a_n, b_{n+1}) -> U_{n+1} = (a_{n+1}, b_{n+2})`` of the map G.

    Parameters
    ----------
    U : array_like, shape (..., 2)
        Points ``(a_n, b_{n+1})``.
    alpha : float
        Hertz exponent, ``alpha > 1``.

    Returns
    -------
    ndarray, shape (..., 2)
        ``a_{n+1} = a_n + sign(b_{n+1}) |b_{n+1}|^(1/alpha)``        (comp1),
        ``b_{n+2} = b_{n+1} - a_{n+1}``                               (comp2).
    """
    a, b = _split(U)
    a1 = a + g_inverse(b, alpha)
    return np.stack([a1, b - a1], axis=-1)


def G_inverse(U: ArrayLike, alpha: float) -> NDArray[np.float64]:
    """Inverse map ``G^{-1}``: ``(a_{n+1}, b_{n+2}) -> (a_n, b_{n+1})``.

    Solves (comp2) for ``b_{n+1} = b_{n+2} + a_{n+1}``, then (comp1) for
    ``a_n = a_{n+1} - sign(b_{n+1}) |b_{n+1}|^(1/alpha)``.

    Parameters
    ----------
    U : array_like, shape (..., 2)
    alpha : float

    Returns
    -------
    ndarray, shape (..., 2)
    """
    a1, b2 = _split(U)
    b = b2 + a1
    return np.stack([a1 - g_inverse(b, alpha), b], axis=-1)


def jacobian(U: ArrayLike, alpha: float) -> NDArray[np.float64]:
    """Analytic Jacobian matrix DG(U) of (comp1)-(comp2).

    With ``phi(b) = sign(b)|b|^(1/alpha)`` and ``phi'(b) = |b|^(1/alpha - 1) / alpha``,

        DG = [[1, phi'(b)], [-1, 1 - phi'(b)]],   det DG = 1,

    so G is area-preserving on ``b != 0`` (phi' is infinite at ``b = 0``:
    G is not differentiable there, in particular not at the fixed point 0).

    Parameters
    ----------
    U : array_like, shape (..., 2)
    alpha : float

    Returns
    -------
    ndarray, shape (..., 2, 2)
    """
    a, b = _split(U)
    with np.errstate(divide="ignore"):
        dphi = np.abs(b) ** (1.0 / alpha - 1.0) / alpha
    one = np.ones_like(a)
    row0 = np.stack([one, dphi], axis=-1)
    row1 = np.stack([-one, 1.0 - dphi], axis=-1)
    return np.stack([row0, row1], axis=-2)


def reversor(U: ArrayLike) -> NDArray[np.float64]:
    """The reversing symmetry ``R(a, b) = (a, -a - b)`` of G: ``R G^{-1} = G R``.

    R is an involution; it comes from the invariance ``n -> -n`` of (dpsstn):
    ``{U_n}`` is an orbit of G iff ``{R U_{-n}}`` is one.
    """
    a, b = _split(U)
    return np.stack([a, -a - b], axis=-1)


@checked(n_iter="iterations")
def orbits(starts: ArrayLike, n_iter: int, alpha: float, box: float | None = None) -> NDArray[np.float64]:
    """Orbits of G from several starting points at once.

    Parameters
    ----------
    starts : array_like, shape (n_orbits, 2)
        Initial points ``U_0 = (a_0, b_1)``.
    n_iter : int
        Number of iterations; ``n_iter + 1`` points are returned per orbit.
    alpha : float
    box : float, optional
        If given, an orbit is cut at its first point with ``||U||_inf > box``:
        that point and all later ones are NaN (blown-up orbits never overflow).

    Returns
    -------
    ndarray, shape (n_orbits, n_iter + 1, 2)
    """
    n_iter = int(n_iter)
    if n_iter < 0:
        raise ValueError(f"n_iter must be >= 0, got {n_iter}")
    U = np.array(starts, dtype=float).reshape(-1, 2)
    out = np.empty((U.shape[0], n_iter + 1, 2))
    alive = np.ones(U.shape[0], dtype=bool)
    for j in range(n_iter + 1):
        if j:
            U = G(U, alpha)
        if box is not None:
            alive &= np.max(np.abs(U), axis=-1) <= box  # NaN compares False
            U[~alive] = np.nan
        out[:, j] = U
    return out


def orbit(U0: ArrayLike, n_iter: int, alpha: float, box: float | None = None) -> NDArray[np.float64]:
    """The orbit ``U_0, G(U_0), ..., G^{n_iter}(U_0)`` as an array (n_iter+1, 2).

    See :func:`orbits` for ``box``.
    """
    return orbits(np.asarray(U0, dtype=float).reshape(1, 2), n_iter, alpha, box)[0]


def starting_points(starts: ArrayLike | None = None,
                    line: tuple[ArrayLike, ArrayLike, int] | None = None) -> NDArray[np.float64]:
    """Starting points ``(K, 2)`` of the orbits of G: ``starts`` (pairs [a_0, b_1]), then ``line``
    ``(from, to, count)``: ``count`` points equally spaced on the segment from ``from`` to ``to``, both
    ends included. At least one of the two must be given."""
    parts = []
    if starts is not None:
        parts.append(np.asarray(starts, dtype=float).reshape(-1, 2))
    if line is not None:
        p0, p1, count = line
        p0, p1 = np.asarray(p0, dtype=float), np.asarray(p1, dtype=float)
        t = np.linspace(0.0, 1.0, count)[:, None]
        parts.append(p0 + t * (p1 - p0))
    if not parts:
        raise ValueError("orbits of G need starts or a line of starting points")
    return np.concatenate(parts, axis=0)


@checked
def explicit_periodic_orbits(alpha: float) -> dict[str, NDArray[np.float64]]:
    """The explicit period-2, -3 and -4 orbits of G (caption of figure traj2).

    * ``"period2"``: ``a_n = 2^((alpha+1)/(1-alpha)) (-1)^n``
    * ``"period3"``: ``{a_n} = {0, a, -a}``, ``a = (1 + 2^alpha)^(1/(1-alpha))``
    * ``"period4"``: ``{a_n} = {0, -a, 0, a}``, ``a = 2^(1/(1-alpha))``

    The b component follows from (homeo), ``b_n = g(a_n - a_{n-1})``, so
    the returned points are ``U_n = (a_n, b_{n+1})``, n = 0 .. period-1.

    Returns
    -------
    dict
        name -> ndarray of shape (period, 2); also ``"<name>_a"`` -> the
        one-period sequence ``a_n`` itself.
    """
    c2 = 2.0 ** ((alpha + 1.0) / (1.0 - alpha))
    c3 = (1.0 + 2.0**alpha) ** (1.0 / (1.0 - alpha))
    c4 = 2.0 ** (1.0 / (1.0 - alpha))
    seqs = {
        "period2": np.array([c2, -c2]),
        "period3": np.array([0.0, c3, -c3]),
        "period4": np.array([0.0, -c4, 0.0, c4]),
    }
    out = {}
    for name, a in seqs.items():
        b_next = g(np.roll(a, -1) - a, alpha)  # b_{n+1} = g(a_{n+1} - a_n)
        out[name] = np.stack([a, b_next], axis=-1)
        out[name + "_a"] = a
    return out


@checked
def stationary_residual(a: ArrayLike, alpha: float, mu: float = 1.0, bc: str = "periodic") -> NDArray[np.float64]:
    """Residual of the stationary DpS equation (dpsstn).

    ``r_n = g(a_{n+1} - a_n) - g(a_n - a_{n-1}) + sign(mu) a_n``, zero on solutions.

    Parameters
    ----------
    a : array_like, shape (..., N)
        Sites along the last axis.
    alpha : float
    mu : float, nonzero
        Only its sign enters (the equation is renormalised by ``|mu|``).
    bc : {"periodic", "free"}
        ``"periodic"``: ``a_{n+N} = a_n``. ``"free"``: no bond beyond the
        ends, i.e. the g-terms of the missing bonds vanish.

    Returns
    -------
    ndarray, shape (..., N)
    """
    if mu == 0:
        raise ValueError("mu must be nonzero in (dpsstn)")
    return p_laplacian(np.asarray(a, dtype=float), alpha, bc) + np.sign(mu) * a
