"""Read a gearcli results folder back (for analyze and report), refusing bad folders."""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from gearcli.errors import ResultsError

FILES = ("manifest.json", "summary.json", "timeseries.csv")
#: The time series may also be Parquet (`gearcli simulate --format parquet`).
TIMESERIES = ("timeseries.csv", "timeseries.parquet")


@dataclass(frozen=True)
class StoredRun:
    folder: Path
    manifest: dict
    summary: dict
    columns: dict[str, np.ndarray]

    def column(self, name: str) -> np.ndarray:
        return self.columns[name]


def read_run(folder: str | Path) -> StoredRun:
    """Load manifest, summary and time series; every problem is a one-line ResultsError."""
    p = Path(folder)
    if not p.exists():
        raise ResultsError(f"{p}: not found; expected a results folder from gearcli simulate")
    if not p.is_dir():
        raise ResultsError(f"{p}: not a folder; expected a results folder from gearcli simulate")
    series = next((p / f for f in TIMESERIES if (p / f).is_file()), p / TIMESERIES[0])
    missing = [f for f in FILES[:2] + (series.name,) if not (p / f).is_file()]
    if missing:
        raise ResultsError(f"{p}: missing {', '.join(missing)}; expected a folder written by "
                           "gearcli simulate")
    manifest = read_json(p / "manifest.json")
    if not isinstance(manifest, dict) or manifest.get("gearcli_manifest") != 1:
        raise ResultsError(f"{p / 'manifest.json'}: not a gearcli manifest; expected a folder "
                           "written by gearcli simulate")
    summary = read_json(p / "summary.json")
    if not isinstance(summary, dict) or summary.get("status") != "ok" or "rows" not in summary:
        raise ResultsError(f"{p / 'summary.json'}: incomplete summary; expected a finished "
                           "gearcli simulate run")
    if series.suffix == ".parquet":
        columns = read_parquet_columns(series, "t_s", int(summary["rows"]))
    else:
        columns = read_columns(series, "t_s", int(summary["rows"]))
    return StoredRun(p, manifest, summary, columns)


def read_parquet_columns(path: Path, key: str, rows: int) -> dict[str, np.ndarray]:
    """The float64 columns of a Parquet time series, checked like :func:`read_columns`."""
    from gearcli.io.tables import parquet_to_columns

    try:
        columns = parquet_to_columns(path)
    except Exception as exc:  # pyarrow's errors: ArrowInvalid, OSError, ...
        raise ResultsError(f"{path}: unreadable Parquet ({exc}); expected a table written by "
                           "gearcli") from None
    if key not in columns:
        raise ResultsError(f"{path}: no {key} column; expected a table written by gearcli")
    if any(c.shape != (rows,) or not np.all(np.isfinite(c)) for c in columns.values()):
        raise ResultsError(f"{path}: not {rows} finite rows per column, as summary.json says; "
                           "the file is truncated or was edited")
    return columns


def read_json(path: Path, remedy: str = "expected gearcli output"):
    """A JSON file of a results folder; unreadable -> ResultsError saying ``remedy``."""
    try:
        return json.loads(path.read_text())
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise ResultsError(f"{path}: unreadable JSON ({exc}); {remedy}") from None


def read_columns(path: Path, key: str, rows: int | None = None) -> dict[str, np.ndarray]:
    """A CSV table written by gearcli (header of names, finite numbers) as named columns.

    ``key`` must be one of the columns; ``rows``, when given, is the expected row count (a
    shorter file was truncated).
    """
    try:
        text = path.read_text()
    except (OSError, UnicodeDecodeError) as exc:
        raise ResultsError(f"{path}: unreadable ({exc})") from None
    lines = text.splitlines()
    if not lines:
        raise ResultsError(f"{path}: empty; expected a table written by gearcli")
    names = lines[0].split(",")
    if key not in names:
        raise ResultsError(f"{path}: no {key} column; expected a table written by gearcli")
    if rows is not None and (len(lines) - 1 != rows or not text.endswith("\n")):
        raise ResultsError(f"{path}: {len(lines) - 1} rows, summary.json says {rows}; the file "
                           "is truncated or was edited")
    try:
        data = np.loadtxt(lines[1:], delimiter=",", ndmin=2)
    except ValueError as exc:
        raise ResultsError(f"{path}: malformed row ({exc}); expected numbers") from None
    if data.shape[1] != len(names) or not np.all(np.isfinite(data)):
        raise ResultsError(f"{path}: malformed rows (wrong column count or non-finite values)")
    return {n: data[:, i] for i, n in enumerate(names)}
