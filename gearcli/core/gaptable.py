"""Cubic Hermite lookup of the tabulated flank-gap functions G(x).

The caller tabulates each gap function (value and slope) on one uniform grid of roll positions
``x_lo + i h``, ``i = 0 .. n-1``, ``h = (x_hi - x_lo)/(n - 1)`` [mm]. Between grid points the
gap is the cubic Hermite interpolant, and the slope returned is the derivative OF THAT
INTERPOLANT, so contact forces are exact gradients of the contact potential (energy
consistent; docs/theory.md §3).

References
----------
Fritsch & Carlson, "Monotone piecewise cubic interpolation", SIAM J. Numer. Anal. 17 (1980),
for the Hermite basis h00, h10, h01, h11; any numerical-analysis text (e.g. Burden & Faires,
§3.4) gives the same.
"""

import math

import numpy as np

from gearcli.core.layout import TABLE_GAP, TABLE_SLOPE
from gearcli.core.nrt import jit_noalloc, jit_noalloc_inline


@jit_noalloc
def hermite(tables, k, x_lo, x_hi, h, inv_h, x):
    """Gap value [mm] and slope [mm/mm] of table ``k`` at roll position ``x`` [mm].

    Parameters
    ----------
    tables : ndarray, shape (N_TABLES, 2, n)
        ``tables[k, TABLE_GAP, i]`` gap value [mm], ``tables[k, TABLE_SLOPE, i]`` slope dG/dx
        [-] (layout.py) at the grid
        point ``x_lo + i (x_hi - x_lo)/(n - 1)``; ``n >= 2``.
    k : int
        Table index.
    x_lo, x_hi : float
        Grid ends [mm].
    h, inv_h : float
        Grid spacing ``(x_hi - x_lo) / (n - 1)`` [mm] and its inverse [1/mm].
    x : float
        Roll position [mm].

    Returns
    -------
    inside : bool
        Whether ``x_lo <= x <= x_hi`` (outside: the slot is not in contact; value 0).
    value : float
        ``G(x) = h00 y0 + h10 h m0 + h01 y1 + h11 h m1`` [mm].
    slope : float
        ``dG/dx`` of the same cubic [-].
    """
    if not (x >= x_lo and x <= x_hi):
        return False, 0.0, 0.0
    n = tables.shape[2]
    q = (x - x_lo) * inv_h
    i = int(q)
    if i > n - 2:
        i = n - 2
    t = q - i
    y0 = tables[k, TABLE_GAP, i]
    y1 = tables[k, TABLE_GAP, i + 1]
    m0 = tables[k, TABLE_SLOPE, i] * h
    m1 = tables[k, TABLE_SLOPE, i + 1] * h
    t2 = t * t
    t3 = t2 * t
    value = (2.0 * t3 - 3.0 * t2 + 1.0) * y0 + (t3 - 2.0 * t2 + t) * m0 \
        + (3.0 * t2 - 2.0 * t3) * y1 + (t3 - t2) * m1
    slope = ((6.0 * t2 - 6.0 * t) * (y0 - y1) + (3.0 * t2 - 4.0 * t + 1.0) * m0
             + (3.0 * t2 - 2.0 * t) * m1) * inv_h
    return True, value, slope


def table_floors(tables, h) -> np.ndarray:
    """Lower bound [mm] of the Hermite interpolant of every table over its whole grid (set-up,
    plain numpy; one entry per table of ``tables``).

    On each interval ``G = y0 h00 + y1 h01 + h (m0 h10 + m1 h11)`` (slopes m [-], spacing
    ``h`` [mm]) with ``h00 + h01 = 1``, ``h00, h01 >= 0`` and ``|h10|, |h11| <= 4/27`` on
    [0, 1], so ``G >= min(y0, y1) - 4/27 h (|m0| + |m1|)``.
    """
    gap = tables[:, TABLE_GAP]
    slope = np.abs(tables[:, TABLE_SLOPE])
    lows = np.minimum(gap[:, :-1], gap[:, 1:]) - 4.0 / 27.0 * h * (slope[:, :-1] + slope[:, 1:])
    return lows.min(axis=1) if lows.shape[1] else np.full(tables.shape[0], math.inf)


@jit_noalloc
def hermite_many(tables, k, x_lo, x_hi, x, value, slope):
    """:func:`hermite` of table ``k`` at every position of ``x`` [mm] into ``value`` [mm] and
    ``slope`` [-] (NaN outside ``[x_lo, x_hi]``): the kernel's interpolant for set-up and
    quasi-static code (model/ltca.py), one implementation."""
    n = tables.shape[2]
    h = (x_hi - x_lo) / (n - 1)
    inv_h = 1.0 / h
    for i in range(x.shape[0]):
        inside, v, s = hermite(tables, k, x_lo, x_hi, h, inv_h, x[i])
        value[i] = v if inside else math.nan
        slope[i] = s if inside else math.nan


@jit_noalloc_inline
def linear(table, g, i, x_lo, inv_h, x):
    """Linear interpolation of row ``table[g, i]`` at ``x`` [mm] and its slope (the stiffness
    factors of a tooth, docs/theory.md §4b.2): ``f_m + t (f_m+1 - f_m)`` and
    ``(f_m+1 - f_m) / h``, ``m = floor((x - x_lo)/h)`` (clamped to the last interval),
    ``t = (x - x_lo)/h - m``, for ``x_lo <= x <= x_lo + (n - 1) h`` (``inv_h = 1/h``
    [1/mm], ``n = table.shape[2] >= 2``). The slope is the derivative of the interpolant
    itself (piecewise constant), so forces derived from it are exact gradients of the
    interpolated potential."""
    q = (x - x_lo) * inv_h
    m = int(q)
    if m > table.shape[2] - 2:
        m = table.shape[2] - 2
    a = table[g, i, m]
    b = table[g, i, m + 1]
    return a + (q - m) * (b - a), (b - a) * inv_h
