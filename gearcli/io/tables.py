"""Column tables to CSV (header with units in the names) and to Parquet."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np


def columns_to_csv(columns: dict[str, np.ndarray]) -> str:
    """CSV text of equal-length columns; floats with 10 significant digits."""
    names = list(columns)
    data = np.column_stack([np.asarray(columns[n], dtype=float) for n in names])
    buf = io.StringIO()
    buf.write(",".join(names) + "\n")
    np.savetxt(buf, data, delimiter=",", fmt="%.10g")
    return buf.getvalue()


def columns_to_frame(columns: dict[str, np.ndarray], index: str):
    """Named columns as a pandas DataFrame indexed by the column ``index`` (the API's tables:
    a run's time series by ``t_s``, spectra by ``frequency_Hz``, a mesh table by ``roll_mm``)."""
    import pandas as pd

    rest = dict(columns)
    key = rest.pop(index)
    return pd.DataFrame(rest, index=pd.Index(key, name=index))


def columns_to_parquet(columns: dict[str, np.ndarray], path: str | Path) -> None:
    """Equal-length float64 columns as one Parquet table at ``path`` (pyarrow, imported here:
    only this format needs it). Full float64 precision; zstd-compressed columns; written
    through the one writer (io/files.write_atomic: links refused, atomic, checked)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    from gearcli.io.files import write_atomic

    table = pa.table({n: np.asarray(c, dtype=float) for n, c in columns.items()})
    buf = io.BytesIO()
    pq.write_table(table, buf, compression="zstd")
    write_atomic(path, buf.getvalue())


def parquet_to_columns(path: str | Path) -> dict[str, np.ndarray]:
    """The float64 columns of a Parquet table written by :func:`columns_to_parquet`."""
    import pyarrow.parquet as pq

    table = pq.read_table(path)
    return {n: table.column(n).to_numpy().astype(float, copy=False) for n in table.column_names}
