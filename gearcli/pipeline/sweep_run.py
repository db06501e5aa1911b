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

from gearcli.errors import GearcliError, OutputError
from gearcli.pipeline.sweep_metrics import METRICS
from gearcli.pipeline.sweep_study import Study

SUMMARY = "summary.csv"
#: Columns that differ between runs of the same point (timings): not compared across executors.
TIMING_COLUMNS = ("wall_time_s", "solver_time_s")


def summary_columns(study: Study) -> list[str]:
    """Fixed column order: point, varied parameters (with units), metrics, status, ..."""
    metrics = list(study.metrics or METRICS)
    check_col = ["checks"] if study.checks else []
    return ["point", *study.parameter_columns, *metrics, *check_col, "status", "error",
            "warnings", *TIMING_COLUMNS, "case_hash"]


def run_point(payload: dict) -> dict:
    """Simulate one resolved case and measure its metrics; failures become a 'failed' row.

    Runs in a worker: only plain data in and out (picklable, executor-independent).
    """
    t0 = time.perf_counter()
    row: dict = {"point": payload["index"], "case_hash": payload["case_hash"]}
    try:
        from gearcli.case.load import load_case
        from gearcli.pipeline.simulate import run_simulation
        from gearcli.pipeline.sweep_metrics import point_metrics

        keep = payload.get("keep_dir")
        if keep:  # the resolved case beside the results: `gearcli simulate` can rerun it
            case_file = Path(f"{keep}.case.yaml")
            case_file.parent.mkdir(parents=True, exist_ok=True)
            case_file.write_text(payload["case_json"] + "\n")
            loaded = load_case(case_file)
        else:
            loaded = _case_from_json(payload["case_json"], payload["name"])
        res = run_simulation(loaded)
        row.update(point_metrics(res))
        row.update(status="ok", error="", warnings="; ".join(res.warnings),
                   solver_time_s=res.wall_time_s)
        if keep:
            from gearcli.pipeline.outputs import write_simulation

            write_simulation(res, keep, True, fmt=payload.get("format", "csv"))
    except GearcliError as exc:
        row.update(status="failed", error=str(exc).splitlines()[0])
    except Exception as exc:  # a bug in one point must not end the study
        row.update(status="failed", error=f"internal error: {exc!r}")
    row["wall_time_s"] = time.perf_counter() - t0
    return row


def _case_from_json(text: str, name: str):
    """Validate a resolved case given as JSON (json is ~20x faster than PyYAML for this)."""
    import json

    from gearcli.case.load import validate_source
    from gearcli.case.yamlsrc import Source

    return validate_source(Source(name, json.loads(text), text.splitlines()), name)


def _warm_up() -> None:
    """Worker initializer: import the pipeline (and load the compiled solver) once."""
    import gearcli.pipeline.simulate  # noqa: F401


# --- summary.csv -------------------------------------------------------------------------------
def read_summary(path: Path, columns: list[str]) -> dict[str, dict]:
    """Complete rows of an earlier summary.csv by case hash; a torn last line is ignored."""
    if not path.exists():
        return {}
    text = path.read_text(encoding="utf-8")
    lines = text.splitlines(keepends=True)
    if lines and not lines[-1].endswith("\n"):
        lines = lines[:-1]  # a line cut by a kill: never complete
    if not lines:
        return {}
    header = next(csv.reader([lines[0]]))
    if header != columns:
        raise OutputError(f"{path}: written by a different study (other columns); use "
                          "--force to start over or another output folder")
    rows = {}
    for rec in csv.DictReader(io.StringIO("".join(lines))):
        if None in rec or any(v is None for v in rec.values()):
            continue  # wrong field count
        if rec["status"] in ("ok", "failed") and rec["case_hash"]:
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


def _write_atomic(path: Path, text: str) -> None:
    tmp = path.with_name(f".{path.name}.tmp")
    with open(tmp, "w", encoding="utf-8") as fh:
        fh.write(text)
        fh.flush()
        os.fsync(fh.fileno())
    os.replace(tmp, path)


# --- executors ---------------------------------------------------------------------------------
def _serial(payloads: list[dict], jobs: int, scheduler) -> Iterator[dict]:
    _warm_up()
    for p in payloads:
        yield run_point(p)


def _processes(payloads: list[dict], jobs: int, scheduler) -> Iterator[dict]:
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor, as_completed

    ctx = mp.get_context("fork") if "fork" in mp.get_all_start_methods() else None
    with ProcessPoolExecutor(max_workers=jobs, mp_context=ctx, initializer=_warm_up) as pool:
        futures = [pool.submit(run_point, p) for p in payloads]
        try:
            for fut in as_completed(futures):
                yield fut.result()
        except BaseException:
            for f in futures:
                f.cancel()
            raise


def _dask(payloads: list[dict], jobs: int, scheduler: str) -> Iterator[dict]:
    try:
        from distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise OutputError("--scheduler needs Dask: pip install 'dask[distributed]'") from None
    cluster = None
    if scheduler == "local":
        cluster = LocalCluster(n_workers=jobs, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
    else:
        try:
            client = Client(scheduler, timeout="10s")
        except OSError as exc:
            raise OutputError(f"--scheduler {scheduler}: cannot connect ({exc})") from None
    try:
        client.run(_warm_up)
        futures = [client.submit(run_point, p, pure=False) for p in payloads]
        for fut in as_completed(futures):
            yield fut.result()
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


@dataclass
class SweepOutcome:
    folder: Path
    total: int
    skipped: int
    ran: int
    failed: int
    wall_time_s: float
    rows: list[dict]


Progress = Callable[[int, int, int], None]  # (done, failed, total)


def run_study(study: Study, folder: str | Path, jobs: int | None = None,
              scheduler: str | None = None, keep_timeseries: bool = False,
              force: bool = False, progress: Progress | None = None,
              timeseries_format: str = "csv") -> SweepOutcome:
    """Run the points of ``study`` that have no row yet; returns all rows, sorted by point.
    With ``keep_timeseries`` each point's results folder is written too, its time series as
    ``timeseries_format`` (pipeline.outputs.TIMESERIES_FORMATS)."""
    t_start = time.perf_counter()
    out = Path(folder)
    if out.exists() and not out.is_dir():
        raise OutputError(f"{out}: exists and is not a folder")
    out.mkdir(parents=True, exist_ok=True)
    path = out / SUMMARY
    columns = summary_columns(study)
    if force and path.exists():
        path.unlink()
    earlier = read_summary(path, columns)
    by_hash = {p.case_hash: p for p in study.points}
    done: dict[int, dict] = {}
    for h, rec in earlier.items():
        if h in by_hash:
            p = by_hash[h]
            done[p.index] = {**rec, "point": p.index, **_param_cells(p)}
    todo = [p for p in study.points if p.index not in done]
    # rewrite what is kept (drops a torn line), then append new rows one by one
    _write_atomic(path, _line(columns, dict(zip(columns, columns, strict=True)))
                  + "".join(_line(columns, done[i]) for i in sorted(done)))
    payloads = [{"index": p.index, "case_hash": p.case_hash, "case_json": p.case_json,
                 "name": study.name, "format": timeseries_format,
                 "keep_dir": str(out / "points" / f"{p.index:05d}") if keep_timeseries else None}
                for p in todo]
    n_failed = sum(1 for r in done.values() if r["status"] == "failed")
    if progress:
        progress(len(done), n_failed, len(study.points))
    jobs = jobs or os.cpu_count() or 1
    if scheduler:
        execute = _dask
    elif jobs == 1 or len(payloads) <= 1:
        execute = _serial
    else:
        execute = _processes
    ran = 0
    if payloads:
        with open(path, "a", encoding="utf-8") as fh:
            for row in execute(payloads, min(jobs, len(payloads)), scheduler):
                p = study.points[row["point"]]
                row.update(_param_cells(p))
                _apply_checks(study, row)
                fh.write(_line(columns, row))
                fh.flush()
                os.fsync(fh.fileno())
                done[p.index] = row
                ran += 1
                n_failed += row["status"] == "failed"
                if progress:
                    progress(len(done), n_failed, len(study.points))
    rows = [done[i] for i in sorted(done)]
    _write_atomic(path, _line(columns, dict(zip(columns, columns, strict=True)))
                  + "".join(_line(columns, r) for r in rows))
    return SweepOutcome(out, len(study.points), len(study.points) - len(todo), ran, n_failed,
                        time.perf_counter() - t_start, rows)


def _param_cells(point) -> dict:
    return dict(point.values)


def _apply_checks(study: Study, row: dict) -> None:
    if not study.checks:
        return
    if row["status"] != "ok":
        row["checks"] = ""
        return
    failed = []
    for c in study.checks:
        v = row.get(c.metric)
        if v is None:
            failed.append(f"{c.metric} missing")
        elif c.max is not None and v > c.max:
            failed.append(f"{c.metric} {v:.6g} > {c.max:g}")
        elif c.min is not None and v < c.min:
            failed.append(f"{c.metric} {v:.6g} < {c.min:g}")
    row["checks"] = "pass" if not failed else "fail: " + "; ".join(failed)


def rows_as_table(rows: Iterable[dict], columns: list[str]):
    """The rows as a pandas DataFrame with numbers parsed (for trends and tests)."""
    import pandas as pd

    df = pd.DataFrame([{c: r.get(c) for c in columns} for r in rows], columns=columns)
    for c in df.columns:
        if c not in ("status", "error", "warnings", "case_hash", "checks"):
            df[c] = pd.to_numeric(df[c].replace("", None), errors="ignore")
    return df
