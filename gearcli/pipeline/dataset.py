"""A labelled fault dataset: `gearcli sweep` of a study file with ``dataset:`` (docs/theory.md,
"Fault datasets").

A study file with a top-level ``dataset: {signal: ...}`` (any design but speed_curve; typically
a grid crossing ``faults`` — whole fault lists as values — with speed, load and
``sensors.noise.seed``) is run on the sweep's machinery (serial, worker processes or Dask:
pipeline/sweep/run.run_study, called by api.sweep) keeping every point's results folder with its
time series and sensors table as Parquet (``points/NNNNN/``). Then one
labels table (``labels.csv`` and ``labels.parquet``) gets a row per point: where its signals
are, its labels read from its resolved case (fault kind, gear, tooth, size; pinion speed, load,
noise seed and SNR) and the condition-monitoring metrics of its TSA per shaft (`gearcli
monitor` of the sensors' ``signal``), so a detector can be trained on the signals and checked
against the classical metrics.
"""

from __future__ import annotations

import math
from pathlib import Path

from gearcli.errors import GearcliError

LABELS = "labels"
#: The fault-size key of each kind (the quantity a size sweep varies) [mm]; a missing tooth
#: has size 1 (a whole tooth).
SIZE_KEY = {"root_crack": "depth", "spall": "length", "chipped_tip": "height"}
#: Monitoring metrics put in the labels table, per shaft.
LABEL_METRICS = ("rms", "kurtosis", "fm4", "na4", "m6a", "energy_ratio", "sideband_index")


def point_labels(case) -> dict:
    """The labels of one point from its resolved case (internal units -> the columns' units):
    fault kind ("healthy" without faults; several joined by "+"), gear, tooth, size [mm] and
    width share of the first fault; pinion speed [rpm] and load torque [N·m] where the run
    ends; the noise seed and SNR [dB] (NaN without sensors or SNR)."""
    faults = [f for f in case.faults if _size(f) != 0.0]
    first = faults[0] if faults else None
    t_end = case.run.end_time
    speed = case.drive.speed.pp(t_end) if case.drive.speed is not None else math.nan
    noise = case.sensors.noise if case.sensors is not None else None
    return {
        "fault_kind": "+".join(f.kind for f in faults) or "healthy",
        "fault_gear": first.gear if first else "",
        "fault_tooth": first.tooth if first else -1,
        "fault_size_mm": _size(first) if first else 0.0,
        "fault_width": getattr(first, "width", 1.0) if first else 0.0,
        "pinion_speed_rpm": float(speed) * 30.0 / math.pi,
        "load_torque_Nm": float(case.load.torque.pp(t_end)) / 1000.0,
        "noise_seed": noise.seed if noise is not None else -1,
        "snr_db": noise.snr_db if noise is not None and noise.snr_db is not None else math.nan,
    }


def _size(fault) -> float:
    """The fault's size [mm] (:data:`SIZE_KEY`; 1 for a missing tooth), 0 when it has none
    (zero size or zero width: the healthy tooth, docs/theory.md "Tooth faults")."""
    if fault.kind == "missing_tooth":
        return 1.0
    if not getattr(fault, "width", 1.0) or getattr(fault, "depth", 1.0) == 0.0:
        return 0.0
    return float(getattr(fault, SIZE_KEY[fault.kind]))


def point_metrics(folder: Path, signal: str) -> dict:
    """The monitoring metrics of a point's results folder, ``<shaft>_<metric>`` (NaN where the
    run has no such signal or too short a window)."""
    from gearcli.pipeline.monitor import monitor

    out = {f"{s}_{m}": math.nan for s in ("pinion", "gear") for m in LABEL_METRICS}
    try:
        doc = monitor(folder, signal=signal)
    except GearcliError:
        return out
    for s in doc.shafts:
        for m in LABEL_METRICS:
            v = s.value(m)
            out[f"{s.shaft}_{m}"] = math.nan if v is None else float(v)
    return out


def labels_table(out: Path, rows: list[dict], signal: str) -> list[dict]:
    """One label row per sweep row: point, status, the point's folder (relative to ``out``),
    :func:`point_labels` and :func:`point_metrics` (ok points only)."""
    from gearcli.case.load import load_case

    table = []
    for row in rows:
        i = int(row["point"])
        folder = out / "points" / f"{i:05d}"
        rec = {"point": i, "status": row["status"], "folder": f"points/{i:05d}"}
        case_file = Path(f"{folder}.case.yaml")
        if case_file.is_file():
            rec.update(point_labels(load_case(case_file).case))
        if row["status"] == "ok" and folder.is_dir():
            rec.update(point_metrics(folder, signal))
        table.append(rec)
    return table


def write_labels(out: Path, table: list[dict]) -> tuple[Path, Path]:
    """labels.csv and labels.parquet in ``out`` (all rows, the union of their columns)."""
    import io

    import pandas as pd

    from gearcli.io.files import write_atomic

    frame = pd.DataFrame(table)
    csv_path, parquet_path = out / f"{LABELS}.csv", out / f"{LABELS}.parquet"
    write_atomic(csv_path, frame.to_csv(index=False))
    buf = io.BytesIO()
    frame.to_parquet(buf, index=False)
    write_atomic(parquet_path, buf.getvalue())
    return csv_path, parquet_path


def write_dataset(out: Path, rows: list[dict], signal: str) -> list[dict]:
    """The labels table of a dataset study's finished sweep (its summary rows, every point's
    folder kept with Parquet signals) in ``out``: labels.csv and labels.parquet; returns its
    rows."""
    table = labels_table(Path(out), rows, signal)
    write_labels(Path(out), table)
    return table
