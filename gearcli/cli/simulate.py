"""`gearcli simulate CASE -o DIR`: run the tooth-contact solver, write the results folder."""

from __future__ import annotations

from pathlib import Path

import typer

from gearcli.cli.app import app
from gearcli.cli.common import (
    display_units,
    handle_errors,
    print_quantity_table,
    status_reporter,
    table_options,
)
from gearcli.io.files import write_stdout


@app.command()
@handle_errors
@table_options
def simulate(
    case: Path = typer.Argument(..., help="Case file (YAML)."),
    out: str = typer.Option(..., "-o", "--out", help="Results folder, or '-' for CSV on stdout."),
    set_: list[str] = typer.Option(
        [], "--set", help="Override a case value: key.path=value (repeatable)."
    ),
    force: bool = typer.Option(False, "--force", help="Replace an earlier results folder "
                               "(files gearcli did not write stay)."),
    quiet: bool = typer.Option(False, "--quiet", "-q",
                               help="No progress, no summary table, no warnings (summary.json "
                               "keeps them)."),
    as_json: bool = typer.Option(False, "--json", help="Print summary.json to stdout."),
    fmt: str = typer.Option(
        "csv", "--format",
        help="Time series as 'csv' (10 significant digits) or 'parquet' (full precision, "
             "compressed: long runs; needs -o DIR)."),
) -> None:
    """Integrate the tooth-contact model (torsional or lateral-torsional, with the case's shafts
    and inertias); write timeseries.csv (or .parquet),
    summary.json, manifest.json (atomically; never over earlier results without --force).

    Example: gearcli simulate cases/seed.yaml -o out/seed --set run.end_time=2
    """
    import json

    from gearcli import api
    from gearcli.errors import OutputError
    from gearcli.io.outdir import check_target
    from gearcli.pipeline.outputs import TIMESERIES_FORMATS, summary_document, timeseries_csv

    to_stdout = out == "-"
    if fmt not in TIMESERIES_FORMATS:
        raise OutputError(f"--format {fmt}: expected one of {', '.join(TIMESERIES_FORMATS)}")
    if to_stdout and as_json:  # one stream, two documents: neither CSV nor JSON
        raise OutputError("--json with -o -: both print to stdout; expected one of them "
                          "(-o DIR --json: the results folder and summary.json on stdout)")
    if to_stdout and fmt != "csv":
        raise OutputError("--format parquet writes a file: give a results folder with -o DIR")
    if not to_stdout:
        check_target(out, force)  # fail before a long run, not after
    with status_reporter(enabled=not quiet and not to_stdout and not as_json) as status:
        sim = api.simulate(case, set_, status=status, zoom=True,
                           progress=status.progress if status else None)
    result = sim
    if to_stdout:
        write_stdout(timeseries_csv(result))
    else:
        sim.save(out, force, fmt)
    doc = summary_document(result)
    if as_json:
        write_stdout(json.dumps(doc.to_dict(), indent=2) + "\n")
    elif not quiet and not to_stdout:
        print_input_digest(doc.input_digest)
        _print_summary(doc, out, display_units())
    if not quiet and (as_json or to_stdout):
        print_input_digest(doc.input_digest, line=False)  # its warnings
    for w in result.warnings:
        if not quiet:
            typer.echo(f"warning: {w}", err=True)
    if result.status != "ok":
        from gearcli.errors import InvalidResultError

        where = "" if to_stdout else f"; the results in {out} are marked invalid"
        raise InvalidResultError(f"{case}: {result.invalid_reason}{where}")


def print_input_digest(digest, line: bool = True) -> None:
    """The input digest (gearcli/pipeline/digest.py): one line a person checks at a glance
    (when ``line``), and its warnings on stderr."""
    if digest is None:
        return
    for w in digest.warnings:
        typer.echo(f"warning: {w}", err=True)
    if not line:
        return
    typer.echo(f"input: P = {digest.power_kW:.4g} kW, v = {digest.pitch_line_velocity_m_s:.4g} "
               f"m/s, F_t/b = {digest.line_load_N_mm:.4g} N/mm, σ_H0 = "
               f"{digest.sigma_H0_MPa:.4g} MPa, f_z = {digest.gear_mesh_frequency_Hz:.4g} Hz, "
               f"N = f_z/f_n = {digest.resonance_ratio:.3g}")


def _print_summary(doc, out: str, units: str) -> None:
    """The summary table: the metrics shown at "simulate" (gearcli/results/) and the
    solver's counters."""
    from gearcli.results import shown_values
    from gearcli.results.metrics import rows as metric_rows

    s, sv = doc.scalars, doc.solver
    w0, w1 = s.window_s
    shown = shown_values(s, "simulate")
    if doc.status != "ok":
        shown["dynamic_factor"] = "not valid (see the error below)"
    elif s.operating_state != "steady" and s.dynamic_factor is not None:
        shown["dynamic_factor"] = f"{s.dynamic_factor:.4g} (unsteady: see the warnings)"
    rows = metric_rows(shown, shown, units) + [
        ("solver steps / RHS evaluations",
         f"{sv['accepted_steps']} (+{sv['rejected_steps']} rejected) / "
         f"{sv['rhs_evaluations']}", ""),
        ("solver wall time" + (" (including the one-off compilation)"
                               if sv.get("wall_time_includes_compilation") else ""),
         sv["wall_time_s"], "s"),
    ]
    print_quantity_table(f"{doc.case}: steady window {w0:.3f}-{w1:.3f} s", rows)
    typer.echo(f"results written to {out}/")
