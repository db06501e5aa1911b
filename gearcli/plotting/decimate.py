"""Decimation of long time series for drawing, keeping every extremum a pixel column shows.

A line drawn through N samples into a plot W pixels wide (N >> W) shows, in each pixel column,
a vertical stroke from the column's smallest to its largest value joined to its neighbours
through the first and last samples of the column. Keeping only those four samples per column
(first, min, max, last, in time order) draws the same picture with at most 4·W points: the
"M4" aggregation of Jugel et al., "M4: a visualization-oriented time series data aggregation",
Proc. VLDB Endowment 7(10), 2014, pp. 797-808. Unlike a stride (every k-th sample) it never
drops a peak, which is what the report's force and DTE figures are read for (their true extrema:
docs/theory.md section 7.4).

Pure numpy, no matplotlib: the figures of gearcli/plotting call it before ``ax.plot``.
"""

from __future__ import annotations

import numpy as np

__all__ = ["DRAW_COLUMNS", "minmax_decimate"]

#: Columns the time-series figures decimate to: more than the pixel width of their axes (a
#: 10 in wide figure saved at 110 dpi, gearcli/report/figures.PNG_DPI, is 1100 px wide).
DRAW_COLUMNS = 1200


def minmax_decimate(t, y, n_columns: int = DRAW_COLUMNS) -> tuple[np.ndarray, np.ndarray]:
    """The polyline (t, y) reduced to the first, smallest, largest and last sample of each of
    ``n_columns`` equal spans of time between t[0] and t[-1], in time order.

    Parameters
    ----------
    t : sample times, non-decreasing (any unit; the output keeps it)
    y : values at ``t`` (same length); the extrema are those of the numbers, and one NaN of
        each column holding any is kept, so that a gap stays a gap
    n_columns : pixel columns of the drawing (>= 1)

    Returns
    -------
    (t, y) subsets of the inputs (copies), at most 4·n_columns samples (5 in columns with a
    NaN), containing every column's minimum and maximum, hence the global minimum and
    maximum. Inputs with no more than 4·n_columns samples, or a zero time span, are returned
    whole.
    """
    t = np.asarray(t, float)
    y = np.asarray(y, float)
    if t.shape != y.shape or t.ndim != 1:
        raise ValueError(f"t and y must be 1-D arrays of one length; got {t.shape}, {y.shape}")
    if n_columns < 1:
        raise ValueError(f"n_columns must be >= 1; got {n_columns}")
    span = t[-1] - t[0] if t.size else 0.0
    if t.size <= 4 * n_columns or not span > 0:
        return t.copy(), y.copy()
    column = np.minimum(((t - t[0]) * (n_columns / span)).astype(np.int64), n_columns - 1)
    # t is sorted, so every column is one contiguous run of samples: its first and last index
    starts = np.flatnonzero(np.diff(column, prepend=-1))
    ends = np.append(starts[1:], t.size) - 1
    # per column, the indices of the min and max: sort by (column, NaN, value), so that in each
    # column the values come first in ascending order and its NaN samples after them
    number = ~np.isnan(y)
    order = np.lexsort((np.where(number, y, 0.0), ~number, column))
    n_numbers = np.add.reduceat(number.astype(np.int64), starts)
    i_min = order[starts]
    i_max = order[starts + np.maximum(n_numbers, 1) - 1]
    # one NaN of each column that has any, so that a gap in the data stays a gap in the line
    gap = n_numbers < ends - starts + 1
    i_nan = order[(starts + n_numbers)[gap]]
    keep = np.unique(np.concatenate((starts, ends, i_min, i_max, i_nan)))
    return t[keep], y[keep]
