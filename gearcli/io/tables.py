"""Column tables to CSV (header with units in the names)."""

from __future__ import annotations

import io

import numpy as np


def columns_to_csv(columns: dict[str, np.ndarray]) -> str:
    """CSV text of equal-length columns; floats with 10 significant digits."""
    names = list(columns)
    data = np.column_stack([np.asarray(columns[n], dtype=float) for n in names])
    buf = io.StringIO()
    buf.write(",".join(names) + "\n")
    np.savetxt(buf, data, delimiter=",", fmt="%.10g")
    return buf.getvalue()
