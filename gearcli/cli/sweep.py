"""`gearcli sweep STUDY -o DIR`: run a parametric study; summary.csv, trends.csv/.md, plots."""

from __future__ import annotations

from contextlib import contextmanager
from pathlib import Path

import typer

from gearcli.cli.app import app
from gearcli.cli.common import display_units, handle_errors, rich_progress


def _check_scheduler(value: str | None) -> str | None:
    """'local' or PROTOCOL://HOST:PORT (a usage error, exit 2, otherwise)."""
    from gearcli.errors import OutputError
    from gearcli.pipeline.sweep.workers import check_scheduler

    try:
        return check_scheduler(value)
    except OutputError as exc:
        raise typer.BadParameter(str(exc)) from None


#: At most this many worker processes per CPU (more only costs memory).
JOBS_PER_CPU = 4


def _check_jobs(value: int) -> int:
    import os

    limit = JOBS_PER_CPU * (os.cpu_count() or 1)
    if value > limit:
        raise typer.BadParameter(f"{value}: expected at most {limit} ({JOBS_PER_CPU} per CPU)")
    return value


@app.command()
@handle_errors
def sweep(
    study: Path = typer.Argument(..., help="Study file (YAML): base case, parameters, design."),
    out: Path = typer.Option(..., "-o", "--out", help="Output folder (summary.csv, trends)."),
    jobs: int = typer.Option(0, "--jobs", "-j", min=0, callback=_check_jobs,
                             help="Worker processes (0 = all cores; 1 = serial)."),
    scheduler: str = typer.Option(None, "--scheduler", callback=_check_scheduler,
                                  help="Dask: 'local' (embedded LocalCluster) or tcp://host:port."),
    keep_timeseries: bool = typer.Option(False, "--keep-timeseries",
                                         help="Also write each point's results folder (always for "
                                         "a study with dataset:)."),
    fmt: str = typer.Option("csv", "--format",
                            help="Kept time series as 'csv' or 'parquet' (full precision, "
                                 "compressed)."),
    force: bool = typer.Option(False, "--force", help="Start over (discard summary.csv)."),
    yes: bool = typer.Option(False, "--yes", "-y", help="Run studies of more than 1000 points."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="No progress bar, no summary line."),
    point_timeout: float = typer.Option(
        None, "--point-timeout", min=0.001,
        help="Seconds a point may run before it is recorded as failed (timed out; a resume "
             "retries it). Default: from the solver's step limit, at least 20x the slowest "
             "point so far."),
) -> None:
    """Run every point of STUDY (resumable: points already in DIR/summary.csv are skipped);
    failed points are recorded, never abort the study.

    A study with ``dataset: {signal: NAME}`` is a labelled dataset: every point's signals
    (time series and sensors table) kept as Parquet in DIR/points/, and labels.csv/.parquet with
    each point's fault, speed, load, noise seed and the monitoring metrics of NAME
    (docs/theory.md, "Fault datasets").

    Exit codes: 0 ok, 4 a point failed the study's checks or could not be run, 1 bad input.

    Example: gearcli sweep cases/studies/speed_curve.yaml -o out/speed_curve -j 2;
    gearcli sweep cases/studies/fault_dataset.yaml -o out/faults -j 2
    """
    from gearcli import api
    from gearcli.pipeline.sweep.run import check_timeseries_format
    from gearcli.pipeline.sweep.study import load_study

    spec = load_study(study, allow_large=yes)
    check_timeseries_format(fmt, keep_timeseries or spec.dataset is not None)  # a dataset keeps
    if spec.design == "speed_curve":
        from gearcli.io.outdir import check_target

        check_target(out, force)  # before the message and the runs
        if not quiet:
            typer.echo(f"speed curve: {len(spec.points)} speeds, run up and down (2 runs)",
                       err=True)
        df = api.sweep(spec, out, jobs or None, scheduler, force,
                       point_timeout=point_timeout, units=display_units())
        if not quiet:
            invalid = int((df["status"] == "invalid").sum())
            failed = int((df["status"] == "failed").sum())
            unsettled = int((df["status"] == "unsettled").sum())
            typer.echo(f"{len(df)} points, {invalid} outside the model's validity, "
                       f"{failed} failed, {unsettled} not settled; results in {out}/ "
                       "(summary.csv, speed_curve.png)")
        for e in df.attrs["errors"]:
            typer.echo(f"warning: a direction failed: {e}", err=True)
        for note in df.attrs["notes"]:
            typer.echo(f"note: {note}", err=True)
        _raise_if_checks_failed(df, out)
        _raise_if_points_failed(df, out)
        return
    with _progress(enabled=not quiet, total=len(spec.points)) as progress:
        df = api.sweep(spec, out, jobs or None, scheduler, force, keep_timeseries, fmt,
                       progress, point_timeout=point_timeout, units=display_units())
    checks_failed = int(df["checks"].astype(str).str.startswith("fail").sum()) \
        if "checks" in df.columns else 0
    if not quiet:
        a = df.attrs
        invalid = int((df["status"] == "invalid").sum())
        checked = f", {checks_failed} failed the study's checks" if "checks" in df.columns else ""
        typer.echo(f"{a['total']} points: {a['ran']} run, {a['skipped']} already done, "
                   f"{a['failed']} failed (the run did not finish), {invalid} invalid "
                   f"(outside the model's validity){checked} "
                   f"({a['wall_time_s']:.1f} s); results in {out}/ (summary.csv, trends.md)")
        if a["labels"] is not None:
            kinds = sorted({r.get("fault_kind", "") for r in a["labels"]})
            typer.echo(f"dataset: fault kinds {', '.join(kinds)}; each point's signals "
                       f"(Parquet) in {out}/points/, labels in {out}/labels.csv and "
                       "labels.parquet")
    _raise_if_checks_failed(df, out)
    _raise_if_points_failed(df, out)


def _raise_if_checks_failed(df, out) -> None:
    if "checks" not in df.columns:
        return
    checks_failed = int(df["checks"].astype(str).str.startswith("fail").sum())
    if checks_failed:
        from gearcli.errors import CheckFailed

        raise CheckFailed(f"{out}: {checks_failed} of {len(df)} points failed the study's "
                          "checks (column 'checks' of summary.csv)")


def _raise_if_points_failed(df, out) -> None:
    """Exit 4 when points could not be run (their rows say why): a script must not take a
    study with holes for a complete one."""
    failed = int((df["status"] == "failed").sum())
    if failed:
        from gearcli.errors import CheckFailed

        retry = int((df["cause"] == "environment").sum()) if "cause" in df.columns else 0
        again = (f"; {retry} failed for their environment (full disk, killed worker, timeout): "
                 "the same command again retries them") if retry else ""
        raise CheckFailed(f"{out}: {failed} of {len(df)} points failed (status 'failed', the "
                          f"reason in column 'error' of summary.csv){again}")


def _sweep_columns():
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    return (TextColumn("sweep"), BarColumn(), MofNCompleteColumn(),
            TextColumn("{task.fields[failed]} failed, {task.fields[left]} left"),
            TimeElapsedColumn(), TextColumn("ETA"), TimeRemainingColumn())


@contextmanager
def _progress(enabled: bool, total: int):
    """A rich progress bar (done/failed/remaining, ETA) on a terminal; nothing otherwise."""
    with rich_progress(enabled, _sweep_columns) as pr:
        if pr is None:
            yield None
            return
        task = pr.add_task("sweep", total=total, failed=0, left=total)

        def update(done: int, failed: int, n: int) -> None:
            pr.update(task, completed=done, failed=failed, left=n - done)

        yield update
