"""`gearcli analyze DIR`: metrics, spectra, mesh lines and checks with exit codes."""

from __future__ import annotations

from pathlib import Path

import typer

from gearcli.cli.app import app
from gearcli.cli.common import (
    check_figure_path,
    display_units,
    handle_errors,
    option_quantities,
    print_checks_table,
    print_quantity_table,
    report_findings,
    table_options,
)
from gearcli.io.files import write_stdout


@app.command()
@handle_errors
@table_options
def analyze(
    folder: Path = typer.Argument(..., help="Results folder written by gearcli simulate."),
    window: tuple[str, str] | None = typer.Option(
        None, "--window", help="Analysis window T0 T1: times with units ('2 s' '4000 ms') or "
        "numbers in s (default: automatic steady state).",
        metavar="T0 T1"),
    as_json: bool = typer.Option(False, "--json", help="Print analysis.json to stdout."),
    strict: bool = typer.Option(False, "--strict", help="Warnings count as failed checks."),
    remedy: bool = typer.Option(True, "--remedy/--no-remedy", help="A failed dynamic factor or "
                                "contact loss names the tip relief that minimises the loaded "
                                "STE and the dynamic factor with it (a short run); a failed "
                                "resonance margin the speeds to avoid."),
    force: bool = typer.Option(False, "--force", help="Replace an earlier analysis in DIR."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="No tables; errors only."),
    orders: Path | None = typer.Option(
        None, "--orders", help="Also draw the order map of the run (spectra of the mesh force "
        "against pinion speed and time, mesh orders and modes) to FILE (.png, .svg, .pdf)."),
    spectra: Path | None = typer.Option(
        None, "--spectra", help="Also draw the spectra of the window (gear speed, DTE, force; "
        "mesh harmonics marked) to FILE (.png, .svg, .pdf)."),
    order_axis: bool = typer.Option(False, "--order-axis", help="--spectra against the "
                                    "order per pinion revolution instead of Hz."),
    db: bool = typer.Option(False, "--db", help="--spectra in dB re each panel's largest "
                            "amplitude instead of a log axis (the order map is in dB)."),
) -> None:
    """Check a run: speed ratio, mesh-frequency lines, aliasing, resonance margin, dynamic
    factor, contact loss, energy; writes analysis.json, spectrum.csv, harmonics.csv into DIR.

    Exit codes: 0 every check passed, 4 a check failed, 1 bad input.

    Example: gearcli analyze out/seed --window 2 4 --force --spectra spectra.png --order-axis
    """
    import json

    from gearcli import api
    from gearcli.io.files import check_no_earlier, record_outputs, save_figure
    from gearcli.io.owner import folder_lock
    from gearcli.pipeline.analysis_io import ANALYSIS_FILES, write_analysis

    if (order_axis or db) and spectra is None:
        from gearcli.errors import OutputError

        raise OutputError("--order-axis and --db shape the --spectra figure; give --spectra "
                          "FILE too")
    with folder_lock(folder):  # nothing replaces the run between reading it and writing
        check_no_earlier(folder, ANALYSIS_FILES, force, "analysis")
        check_figure_path("--orders", orders, force)
        check_figure_path("--spectra", spectra, force)
        analysis = api.analyze(folder, option_quantities(window, "TIME", "--window"),
                               strict, remedy)
        result = analysis
        doc = write_analysis(result)
        from gearcli.results import AnalysisDocument

        typed = AnalysisDocument.from_document(doc)  # as the report reads it back
        if orders is not None:
            _save_order_map(result, orders, display_units())
        if spectra is not None:
            from gearcli.pipeline.analysis_io import spectrum_columns
            from gearcli.report.figures import spectra_figure

            harmonics = result.case.checks.harmonics
            save_figure(spectra_figure(spectrum_columns(result), typed, harmonics, order_axis,
                                       db, display_units()), spectra, 110)
        record_outputs(folder, ANALYSIS_FILES)
    if as_json:
        write_stdout(json.dumps(doc, indent=2) + "\n")
    elif not quiet:
        print_checks(typed, display_units())
    report_findings(result.checks, f"{folder}/analysis.json")


def _save_order_map(result, path: Path, units: str) -> None:
    from gearcli.io.files import save_figure
    from gearcli.plotting.orders import plot_order_map

    c, s = result.run.columns, result.run.summary.scalars
    teeth = result.case.gears.pinion.teeth
    modes = [m.natural_frequency_Hz for m in s.modes
             if not m.rigid_body and m.natural_frequency_Hz]
    fig = plot_order_map(c["t_s"], c["force_total_N"], c["omega1_rad_s"], teeth, modes,
                         label="mesh force", unit="N", units=units)
    save_figure(fig, path, 110)


def print_checks(doc, units: str = "engineering") -> None:
    """The analysis table (the metrics shown at "analyze", gearcli/results/, in the display
    ``units``) and the checks table of an analysis (gearcli.results.AnalysisDocument)."""
    from gearcli.results import shown_values
    from gearcli.results.metrics import rows as metric_rows

    m = doc.metrics
    shown = shown_values(m, "analyze")
    rows = metric_rows(shown, shown, units)
    w0, w1 = m.window_s
    print_quantity_table(f"{doc.case}: window {w0:.3f}-{w1:.3f} s ({m.window_reason})",
                         rows)
    print_checks_table(doc.checks, units)
