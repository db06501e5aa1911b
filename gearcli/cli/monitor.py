"""`gearcli monitor RUN`: condition-monitoring metrics (TSA, FM4, NA4, ...) of a finished run."""

from __future__ import annotations

from pathlib import Path

import typer

from gearcli.cli.app import app
from gearcli.cli.common import emit, handle_errors, table_options


@app.command()
@handle_errors
@table_options
def monitor(
    run: Path = typer.Argument(..., help="Results folder written by gearcli simulate."),
    baseline: Path | None = typer.Option(
        None, "--baseline", help="A healthy run's results folder: NA4 and NB4 are normalised "
        "by its revolutions (default: the run's own)."),
    as_json: bool = typer.Option(False, "--json", help="Print monitor.json to stdout."),
    out: Path | None = typer.Option(None, "-o", "--out", help="Write monitor.json and "
                                    "manifest.json into this folder."),
    force: bool = typer.Option(False, "--force", help="Replace an earlier results folder "
                               "(files gearcli did not write stay)."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="No tables; errors only."),
) -> None:
    """Condition-monitoring metrics of a run (docs/theory.md, "Condition-monitoring signals"):
    the transmission error from the simulated shaft angles, resampled onto each shaft's angle,
    time-synchronously averaged over the whole revolutions of the steady window, and RMS,
    kurtosis, crest factor, FM0, FM4, M6A, M8A, NA4, NB4, energy ratio and sideband level and
    index of each shaft's average.

    Example: gearcli monitor out/cracked --baseline out/healthy

    Exit codes: 0 done, 1 bad input (e.g. less than one whole revolution in the window).
    """
    import json

    from gearcli import api
    from gearcli.io.outdir import check_target
    from gearcli.pipeline.monitor import write_monitor

    if out is not None:
        check_target(out, force)  # before the work, not after
    doc = api.monitor(run, baseline)
    if out is not None:
        write_monitor(doc, out, force)
    if as_json:
        typer.echo(json.dumps(doc.to_dict(), indent=2))
    elif not quiet:
        print_monitor(doc)
        if out is not None:
            typer.echo(f"wrote {out}")


def print_monitor(doc) -> None:
    """One table per shaft: metric, value, definition and its reference."""
    from rich.markup import escape
    from rich.table import Table

    from gearcli.cli.common import format_value
    from gearcli.results.monitor import METRIC_DEFINITIONS

    w0, w1 = doc.window_s
    for s in doc.shafts:
        t = Table(title=escape(f"{doc.case}, {s.shaft} ({s.teeth} teeth): TSA of {s.n_revolutions} "
                               f"revolution(s) in {w0:.3f}-{w1:.3f} s, {doc.signal} "
                               f"[{doc.signal_unit}]; {s.normalisation}"),
                  title_justify="left")
        for col in ("metric", "value", "definition", "reference"):
            t.add_column(col, justify="right" if col == "value" else "left")
        for name, definition, ref in METRIC_DEFINITIONS:
            value = s.value(name)
            t.add_row(name, escape("—" if value is None else format_value(value)),
                      escape(definition), escape(ref))
        emit(t)
