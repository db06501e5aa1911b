"""Compiled evaluation of piecewise polynomials of time (drive speed, load torque, ...).

The arrays come from :meth:`gearcli.model.timefunction.PiecewisePolynomial.to_arrays`:
``breaks`` (n,), ``coefs`` (n + 1, degree + 1) with ``coefs[k, p]`` multiplying
``(t - origins[k])**p``, and ``origins`` (n + 1,). Piece ``k`` covers ``[breaks[k-1], breaks[k])``
(piece 0 everything before ``breaks[0]``, piece n everything from ``breaks[n-1]`` on).
"""

import math

from gearcli.core.jit import jit


@jit
def pp_piece(breaks, t):
    """Index of the piece containing ``t`` [s]: the number of breakpoints ``<= t``.

    Binary search, O(log n). A NaN ``t`` gives piece 0 (and a NaN value).
    """
    lo = 0
    hi = breaks.shape[0]
    while lo < hi:
        mid = (lo + hi) // 2
        if breaks[mid] <= t:
            lo = mid + 1
        else:
            hi = mid
    return lo


@jit
def top_degree(coefs, k):
    """Degree of piece ``k``: its highest nonzero coefficient (0 for a zero piece). Horner
    from there gives the same value as from the table's top degree (the skipped terms are
    exact zeros) without their multiply-add latency (a constant speed is a degree-0 piece of a
    quintic ramp table)."""
    p = coefs.shape[1] - 1
    while p > 0 and coefs[k, p] == 0.0:
        p -= 1
    return p


@jit
def pp_eval(breaks, coefs, origins, t):
    """Value of the piecewise polynomial at ``t`` [s] (Horner in the local variable).

    Parameters
    ----------
    breaks : ndarray of float64, shape (n,)
        Breakpoints [s], strictly increasing.
    coefs : ndarray of float64, shape (n + 1, degree + 1)
        Local coefficients, ``coefs[k, p]`` multiplies ``(t - origins[k])**p``.
    origins : ndarray of float64, shape (n + 1,)
        Local origin of each piece [s].
    t : float
        Time [s].

    Returns
    -------
    float
        f(t), in the unit of the coefficients.
    """
    k = pp_piece(breaks, t)
    s = t - origins[k]
    p = top_degree(coefs, k)
    value = coefs[k, p]
    for q in range(p - 1, -1, -1):
        value = value * s + coefs[k, q]
    return value if s == s else math.nan


@jit
def pp_eval_d(breaks, coefs, origins, t):
    """Value and first derivative at ``t`` [s] in one pass (Horner for p and p').

    Parameters are those of :func:`pp_eval`.

    Returns
    -------
    value : float
        f(t).
    slope : float
        df/dt at ``t`` [unit/s]; the right-hand derivative at a breakpoint.
    """
    k = pp_piece(breaks, t)
    s = t - origins[k]
    p = top_degree(coefs, k)
    value = coefs[k, p]
    slope = 0.0
    for q in range(p - 1, -1, -1):
        slope = slope * s + value
        value = value * s + coefs[k, q]
    if s != s:
        return math.nan, math.nan
    return value, slope
