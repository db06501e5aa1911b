"""`gearcli dataset STUDY -o DIR`: a labelled fault dataset (signals as Parquet, one labels
table) on the sweep's machinery."""

from __future__ import annotations

from pathlib import Path

import typer

from gearcli.cli.app import app
from gearcli.cli.common import handle_errors


@app.command()
@handle_errors
def dataset(
    study: Path = typer.Argument(..., help="Study file (YAML), as for gearcli sweep."),
    out: Path = typer.Option(..., "-o", "--out", help="Output folder: points/NNNNN/ (each "
                             "point's Parquet signals), summary.csv, labels.csv/.parquet."),
    jobs: int = typer.Option(0, "--jobs", "-j", min=0, help="Worker processes (0: one per "
                             "core)."),
    scheduler: str | None = typer.Option(None, "--scheduler", help="Dask scheduler: 'local' or "
                                         "an address (needs the 'dask' extra)."),
    signal: str = typer.Option("accel_m_s2", "--signal", help="The signal the labels' "
                               "monitoring metrics are computed from (gearcli monitor "
                               "--signal); te for the encoder TE."),
    force: bool = typer.Option(False, "--force", help="Start over (discard the points)."),
    yes: bool = typer.Option(False, "--yes", "-y", help="Run studies of more than 1000 points."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="No summary line."),
) -> None:
    """Run every point of STUDY keeping its signals (time series and sensors table as Parquet)
    and write one labels table: fault kind, gear, tooth and size, speed, load, noise seed, and
    the monitoring metrics of each point (docs/theory.md, "Fault datasets"). Resumable as a
    sweep is.

    Example: gearcli dataset cases/studies/fault_dataset.yaml -o out/faults -j 2

    Exit codes: 0 ok, 4 a point could not be run, 1 bad input.
    """
    from gearcli.errors import CheckFailed
    from gearcli.pipeline.dataset import run_dataset

    outcome, table = run_dataset(study, out, jobs or None, scheduler, force, signal, yes)
    if not quiet:
        kinds = sorted({r.get("fault_kind", "") for r in table})
        typer.echo(f"{outcome.total} points: {outcome.ran} run, {outcome.skipped} already "
                   f"done, {outcome.failed} failed ({outcome.wall_time_s:.1f} s); fault kinds "
                   f"{', '.join(kinds)}; labels in {out}/labels.csv and labels.parquet")
    if outcome.failed:
        raise CheckFailed(f"{out}: {outcome.failed} point(s) failed (status 'failed' in "
                          "labels.csv and summary.csv)")
