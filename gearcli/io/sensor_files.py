"""The sensors table of a results folder (sensors.csv / sensors.parquet, written by
pipeline/outputs.write_sensors) and WAV audio files (docs/theory.md, "What a sensor sees")."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from gearcli.errors import OutputError, ResultsError

SENSOR_TABLES = ("sensors.csv", "sensors.parquet")


def read_sensors(folder: str | Path) -> dict[str, np.ndarray]:
    """The sensors table's columns (``t_s`` and the channels); a one-line ResultsError when the
    folder has none (the case had no ``sensors:`` section)."""
    from gearcli.io.results import read_columns
    from gearcli.io.tables import parquet_to_columns

    p = Path(folder)
    path = next((p / f for f in SENSOR_TABLES if (p / f).is_file()), None)
    if path is None:
        raise ResultsError(f"{p}: no sensors table (sensors.csv or sensors.parquet); expected a "
                           "run of a case with a 'sensors:' section")
    if path.suffix == ".csv":
        return read_columns(path, "t_s")
    try:
        columns = parquet_to_columns(path)
    except Exception as exc:  # pyarrow's errors
        raise ResultsError(f"{path}: unreadable Parquet ({exc})") from None
    if "t_s" not in columns:
        raise ResultsError(f"{path}: no t_s column; expected a table written by gearcli")
    return columns


def write_wav(path: str | Path, rate_Hz: int, samples: np.ndarray) -> Path:
    """A mono 16-bit PCM WAV file (scipy.io.wavfile) of int16 ``samples`` at ``rate_Hz``,
    written atomically through the one writer (io/files.write_atomic)."""
    import io

    from scipy.io import wavfile

    from gearcli.io.files import write_atomic

    target = Path(path)
    if not target.parent.is_dir():
        raise OutputError(f"--wav {target}: folder {target.parent} does not exist")
    buf = io.BytesIO()
    wavfile.write(buf, int(rate_Hz), np.asarray(samples, dtype=np.int16))
    write_atomic(target, buf.getvalue())  # links refused, atomic, checked (io/files.py)
    return target
