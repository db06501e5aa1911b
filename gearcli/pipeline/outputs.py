"""Write a simulation's results folder: the time series (timeseries.csv, or
timeseries.parquet), summary.json, manifest.json."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from gearcli.errors import OutputError
from gearcli.io.files import write_atomic
from gearcli.io.manifest import RESULTS_SCHEMA_VERSION, manifest
from gearcli.io.outdir import atomic_dir
from gearcli.results import SummaryDocument

#: Formats of the time series: CSV (10 significant digits, the default; any tool reads it)
#: and Parquet (full float64 precision, compressed: for long runs and sweeps).
TIMESERIES_FORMATS = ("csv", "parquet")
#: The dense-output samples around the force maximum and at the end of the run.
ZOOM_FILE = "zoom.csv"


def summary_document(res) -> SummaryDocument:
    """summary.json of a run (its JSON: ``.to_dict()``)."""
    from gearcli.pipeline.digest import input_digest

    k = res.kernel
    return SummaryDocument(
        schema_version=RESULTS_SCHEMA_VERSION,
        case=res.name,
        status=res.status,
        invalid_reason=res.invalid_reason if res.status != "ok" else None,
        solver={
            "message": k.message,
            **k.counters,
            "wall_time_s": res.wall_time_s,
            "wall_time_includes_compilation": res.compiled,
            "engagement": res.loaded.case.contact.engagement,
            "drive": res.loaded.case.drive.type,
        },
        rows=int(k.series.shape[0]),
        slots=int(k.slot_force.shape[1]),
        warnings=tuple(res.warnings),
        scalars=res.summary,
        input_digest=input_digest(res),
    )


def timeseries_csv(res) -> str:
    """The time series as CSV text: header of column names with units, numbers as ``%.10g``
    (compiled, gearcli.core.csvtext: the text numpy.savetxt wrote, ~4x faster)."""
    from gearcli.core.csvtext import csv_text

    columns = res.columns()
    return csv_text(list(columns), np.column_stack(list(columns.values())))


def write_timeseries(res, folder: Path, fmt: str = "csv") -> Path:
    """``folder``/timeseries.<fmt>; returns its path."""
    if fmt not in TIMESERIES_FORMATS:
        raise OutputError(f"time-series format {fmt!r}: expected one of "
                          f"{', '.join(TIMESERIES_FORMATS)}")
    path = folder / f"timeseries.{fmt}"
    if fmt == "csv":
        write_atomic(path, timeseries_csv(res))
    else:
        from gearcli.io.tables import columns_to_parquet

        columns_to_parquet(res.columns(), path)
    return path


def write_simulation(res, target: str | Path, force: bool,
                     overrides: list[str] | None = None, fmt: str = "csv") -> Path:
    """Write the three files atomically into ``target`` (see io.outdir); the time series as
    ``fmt`` (:data:`TIMESERIES_FORMATS`)."""
    with atomic_dir(target, force) as tmp:
        write_simulation_files(res, tmp, overrides, fmt)
    return Path(target)


def write_simulation_files(res, folder: Path,
                           overrides: list[str] | None = None, fmt: str = "csv") -> None:
    """The time series, summary.json and manifest.json into an existing (temporary) folder."""
    case_json = json.loads(res.loaded.case.model_dump_json())
    write_timeseries(res, folder, fmt)
    if res.zoom:  # the dense output for the figures' zooms (pipeline/simulate.dense_zoom)
        from gearcli.io.tables import columns_to_csv

        write_atomic(folder / ZOOM_FILE, columns_to_csv(res.zoom))
    if res.loaded.case.sensors is not None:
        write_sensors(res, folder, fmt)
    summary = summary_document(res).to_dict()
    write_atomic(folder / "summary.json", json.dumps(summary, indent=2) + "\n")
    doc = manifest(res.loaded.source, case_json, overrides)
    write_atomic(folder / "manifest.json", json.dumps(doc, indent=2) + "\n")


def write_sensors(res, folder: Path, fmt: str = "csv") -> Path:
    """``folder``/sensors.<fmt> (pipeline/sensors.py: what a rig would record) and
    sensors.json (its channels, units, sources and noise); returns the table's path."""
    from gearcli.pipeline.sensors import sensor_table

    columns, doc = sensor_table(res)
    path = folder / f"sensors.{fmt}"
    if fmt == "csv":
        from gearcli.io.tables import columns_to_csv

        write_atomic(path, columns_to_csv(columns))
    else:
        from gearcli.io.tables import columns_to_parquet

        columns_to_parquet(columns, path)
    write_atomic(folder / "sensors.json", json.dumps(doc.to_dict(), indent=2) + "\n")
    return path
