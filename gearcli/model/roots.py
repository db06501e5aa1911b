"""A scalar root in a sign-changing bracket, without importing ``scipy.optimize``.

``scipy.optimize`` takes ~0.5 s to import (it pulls in linprog, linalg, sparse and special);
the geometry of every case needs one or two bracketed roots (the undercut crossing of
:mod:`gearcli.model.profile`, the 30° tangent of :mod:`gearcli.model.rating`), and
``gearcli geometry`` itself takes about that long. :func:`brent_root` is Brent's method with
the step rules and the arithmetic, operation for operation, of SciPy's ``brentq``, so it
returns the same float after the same function evaluations (tests/unit/test_roots.py
compares the two on a family of functions and brackets).

References
----------
R. P. Brent, *Algorithms for Minimization without Derivatives*, Prentice-Hall 1973, ch. 4
(procedure *zero*: bisection safeguarding secant and inverse quadratic interpolation steps;
convergence when half the bracket is below the tolerance 2δ = xtol + rtol·|b|).
SciPy ``scipy.optimize.brentq`` (C. Harris's implementation of Brent's method): the form of
the interpolation and extrapolation steps and of the acceptance test reproduced here.
"""

from __future__ import annotations

import math
from collections.abc import Callable

__all__ = ["brent_root", "RTOL_MIN"]

#: Smallest relative tolerance: 4 machine epsilons (as SciPy's brentq).
RTOL_MIN = 4.0 * 2.220446049250313e-16


def brent_root(f: Callable[[float], float], a: float, b: float, xtol: float = 2e-12,
               rtol: float = RTOL_MIN, maxiter: int = 100) -> float:
    """Root of ``f`` in [a, b] (f(a), f(b) of opposite signs) by Brent's method.

    Parameters
    ----------
    f : the function, called with floats, returning a float
    a, b : the bracket
    xtol, rtol : convergence when half the bracket |b_blk − b| / 2 < (xtol + rtol |b|) / 2,
        the best point b then within xtol + rtol |b| of the root (Brent 1973, ch. 4)
    maxiter : iterations before giving up

    Raises
    ------
    ValueError : f(a) and f(b) have the same sign, or a tolerance is out of range
    RuntimeError : no convergence in ``maxiter`` iterations
    """
    if xtol <= 0.0 or rtol < RTOL_MIN:
        raise ValueError(f"brent_root: need xtol > 0 and rtol >= {RTOL_MIN:g}")
    x_pre, x_cur = float(a), float(b)
    f_pre, f_cur = float(f(x_pre)), float(f(x_cur))
    if f_pre == 0.0:
        return x_pre
    if f_cur == 0.0:
        return x_cur
    if math.copysign(1.0, f_pre) == math.copysign(1.0, f_cur):
        raise ValueError("brent_root: f(a) and f(b) must have different signs")
    x_blk = f_blk = s_pre = s_cur = 0.0
    for _ in range(maxiter):
        if f_pre != 0.0 and f_cur != 0.0 and \
                math.copysign(1.0, f_pre) != math.copysign(1.0, f_cur):
            x_blk, f_blk = x_pre, f_pre  # the root lies between x_cur and x_blk
            s_pre = s_cur = x_cur - x_pre
        if abs(f_blk) < abs(f_cur):  # x_cur: the better end
            x_pre, x_cur, x_blk = x_cur, x_blk, x_cur
            f_pre, f_cur, f_blk = f_cur, f_blk, f_cur
        delta = (xtol + rtol * abs(x_cur)) / 2.0
        s_bis = (x_blk - x_cur) / 2.0
        if f_cur == 0.0 or abs(s_bis) < delta:
            return x_cur
        step = s_bis  # bisection unless an interpolation step is short enough
        if abs(s_pre) > delta and abs(f_cur) < abs(f_pre):
            if x_pre == x_blk:  # secant
                s_try = -f_cur * (x_cur - x_pre) / (f_cur - f_pre)
            else:  # inverse quadratic interpolation through the three points
                d_pre = (f_pre - f_cur) / (x_pre - x_cur)
                d_blk = (f_blk - f_cur) / (x_blk - x_cur)
                s_try = -f_cur * (f_blk * d_blk - f_pre * d_pre) \
                    / (d_blk * d_pre * (f_blk - f_pre))
            bound = 3.0 * abs(s_bis) - delta
            if abs(s_pre) < bound:  # min(|s_pre|, bound), NaN-safe as in C
                bound = abs(s_pre)
            if 2.0 * abs(s_try) < bound:
                s_pre, step = s_cur, s_try
            else:
                s_pre = s_bis
        else:
            s_pre = s_bis
        s_cur = step
        x_pre, f_pre = x_cur, f_cur
        x_cur += s_cur if abs(s_cur) > delta else (delta if s_bis > 0.0 else -delta)
        f_cur = float(f(x_cur))
    raise RuntimeError(f"brent_root: no convergence in {maxiter} iterations")
