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

import contextlib
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
from gearcli.pipeline.sweep.folder import SUMMARY, claim_folder
from gearcli.pipeline.sweep.metrics import METRICS
from gearcli.pipeline.sweep.study import Study

#: Largest summary.csv read back for resuming [bytes] (~1 kB a row, 100 000 points).
MAX_SUMMARY_BYTES = 200_000_000
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
        row.update(status="failed", error=str(exc).splitlines()[0])
    except Exception as exc:  # a bug in one point must not end the study
        row.update(status="failed", error=f"internal error: {exc!r}")
    row["wall_time_s"] = time.perf_counter() - t0
    return row


def case_from_json(text: str, name: str):
    """Validate a resolved case given as JSON (json is ~20x faster than PyYAML for this)."""
    import json

    from gearcli.case.load import validate_source
    from gearcli.case.yamlsrc import Source

    return validate_source(Source(name, json.loads(text), text.splitlines()), name)


def execute(fn, payloads: list[dict], jobs: int | None, scheduler: str | None) -> Iterator[dict]:
    """``fn(payload)`` for every payload, serially, in ``jobs`` local processes, or on Dask
    (``scheduler``: "local" or an address); results in completion order."""
    jobs = jobs or os.cpu_count() or 1
    if scheduler:
        return _dask(payloads, min(jobs, len(payloads)), scheduler, fn)
    if jobs == 1 or len(payloads) <= 1:
        return _serial(payloads, 1, None, fn)
    return _processes(payloads, min(jobs, len(payloads)), None, fn)


def _warm_up(parent_pid: int | None = None) -> None:
    """Worker initializer: import the pipeline (and load the compiled solver) once; with
    ``parent_pid``, end the worker when that process (the sweep) is gone."""
    if parent_pid is not None:
        watch_parent(parent_pid)
        _default_signals()
    import gearcli.pipeline.simulate  # noqa: F401


def _default_signals() -> None:
    """In a forked worker: SIGTERM/SIGHUP end it (not the CLI's handler inherited from the
    sweep, which would only fail the point in flight); Ctrl-C is the sweep's to handle."""
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        return
    for name in ("SIGTERM", "SIGHUP"):
        if hasattr(signal, name):
            signal.signal(getattr(signal, name), signal.SIG_DFL)
    signal.signal(signal.SIGINT, signal.SIG_IGN)


#: How often a worker checks that the sweep that started it still runs [s].
PARENT_POLL_S = 0.5


def watch_parent(pid: int) -> None:
    """End this process soon after process ``pid`` ends, even by kill -9 (which runs no
    cleanup in the sweep): a daemon thread polls it. Idempotent per process; nothing to do
    in the process ``pid`` itself."""
    import threading

    if pid == os.getpid() or getattr(watch_parent, "watching", None) == pid:
        return
    watch_parent.watching = pid
    direct = os.getppid() == pid  # then re-parenting tells at once, whatever the pid reuse

    def watch() -> None:
        while True:
            time.sleep(PARENT_POLL_S)
            if (direct and os.getppid() != pid) or not _alive(pid):
                os._exit(1)

    threading.Thread(target=watch, name="gearcli-parent-watch", daemon=True).start()


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


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


# --- executors ---------------------------------------------------------------------------------
def _serial(payloads: list[dict], jobs: int, scheduler, fn=run_point) -> Iterator[dict]:
    _warm_up()
    for p in payloads:
        yield fn(p)


def _processes(payloads: list[dict], jobs: int, scheduler, fn=run_point) -> Iterator[dict]:
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor, as_completed

    ctx = mp.get_context("fork") if "fork" in mp.get_all_start_methods() else None
    pool = ProcessPoolExecutor(max_workers=jobs, mp_context=ctx, initializer=_warm_up,
                               initargs=(os.getpid(),))
    futures = [pool.submit(fn, p) for p in payloads]
    try:
        for fut in as_completed(futures):
            yield fut.result()
    except BaseException:  # Ctrl-C, SIGTERM, a closed generator: points in flight are lost
        procs = list((getattr(pool, "_processes", None) or {}).values())  # shutdown drops them
        pool.shutdown(wait=False, cancel_futures=True)
        _terminate(procs)
        raise
    pool.shutdown(wait=True)


def _terminate(procs: list) -> None:
    """Stop worker processes now (the pool's shutdown alone waits for running points)."""
    for proc in procs:
        with contextlib.suppress(Exception):
            proc.terminate()
    for proc in procs:
        with contextlib.suppress(Exception):
            proc.join(5.0)


def _dask(payloads: list[dict], jobs: int, scheduler: str, fn=run_point) -> Iterator[dict]:
    try:
        from distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise OutputError("--scheduler needs Dask: pip install 'dask[distributed]'") from None
    cluster = None
    timeout = guards.NETWORK_TIMEOUT_S
    if scheduler == "local":
        cluster = LocalCluster(n_workers=jobs, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
    else:
        probe_scheduler(scheduler, timeout)
        client = _bounded(lambda: Client(scheduler, timeout=f"{timeout}s"), timeout * 2,
                          f"--scheduler {scheduler}")
    try:
        try:
            client.wait_for_workers(1, timeout=timeout * 3)
        except (TimeoutError, OSError) as exc:
            raise OutputError(f"--scheduler {scheduler}: no worker joined within "
                              f"{3 * timeout:g} s ({exc.__class__.__name__})") from None
        # local workers end with the sweep (a LocalCluster's nannies run in this process:
        # they are not watched, they end with it)
        client.run(_warm_up, os.getpid() if cluster is not None else None)
        futures = [client.submit(fn, p, pure=False) for p in payloads]
        for fut in as_completed(futures):
            yield fut.result()
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def probe_scheduler(address: str, timeout: float) -> None:
    """Connect to a ``tcp://host:port`` scheduler and wait for the first bytes of its Dask
    handshake (a scheduler writes it as soon as it accepts): a peer that accepts but never
    speaks Dask is refused after ``timeout`` instead of hanging the client forever."""
    import socket
    from urllib.parse import urlsplit

    if not address.startswith("tcp://"):
        return  # tls:// and others: the client's own timeouts
    parts = urlsplit(address)
    try:
        with socket.create_connection((parts.hostname, parts.port), timeout=timeout) as sock:
            sock.settimeout(timeout)
            if not sock.recv(1):
                raise OutputError(f"--scheduler {address}: the peer closed the connection; "
                                  "expected a Dask scheduler")
    except TimeoutError:
        raise OutputError(f"--scheduler {address}: accepts connections but sent no Dask "
                          f"handshake within {timeout:g} s; expected a Dask scheduler") from None
    except (OSError, ValueError) as exc:
        reason = getattr(exc, "strerror", None) or str(exc)
        raise OutputError(f"--scheduler {address}: cannot connect ({reason})") from None


def _bounded(make, timeout: float, what: str):
    """``make()`` in a daemon thread, given up after ``timeout`` s (an OutputError naming
    ``what``). A connection that hangs past its own timeouts then cannot hang the sweep."""
    import threading

    box: dict = {}

    def target() -> None:
        try:
            box["value"] = make()
        except BaseException as exc:  # re-raised in the caller
            box["error"] = exc

    thread = threading.Thread(target=target, name="gearcli-dask-connect", daemon=True)
    thread.start()
    thread.join(timeout)
    if thread.is_alive():
        raise OutputError(f"{what}: no Dask handshake within {timeout:g} s; expected a Dask "
                          "scheduler")
    if "error" in box:
        exc = box["error"]
        if isinstance(exc, OSError | TimeoutError | ValueError):
            raise OutputError(f"{what}: cannot connect ({exc})") from None
        raise exc
    return box["value"]


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
              timeseries_format: str = "csv") -> SweepOutcome:
    """Run the points of ``study`` that have no row yet; returns all rows, sorted by point.
    With ``keep_timeseries`` each point's results folder is written too, its time series as
    ``timeseries_format`` (pipeline.outputs.TIMESERIES_FORMATS)."""
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
            try:  # pandas 3 dropped errors="ignore": a column of text stays text
                df[c] = pd.to_numeric(df[c].replace("", None))
            except (ValueError, TypeError):
                pass
    return df
