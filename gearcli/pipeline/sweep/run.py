"""Run a study's points (serial, worker processes or a Dask cluster) into ``DIR/summary.csv``.

- Every point runs in a long-lived worker (the solver compiles / loads its cache once per
  process), gets its metrics, and comes back as one row; a failing point becomes a row with
  status ``failed`` and the error message, never an aborted study.
- Rows are appended as complete lines, flushed and fsync'ed one by one: a killed study loses at
  most the points in flight. Reading ignores a torn last line. Rerunning skips points whose case
  hash already has a row (resume); the final file is rewritten atomically, sorted by point.
- Results do not depend on the executor: a worker gets only the resolved case JSON, and every
  column but the two timing ones is a deterministic function of it.
"""

from __future__ import annotations

import csv
import io
import os
import time
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path

from gearcli import guards
from gearcli.errors import GearcliError, OutputError
from gearcli.io.files import record_outputs, write_atomic
from gearcli.io.owner import check_producer
from gearcli.pipeline.sweep import workers
from gearcli.pipeline.sweep.folder import SUMMARY, claim_folder, study_lock
from gearcli.pipeline.sweep.metrics import METRICS
from gearcli.pipeline.sweep.study import Study
from gearcli.pipeline.sweep.workers import (
    ENVIRONMENT,
    Lost,
    PointTimeout,
    failure_cause,
    lost_point,
    probe_scheduler,  # noqa: F401  (where it was)
)

#: Largest summary.csv read back for resuming [bytes] (~1 kB a row, 100 000 points).
MAX_SUMMARY_BYTES = 200_000_000
#: Columns that differ between runs of the same point (timings): not compared across executors.
TIMING_COLUMNS = ("wall_time_s", "solver_time_s")


def summary_columns(study: Study) -> list[str]:
    """Fixed column order: point, varied parameters (with units), metrics, status, ..."""
    metrics = list(study.metrics or METRICS)
    check_col = ["checks"] if study.checks else []
    return ["point", *study.parameter_columns, *metrics, *check_col, "status", "error",
            "cause", "warnings", *TIMING_COLUMNS, "case_hash"]


def check_timeseries_format(fmt, keep_timeseries: bool) -> None:
    """The kept time series' format: 'csv' or 'parquet', the latter only with them kept."""
    if fmt not in ("csv", "parquet"):
        raise OutputError(f"--format {str(fmt):.40}: expected csv or parquet")
    if fmt != "csv" and not keep_timeseries:
        raise OutputError(f"--format {fmt}: the format of the time series --keep-timeseries "
                          "keeps; expected --keep-timeseries with it (summary.csv is CSV)")


def run_point(payload: dict) -> dict:
    """Simulate one resolved case and measure its metrics; failures become a 'failed' row.

    Runs in a worker: only plain data in and out (picklable, executor-independent).
    """
    t0 = time.perf_counter()
    row: dict = {"point": payload["index"], "case_hash": payload["case_hash"]}
    try:
        from gearcli.case.load import load_case
        from gearcli.pipeline.simulate import run_simulation
        from gearcli.pipeline.sweep.metrics import point_metrics

        keep = payload.get("keep_dir")
        if keep:  # the resolved case beside the results: `gearcli simulate` can rerun it
            case_file = Path(f"{keep}.case.yaml")
            case_file.parent.mkdir(parents=True, exist_ok=True)
            write_atomic(case_file, payload["case_json"] + "\n", case_file.parents[1])
            loaded = load_case(case_file)
        else:
            loaded = case_from_json(payload["case_json"], payload["name"])
        res = run_simulation(loaded, zoom=bool(keep))
        if res.status == "ok":
            row.update(point_metrics(res))
        # an invalid run's numbers are not results: its metric cells stay empty
        row.update(status=res.status, error=res.invalid_reason,
                   warnings="; ".join(res.warnings), solver_time_s=res.wall_time_s)
        if keep:
            from gearcli.pipeline.outputs import write_simulation

            write_simulation(res, keep, True, fmt=payload.get("format", "csv"))
    except GearcliError as exc:
        row.update(status="failed", error=str(exc).splitlines()[0], cause=failure_cause(exc))
    except OSError as exc:  # writing the point's files: a full disk, a quota
        row.update(status="failed", error=f"cannot write the point's results "
                   f"({exc.strerror or exc})", cause=failure_cause(exc))
    except Exception as exc:  # a bug in one point must not end the study
        row.update(status="failed", error=f"internal error: {exc!r}", cause=failure_cause(exc))
    row["wall_time_s"] = time.perf_counter() - t0
    return row


def case_from_json(text: str, name: str):
    """Validate a resolved case given as JSON (json is ~20x faster than PyYAML for this)."""
    import json

    from gearcli.case.load import validate_source
    from gearcli.case.yamlsrc import Source

    return validate_source(Source(name, json.loads(text), text.splitlines()), name)


def execute(fn, payloads: list[dict], jobs: int | None, scheduler: str | None,
            lost: Lost = lost_point, point_timeout: float | None = None) -> Iterator:
    """``fn(payload)`` for every payload, serially, in ``jobs`` local processes, or on Dask
    (``scheduler``: "local" or an address); results in completion order. A payload whose
    worker died or that timed out gives ``lost(payload, reason)`` (pipeline/sweep/workers.py)."""
    jobs = min(jobs or os.cpu_count() or 1, max(len(payloads), 1))
    timeout = PointTimeout(point_timeout)
    if scheduler:
        return workers.dask(payloads, jobs, scheduler, fn, lost, timeout)
    if jobs == 1:
        return workers.serial(payloads, fn)
    return workers.processes(payloads, jobs, fn, lost, timeout)


# --- summary.csv -------------------------------------------------------------------------------
def read_summary(path: Path, columns: list[str]) -> dict[str, dict]:
    """Complete rows of an earlier summary.csv by case hash; a torn last line is ignored."""
    if not path.exists() and not path.is_symlink():
        return {}
    if not path.is_file():
        raise OutputError(f"{path}: exists and is not a file; remove it or choose another "
                          "output folder")
    try:
        raw = guards.read_bounded(path, limit=MAX_SUMMARY_BYTES)
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        raise OutputError(f"{path}: not UTF-8 text; expected the summary.csv of an earlier "
                          "sweep (use --force to start over)") from None
    except (OSError, TimeoutError, guards.InputTooLarge) as exc:
        reason = getattr(exc, "strerror", None) or str(exc)
        raise OutputError(f"{path}: cannot read ({reason}); use --force to start over") from None
    lines = text.splitlines(keepends=True)
    if lines and not lines[-1].endswith("\n"):
        lines = lines[:-1]  # a line cut by a kill: never complete
    if not lines:
        return {}
    header = next(csv.reader([lines[0]]))
    if header == [c for c in columns if c != "cause"]:  # before failures had a cause
        old = [r for r in csv.DictReader(io.StringIO("".join(lines)))
               if None not in r and all(v is not None for v in r.values())]
        lines = [_line(columns, dict(zip(columns, columns, strict=True)))]
        lines += [_line(columns, r) for r in old]
        header = columns
    if header != columns:
        raise OutputError(f"{path}: written by a different study (other columns); use "
                          "--force to start over or another output folder")
    rows = {}
    for rec in csv.DictReader(io.StringIO("".join(lines))):
        if None in rec or any(v is None for v in rec.values()):
            continue  # wrong field count
        if rec["status"] in ("ok", "invalid", "failed") and rec["case_hash"]:
            rows[rec["case_hash"]] = rec
    return rows


def _line(columns: list[str], row: dict) -> str:
    buf = io.StringIO()
    csv.writer(buf, lineterminator="\n").writerow([_cell(row.get(c)) for c in columns])
    return buf.getvalue()


def _cell(value) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return repr(value)
    return str(value)




@dataclass
class SweepOutcome:
    folder: Path
    total: int
    skipped: int  #: points whose rows an earlier run of the study wrote
    ran: int  #: cases run now (points that resolve to one case share its run)
    failed: int
    wall_time_s: float
    rows: list[dict]


Progress = Callable[[int, int, int], None]  # (done, failed, total)


def run_study(study: Study, folder: str | Path, jobs: int | None = None,
              scheduler: str | None = None, keep_timeseries: bool = False,
              force: bool = False, progress: Progress | None = None,
              timeseries_format: str = "csv",
              point_timeout: float | None = None) -> SweepOutcome:
    """Run the points of ``study`` that have no row yet; returns all rows, sorted by point.
    With ``keep_timeseries`` each point's results folder is written too, its time series as
    ``timeseries_format`` (pipeline.outputs.TIMESERIES_FORMATS). A point that failed for its
    environment (cause ``environment``: full disk, killed worker, timeout) has no row yet.
    ``point_timeout`` [s]: a point without a result by then fails (default: workers.py).
    The study holds the folder's lock throughout (:func:`folder.study_lock`)."""
    with study_lock(Path(folder)):
        return _run_study(study, folder, jobs, scheduler, keep_timeseries, force, progress,
                          timeseries_format, point_timeout)


def _run_study(study: Study, folder: str | Path, jobs, scheduler, keep_timeseries: bool,
               force: bool, progress: Progress | None, timeseries_format: str,
               point_timeout: float | None) -> SweepOutcome:
    t_start = time.perf_counter()
    if str(folder).strip() == "":
        raise OutputError("-o '': empty path; expected the name of an output folder")
    out = Path(folder)
    if out.exists() and not out.is_dir():
        raise OutputError(f"{out}: exists and is not a folder")
    prod = claim_folder(out, study, summary_columns(study), force)
    if out.is_dir() and not (out / SUMMARY).exists() and any(out.iterdir()) and not force:
        raise OutputError(f"{out}: folder holds other files and no {SUMMARY} of a sweep; "
                          "expected a new or empty folder or an earlier sweep's (--force writes "
                          "into it anyway)")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"{out}: cannot create the output folder ({exc.strerror})") from None
    path = out / SUMMARY
    if (path.exists() or path.is_symlink()) and not path.is_file():
        raise OutputError(f"{path}: exists and is not a file; remove it or choose another "
                          "output folder")
    columns = summary_columns(study)
    if force and path.is_file():  # starting over: the old points' folders go with their rows
        path.unlink()
        if (out / "points").is_dir():
            import shutil

            shutil.rmtree(out / "points")
    earlier = read_summary(path, columns)
    by_hash: dict[str, list] = {}  # points that resolve to one case ("10 mm", "0.01 m")
    for p in study.points:
        by_hash.setdefault(p.case_hash, []).append(p)
    foreign = sum(1 for h in earlier if h not in by_hash)
    if foreign:  # resuming keeps this study's rows only: the others would be lost
        raise OutputError(f"{path}: holds {foreign} result(s) of cases this study does not have "
                          "(another study, or changed settings); use --force to start over or "
                          "another output folder")
    check_producer(out, prod, force)  # a folder holds one study's rows
    record_outputs(out, [SUMMARY, *(["points"] if keep_timeseries else [])], prod)
    done: dict[int, dict] = {}
    for h, rec in earlier.items():
        if rec["status"] == "failed" and rec.get("cause") == ENVIRONMENT:
            continue  # the disk was full, the worker killed: run it again
        for p in by_hash.get(h, []):
            done[p.index] = {**rec, "point": p.index, **_param_cells(p)}
    skipped = len(done)
    todo = [p for p in study.points if p.index not in done]
    # a case is run once: its other points copy the row (unless each keeps its time series)
    todo = todo if keep_timeseries else [p for p in todo if by_hash[p.case_hash][0] is p]
    # rewrite what is kept (drops a torn line), then append new rows one by one
    write_atomic(path, _line(columns, dict(zip(columns, columns, strict=True)))
                  + "".join(_line(columns, done[i]) for i in sorted(done)))
    payloads = [{"index": p.index, "case_hash": p.case_hash, "case_json": p.case_json,
                 "name": study.name, "format": timeseries_format,
                 "keep_dir": str(out / "points" / f"{p.index:05d}") if keep_timeseries else None}
                for p in todo]
    n_failed = sum(1 for r in done.values() if r["status"] == "failed")
    if progress:
        progress(len(done), n_failed, len(study.points))
    ran = 0
    if payloads:
        with open(path, "a", encoding="utf-8") as fh:
            for row in execute(run_point, payloads, jobs, scheduler,
                               point_timeout=point_timeout):
                first = study.points[row["point"]]
                ran += 1
                same = [first] if keep_timeseries else by_hash[first.case_hash]
                for p in same:
                    cells = {**row, "point": p.index, **_param_cells(p)}
                    _apply_checks(study, cells)
                    fh.write(_line(columns, cells))
                    done[p.index] = cells
                    n_failed += cells["status"] == "failed"
                fh.flush()
                os.fsync(fh.fileno())
                if progress:
                    progress(len(done), n_failed, len(study.points))
    rows = [done[i] for i in sorted(done)]
    write_atomic(path, _line(columns, dict(zip(columns, columns, strict=True)))
                  + "".join(_line(columns, r) for r in rows))
    return SweepOutcome(out, len(study.points), skipped, ran, n_failed,
                        time.perf_counter() - t_start, rows)


def _param_cells(point) -> dict:
    return dict(point.values)


def _apply_checks(study: Study, row: dict) -> None:
    if study.checks:
        row["checks"] = check_verdict(study.checks, row)


def check_verdict(checks, row: dict) -> str:
    """The ``checks`` cell of a row: "pass", "fail: <what>", or "" for a row that is not
    ``ok`` (no results to check). A missing or NaN metric fails its check."""
    if row["status"] != "ok":
        return ""
    failed = []
    for c in checks:
        v = row.get(c.metric)
        if v is None or v != v:
            failed.append(f"{c.metric} missing")
        elif c.max is not None and v > c.max:
            failed.append(f"{c.metric} {v:.6g} > {c.max:g}")
        elif c.min is not None and v < c.min:
            failed.append(f"{c.metric} {v:.6g} < {c.min:g}")
    return "pass" if not failed else "fail: " + "; ".join(failed)


def rows_as_table(rows: Iterable[dict], columns: list[str]):
    """The rows as a pandas DataFrame with numbers parsed (for trends and tests)."""
    import pandas as pd

    df = pd.DataFrame([{c: r.get(c) for c in columns} for r in rows], columns=columns)
    for c in df.columns:
        if c not in ("status", "error", "cause", "warnings", "case_hash", "checks"):
            try:  # pandas 3 dropped errors="ignore": a column of text stays text
                df[c] = pd.to_numeric(df[c].replace("", None))
            except (ValueError, TypeError):
                pass
    return df
