"""`gearcli report DIR` and `gearcli run CASE -o DIR` (simulate + analyze + report)."""

from __future__ import annotations

from pathlib import Path

import typer

from gearcli.cli.app import app
from gearcli.cli.common import (
    display_units,
    handle_errors,
    report_findings,
    status_reporter,
    table_options,
)


@app.command()
@handle_errors
def report(
    folder: Path = typer.Argument(..., help="Results folder (after gearcli analyze)."),
    fmt: str = typer.Option("html", "--format", help="html (one self-contained file) or md."),
    out: Path | None = typer.Option(
        None, "-o", "--out", help="Report file (default DIR/report.*)."
    ),
    force: bool = typer.Option(False, "--force", help="Replace an earlier report."),
    svg: bool = typer.Option(False, "--svg", help="Also write every figure as SVG (vector; "
                             "slower: the PNGs alone make the report)."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="Print nothing but errors."),
) -> None:
    """Figures (PNG; SVG too with --svg) and a report: case tables, geometry, results, checks,
    manifest.

    Example: gearcli report out/seed --format md"""
    from gearcli.errors import OutputError
    from gearcli.io.files import check_new_file, check_no_earlier
    from gearcli.report import build_report

    if fmt not in ("html", "md"):
        raise OutputError(f"--format {fmt}: expected html or md")
    target = out if out is not None else folder / f"report.{fmt}"
    check_new_file(target, force, "-o" if out is not None else "the report")
    if out is None:
        check_no_earlier(folder, ("figures",), force, "report's figures")
    path = build_report(folder, fmt, out, display_units(), svg)
    if not quiet:
        typer.echo(f"report written to {path}")


@app.command()
@handle_errors
@table_options
def run(
    case: Path = typer.Argument(..., help="Case file (YAML)."),
    out: Path = typer.Option(..., "-o", "--out", help="Results folder."),
    set_: list[str] = typer.Option([], "--set", help="Override a case value: key.path=value."),
    force: bool = typer.Option(False, "--force", help="Replace an earlier results folder "
                               "(files gearcli did not write stay)."),
    fmt: str = typer.Option("html", "--format", help="Report format: html or md."),
    svg: bool = typer.Option(False, "--svg", help="Also write every figure as SVG (vector; "
                             "slower: the PNGs alone make the report)."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="Only errors and the report path."),
) -> None:
    """simulate + analyze + report in one go; the exit code is analyze's (4: a check failed).

    All or nothing: the results, the analysis and the report are written into one temporary
    folder that replaces DIR only when all of them are complete (earlier results survive
    until then).

    Example: gearcli run cases/iso_pair.yaml -o out/iso --format md
    """
    from gearcli import api
    from gearcli.cli.analyze import print_checks
    from gearcli.errors import InvalidResultError, OutputError
    from gearcli.io.outdir import atomic_dir, check_target
    from gearcli.pipeline.analysis_io import write_analysis
    from gearcli.pipeline.outputs import write_simulation_files
    from gearcli.report import build_report

    if fmt not in ("html", "md"):
        raise OutputError(f"--format {fmt}: expected html or md")
    check_target(out, force)
    units = display_units()
    with status_reporter(enabled=not quiet) as status:
        result = api.simulate(case, set_, status=status, zoom=True,
                              progress=status.progress if status else None)
        if result.status != "ok":  # keep the run for diagnosis; nothing to analyse
            with atomic_dir(out, force) as tmp:
                write_simulation_files(result, tmp, set_)
            raise InvalidResultError(f"{case}: {result.invalid_reason}; the results in {out} "
                                     "are marked invalid, no analysis or report was made")
        if status:
            status("analysing and writing the report")
        with atomic_dir(out, force) as tmp:
            write_simulation_files(result, tmp, set_)
            analysis = api.analyze(tmp, remedies=True)
            doc = write_analysis(analysis)
            rating_note = _write_rating(tmp, result.loaded)
            name = build_report(tmp, fmt, None, units, svg).name
    path = out / name
    if not quiet:
        from gearcli.cli.simulate import print_input_digest
        from gearcli.pipeline.outputs import summary_document
        from gearcli.results import AnalysisDocument

        print_input_digest(summary_document(result).input_digest)
        print_checks(AnalysisDocument.from_document(doc), units)
        for w in result.warnings:
            typer.echo(f"warning: {w}", err=True)
        if rating_note:
            typer.echo(f"not rated (ISO 6336): {rating_note}", err=True)
    typer.echo(f"report written to {path}")
    report_findings(analysis.checks, str(path))


def _write_rating(folder: Path, loaded) -> str:
    """rating.json (ISO 6336: the ISO and the simulated column) of the run in ``folder`` when
    its case can be rated, returning ""; else, writing nothing, why it was not rated."""
    import json

    from gearcli.io.files import write_atomic
    from gearcli.pipeline.run_rating import rate_run

    rating, why_not = rate_run(folder, loaded)
    if rating is not None:
        write_atomic(folder / "rating.json", json.dumps(rating.to_dict(), indent=2) + "\n")
    return why_not
