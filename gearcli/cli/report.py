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

#: The file names a report of each --format may have.
REPORT_SUFFIXES = {"html": (".html", ".htm"), "md": (".md", ".markdown")}


@app.command()
@handle_errors
def report(
    folder: Path = typer.Argument(..., help="Results folder (after gearcli analyze)."),
    fmt: str = typer.Option("html", "--format", help="html (one self-contained file) or md."),
    out: Path | None = typer.Option(
        None, "-o", "--out",
        help="Report file, named .html or .md after --format (default DIR/report.*)."
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
    from gearcli.io.files import (
        check_new_file,
        check_no_earlier,
        check_suffix,
        record_outputs,
    )
    from gearcli.io.owner import folder_lock
    from gearcli.io.results import check_folder
    from gearcli.report import build_report

    if fmt not in ("html", "md"):
        raise OutputError(f"--format {fmt}: expected html or md")
    check_folder(folder)  # before its report's path: "DIR: not found", not "folder DIR ..."
    target = out if out is not None else folder / f"report.{fmt}"
    with folder_lock(folder):  # nothing replaces the run between reading it and writing
        check_new_file(target, force, "-o" if out is not None else "the report")
        check_suffix("-o", target, REPORT_SUFFIXES[fmt])
        # the figures go into DIR with -o too: an earlier report (report.md links them) keeps
        # its own unless --force
        check_no_earlier(folder, ("figures",) if out is not None else ("figures", target.name),
                         force, "report's figures")
        _note_monitor(_write_monitor(folder), quiet)  # faults: the monitoring section
        figures = folder / "figures"
        new_figures = not (figures.exists() or figures.is_symlink())
        try:
            path = build_report(folder, fmt, out, display_units(), svg)
        except BaseException:  # a full disk: no half-made figures folder that is nobody's
            if new_figures and figures.is_dir() and not figures.is_symlink():
                import shutil

                shutil.rmtree(figures, ignore_errors=True)
            raise
        record_outputs(folder, ["figures", *([path.name] if out is None else [])])
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
    """simulate + analyze + report in one go; exit 4 when a check failed or an ISO 6336
    safety is below its minimum (cases with a rating: section or fatigue limits).

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
            rating, rating_note = _write_rating(tmp, result.loaded)
            monitor_note = _write_monitor(tmp)  # faults: the monitoring section
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
        for line in _rating_lines(rating):
            typer.echo(line)
        _note_monitor(monitor_note, quiet)
    typer.echo(f"report written to {path}")
    also = ["ISO 6336 rating (rating.json)"] if rating is not None and not rating.ok else []
    report_findings(analysis.checks, str(path), also)  # a safety below its minimum: a finding


def _rating_lines(rating) -> list[str]:
    """One line per rating column: the safeties of both gears against their minimums."""
    if rating is None:
        return []
    out = []
    for label, col in (("ISO", rating.iso), ("simulated", rating.simulated)):
        if col is None:
            continue
        p, g = col.pinion, col.gear
        out.append(f"rating ({label}, ISO 6336): S_H {p.S_H:.3f}/{g.S_H:.3f} "
                   f"(minimum {p.S_H_min:g}), S_F {p.S_F:.3f}/{g.S_F:.3f} "
                   f"(minimum {p.S_F_min:g}) pinion/gear: {'pass' if col.ok else 'FAIL'}")
    # a run off its operating point has no simulated column: say why (pipeline/run_rating)
    out += [f"rating: {n}" for n in rating.notes if n.startswith("no simulated column")]
    return out


def _write_monitor(folder: Path) -> str:
    """monitor.json for the report of a run with ``faults:`` (pipeline/monitor.write_run_monitor,
    imported only then: the monitoring model and scipy.signal take ~1.5 s to import, most of a
    healthy case's report); "" when written or not needed, else why not."""
    from gearcli.io.results import case_has_faults

    if not case_has_faults(folder):
        return ""
    from gearcli.pipeline.monitor import write_run_monitor

    return write_run_monitor(folder)


def _note_monitor(why_not: str, quiet: bool) -> None:
    """Say on stderr why a faulted case's report has no monitoring section."""
    if why_not and not quiet:
        typer.echo(f"no condition-monitoring section: {why_not}", err=True)


def _write_rating(folder: Path, loaded):
    """rating.json (ISO 6336: the ISO and the simulated column; S_H, S_F also in summary.json)
    of the run in ``folder`` when its case can be rated: (the rating, ""); else, writing
    nothing, (None, why it was not rated)."""
    from gearcli.pipeline.run_rating import rate_run, write_rating

    rating, why_not = rate_run(folder, loaded, stress_files=True)  # stress.json: the figure
    if rating is not None:  # rating.json, and the safeties into summary.json
        write_rating(folder, rating)
    return rating, why_not
